//! The error type of the checked entry points.
//!
//! ```
//! use ppoe::{Error, Transform};
//! // A scaled "rotation" is rejected with a reason, not used.
//! let t = Transform::from_parts([[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [0.0; 3]);
//! assert_eq!(t.check(), Err(Error::NotARotation));
//! ```

use core::fmt;

/// What was wrong with an input. Every checked function returns one of these instead of
/// panicking or producing NaN.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// An input contains NaN or ±∞.
    NonFinite,
    /// A covariance is not symmetric within tolerance.
    NotSymmetric,
    /// A covariance has a negative eigenvalue beyond tolerance.
    NotPositiveSemidefinite,
    /// A matrix that must be inverted (a covariance in pose fusion, an information
    /// matrix) is singular or not positive definite.
    Singular,
    /// A rotation part is not orthonormal with positive determinant within tolerance.
    NotARotation,
    /// A screw or joint axis has zero length.
    ZeroAxis,
    /// A collection input (samples, poses) is empty.
    Empty,
    /// The operation needs more inputs than were given (e.g. a sample covariance from
    /// one sample).
    TooFewSamples,
    /// An output buffer is too small for the requested result.
    BufferTooSmall,
    /// Inputs of mismatched lengths (e.g. joint values and joint covariances).
    LengthMismatch,
    /// A surface grid with fewer than 2 steps (it needs both poles).
    GridSize,
    /// A joint's displacement constants ([`crate::chain::JointConstants`]) are not those
    /// of its screw axis (changed after they were computed, or written by hand).
    InconsistentConstants,
    /// Valid inputs gave a result that is not finite: an intermediate overflowed (e.g.
    /// huge lengths times large covariances), so no trustworthy result exists in this
    /// precision.
    Overflow,
    /// A screw axis that must be a unit vector (a joint's rotation part, or a prismatic
    /// joint's translation part) is not one within tolerance; its length may be nonzero.
    NotUnitAxis,
    /// An index into another input is out of its range (a mimic joint's master beyond the
    /// independent joint values, see [`crate::chain::Coupling`]).
    IndexOutOfRange,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Error::NonFinite => "input contains NaN or infinity",
            Error::NotSymmetric => "covariance is not symmetric",
            Error::NotPositiveSemidefinite => "covariance is not positive semi-definite",
            Error::Singular => "matrix is singular or not positive definite",
            Error::NotARotation => "rotation part is not orthonormal with determinant +1",
            Error::ZeroAxis => "axis has zero length",
            Error::Empty => "no input elements",
            Error::TooFewSamples => "too few samples",
            Error::BufferTooSmall => "output buffer too small",
            Error::LengthMismatch => "inputs have mismatched lengths",
            Error::GridSize => "surface grid needs at least 2 steps",
            Error::InconsistentConstants => "joint constants do not match its screw axis",
            Error::Overflow => "result is not finite: an intermediate overflowed",
            Error::NotUnitAxis => "screw axis is not a unit vector",
            Error::IndexOutOfRange => "index out of range",
        })
    }
}

impl core::error::Error for Error {}
