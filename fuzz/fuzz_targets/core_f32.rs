#![no_main]
//! Every core operation on arbitrary f32 bit patterns (see FUZZING.md).
use libfuzzer_sys::fuzz_target;
use ppoe_fuzz::core_checks::{run, CoreInput};

fuzz_target!(|inp: CoreInput| run::<f32>(&inp));
