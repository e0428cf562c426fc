//! Uncertain transforms: a mean [`Transform`] with a 6×6 covariance of its exponential
//! coordinates (rotation first). The port of pytransform3d's `uncertainty` module.
//!
//! Two perturbation conventions appear, and every function says which it uses:
//! * **left / global**: `T = Exp(ξ)·T̄`, ξ ~ N(0, Σ) expressed in the *output* frame of
//!   `T̄ = A2B` (frame B). pytransform3d's default.
//! * **right / local**: `T = T̄·Exp(ξ)`, ξ expressed in the *input* frame A.
//!
//! They are related by `Σ_left = Ad(T̄)·Σ_right·Ad(T̄)ᵀ` ([`right_to_left`]).
//! Every returned covariance is exactly symmetric (one triangle computed and mirrored,
//! or averaged with its transpose).

use crate::ellipsoid::SymmetricEigen;
use crate::error::Error;
use crate::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::se3::{self, Transform};
use crate::so3;

/// The order of the covariance compounding in [`concat_globally`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Order {
    /// Second order: `Σ = Σ₂ + Ad(T₂)·Σ₁·Ad(T₂)ᵀ`. Positive semi-definite (to rounding)
    /// for PSD inputs: a sum of congruences of PSD matrices.
    Second,
    /// Fourth order: second order plus the Barfoot & Furgale (2014) fourth-order terms,
    /// exactly as pytransform3d computes them. **Not positive semi-definite in general**:
    /// the fourth-order terms are a truncated series, and for ordinary PSD inputs (two
    /// single-axis rotation variances of 0.05 rad² suffice) the sum has negative
    /// eigenvalues, down to −0.76·λ_max in pytransform3d's own test distribution. Use it
    /// to reproduce the reference; use [`Order::FourthPsd`] where a covariance is needed.
    Fourth,
    /// [`Order::Fourth`] projected onto the nearest positive semi-definite matrix (in the
    /// Frobenius norm: negative eigenvalues set to 0, Higham 1988) when it is not positive
    /// definite; bit-identical to [`Order::Fourth`] when it is. Always PSD (to rounding).
    /// The default.
    #[default]
    FourthPsd,
}

/// Converts a right (local) covariance of `mean` into the left (global) one:
/// `Ad(T̄)·Σ·Ad(T̄)ᵀ`.
#[inline]
pub fn right_to_left<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Mat6<T> {
    mean.transport_covariance(cov)
}

/// Converts a left (global) covariance of `mean` into the right (local) one:
/// `Ad(T̄⁻¹)·Σ·Ad(T̄⁻¹)ᵀ`.
#[inline]
pub fn left_to_right<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Mat6<T> {
    mean.inverse().transport_covariance(cov)
}

/// Concatenates two uncertain transforms with **left (global)** perturbations:
/// `Exp(ξ')·T_AC = Exp(ξ_C)·T_BC·Exp(ξ_B)·T_AB`; returns `(T_BC·T_AB, Σ_AC)` with
/// `Σ_AC` in frame C.
///
/// Corresponds to pytransform3d's `concat_globally_uncertain_transforms(mean_A2B,
/// cov_A2B, mean_B2C, cov_B2C)` (same argument order). With [`Order::Fourth`] it adds the
/// fourth-order terms of Barfoot & Furgale, *Associating Uncertainty With
/// Three-Dimensional Poses for Use in Estimation Problems*, IEEE T-RO 2014, eq. 55–57,
/// exactly as pytransform3d does. Cost: two 6×6 congruences (second order),
/// about 30 3×3 products more (fourth), plus a 6×6 Cholesky and, where it fails, a
/// Jacobi eigen-decomposition ([`Order::FourthPsd`]).
///
/// Guarantees: the result is exactly symmetric. It is positive semi-definite for PSD
/// inputs with [`Order::Second`] and [`Order::FourthPsd`], but **not** with
/// [`Order::Fourth`] (see there).
pub fn concat_globally<T: Real>(
    mean_a2b: &Transform<T>,
    cov_a2b: &Mat6<T>,
    mean_b2c: &Transform<T>,
    cov_b2c: &Mat6<T>,
    order: Order,
) -> (Transform<T>, Mat6<T>) {
    let moved = mean_b2c.transport_covariance(cov_a2b);
    let mut cov = *cov_b2c + moved;
    if order != Order::Second {
        cov += fourth_order_terms(cov_b2c, &moved);
    }
    let cov = cov.symmetrize();
    let cov = if order == Order::FourthPsd {
        nearest_psd(&cov)
    } else {
        cov
    };
    (*mean_b2c * *mean_a2b, cov)
}

/// The nearest positive semi-definite matrix to a symmetric `m` in the Frobenius norm
/// (Higham 1988): its eigen-decomposition with the negative eigenvalues set to 0.
///
/// `m` itself (same bits) when it is positive definite (its Cholesky factorisation
/// exists) or not finite; otherwise `V·diag(max(λ, 0))·Vᵀ`, exactly symmetric, accurate
/// to O(N·ε·‖m‖) ([`SymmetricEigen`]).
///
/// ```
/// use ppoe::{uncertainty::nearest_psd, Matrix};
/// // Eigenvalues 3 and −1 (eigenvectors (1, 1)/√2 and (1, −1)/√2): −1 becomes 0.
/// let p = nearest_psd(&Matrix([[1.0_f64, 2.0], [2.0, 1.0]]));
/// assert!((p.0[0][0] - 1.5).abs() < 1e-15 && (p.0[0][1] - 1.5).abs() < 1e-15);
/// ```
pub fn nearest_psd<T: Real, const N: usize>(m: &Matrix<T, N, N>) -> Matrix<T, N, N> {
    if m.cholesky().is_some() {
        return *m;
    }
    match SymmetricEigen::new(m) {
        Ok(e) if e.min_value() < T::ZERO => e.clamped().reconstruct(),
        _ => *m,
    }
}

/// `⟨⟨M⟩⟩ = −tr(M)·I + M` (Barfoot & Furgale 2014, eq. 39).
#[inline]
fn dbl<T: Real>(m: &Mat3<T>) -> Mat3<T> {
    *m - Mat3::identity() * m.trace()
}

/// `⟨⟨M, N⟩⟩ = ⟨⟨M⟩⟩⟨⟨N⟩⟩ + ⟨⟨N·M⟩⟩`.
#[inline]
fn dbl2<T: Real>(m: &Mat3<T>, n: &Mat3<T>) -> Mat3<T> {
    dbl(m) * dbl(n) + dbl(&(*n * *m))
}

/// Swaps rotation-first and translation-first block order: `[[A, B], [C, D]] ↦
/// [[D, C], [B, A]]` (its own inverse).
#[inline]
fn swap_order<T: Real>(m: &Mat6<T>) -> Mat6<T> {
    Mat6::from_blocks(
        &m.block(1, 1),
        &m.block(1, 0),
        &m.block(0, 1),
        &m.block(0, 0),
    )
}

/// The fourth-order compounding terms F(Σ₁, Σ₂) of Barfoot & Furgale (2014), where Σ₁ is
/// the second transform's covariance and Σ₂ the first one moved into the output frame.
/// Computed in translation-first order, as in the paper.
pub(crate) fn fourth_order_terms<T: Real>(s1: &Mat6<T>, s2: &Mat6<T>) -> Mat6<T> {
    let a = swap_order(s1);
    let b = swap_order(s2);
    let (a11, a12, a22) = (a.block(0, 0), a.block(0, 1), a.block(1, 1));
    let (b11, b12, b22) = (b.block(0, 0), b.block(0, 1), b.block(1, 1));
    let zero = Mat3::zeros();
    let big_a1 = Mat6::from_blocks(
        &dbl(&a22),
        &dbl(&(a12 + a12.transpose())),
        &zero,
        &dbl(&a22),
    );
    let big_a2 = Mat6::from_blocks(
        &dbl(&b22),
        &dbl(&(b12 + b12.transpose())),
        &zero,
        &dbl(&b22),
    );
    let b11_ = dbl2(&a22, &b11)
        + dbl2(&a12.transpose(), &b12)
        + dbl2(&a12, &b12.transpose())
        + dbl2(&a11, &b22);
    let b12_ = dbl2(&a22, &b12.transpose()) + dbl2(&a12.transpose(), &b22);
    let b22_ = dbl2(&a22, &b22);
    let big_b = Mat6::from_blocks(&b11_, &b12_, &b12_.transpose(), &b22_);
    let a1b = big_a1 * b;
    let a2a = big_a2 * a;
    let sum = a1b + a1b.transpose() + a2a + a2a.transpose();
    swap_order(&(sum * T::lit(1.0 / 12.0) + big_b * T::lit(0.25)))
}

/// Concatenates two uncertain transforms with **right (local)** perturbations:
/// `T_AC·Exp(ξ'_A) = T_BC·Exp(ξ_B)·T_AB·Exp(ξ_A)`; returns `(T_BC·T_AB, Σ'_A)` with
/// `Σ'_A = Ad(T_AB⁻¹)·Σ_B·Ad(T_AB⁻¹)ᵀ + Σ_A` in frame A (second order).
///
/// Corresponds to pytransform3d's `concat_locally_uncertain_transforms(mean_A2B,
/// mean_B2C, cov_A, cov_B)` (same argument order; note it differs from
/// [`concat_globally`]). This is the building block of the PPOE (Meyer et al. 2022).
pub fn concat_locally<T: Real>(
    mean_a2b: &Transform<T>,
    mean_b2c: &Transform<T>,
    cov_a: &Mat6<T>,
    cov_b: &Mat6<T>,
) -> (Transform<T>, Mat6<T>) {
    let moved = mean_a2b.inverse().transport_covariance(cov_b);
    // Symmetrised: cov_a may be symmetric only within tolerance.
    (*mean_b2c * *mean_a2b, (moved + *cov_a).symmetrize())
}

/// Inverts an uncertain transform with **left (global)** perturbation: returns
/// `(T̄⁻¹, Ad(T̄⁻¹)·Σ·Ad(T̄⁻¹)ᵀ)`, the covariance of the left perturbation of the inverse.
///
/// Corresponds to pytransform3d's `invert_uncertain_transform`.
pub fn invert<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> (Transform<T>, Mat6<T>) {
    let inv = mean.inverse();
    (inv, inv.transport_covariance(cov))
}

/// Options of the iterative estimators ([`pose_fusion`], [`frechet_mean`]).
///
/// Both tolerances are **relative to the scale of the data**: a step ξ = (ω, v) is
/// compared with `tolerance · s`, `s = 1 + max ‖pₖ‖` over the input translations pₖ
/// (`s = 1` for rotations). The rounding of the residuals `Log(T·Tₖ⁻¹)` is ≈ ε·s (a
/// product of poses |p| from the origin is known to ε·|p|), so an absolute tolerance of a
/// few ε can never be met 100 m from the origin and the loop would run to its cap.
///
/// The iteration stops at the first step of norm ≤ `step_tolerance · s`, or, once
/// converged, at the first step that is not shorter than the one before: both
/// iterations converge linearly, with steps shrinking by a constant factor, until
/// rounding dominates and the steps stop shrinking. So the result is at the rounding
/// floor of the problem, not one stopping tolerance away from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterationOptions<T> {
    /// Maximum number of iterations.
    pub max_iterations: usize,
    /// The iteration stops once the update step's norm is at most this times the scale.
    pub step_tolerance: T,
    /// The result is reported as converged if the last step's norm is at most this times
    /// the scale.
    pub converged_tolerance: T,
}

impl<T: Real> IterationOptions<T> {
    /// Whether to stop after a step of norm `norm` that followed one of norm `previous`,
    /// for data of scale `scale` (see [`IterationOptions`]).
    fn stop(&self, norm: T, previous: T, scale: T) -> bool {
        norm <= self.step_tolerance * scale
            || (norm <= self.converged_tolerance * scale && norm >= previous)
    }
}

impl<T: Real> Default for IterationOptions<T> {
    /// 20 iterations at most (pytransform3d's fixed count), stop at a step of 4·ε·s or
    /// when converged steps stop shrinking, converged below √ε·s (s: the scale of the
    /// data, see [`IterationOptions`]).
    fn default() -> Self {
        Self {
            max_iterations: 20,
            step_tolerance: T::EPS * T::lit(4.0),
            converged_tolerance: T::TOL,
        }
    }
}

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

/// The scale `1 + max ‖pₖ‖` of a set of poses, to which the tolerances of
/// [`IterationOptions`] are relative.
fn translation_scale<T: Real, G: LieGroup<T, D>, const D: usize>(items: &[G]) -> T {
    T::ONE + items.iter().fold(T::ZERO, |m, g| m.max(g.magnitude()))
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
/// [`IterationOptions`]) and reports convergence. Where pytransform3d converges both reach the same minimum; from the
/// identity it can stall or fail when the mean rotation is near π or the poses are far
/// from the origin, which the start here avoids. The covariance is the inverse
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

/// A checked result that is not finite although its inputs were: an overflow inside.
fn non_finite_is_overflow(e: Error) -> Error {
    if e == Error::NonFinite {
        Error::Overflow
    } else {
        e
    }
}

/// A Lie group for the Fréchet mean: the right difference `Log(self⁻¹·x)` and the
/// right update `self·Exp(d)`, in `D` tangent coordinates.
pub trait LieGroup<T: Real, const D: usize>: Copy {
    /// The right (body-frame) difference `Log(self⁻¹·x)`.
    fn right_difference(&self, x: &Self) -> Vector<T, D>;
    /// The right update `self·Exp(d)`.
    fn right_update(&self, d: &Vector<T, D>) -> Self;
    /// `true` if every element is finite.
    fn is_finite(&self) -> bool;
    /// Checks that `self` is an element of the group within [`Real::TOL`].
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] or [`Error::NotARotation`] (the default only checks
    /// finiteness).
    fn check(&self) -> Result<(), Error> {
        if self.is_finite() {
            Ok(())
        } else {
            Err(Error::NonFinite)
        }
    }
    /// The size of the element's translation (0 for rotations, the default), which sets
    /// the scale of the tolerances of [`IterationOptions`].
    fn magnitude(&self) -> T {
        T::ZERO
    }
}

impl<T: Real> LieGroup<T, 6> for Transform<T> {
    #[inline]
    fn right_difference(&self, x: &Self) -> Vec6<T> {
        se3::log(&(self.inverse() * *x))
    }
    #[inline]
    fn right_update(&self, d: &Vec6<T>) -> Self {
        *self * se3::exp(d)
    }
    #[inline]
    fn is_finite(&self) -> bool {
        self.rotation.is_finite() && self.translation.is_finite()
    }
    fn check(&self) -> Result<(), Error> {
        Transform::check(self)
    }
    fn magnitude(&self) -> T {
        self.translation.norm()
    }
}

impl<T: Real> LieGroup<T, 3> for Mat3<T> {
    #[inline]
    fn right_difference(&self, x: &Self) -> Vec3<T> {
        so3::log(&(self.transpose() * *x))
    }
    #[inline]
    fn right_update(&self, d: &Vec3<T>) -> Self {
        *self * so3::exp(d)
    }
    #[inline]
    fn is_finite(&self) -> bool {
        Matrix::is_finite(self)
    }
    fn check(&self) -> Result<(), Error> {
        if !Matrix::is_finite(self) {
            Err(Error::NonFinite)
        } else if !so3::is_rotation(self, T::TOL) {
            Err(Error::NotARotation)
        } else {
            Ok(())
        }
    }
}

/// The result of [`frechet_mean`] and the Gaussian estimators.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate<G, C> {
    /// The Fréchet mean.
    pub mean: G,
    /// The sample covariance (divisor N − 1) of the right differences `Log(mean⁻¹·Xᵢ)`
    /// at the returned mean (right / local perturbation).
    pub cov: C,
    /// Iterations performed.
    pub iterations: usize,
    /// Whether the last update step was below the convergence tolerance.
    pub converged: bool,
}

/// Fréchet (Karcher) mean of samples on a Lie group by the fixed-point iteration
/// `mean ← mean·Exp(avgᵢ Log(mean⁻¹·Xᵢ))`, starting at the first sample, plus the
/// sample covariance of the right differences.
///
/// Corresponds to pytransform3d's `frechet_mean` as used by its two estimators, with one
/// deliberate difference: pytransform3d takes right differences but applies a *left*
/// update, which converges only for mean rotations below 60° (linearised, an error e of
/// the mean maps to `(I − Rᵀ)·e`, whose spectral radius `2·sin(θ/2)` is below 1 only for
/// θ < π/3). The
/// consistent right update here has the same fixed point (so the results agree
/// wherever pytransform3d converges) and converges at any angle. The tolerances are
/// relative to the scale of the samples (see [`IterationOptions`]).
///
/// # Errors
///
/// [`Error::Empty`] for no samples, [`Error::TooFewSamples`] for one sample (the sample
/// covariance needs two), [`Error::NonFinite`] or [`Error::NotARotation`] for a sample
/// that fails [`LieGroup::check`] (e.g. a reflection or a scaled matrix: not a group
/// element, so no mean exists), [`Error::Overflow`] if finite samples give a non-finite
/// step, mean or covariance.
pub fn frechet_mean<T: Real, G: LieGroup<T, D>, const D: usize>(
    samples: &[G],
    options: &IterationOptions<T>,
) -> Result<Estimate<G, Matrix<T, D, D>>, Error> {
    let first = samples.first().ok_or(Error::Empty)?;
    if samples.len() < 2 {
        return Err(Error::TooFewSamples);
    }
    // Non-finite input first, wherever it is, then group membership.
    if !samples.iter().all(|s| s.is_finite()) {
        return Err(Error::NonFinite);
    }
    for s in samples {
        s.check()?;
    }
    let scale = translation_scale(samples);
    let n = T::from_usize(samples.len());
    let average = |mean: &G| {
        let mut sum = Vector::<T, D>::zeros();
        for s in samples {
            sum += mean.right_difference(s);
        }
        sum.scale(T::ONE / n)
    };
    let mut mean = *first;
    let mut iterations = 0;
    let mut converged = false;
    let mut previous = T::infinity();
    while iterations < options.max_iterations {
        let step = average(&mean);
        if !step.is_finite() {
            return Err(Error::Overflow);
        }
        mean = mean.right_update(&step);
        iterations += 1;
        let norm = step.norm();
        converged = norm <= options.converged_tolerance * scale;
        if options.stop(norm, previous, scale) {
            break;
        }
        previous = norm;
    }
    let avg = average(&mean);
    let mut cov = Matrix::<T, D, D>::zeros();
    for s in samples {
        let d = mean.right_difference(s) - avg;
        cov += d.outer(&d);
    }
    let cov = cov.scale(T::ONE / (n - T::ONE)).symmetrize();
    if !cov.is_finite() {
        // Finite samples so large that their differences overflow.
        return Err(Error::Overflow);
    }
    mean.check().map_err(non_finite_is_overflow)?;
    Ok(Estimate {
        mean,
        cov,
        iterations,
        converged,
    })
}

/// Estimates a Gaussian on SE(3) from sample poses: Fréchet mean and the covariance of
/// the right (local) differences. See [`frechet_mean`] (50 iterations at most).
///
/// Corresponds to pytransform3d's `estimate_gaussian_transform_from_samples`.
///
/// # Errors
///
/// As [`frechet_mean`]: a sample that is not a rigid transform is
/// [`Error::NotARotation`].
pub fn estimate_gaussian_transform<T: Real>(
    samples: &[Transform<T>],
) -> Result<Estimate<Transform<T>, Mat6<T>>, Error> {
    frechet_mean(samples, &estimator_options())
}

/// Estimates a Gaussian on SO(3) from sample rotations: Fréchet mean and the covariance
/// of the right (local) differences. See [`frechet_mean`] (50 iterations at most).
///
/// Corresponds to pytransform3d's `estimate_gaussian_rotation_matrix_from_samples`.
///
/// # Errors
///
/// As [`frechet_mean`]: a sample that is not a rotation matrix (a reflection, a scaled
/// matrix) is [`Error::NotARotation`].
pub fn estimate_gaussian_rotation<T: Real>(
    samples: &[Mat3<T>],
) -> Result<Estimate<Mat3<T>, Mat3<T>>, Error> {
    frechet_mean(samples, &estimator_options())
}

fn estimator_options<T: Real>() -> IterationOptions<T> {
    IterationOptions {
        max_iterations: 50,
        ..IterationOptions::default()
    }
}

/// Checks a covariance: finite, symmetric within `T::TOL`·max(1, ‖Σ‖_max) and positive
/// semi-definite within `T::TOL`·‖Σ‖_max (no eigenvalue below −tol·‖Σ‖_max).
///
/// Method: symmetry element-wise; PSD by a Cholesky factorisation of
/// `Σ/‖Σ‖_max + tol·I`, which exists iff the smallest eigenvalue of Σ exceeds
/// −tol·‖Σ‖_max. The division by ‖Σ‖_max keeps the factorisation's squares finite for
/// any finite Σ (a PSD covariance with elements near the largest finite number passes).
/// Cost: one 6×6 Cholesky.
///
/// # Errors
///
/// [`Error::NonFinite`], [`Error::NotSymmetric`], [`Error::NotPositiveSemidefinite`].
pub fn check_covariance<T: Real, const N: usize>(cov: &Matrix<T, N, N>) -> Result<(), Error> {
    if !cov.is_finite() {
        return Err(Error::NonFinite);
    }
    let scale = cov.amax();
    if cov.asymmetry() > T::TOL * scale.max(T::ONE) {
        return Err(Error::NotSymmetric);
    }
    if scale == T::ZERO {
        return Ok(());
    }
    // Divided rather than multiplied by 1/scale, which overflows for subnormal scales.
    let unit = cov.map(|x| x / scale).symmetrize();
    match (unit + Matrix::identity() * T::TOL).cholesky() {
        Some(_) => Ok(()),
        None => Err(Error::NotPositiveSemidefinite),
    }
}
