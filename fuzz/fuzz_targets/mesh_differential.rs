//! Valid meshes from the fuzz bytes, refined by the native engine and by
//! OpenSubdiv: both refuse, or both give the same topology and positions
//! (within 1e-9 of the bounding-box diagonal).
#![no_main]

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(case) = subdiv_fuzz::mesh_case(&mut u, false) else {
        return;
    };
    subdiv_fuzz::check_differential(&case);
});
