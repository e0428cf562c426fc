#![no_main]
//! Bytes → strict JSON and the noise model, its items generated (see FUZZING.md).
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| ppoe_fuzz::noise_checks::run(data));
