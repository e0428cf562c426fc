#![no_main]
//! SymmetricEigen and the ellipsoid surfaces on arbitrary symmetric matrices, f32 and f64
//! (see FUZZING.md).
use libfuzzer_sys::fuzz_target;
use ppoe_fuzz::eigen_checks::{run, EigenInput};

fuzz_target!(|inp: EigenInput| {
    run::<f64>(&inp);
    run::<f32>(&inp);
});
