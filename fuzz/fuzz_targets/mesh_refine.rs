//! A `Mesh` built from the fuzz bytes (valid or, one run in two, anything:
//! bad indices, tiny faces, NaN, malformed offsets and channels): validation,
//! native refinement to a level <= 3 with arbitrary options, interpolation,
//! stencils, limit, face-varying values; with the `osd` feature, the
//! OpenSubdiv bridge with and without Rust's validation in front of the shim.
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
    #[cfg(feature = "osd")]
    subdiv_fuzz::check_osd(&case);
});
