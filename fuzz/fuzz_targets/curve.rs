//! `subdiv::io::points::parse_points` on arbitrary text (after 6 configuration
//! bytes: scheme, degree, tension, closed, levels, tolerance), then the
//! refinement of what it returns with every scheme, flattening, evaluation
//! and the text round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| subdiv_fuzz::check_curve(data));
