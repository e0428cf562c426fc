//! The estimator's error type: every problem with the input names the sample (and the
//! joint) it was found in.

use std::fmt;

/// Why a fit could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum FitError {
    /// A sample's joint values do not match the chain's joint count.
    WrongLength {
        /// The sample's index.
        sample: usize,
        /// How many values it has.
        got: usize,
        /// How many the chain has.
        expected: usize,
    },
    /// A joint value or a pose element is NaN or infinite.
    NonFinite {
        /// The sample's index.
        sample: usize,
        /// Which value.
        what: String,
    },
    /// A pose is not a rigid transform (rotation not orthonormal with determinant +1
    /// within 1e-6, or last row not (0, 0, 0, 1)).
    NotRigid {
        /// The sample's index.
        sample: usize,
        /// What is wrong.
        why: String,
    },
    /// A campaign holds both pose and position samples.
    MixedMeasurements {
        /// The first sample of the other kind.
        sample: usize,
    },
    /// The measurement covariance is not a finite symmetric PSD 6×6 matrix.
    BadMeasurementCov(String),
    /// The chain itself is invalid (from `ppoe`'s check).
    BadChain(String),
    /// Fewer samples than the model needs.
    TooFewSamples {
        /// How many were given.
        got: usize,
        /// How many the model needs at least.
        needed: usize,
    },
    /// The configurations do not vary enough to determine the model.
    NotIdentifiable(String),
    /// The likelihood could not be evaluated (every candidate covariance singular).
    Numerical(String),
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FitError::WrongLength {
                sample,
                got,
                expected,
            } => write!(
                f,
                "sample {sample}: {got} joint values given, the chain has {expected} joints"
            ),
            FitError::NonFinite { sample, what } => {
                write!(f, "sample {sample}: {what} is not finite")
            }
            FitError::NotRigid { sample, why } => {
                write!(
                    f,
                    "sample {sample}: the pose is not a rigid transform: {why}"
                )
            }
            FitError::MixedMeasurements { sample } => write!(
                f,
                "sample {sample}: a campaign's samples are all poses or all positions, not both"
            ),
            FitError::BadMeasurementCov(why) => write!(f, "measurement_cov: {why}"),
            FitError::BadChain(why) => write!(f, "the chain is invalid: {why}"),
            FitError::TooFewSamples { got, needed } => write!(
                f,
                "{got} samples given, the model needs at least {needed} (more for useful \
                 standard errors)"
            ),
            FitError::NotIdentifiable(why) => write!(
                f,
                "the configurations do not vary enough to identify the model: {why}"
            ),
            FitError::Numerical(why) => write!(f, "the fit failed: {why}"),
        }
    }
}

impl std::error::Error for FitError {}
