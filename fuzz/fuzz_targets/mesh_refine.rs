//! A `Mesh` built from the fuzz bytes (valid or, one run in two, anything:
//! bad indices, tiny faces, NaN, malformed offsets and channels): validation,
//! native refinement to a level <= 3 with arbitrary options, interpolation,
//! stencils, limit, face-varying values; then adaptive refinement with
//! arbitrary adaptive options and selected faces (`refine_adaptive`, every
//! level's queries and child maps, interpolation, stencils); with the `osd`
//! feature, the OpenSubdiv bridge with and without Rust's validation in
//! front of the shim.
#![no_main]

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let mut u = Unstructured::new(rest);
    let Ok(case) = subdiv_fuzz::mesh_case(&mut u, first & 1 == 1) else {
        return;
    };
    subdiv_fuzz::check_native(&case);
    let wild = first & 1 == 1;
    let adaptive =
        subdiv_fuzz::adaptive_case(&mut u, case.mesh.face_count(), wild).unwrap_or_default();
    subdiv_fuzz::check_native_adaptive(&case, &adaptive);
    #[cfg(feature = "osd")]
    subdiv_fuzz::check_osd(&case);
});
