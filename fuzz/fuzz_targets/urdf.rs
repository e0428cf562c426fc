#![no_main]
//! URDF bytes → ppoe-build: parse, chains, generated tables, runtime PPOE (see FUZZING.md).
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ppoe_fuzz::urdf_checks::run(data));
