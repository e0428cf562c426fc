#![no_main]
//! Arbitrary chain, names and noise strings → Rust and C tables (see FUZZING.md).
use libfuzzer_sys::fuzz_target;

fuzz_target!(|t: ppoe_fuzz::table_checks::TableIn| ppoe_fuzz::table_checks::run(&t));
