//! defmt (feature `defmt`): every public data type is `defmt::Format` for f32 and f64.
//! The output itself needs a defmt logger and host decoder (firmware); here the impls
//! are checked to exist for each type, and `scripts/features-check.sh` builds them for
//! thumbv7em.
#![cfg(feature = "defmt")]

use ppoe::chain::{Chain, Convention, Joint, JointKind, UncertainPose};
use ppoe::{Error, Mat3, Mat6, Matrix, Transform, Vec3, Vec6};

/// The bound is the test: this compiles only for types that are `defmt::Format`.
#[allow(clippy::extra_unused_type_parameters)]
fn is_format<T: defmt::Format>() -> bool {
    true
}

fn all_for<T: defmt::Format>() -> bool {
    is_format::<Vec3<T>>()
        && is_format::<Vec6<T>>()
        && is_format::<Mat3<T>>()
        && is_format::<Mat6<T>>()
        && is_format::<Matrix<T, 6, 7>>()
        && is_format::<Transform<T>>()
        && is_format::<Joint<T>>()
        && is_format::<Chain<T, 6>>()
        && is_format::<UncertainPose<T>>()
}

#[test]
fn public_types_are_format() {
    assert!(all_for::<f32>() && all_for::<f64>());
    assert!(is_format::<JointKind>() && is_format::<Convention>() && is_format::<Error>());
}
