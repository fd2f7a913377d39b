//! Valid meshes and adaptive options from the fuzz bytes (isolation 0-6,
//! secondary 0-15, every flag, a few selected faces), refined
//! feature-adaptively by the native engine and by OpenSubdiv: both refuse
//! with the same kind of error, or every level agrees — topology,
//! relations, child maps, positions and varying data bit for bit, and the
//! stencil table.
#![no_main]

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(case) = subdiv_fuzz::mesh_case(&mut u, false) else {
        return;
    };
    let Ok(adaptive) = subdiv_fuzz::adaptive_case(&mut u, case.mesh.face_count(), false) else {
        return;
    };
    subdiv_fuzz::check_adaptive_differential(&case, &adaptive);
});
