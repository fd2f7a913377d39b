//! Bfr from the fuzz bytes: a tessellation pattern (scheme, face size 1-40,
//! 0-8 rates of 0-40, facet options) made natively and by OpenSubdiv — both
//! refuse or both give the same rates, counts, coordinates (bit for bit in
//! f32 and f64) and facets; and a small mesh's limit surfaces evaluated at
//! coordinates of the fuzz's choosing (some off the face) by both engines:
//! both refuse or agree within 1e-9 of the mesh's size.
#![no_main]

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    subdiv_fuzz::check_bfr_pattern(&mut u);
    let Ok(case) = subdiv_fuzz::mesh_case(&mut u, false) else {
        return;
    };
    subdiv_fuzz::check_bfr_surfaces(&case, &mut u);
});
