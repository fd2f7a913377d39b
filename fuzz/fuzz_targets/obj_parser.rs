//! `subdiv::io::parse_obj` (OBJ + OpenSubdiv `t` tags) on arbitrary bytes:
//! errors name a real line, successes survive a round trip through the
//! writer, and small valid meshes refine (natively, and through OpenSubdiv
//! with the `osd` feature).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| subdiv_fuzz::check_obj(data));
