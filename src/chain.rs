//! Kinematic chains: screw axes in the base frame, the home pose of the tip, joint kinds
//! and limits; rigid forward kinematics and the PPOE.

use crate::linalg::Vec6;
use crate::scalar::Real;
use crate::se3::Transform;

/// The kind of a moving joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// Rotation about the screw axis; the value is an angle in radians, clipped to the
    /// limits.
    Revolute,
    /// Rotation without limits (URDF `continuous`). The stored limits are only used by the
    /// pytransform3d-compatible mode, which clips continuous joints like revolute ones.
    Continuous,
    /// Translation along the screw axis; the value is a distance in metres, clipped to the
    /// limits.
    Prismatic,
}

/// One moving joint of a chain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint<T> {
    /// The joint's name (from the URDF).
    pub name: &'static str,
    /// The joint's kind.
    pub kind: JointKind,
    /// The screw axis S = (ω, v) in the base frame at the home pose, rotation first:
    /// `(ŝ, q × ŝ)` for revolute joints, `(0, ŝ)` for prismatic ones.
    pub screw: Vec6<T>,
    /// Lower limit (may be −∞).
    pub lower: T,
    /// Upper limit (may be +∞).
    pub upper: T,
}

impl<T: Real> Joint<T> {
    /// A joint; usable in `const` items (this is what `ppoe-build` emits).
    #[inline]
    pub const fn new(name: &'static str, kind: JointKind, screw: [T; 6], lower: T, upper: T) -> Self {
        Self {
            name,
            kind,
            screw: crate::linalg::Vector(screw),
            lower,
            upper,
        }
    }
}

/// A serial kinematic chain of `N` moving joints from a base link to a tip link.
///
/// The forward kinematics is the product of exponentials
/// `T(θ) = Exp(S₁θ₁)·…·Exp(Sₙθₙ)·M` with screw axes Sᵢ in the base frame (rotation first)
/// and the home pose M (tip to base at θ = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chain<T, const N: usize> {
    /// Name of the base link.
    pub base: &'static str,
    /// Name of the tip link.
    pub tip: &'static str,
    /// The moving joints from base to tip.
    pub joints: [Joint<T>; N],
    /// The home pose M: tip to base at θ = 0.
    pub home: Transform<T>,
}

impl<T: Real, const N: usize> Chain<T, N> {
    /// A chain; usable in `const` items (this is what `ppoe-build` emits).
    #[inline]
    pub const fn new(
        base: &'static str,
        tip: &'static str,
        joints: [Joint<T>; N],
        home: Transform<T>,
    ) -> Self {
        Self {
            base,
            tip,
            joints,
            home,
        }
    }
}
