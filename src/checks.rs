//! Output validation of the checked entry points: a result computed from valid inputs is
//! returned only if it is itself valid, so that an overflow inside never comes back as
//! `Ok` with ±∞ or NaN, and a non-unit axis is not reported as a zero one.

use crate::error::Error;
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::Transform;

/// Validates an uncertain pose computed from valid inputs: the pose passes
/// [`Transform::check`] and the covariance is finite.
///
/// # Errors
///
/// [`Error::Overflow`] if any element is not finite (the inputs were finite, so an
/// intermediate overflowed), [`Error::NotARotation`] if the rotation is not orthonormal.
pub(crate) fn validate_uncertain_pose<T: Real>(
    pose: &Transform<T>,
    cov: &Mat6<T>,
) -> Result<(), Error> {
    if !cov.is_finite() {
        return Err(Error::Overflow);
    }
    pose.check().map_err(|e| match e {
        Error::NonFinite => Error::Overflow,
        other => other,
    })
}

/// The error for a screw axis whose relevant part has the given length where 1 was
/// required: [`Error::ZeroAxis`] only if it is exactly zero, else [`Error::NotUnitAxis`].
pub(crate) fn axis_length_error<T: Real>(length: T) -> Error {
    if length == T::ZERO {
        Error::ZeroAxis
    } else {
        Error::NotUnitAxis
    }
}
