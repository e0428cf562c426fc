//! The PPOE for joint-value noise only: one variance per joint along its own screw axis.
//!
//! With `covsᵢ = σᵢ²·SᵢSᵢᵀ` ([`chain::screw_noise`](crate::chain::screw_noise)), every term of the
//! PPOE's sum is rank one: `Ad(X)·σᵢ²SᵢSᵢᵀ·Ad(X)ᵀ = σᵢ²·(Ad(X)·Sᵢ)(Ad(X)·Sᵢ)ᵀ`. So the
//! screw axis is transported (a 6-vector, 18 multiplications) instead of a 6×6 matrix, and
//! the sum is 21 multiply-adds per joint. The transported axes are the columns of the body
//! Jacobian (Right: `Ad(Gᵢ⁻¹)·Sᵢ`, `Gᵢ = Dᵢ₊₁…Dₙ·M`, since `Ad(Dᵢ⁻¹)·Sᵢ = Sᵢ`) or of the
//! space Jacobian (Left: `Ad(D₁…Dᵢ₋₁)·Sᵢ`), so `Σ = J·diag(σ²)·Jᵀ`.
//!
//! Same model, same clipping and same [`Convention`]s as
//! [`ChainView::ppoe`](crate::chain::ChainView::ppoe); the result equals the dense path with
//! `screw_noise` covariances up to rounding (measured by the repository's rank-1 tests:
//! within 1e-14 of ‖Σ‖ in f64 and
//! 1e-6 in f32 on the golden chains). On random states of a 6-joint arm the f32 error against
//! an f64 oracle stays within 8ε of ‖Σ‖ in the tip frame and 16ε with [`Convention::Left`],
//! whose base-frame sum has lever arms that cancel; the dense path's error is of the same size.

use super::{Convention, UncertainPose};
use crate::error::Error;
use crate::joint::{screw_noise, Joint};
use crate::kinematics::{Chain, ChainView};
use crate::linalg::{Mat6, Vec6};
use crate::scalar::Real;
use crate::se3::congruence::mirror_lower;
use crate::se3::Transform;

/// `Ad(t⁻¹)·s` without forming the adjoint: `(Rᵀω, Rᵀ(v − p×ω))` (rotation first).
#[inline(always)]
fn inverse_adjoint_apply<T: Real>(t: &Transform<T>, s: &Vec6<T>) -> Vec6<T> {
    let w = s.rotation();
    let v = s.translation() - t.translation.cross(&w);
    let r = t.rotation.transpose();
    Vec6::from_parts(r * w, r * v)
}

/// `Ad(t)·s` without forming the adjoint: `(Rω, p×Rω + Rv)` (rotation first).
#[inline(always)]
fn adjoint_apply<T: Real>(t: &Transform<T>, s: &Vec6<T>) -> Vec6<T> {
    let w = t.rotation * s.rotation();
    let v = t.translation.cross(&w) + t.rotation * s.translation();
    Vec6::from_parts(w, v)
}

/// Adds `σ²·u·uᵀ` to the lower triangle of `acc`.
#[inline(always)]
fn add_rank1_lower<T: Real>(u: &Vec6<T>, sigma2: T, acc: &mut [[T; 6]; 6]) {
    let su = u.scale(sigma2);
    for (r, row) in acc.iter_mut().enumerate() {
        for (c, a) in row.iter_mut().enumerate().take(r + 1) {
            *a += su.0[r] * u.0[c];
        }
    }
}

/// The rank-one PPOE on a slice of joints (the body of every entry point; lengths already
/// checked).
fn rank1<T: Real>(
    joints: &[Joint<T>],
    home: &Transform<T>,
    thetas: &[T],
    sigma2: &[T],
    convention: Convention,
) -> UncertainPose<T> {
    let clip_continuous = convention == Convention::Pytransform3d;
    let mut acc = [[T::ZERO; 6]; 6];
    let pose = if convention == Convention::Left {
        // Space Jacobian: uᵢ = Ad(D₁…Dᵢ₋₁)·Sᵢ, base to tip.
        let mut p = Transform::identity();
        for ((j, t), s2) in joints.iter().zip(thetas).zip(sigma2) {
            add_rank1_lower(&adjoint_apply(&p, &j.screw), *s2, &mut acc);
            p = p * j.displacement(j.clip(*t, clip_continuous));
        }
        p * *home
    } else {
        // Body Jacobian: uᵢ = Ad(Gᵢ⁻¹)·Sᵢ, Gᵢ = Dᵢ₊₁…Dₙ·M (Right) or Dᵢ₊₁…Dₙ
        // (Pytransform3d, moved by Ad(M) at the end), tip to base.
        let mut g = if convention == Convention::Right {
            *home
        } else {
            Transform::identity()
        };
        for ((j, t), s2) in joints.iter().zip(thetas).zip(sigma2).rev() {
            let u = inverse_adjoint_apply(&g, &j.screw);
            let u = if convention == Convention::Right {
                u
            } else {
                adjoint_apply(home, &u)
            };
            add_rank1_lower(&u, *s2, &mut acc);
            g = j.displacement(j.clip(*t, clip_continuous)) * g;
        }
        if convention == Convention::Right {
            g
        } else {
            g * *home
        }
    };
    UncertainPose {
        pose,
        cov: mirror_lower(acc),
    }
}

/// The checks of the `_checked` entry points: the chain, finite θ, finite σ² ≥ 0; then
/// the rank-one PPOE, whose output must be finite.
fn rank1_checked<T: Real>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    sigma2: &[T],
    convention: Convention,
) -> Result<UncertainPose<T>, Error> {
    if thetas.len() != chain.joints.len() || sigma2.len() != chain.joints.len() {
        return Err(Error::LengthMismatch);
    }
    chain.check()?;
    if !thetas.iter().chain(sigma2).all(|x| x.is_finite()) {
        return Err(Error::NonFinite);
    }
    if sigma2.iter().any(|s| *s < T::ZERO) {
        return Err(Error::NotPositiveSemidefinite);
    }
    let out = rank1(chain.joints, &chain.home, thetas, sigma2, convention);
    crate::checks::validate_uncertain_pose(&out.pose, &out.cov)?;
    Ok(out)
}

impl<T: Real> ChainView<'_, T> {
    /// The PPOE for joint-value noise, unchecked: the same pose and covariance as
    /// [`ChainView::ppoe`] with `covsᵢ = σᵢ²·SᵢSᵢᵀ`
    /// ([`chain::screw_noise`](crate::chain::screw_noise)), `sigma2[i]` = σᵢ² the variance of
    /// joint i's value (rad² or m²), computed with one 6-vector per joint instead of a 6×6
    /// matrix: every term of the sum is rank one, `σᵢ²·uᵢuᵢᵀ` with uᵢ the transported screw
    /// axis, a column of the body Jacobian (Right: `Ad(Gᵢ⁻¹)·Sᵢ`, `Gᵢ = Dᵢ₊₁…Dₙ·M`) or of
    /// the space Jacobian (Left), so `Σ = J·diag(σ²)·Jᵀ`. Same [`Convention`]s and clipping.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `thetas` or `sigma2` does not have one value per joint.
    ///
    /// # Accuracy
    /// Equal to the dense path up to rounding (within 1e-14·‖Σ‖ in f64, 1e-6·‖Σ‖ in f32 on
    /// the test chains); exactly symmetric, PSD within rounding for σ² ≥ 0. On random
    /// states of a 6-joint arm the f32 error against an f64 oracle stays within 8ε of ‖Σ‖
    /// in the tip frame and 16ε with [`Convention::Left`], whose base-frame sum has lever
    /// arms that cancel; the dense path's error is of the same size.
    pub fn ppoe_rank1(
        &self,
        thetas: &[T],
        sigma2: &[T],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        if thetas.len() != self.joints.len() || sigma2.len() != self.joints.len() {
            return Err(Error::LengthMismatch);
        }
        Ok(rank1(self.joints, &self.home, thetas, sigma2, convention))
    }

    /// [`ChainView::ppoe_rank1`] with checks of its input and output.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for wrong lengths; the chain's own errors
    /// ([`ChainView::check`]); [`Error::NonFinite`] if a θ or σ² is NaN or infinite;
    /// [`Error::Overflow`] if the result is not finite (finite inputs that overflow
    /// inside); [`Error::NotPositiveSemidefinite`] if a σ² is negative.
    pub fn ppoe_rank1_checked(
        &self,
        thetas: &[T],
        sigma2: &[T],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        rank1_checked(self, thetas, sigma2, convention)
    }
}

impl<T: Real, const N: usize> Chain<T, N> {
    /// The PPOE for joint-value noise (unchecked): [`ChainView::ppoe_rank1`] on this chain,
    /// `sigma2[i]` the variance of joint i's value.
    ///
    /// ```
    /// use ppoe::chain::{screw_noise, Chain, Convention, Joint, JointKind};
    /// use ppoe::Transform;
    /// const INF: f64 = f64::INFINITY;
    /// const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    ///     Joint::new("j1", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    ///     Joint::new("j2", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let fast = ARM.ppoe_rank1(&[0.3, -0.2], &[1e-4, 4e-4], Convention::Right);
    /// let covs = [screw_noise(&ARM.joints[0].screw, 1e-4),
    ///             screw_noise(&ARM.joints[1].screw, 4e-4)];
    /// let dense = ARM.ppoe(&[0.3, -0.2], &covs, Convention::Right);
    /// assert!((fast.cov.0[2][2] - dense.cov.0[2][2]).abs() < 1e-18);
    /// assert!((fast.cov.0[2][2] - 5e-4).abs() < 1e-18); // yaw: both variances add up
    /// ```
    pub fn ppoe_rank1(
        &self,
        thetas: &[T; N],
        sigma2: &[T; N],
        convention: Convention,
    ) -> UncertainPose<T> {
        rank1(&self.joints, &self.home, thetas, sigma2, convention)
    }

    /// The checked rank-one PPOE ([`ChainView::ppoe_rank1_checked`]).
    ///
    /// # Errors
    /// As [`ChainView::ppoe_rank1_checked`].
    pub fn ppoe_rank1_checked(
        &self,
        thetas: &[T; N],
        sigma2: &[T; N],
        convention: Convention,
    ) -> Result<UncertainPose<T>, Error> {
        rank1_checked(&self.as_ref(), thetas, sigma2, convention)
    }
}

/// The covariance of joint-value noise as the dense path takes it: `σᵢ²·SᵢSᵢᵀ` per joint
/// ([`chain::screw_noise`](crate::chain::screw_noise)), for comparing both paths.
pub fn dense_covariances<T: Real, const N: usize>(
    chain: &Chain<T, N>,
    sigma2: &[T; N],
) -> [Mat6<T>; N] {
    let mut out = [Mat6::zeros(); N];
    for ((o, j), s) in out.iter_mut().zip(&chain.joints).zip(sigma2) {
        *o = screw_noise(&j.screw, *s);
    }
    out
}
