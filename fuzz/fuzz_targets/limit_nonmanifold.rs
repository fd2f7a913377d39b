//! The limit on high-valence non-manifold meshes: books of up to 40 pages
//! per spine (OpenSubdiv 3.5's `PrimvarRefiner::Limit` overran its masks from
//! 14), with creases, joined pages and UVs, under every scheme to level 3.
//! The bridge refuses exactly with `Unsafe` or agrees with the native engine
//! (`subdiv_fuzz::limit`).
#![no_main]

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(case) = subdiv_fuzz::limit::book_case(&mut u) else {
        return;
    };
    subdiv_fuzz::limit::check_book(&case);
});
