//! The iterative estimators of the uncertainty module: Fréchet means with sample
//! covariances ([`frechet_mean`], [`estimate_gaussian_transform`],
//! [`estimate_gaussian_rotation`]) and the options they share with
//! [`pose_fusion`](super::pose_fusion). Re-exported by [`crate::uncertainty`], whose
//! perturbation conventions they follow.

use crate::error::Error;
use crate::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::se3::{self, Transform};
use crate::so3;

/// Options of the iterative estimators ([`pose_fusion`](super::pose_fusion), [`frechet_mean`]).
///
/// Both tolerances are **relative to the scale of the data**: a step ξ = (ω, v) is
/// compared with `tolerance · s`, `s = 1 + max ‖pₖ‖` over the input translations pₖ
/// (`s = 1` for rotations). The rounding of the residuals `Log(T·Tₖ⁻¹)` is ≈ ε·s (a
/// product of poses |p| from the origin is known to ε·|p|), so an absolute tolerance of a
/// few ε can never be met 100 m from the origin and the loop would run to its cap.
///
/// The iteration stops at the first step of norm ≤ `step_tolerance · s`, or, once
/// converged, at the first step that is not shorter than the one before: the steps
/// shrink (linearly for the Fréchet mean, quadratically for the fusion's Newton steps)
/// until rounding dominates and they stop shrinking. So the result is at the rounding
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
    pub(super) fn stop(&self, norm: T, previous: T, scale: T) -> bool {
        norm <= self.step_tolerance * scale
            || (norm <= self.converged_tolerance * scale && norm >= previous)
    }
}

impl<T: Real> Default for IterationOptions<T> {
    /// 50 iterations at most (per start of [`pose_fusion`](super::pose_fusion)), stop
    /// at a step of 4·ε·s or when converged steps stop shrinking, converged below √ε·s
    /// (s: the scale of the data, see [`IterationOptions`]). 50 leaves a margin: on
    /// pytransform3d's 200 fusion reference problems the longest run that reaches a
    /// stationary point takes 24 iterations (f64; 22 in f32,
    /// the repository's fusion golden tests), and the Fréchet estimators used 50 already.
    fn default() -> Self {
        Self {
            max_iterations: 50,
            step_tolerance: T::EPS * T::lit(4.0),
            converged_tolerance: T::TOL,
        }
    }
}

/// The scale `1 + max ‖pₖ‖` of a set of poses, to which the tolerances of
/// [`IterationOptions`] are relative.
pub(super) fn translation_scale<T: Real, G: LieGroup<T, D>, const D: usize>(items: &[G]) -> T {
    T::ONE + items.iter().fold(T::ZERO, |m, g| m.max(g.magnitude()))
}

/// A checked result that is not finite although its inputs were: an overflow inside.
pub(super) fn non_finite_is_overflow(e: Error) -> Error {
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
///
/// # Example
///
/// ```
/// use ppoe::uncertainty::{frechet_mean, IterationOptions};
/// use ppoe::{so3, Vec3};
/// // Rotations about one axis commute: the mean angle is the average angle.
/// let samples = [0.1_f64, 0.2, 0.6].map(|a| so3::exp(&Vec3::new(0.0, 0.0, a)));
/// let est = frechet_mean(&samples, &IterationOptions::default())?;
/// approx::assert_abs_diff_eq!(so3::log(&est.mean), Vec3::new(0.0, 0.0, 0.3), epsilon = 1e-15);
/// // Sample variance (divisor N − 1) of the differences −0.2, −0.1, 0.3: 0.07.
/// assert!((est.cov.0[2][2] - 0.07).abs() < 1e-15);
/// # Ok::<(), ppoe::Error>(())
/// ```
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
///
/// # Example
///
/// ```
/// use ppoe::{uncertainty::estimate_gaussian_transform, Transform};
/// let at = |x: f64, y: f64| {
///     Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [x, y, 0.])
/// };
/// let est = estimate_gaussian_transform(&[at(1., 0.), at(-1., 0.), at(0., 2.), at(0., -2.)])?;
/// // Pure translations: the mean and sample covariance (divisor N − 1) of the positions.
/// approx::assert_abs_diff_eq!(est.mean, Transform::identity(), epsilon = 1e-15);
/// assert!((est.cov.0[3][3] - 2.0 / 3.0).abs() < 1e-15);
/// assert!((est.cov.0[4][4] - 8.0 / 3.0).abs() < 1e-14);
/// # Ok::<(), ppoe::Error>(())
/// ```
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
