#![no_main]
//! The pictures' STL / OBJ / COLLADA readers on arbitrary bytes (see FUZZING.md).
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ppoe_fuzz::mesh_checks::run(data));
