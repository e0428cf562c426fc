//! Fusion of uncertain poses ([`pose_fusion`]): the maximum-likelihood pose given K
//! measurements of one frame with left (global) Gaussian noise. Re-exported by
//! [`crate::uncertainty`].

use super::check_covariance;
use super::estimate::{non_finite_is_overflow, translation_scale, IterationOptions};
use crate::error::Error;
use crate::linalg::{Mat6, Vec6};
use crate::scalar::Real;
use crate::se3::{self, Transform};

/// The result of [`pose_fusion`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fusion<T> {
    /// The fused pose.
    pub mean: Transform<T>,
    /// Its covariance (left / global perturbation), the inverse of the information
    /// matrix at `mean`.
    pub cov: Mat6<T>,
    /// The residual cost `V = ½ Σₖ xₖᵀ Σₖ⁻¹ xₖ`, `xₖ = Log(T̄·Tₖ⁻¹)`, at `mean`.
    pub cost: T,
    /// Iterations performed.
    pub iterations: usize,
    /// Whether the last Gauss-Newton step was below the convergence tolerance.
    pub converged: bool,
}

crate::linalg::approx_fields!([T: Real] Fusion<T> { mean, cov, cost });

/// Information matrix, gradient and cost of the fusion problem at `mean`.
fn fusion_terms<T: Real>(
    mean: &Transform<T>,
    means: &[Transform<T>],
    infos: &[Mat6<T>],
) -> (Mat6<T>, Vec6<T>, T) {
    let mut lhs = Mat6::zeros();
    let mut rhs = Vec6::zeros();
    let mut cost = T::ZERO;
    for (tk, wk) in means.iter().zip(infos.iter()) {
        let x = se3::log(&(*mean * tk.inverse()));
        let ji = se3::left_jacobian_inv(&x);
        let wx = *wk * x;
        lhs += wk.congruence(&ji.transpose());
        rhs += ji.tr_mul_vec(&wx);
        cost += T::HALF * x.dot(&wx);
    }
    (lhs, rhs, cost)
}

/// The input pose with the lowest fusion cost: the Gauss-Newton start. Near the optimum
/// whenever the inputs agree, so neither a mean rotation near π (whose logarithm from
/// the identity jumps between the two sides of π) nor poses far from the origin (whose
/// information matrix at the identity is conditioned like ‖p‖⁴) trouble the iteration.
fn fusion_start<T: Real>(means: &[Transform<T>], infos: &[Mat6<T>]) -> Transform<T> {
    let mut best = (Transform::identity(), T::ZERO);
    for (i, m) in means.iter().enumerate() {
        let cost = fusion_terms(m, means, infos).2;
        if i == 0 || cost < best.1 {
            best = (*m, cost);
        }
    }
    best.0
}

/// Fuses K uncertain poses of the same frame (left / global perturbations) by
/// Gauss-Newton with backtracking on `V(T) = ½ Σₖ Log(T·Tₖ⁻¹)ᵀ Σₖ⁻¹ Log(T·Tₖ⁻¹)`,
/// with updates `T ← Exp(δ)·T` (Barfoot & Furgale 2014, §IV.B), starting at the input
/// pose of lowest cost.
///
/// Corresponds to pytransform3d's `pose_fusion(means, covs)`, which starts at the
/// identity and always runs 20 iterations; here the loop stops at the rounding floor or
/// at [`IterationOptions::step_tolerance`] (relative to the scale of the poses, see
/// [`IterationOptions`]) and reports convergence. Where pytransform3d converges both
/// reach the same minimum; from the identity it can stall or fail when the mean rotation
/// is near π or the poses are far from the origin, which the start here avoids. The covariance is the inverse
/// information matrix at the returned mean (pytransform3d evaluates it one update
/// earlier; at convergence they agree).
///
/// # Accuracy
///
/// When the loop stops before its cap, the mean is a local minimum of V to the rounding
/// of the problem: measured (`tests/robustness_fusion.rs`), f32 lands within 2.6× of
/// the distance by which an input perturbation of f32's rounding size moves f64's
/// minimum. Gauss-Newton converges linearly, slowly when the poses disagree by tens of
/// degrees: `converged` may then be reached (last step ≤ √ε·s) but not the floor within
/// 20 iterations; raise [`IterationOptions::max_iterations`] for full precision.
///
/// # Errors
///
/// [`Error::LengthMismatch`] if `means.len() != covs.len()`, [`Error::Empty`] for no
/// poses, [`Error::NonFinite`], [`Error::NotARotation`] ([`Transform::check`]),
/// [`Error::NotSymmetric`] / [`Error::NotPositiveSemidefinite`] ([`check_covariance`]),
/// [`Error::Singular`] if a covariance or the information matrix is not positive
/// definite, [`Error::Overflow`] if a step or the result is not finite. Holds at most 16
/// poses (their information matrices live on the stack); more give
/// [`Error::BufferTooSmall`].
///
/// # Example
///
/// ```
/// use ppoe::uncertainty::{pose_fusion, IterationOptions};
/// use ppoe::{Mat6, Transform, Vec3, Vector};
/// let at = |x| Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [x, 0., 0.]);
/// let cov = Mat6::from_diagonal(&Vector([1e-4, 1e-4, 1e-4, 1e-2, 1e-2, 1e-2]));
/// let options = IterationOptions::default();
/// // Two equally certain measurements 2 m apart: the mean is halfway (by symmetry).
/// let f = pose_fusion(&[at(0.0), at(2.0)], &[cov, cov], &options)?;
/// approx::assert_abs_diff_eq!(f.mean.translation, Vec3::new(1.0, 0.0, 0.0), epsilon = 1e-15);
/// // Two measurements of one pose: information adds, Σ = (Σ₁⁻¹ + Σ₂⁻¹)⁻¹ = ¾·Σ₁ here.
/// let f = pose_fusion(&[at(1.0), at(1.0)], &[cov, cov.scale(3.0)], &options)?;
/// approx::assert_relative_eq!(f.cov, cov.scale(0.75), epsilon = 1e-18, max_relative = 1e-12);
/// assert!(f.converged);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn pose_fusion<T: Real>(
    means: &[Transform<T>],
    covs: &[Mat6<T>],
    options: &IterationOptions<T>,
) -> Result<Fusion<T>, Error> {
    const MAX_POSES: usize = 16;
    if means.len() != covs.len() {
        return Err(Error::LengthMismatch);
    }
    if means.is_empty() {
        return Err(Error::Empty);
    }
    if means.len() > MAX_POSES {
        return Err(Error::BufferTooSmall);
    }
    let mut infos = heapless::Vec::<Mat6<T>, MAX_POSES>::new();
    for (m, c) in means.iter().zip(covs.iter()) {
        m.check()?;
        check_covariance(c)?;
        let w = c.inverse_spd().ok_or(Error::Singular)?;
        infos.push(w).map_err(|_| Error::BufferTooSmall)?;
    }
    let scale = translation_scale(means);
    let mut mean = fusion_start(means, &infos);
    let (mut lhs, mut rhs, mut cost) = fusion_terms(&mean, means, &infos);
    let mut iterations = 0;
    let mut converged = false;
    let mut previous = T::infinity();
    while iterations < options.max_iterations {
        let step = -lhs.solve_spd(&rhs).ok_or(Error::Singular)?;
        if !step.is_finite() {
            return Err(Error::Overflow);
        }
        iterations += 1;
        let norm = step.norm();
        converged = norm <= options.converged_tolerance * scale;
        (mean, (lhs, rhs, cost)) = backtrack(&mean, &step, cost, &rhs, means, &infos);
        if options.stop(norm, previous, scale) {
            break;
        }
        previous = norm;
    }
    let cov = lhs.inverse_spd().ok_or(Error::Singular)?;
    if !cov.is_finite() || !cost.is_finite() {
        return Err(Error::Overflow);
    }
    mean.check().map_err(non_finite_is_overflow)?;
    Ok(Fusion {
        mean,
        cov,
        cost,
        iterations,
        converged,
    })
}

/// One damped Gauss-Newton update `Exp(α·step)·mean`: α halved until the cost does not
/// grow (plain Gauss-Newton, like pytransform3d's, oscillates when the poses are far
/// apart). Near the minimum the full step is taken, so the fixed point is the same.
/// Returns the new mean and its terms.
fn backtrack<T: Real>(
    mean: &Transform<T>,
    step: &Vec6<T>,
    cost: T,
    rhs: &Vec6<T>,
    means: &[Transform<T>],
    infos: &[Mat6<T>],
) -> (Transform<T>, (Mat6<T>, Vec6<T>, T)) {
    let mut alpha = T::ONE;
    let mut candidate = se3::exp(step) * *mean;
    let mut terms = fusion_terms(&candidate, means, infos);
    let slack = cost * T::EPS * T::lit(16.0);
    // Steps whose predicted decrease ½·gᵀH⁻¹g is below √ε of the cost are in the
    // rounding regime of the cost itself: take them whole.
    let predicted = -T::HALF * rhs.dot(step);
    for _ in 0..40 {
        if terms.2 <= cost + slack || predicted <= cost * T::TOL {
            break;
        }
        alpha *= T::HALF;
        candidate = se3::exp(&step.scale(alpha)) * *mean;
        terms = fusion_terms(&candidate, means, infos);
    }
    (candidate, terms)
}
