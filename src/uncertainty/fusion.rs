//! Fusion of uncertain poses ([`pose_fusion`]): the maximum-likelihood pose given K
//! measurements of one frame with left (global) Gaussian noise. Re-exported by
//! [`crate::uncertainty`].

use super::check_covariance;
use super::estimate::{non_finite_is_overflow, translation_scale, IterationOptions};
use crate::error::Error;
use crate::linalg::{Mat6, SymmetricEigen, Vec6};
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
    /// Iterations of the run that produced `mean` (of up to K + 1, see [`pose_fusion`]).
    pub iterations: usize,
    /// Whether `mean` is a stationary point of the cost (the run it comes from ended
    /// with a step ≤ `converged_tolerance`·s; see [`pose_fusion`]).
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

/// Fuses K uncertain poses of the same frame (left / global perturbations): the pose
/// minimising `V(T) = ½ Σₖ Log(T·Tₖ⁻¹)ᵀ Σₖ⁻¹ Log(T·Tₖ⁻¹)` (Barfoot & Furgale 2014,
/// §IV.B), by damped Newton iterations with updates `T ← Exp(δ)·T`.
///
/// Corresponds to pytransform3d's `pose_fusion(means, covs)`, which runs exactly 20
/// Gauss-Newton iterations from the identity. Both seek a stationary point of V (zero
/// gradient `Σₖ J⁻¹(xₖ)ᵀ Σₖ⁻¹ xₖ`, J⁻¹ the inverse left Jacobian of SE(3)), so where
/// pytransform3d converges this function returns the same point or one of lower cost.
/// The covariance is the inverse of pytransform3d's information matrix
/// `Σₖ J⁻¹(xₖ)ᵀ Σₖ⁻¹ J⁻¹(xₖ)` at the returned mean (pytransform3d evaluates it one
/// update earlier; at convergence they agree).
///
/// Method. V is smooth except across the cut locus of each `Tₖ` (a residual rotation
/// of π, where the principal logarithm jumps), and when the poses disagree by tens of
/// degrees it has several local minima. A first run starts at the input pose of lowest
/// cost. If it converges with every residual rotation below π/2 its result is returned
/// (a heuristic that saves K runs where the poses agree; the reference problems below
/// check its results). Otherwise the iteration also runs from the identity (as
/// pytransform3d) and every other input pose, and the converged run of lowest cost is
/// returned (if none converged, the run of lowest cost, with `converged == false`).
/// Each run takes Gauss-Newton steps until one fails to shrink the step at least
/// fourfold, then Newton steps (exact Hessian: quadratic convergence, where
/// Gauss-Newton's approximate one converges linearly, at a rate near 1 for widely
/// spread poses) while the Hessian is positive definite; elsewhere the better of the
/// Gauss-Newton and the saddle-free Newton step (`|H|⁻¹·g`). Every step is halved
/// until the cost does not grow.
///
/// Stopping rule and `converged`. With s = 1 + max‖pₖ‖ (the scale of the input
/// translations, see [`IterationOptions`]), a run stops after a step of norm ≤
/// `step_tolerance·s`, or after a step of norm ≤ `converged_tolerance·s` that is not
/// shorter than the step before (the rounding floor of the problem), or when no
/// halving of the step lowers the cost, or after `max_iterations` steps. It has
/// converged if its last step was ≤ `converged_tolerance·s` (√ε·s by default): the
/// mean is then a stationary point of V to the rounding of the problem (after such a
/// Newton step the error is O(step²)), unless a residual rotation is within √ε of π
/// (there rounding decides the logarithm's branch). A run pressed against a cut locus,
/// where V has no stationary point, does not converge: its steps keep pointing across
/// the jump.
///
/// `converged == false` means no start reached a stationary point within
/// `max_iterations`; the mean is then the lowest-cost point found and **not** a
/// fused estimate. (On such inputs pytransform3d's iteration cycles, with steps of 0.1
/// to 1.5 even after 300 iterations; measured by the repository's fusion golden tests.)
///
/// Cost: one run, or K + 1 (see Method); each iteration evaluates the K residuals, their
/// Jacobians and the gradient once (Gauss-Newton) or 13 times (Newton: 12 for the
/// Hessian), plus once per halving of the step.
///
/// # Accuracy
///
/// A converged mean is a local minimum of V to the rounding of the problem. On
/// pytransform3d's 200 reference problems (the repository's fusion golden tests; 48 with poses up
/// to 150° apart; a third of all with covariances of condition 10³–10⁶), measured against
/// pytransform3d's fixed point wherever it has one (198 problems), error
/// `max|a − b| / max(1, max|b|)`: f64 mean 4.3e-13, covariance 3.8e-15, V 4.4e-13; f32
/// mean 2.2e-6 with well-conditioned covariances, and within 5.5× of the distance by
/// which rounding the inputs to f32 moves f64's answer with ill-conditioned ones.
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
    let problem = Problem {
        means,
        infos: &infos,
        scale: translation_scale(means),
    };
    let first = problem.lowest_cost();
    let mut best = problem.descend(&first, options);
    let half_pi = T::lit(core::f64::consts::FRAC_PI_2);
    let settled =
        matches!(&best, Ok(r) if r.converged && !problem.residual_above(&r.mean, half_pi));
    if !settled {
        for start in core::iter::once(Transform::identity()).chain(means.iter().copied()) {
            if start == first {
                continue;
            }
            let run = problem.descend(&start, options);
            // A start that fails (overflow) does not spoil the others.
            best = match (best, run) {
                (Ok(b), Ok(r)) if !r.better_than(&b) => Ok(b),
                (Ok(b), Err(_)) => Ok(b),
                (_, run) => run,
            };
        }
    }
    let run = best?;
    let (info, _, cost) = run.terms;
    let cov = info.inverse_spd().ok_or(Error::Singular)?;
    if !cov.is_finite() || !cost.is_finite() {
        return Err(Error::Overflow);
    }
    run.mean.check().map_err(non_finite_is_overflow)?;
    Ok(Fusion {
        mean: run.mean,
        cov,
        cost,
        iterations: run.iterations,
        converged: run.converged,
    })
}

/// Information matrix, gradient and cost at a pose.
type Terms<T> = (Mat6<T>, Vec6<T>, T);

/// The data of one fusion problem.
struct Problem<'a, T> {
    means: &'a [Transform<T>],
    infos: &'a [Mat6<T>],
    /// `1 + max ‖pₖ‖`, the scale of the stopping tests.
    scale: T,
}

/// The outcome of one run of the iteration.
struct Run<T> {
    mean: Transform<T>,
    terms: Terms<T>,
    iterations: usize,
    converged: bool,
}

impl<T: Real> Run<T> {
    /// Converged beats not converged, then the lower cost wins.
    fn better_than(&self, other: &Self) -> bool {
        match (self.converged, other.converged) {
            (true, false) => true,
            (false, true) => false,
            _ => self.terms.2 < other.terms.2,
        }
    }
}

impl<T: Real> Problem<'_, T> {
    fn terms(&self, mean: &Transform<T>) -> Terms<T> {
        fusion_terms(mean, self.means, self.infos)
    }

    /// One run of damped Newton iterations from `start` (see [`pose_fusion`]).
    fn descend(
        &self,
        start: &Transform<T>,
        options: &IterationOptions<T>,
    ) -> Result<Run<T>, Error> {
        let mut run = Run {
            mean: *start,
            terms: self.terms(start),
            iterations: 0,
            converged: false,
        };
        let mut previous = T::infinity();
        // Gauss-Newton until it contracts slowly, then Newton (see `steps`).
        let mut newton = false;
        while run.iterations < options.max_iterations {
            let (first, second) = self.steps(&run.mean, &run.terms, newton)?;
            run.iterations += 1;
            let mut next: Option<(T, Transform<T>, Terms<T>)> = None;
            for step in core::iter::once(first).chain(second) {
                if !step.is_finite() {
                    return Err(Error::Overflow);
                }
                if let Some((mean, terms)) = self.backtrack(&run.mean, &step, &run.terms) {
                    if next.as_ref().is_none_or(|n| terms.2 < n.2 .2) {
                        next = Some((step.norm(), mean, terms));
                    }
                }
            }
            // No descent along any step: pressed against a cut locus.
            let Some((norm, mean, terms)) = next else {
                run.converged = false;
                break;
            };
            (run.mean, run.terms) = (mean, terms);
            run.converged = norm <= options.converged_tolerance * self.scale;
            if options.stop(norm, previous, self.scale) {
                break;
            }
            newton |= norm > previous * T::lit(0.25);
            previous = norm;
        }
        // Within √ε of a cut locus, rounding decides which branch of the logarithm, and
        // so which side of V's jump, a residual is on: no stationary point to trust.
        if run.converged && self.on_cut_locus(&run.mean) {
            run.converged = false;
        }
        Ok(run)
    }

    /// Whether a residual `Log(mean·Tₖ⁻¹)` has a rotation angle within √ε of π.
    fn on_cut_locus(&self, mean: &Transform<T>) -> bool {
        self.residual_above(mean, T::lit(core::f64::consts::PI) - T::TOL)
    }

    /// Whether a residual `Log(mean·Tₖ⁻¹)` has a rotation angle above `limit`.
    fn residual_above(&self, mean: &Transform<T>, limit: T) -> bool {
        self.means
            .iter()
            .any(|tk| se3::log(&(*mean * tk.inverse())).rotation().norm() > limit)
    }

    /// The input pose of lowest cost (the first of them on ties). Iterator-based, so no
    /// index can panic (the firmware's panic-never check links this).
    fn lowest_cost(&self) -> Transform<T> {
        let mut best: Option<(Transform<T>, T)> = None;
        for m in self.means {
            let cost = self.terms(m).2;
            if best.is_none_or(|b| cost < b.1) {
                best = Some((*m, cost));
            }
        }
        best.map_or(Transform::identity(), |b| b.0)
    }

    /// The update steps `−H⁻¹·g` at `mean` for the gradient `g`. Without `newton`,
    /// Gauss-Newton's (`H` the information matrix), which costs one evaluation of the
    /// terms where the Hessian costs 12 and suffices while the residuals are small. With
    /// `newton`: Newton's, with `H` the Hessian of V in the left exponential coordinates
    /// at `mean`, where that is positive definite; else Gauss-Newton's and, as an
    /// alternative, the saddle-free Newton step (`H`'s eigenvalues replaced by their
    /// absolute values, floored at √ε of the information matrix's largest element).
    ///
    /// Why Newton: Gauss-Newton drops the residual-curvature term `Σₖ (Σₖ⁻¹xₖ)ᵀ·∂²xₖ`
    /// of the Hessian, which is small only when the residuals xₖ are. Poses that
    /// disagree by tens of degrees make it large, and Gauss-Newton then converges
    /// linearly at a rate near 1 (or not at all). The Hessian is the central difference
    /// of the analytic gradient, symmetrised (the antisymmetric part is the Lie bracket
    /// term `½·gᵀ[eᵢ, eⱼ]`, which vanishes at a stationary point): steps of ε^⅓ rad and
    /// ε^⅓·s (the gradient is quadratic along translations), so its relative error is
    /// ≈ ε^⅔, which changes the rate of convergence, never the fixed point `g = 0`.
    fn steps(
        &self,
        mean: &Transform<T>,
        terms: &Terms<T>,
        newton: bool,
    ) -> Result<(Vec6<T>, Option<Vec6<T>>), Error> {
        let (info, gradient, _) = terms;
        let gauss_newton = -info.solve_spd(gradient).ok_or(Error::Singular)?;
        if !newton {
            return Ok((gauss_newton, None));
        }
        let h = T::EPS.cbrt();
        let mut hessian = Mat6::zeros();
        for j in 0..6 {
            let mut d = Vec6::zeros();
            d.0[j] = if j < 3 { h } else { h * self.scale };
            let plus = self.terms(&(se3::exp(&d) * *mean)).1;
            let minus = self.terms(&(se3::exp(&-d) * *mean)).1;
            let column = (plus - minus).scale(T::HALF / d.0[j]);
            for (row, c) in hessian.0.iter_mut().zip(column.0) {
                row[j] = c;
            }
        }
        let hessian = hessian.symmetrize();
        if let Some(step) = hessian.solve_spd(gradient).filter(|s| s.is_finite()) {
            return Ok((-step, None));
        }
        let floor = info.amax() * T::TOL;
        let saddle_free = SymmetricEigen::new(&hessian)
            .ok()
            .and_then(|e| e.map_values(|l| l.abs().max(floor)).solve_spd(gradient))
            .map(|s| -s);
        Ok((gauss_newton, saddle_free))
    }

    /// One damped update `Exp(α·step)·mean`, α halved until the cost does not grow
    /// (beyond the rounding of the cost), or `None` if no α down to 2⁻⁴⁰ qualifies (the
    /// step points across a cut locus, where V jumps up). Near a minimum the full step
    /// is taken, so the fixed point is the undamped one. Returns the new mean and its
    /// terms.
    fn backtrack(
        &self,
        mean: &Transform<T>,
        step: &Vec6<T>,
        terms: &Terms<T>,
    ) -> Option<(Transform<T>, Terms<T>)> {
        let cost = terms.2;
        // Steps whose predicted decrease ½·gᵀH⁻¹g is below √ε of the cost are in the
        // rounding regime of the cost itself: an increase of that size is noise. A
        // jump across a cut locus is far larger.
        let predicted = -T::HALF * terms.1.dot(step);
        let slack = if predicted <= cost * T::TOL {
            cost * T::TOL
        } else {
            cost * T::EPS * T::lit(16.0)
        };
        let mut alpha = T::ONE;
        for _ in 0..40 {
            let candidate = se3::exp(&step.scale(alpha)) * *mean;
            let new = self.terms(&candidate);
            if new.2 <= cost + slack {
                return Some((candidate, new));
            }
            alpha *= T::HALF;
        }
        None
    }
}
