//! `defmt::Format` (feature `defmt`): firmware logging of ppoe's values through `defmt`,
//! which sends the numbers' bits and formats them on the host, so the firmware carries
//! none of `core::fmt`'s float formatting.
//!
//! Implemented for [`Vector`], [`Matrix`] (rows), [`Transform`], [`JointKind`],
//! [`Joint`], [`Chain`], [`UncertainPose`], [`Convention`] and [`Error`], for scalars
//! that are themselves `defmt::Format` (`f32`, `f64`). Joint constants are not logged
//! (they follow from the screw).
//!
//! In firmware with a defmt logger, `defmt::info!("tool pose: {}", pose)` logs a
//! [`Transform`]; any function taking `impl defmt::Format` takes ppoe's values:
//!
//! ```
//! fn log_value(_: &impl defmt::Format) {}
//! log_value(&ppoe::Transform::<f32>::identity());
//! log_value(&ppoe::Error::NotARotation);
//! ```

use defmt::{write, Format, Formatter};

use crate::chain::{Chain, Convention, Joint, JointKind, UncertainPose};
use crate::error::Error;
use crate::linalg::{Matrix, Vector};
use crate::se3::Transform;

impl<T: Format, const N: usize> Format for Vector<T, N> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "{}", self.0)
    }
}

impl<T: Format, const R: usize, const C: usize> Format for Matrix<T, R, C> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "{}", self.0)
    }
}

impl<T: Format> Format for Transform<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "Transform {{ rotation: {}, translation: {} }}",
            self.rotation, self.translation
        )
    }
}

impl Format for JointKind {
    fn format(&self, f: Formatter<'_>) {
        match self {
            JointKind::Revolute => write!(f, "Revolute"),
            JointKind::Continuous => write!(f, "Continuous"),
            JointKind::Prismatic => write!(f, "Prismatic"),
        }
    }
}

impl<T: Format> Format for Joint<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "Joint {{ name: {=str}, kind: {}, screw: {}, lower: {}, upper: {} }}",
            self.name, self.kind, self.screw, self.lower, self.upper
        )
    }
}

impl<T: Format, const N: usize> Format for Chain<T, N> {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "Chain {{ base: {=str}, tip: {=str}, joints: {}, home: {} }}",
            self.base, self.tip, self.joints, self.home
        )
    }
}

impl<T: Format> Format for UncertainPose<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "UncertainPose {{ pose: {}, cov: {} }}",
            self.pose, self.cov
        )
    }
}

impl Format for Convention {
    fn format(&self, f: Formatter<'_>) {
        match self {
            Convention::Right => write!(f, "Right"),
            Convention::Left => write!(f, "Left"),
            Convention::Pytransform3d => write!(f, "Pytransform3d"),
        }
    }
}

impl Format for Error {
    fn format(&self, f: Formatter<'_>) {
        // The variant's name; `Display`'s sentence would need `core::fmt`.
        let name = match self {
            Error::NonFinite => "NonFinite",
            Error::NotSymmetric => "NotSymmetric",
            Error::NotPositiveSemidefinite => "NotPositiveSemidefinite",
            Error::Singular => "Singular",
            Error::NotARotation => "NotARotation",
            Error::ZeroAxis => "ZeroAxis",
            Error::Empty => "Empty",
            Error::TooFewSamples => "TooFewSamples",
            Error::BufferTooSmall => "BufferTooSmall",
            Error::LengthMismatch => "LengthMismatch",
            Error::GridSize => "GridSize",
            Error::InconsistentConstants => "InconsistentConstants",
            Error::Overflow => "Overflow",
            Error::NotUnitAxis => "NotUnitAxis",
            Error::IndexOutOfRange => "IndexOutOfRange",
        };
        write!(f, "{=str}", name)
    }
}
