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
//!
//! ```
//! use ppoe::uncertainty::{left_to_right, right_to_left};
//! use ppoe::{se3, Mat6, Vector};
//! let mean = se3::exp(&Vector([0.2, -0.1, 0.4, 1.0, 0.5, -0.3]));
//! let right = Mat6::from_diagonal(&Vector([1e-4, 2e-4, 3e-4, 1e-6, 2e-6, 3e-6]));
//! // The same uncertainty, seen from the other side of the mean, and back.
//! let back = left_to_right(&mean, &right_to_left(&mean, &right));
//! approx::assert_relative_eq!(back, right, epsilon = 1e-18, max_relative = 1e-12);
//! ```

use crate::error::Error;
use crate::linalg::{Mat3, Mat6, Matrix, SymmetricEigen};
use crate::scalar::Real;
use crate::se3::Transform;

mod checked;
mod estimate;
mod fusion;
pub use checked::{concat_globally_checked, concat_locally_checked, invert_checked};
pub use estimate::{
    estimate_gaussian_rotation, estimate_gaussian_transform, frechet_mean, Estimate,
    IterationOptions, LieGroup,
};
pub use fusion::{pose_fusion, Fusion};

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
/// [`Order::Fourth`] (see there). Unchecked: [`concat_globally_checked`] validates the
/// inputs and the result.
///
/// ```
/// use ppoe::uncertainty::{concat_globally, Order};
/// use ppoe::{Mat6, Transform, Vector};
/// // A rotation noise about x (0.01 rad², frame B), then a certain shift by 1 along z.
/// let cov_a2b = Mat6::from_diagonal(&Vector([0.01, 0.0, 0.0, 0.0, 0.0, 0.0]));
/// let b2c = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0., 0., 1.]);
/// let (a2c, cov) =
///     concat_globally(&Transform::identity(), &cov_a2b, &b2c, &Mat6::zeros(), Order::Second);
/// assert_eq!(a2c, b2c);
/// // In frame C the rotation about B's origin also moves C's origin: ξ = (ω, p × ω),
/// // p × (ω, 0, 0) = (0, ω, 0), so y and rotation about x are fully correlated.
/// assert_eq!((cov.0[0][0], cov.0[4][4], cov.0[0][4]), (0.01, 0.01, 0.01));
/// ```
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
/// Unchecked: [`concat_locally_checked`] validates the inputs and the result.
///
/// ```
/// use ppoe::uncertainty::concat_locally;
/// use ppoe::{Mat6, Transform, Vector};
/// // Frame B is 1 m along x from frame A; a yaw noise (0.01 rad²) in frame B, none in A.
/// let a2b = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]);
/// let cov_b = Mat6::from_diagonal(&Vector([0.0, 0.0, 0.01, 0.0, 0.0, 0.0]));
/// let (_, cov) = concat_locally(&a2b, &Transform::identity(), &Mat6::zeros(), &cov_b);
/// // Seen from A's origin, 1 m from B's, the yaw moves the origin along y.
/// assert_eq!((cov.0[2][2], cov.0[4][4], cov.0[2][4]), (0.01, 0.01, 0.01));
/// ```
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
/// Corresponds to pytransform3d's `invert_uncertain_transform`. Unchecked:
/// [`invert_checked`] validates the inputs and the result.
///
/// ```
/// use ppoe::uncertainty::invert;
/// use ppoe::{se3, Mat6, Vector};
/// let mean = se3::exp(&Vector([0.3, 0.1, -0.2, 0.5, 1.0, 2.0]));
/// let cov = Mat6::from_diagonal(&Vector([1e-4, 1e-4, 4e-4, 1e-6, 1e-6, 1e-6]));
/// let (inv, inv_cov) = invert(&mean, &cov);
/// assert_eq!(inv, mean.inverse());
/// let (back, back_cov) = invert(&inv, &inv_cov); // inverting twice is the identity
/// approx::assert_abs_diff_eq!(back, mean, epsilon = 1e-15);
/// approx::assert_relative_eq!(back_cov, cov, epsilon = 1e-18, max_relative = 1e-12);
/// ```
pub fn invert<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> (Transform<T>, Mat6<T>) {
    let inv = mean.inverse();
    (inv, inv.transport_covariance(cov))
}

/// Checks a covariance: finite, symmetric within `T::TOL`·‖Σ‖_max and positive
/// semi-definite within `T::TOL`·‖Σ‖_max (no eigenvalue below −tol·‖Σ‖_max), where
/// ‖Σ‖_max is the largest |element| and `T::TOL` = √ε (1.5·10⁻⁸ in f64, 3.5·10⁻⁴ in f32).
///
/// Both tolerances are relative to the matrix's own scale, so the check means the same
/// for a covariance of 10⁻⁸ rad² as for one of 10⁴ mm²: symmetric means
/// `max|Σᵢⱼ − Σⱼᵢ| ≤ tol·‖Σ‖_max`, which rounding (a few ε·‖Σ‖_max) always meets and a
/// matrix that is antisymmetric by a fraction of its own scale never does. This is the
/// one covariance check of the workspace: the checked PPOE (also the C API's), fusion,
/// the `serde` input, and the host tools' noise files, measurement covariances and
/// `eval` inputs all call it.
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
    if cov.asymmetry() > T::TOL * scale {
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
