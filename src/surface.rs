//! Equiprobable surfaces of uncertain poses: where the tool may be, for people to see.
//!
//! * [`to_ellipsoid`]: pytransform3d's `to_ellipsoid` (a 3D covariance as a rotated
//!   ellipsoid).
//! * [`to_projected_ellipsoid`]: pytransform3d's `to_projected_ellipsoid`, kept for
//!   comparison with the reference.
//! * The surfaces for people: [`lift_surface`] (the default, [`Surface::Lift`]),
//!   [`marginal_surface`], the position covariance [`position_covariance`], the
//!   second-order position mean [`position_mean_second_order`], and the χ²₃ helpers
//!   [`chi2_3_radius`] / [`chi2_3_probability`] that turn a probability into the radius k.
//!
//! # Conventions
//!
//! Covariances are 6×6, **rotation first** (ξ = (ω, v)). The surfaces for people take
//! the covariance of the **right (local) perturbation** `T = T̄·Exp(η)`, η ~ N(0, Σ), in
//! the tool frame: what [`crate::uncertainty::concat_locally`] and the PPOE compute. A
//! left (global) covariance converts with [`crate::uncertainty::left_to_right`].
//!
//! All grids use pytransform3d's unit-sphere grid (see [`unit_sphere_point`]): for
//! `n = n_steps`, `φᵢ = π·i/(n−1)`, `θⱼ = 2π·j/(n−1)`, `i, j = 0..n`, both endpoints
//! included, written **row-major** (`i` outer, `j` inner) into a caller-provided buffer
//! of at least `n²` points. Rows `i = 0` and `i = n−1` are the poles (n identical points
//! each), column `j = n−1` repeats column 0: the grid is a closed quad mesh whose faces are
//! `(i, j), (i+1, j), (i+1, j+1), (i, j+1)`. A `[[Vec3<T>; N]; N]` array can be filled
//! through `array.as_flattened_mut()`.
//!
//! # Which surface to draw
//!
//! The reference's `to_projected_ellipsoid` keeps the three largest eigenvalues of the
//! 6×6 covariance whatever their units (rad² or m²) and maps them with a transpose, so on
//! real robots its axes are mostly rotational and it encloses far fewer sampled tool
//! positions than a 3D Gaussian's 0.20 / 0.74 / 0.97 at k = 1 / 2 / 3 (and its shape
//! changes with the length unit). The linear marginal ellipsoid of the tool position
//! ([`marginal_surface`]) is right at small noise but under-covers at the seed robot's
//! noise, because the sampled cloud bends (rotational noise moves the tool on arcs). The
//! **lift** surface ([`lift_surface`]) maps each point of the marginal ellipsoid back to
//! its most likely full perturbation and through the exact exponential, so it bends like
//! the cloud, at one exp per grid point, and is identical to the marginal ellipsoid at
//! first order. It is therefore the default ([`Surface::default`]): the repository's coverage test
//! samples the PPOE's model (10⁵ samples) and checks that the fraction of tool positions
//! inside the triangulated lift surface is within 0.03 of `chi2_3_probability(k)` for
//! k = 1, 2, 3 on the seed robot and another test chain. Its limit: it under-covers
//! somewhat at large noise. Use [`chi2_3_radius`] to get k for a probability:
//! pytransform3d's default factor 1.96 covers only 72 % in 3D, 95 % needs k = 2.796.
//!
//! ```
//! use ppoe::surface::{chi2_3_probability, position_covariance};
//! use ppoe::{se3, Mat6, Vector};
//! // Right covariance of a pose turned 90° about z: the tool's x variance is the base's y.
//! let mean = se3::exp(&Vector([0.0, 0.0, core::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.0]));
//! let cov = Mat6::from_diagonal(&Vector([1e-4, 1e-4, 1e-4, 4e-6, 1e-6, 1e-6]));
//! assert!((position_covariance(&mean, &cov).0[1][1] - 4e-6).abs() < 1e-20);
//! // One standard deviation holds only 20 % of a 3D Gaussian: erf(1/√2) − √(2/π)·e^(−½).
//! assert!((chi2_3_probability(1.0_f64) - 0.198748).abs() < 1e-6);
//! ```

use crate::error::Error;
use crate::linalg::{symmetric_part, Mat3, Mat6, Matrix, SymmetricEigen, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::se3::{self, Transform};

/// Checks the grid arguments and returns the number of points, `n_steps²`.
///
/// # Errors
///
/// [`Error::GridSize`] for `n_steps < 2` (the grid needs both poles),
/// [`Error::BufferTooSmall`] if `len < n_steps²` (or `n_steps²` overflows `usize`).
#[inline]
fn grid_len(n_steps: usize, len: usize) -> Result<usize, Error> {
    if n_steps < 2 {
        return Err(Error::GridSize);
    }
    match n_steps.checked_mul(n_steps) {
        Some(n) if n <= len => Ok(n),
        _ => Err(Error::BufferTooSmall),
    }
}

/// The point `(i, j)` of pytransform3d's unit-sphere grid with `n_steps` steps:
/// `(sin φ·cos θ, sin φ·sin θ, cos φ)` with `φ = i·π/(n−1)`, `θ = j·2π/(n−1)` (numpy's
/// `mgrid[0:π:n·1j, 0:2π:n·1j]`, evaluated as `index·step` like numpy, so the points
/// agree with pytransform3d's `unit_sphere_surface_grid` to an ulp).
///
/// Indices beyond `n_steps − 1` continue the same progression; `n_steps < 2` gives the
/// north pole `(0, 0, 1)`.
#[inline]
pub fn unit_sphere_point<T: Real>(n_steps: usize, i: usize, j: usize) -> Vec3<T> {
    if n_steps < 2 {
        return Vec3::new(T::ZERO, T::ZERO, T::ONE);
    }
    let den = T::from_usize(n_steps - 1);
    let phi = T::from_usize(i) * (T::PI() / den);
    let theta = T::from_usize(j) * ((T::PI() + T::PI()) / den);
    let (sp, cp) = phi.sin_cos_r();
    let (st, ct) = theta.sin_cos_r();
    Vec3::new(sp * ct, sp * st, cp)
}

/// `Ok(n)` if the first `n` points of `out` are finite, else [`Error::Overflow`]: the
/// grids are computed from finite inputs, so a point that is not finite is an overflow
/// inside (a huge covariance or factor, a pose far from the origin), never a point to draw.
#[allow(clippy::eq_op)] // x − x on purpose: 0, or NaN for a non-finite x
fn finite_points<T: Real>(n: usize, out: &[Vec3<T>]) -> Result<usize, Error> {
    // x − x is 0 for finite x and NaN for ±∞ and NaN, so the sum is 0 exactly when every
    // coordinate is finite: one pass with no branch per point (a test per coordinate
    // costs about twice the instructions).
    let points = out.get(..n).ok_or(Error::Overflow)?;
    let mut sum = [T::ZERO; 3];
    for p in points {
        for (s, x) in sum.iter_mut().zip(p.0) {
            *s += x - x;
        }
    }
    if sum.iter().all(|s| *s == T::ZERO) {
        Ok(n)
    } else {
        Err(Error::Overflow)
    }
}

/// Fills `out` with `f(unit_sphere_point(n_steps, i, j))`, row-major: `out[i·n + j]` for
/// `i, j < n_steps`, and nothing else. The callers have checked `n_steps ≥ 2` and
/// `out.len() ≥ n_steps²` ([`grid_len`]); otherwise the first `min(out.len(), n_steps²)`
/// points are written, in the same order (never a panic).
///
/// Method: the row's sin/cos φ is computed once per row and the column's sin/cos θ once
/// per column (2n trigonometric calls instead of n² + n), with the same expressions as
/// [`unit_sphere_point`], so the points are bit-identical to it. The column values are
/// kept, without allocation, in the slots of the last row (as `(cos θ, sin θ, 0)`), which
/// is filled last: each of its slots is read just before it is overwritten. `f` has a
/// single call site, so that it inlines into the loop.
#[inline]
fn fill_grid<T: Real>(n_steps: usize, out: &mut [Vec3<T>], mut f: impl FnMut(&Vec3<T>) -> Vec3<T>) {
    let den = T::from_usize(n_steps.max(2) - 1);
    let phi = |i: usize| (T::from_usize(i) * (T::PI() / den)).sin_cos_r();
    let theta = |j: usize| (T::from_usize(j) * ((T::PI() + T::PI()) / den)).sin_cos_r();
    let total = n_steps.checked_mul(n_steps);
    let count = total.map_or(out.len(), |t| t.min(out.len()));
    // The column cache needs the whole grid (always the case from the public functions).
    let cache = match total {
        Some(t) if n_steps >= 2 && t <= out.len() => Some(t - n_steps),
        _ => None,
    };
    if let Some(base) = cache {
        for (j, slot) in out[base..base + n_steps].iter_mut().enumerate() {
            let (st, ct) = theta(j);
            *slot = Vec3::new(ct, st, T::ZERO);
        }
    }
    let mut k = 0;
    for i in 0..n_steps {
        let (sp, cp) = phi(i);
        for j in 0..n_steps {
            if k >= count {
                return;
            }
            let (ct, st) = match cache {
                Some(base) => (out[base + j].0[0], out[base + j].0[1]),
                None => {
                    let (st, ct) = theta(j);
                    (ct, st)
                }
            };
            out[k] = f(&Vec3::new(sp * ct, sp * st, cp));
            k += 1;
        }
    }
}

/// The ellipsoid of a 3D Gaussian: a transform whose rotation columns are the principal
/// axes and whose translation is the mean, and the radii (standard deviations) along
/// those axes, **ascending**.
///
/// Corresponds to pytransform3d's `to_ellipsoid(mean, cov)`, whose order
/// and sign rule are kept so that results compare: radii ascending, rotation columns the
/// eigenvectors of the same order, all three columns negated if their determinant is
/// negative (so `det R = +1`). The surface at k standard deviations is
/// `{ mean + R·diag(k·radii)·u : ‖u‖ = 1 }`, and `R·diag(radii²)·Rᵀ = cov`.
///
/// Difference: pytransform3d takes `sqrt(|λ|)`; here negative eigenvalues (rounding
/// noise of a positive semi-definite covariance, or an invalid input) are clamped to 0,
/// so a rank-deficient covariance gets radius 0 instead of a rounding-noise radius of
/// ≈ 10⁻⁸·√‖Σ‖. Use [`SymmetricEigen::is_psd`] to reject invalid inputs. The
/// eigenvectors are ours ([`SymmetricEigen`]), so R may differ from pytransform3d's in
/// the sign of column pairs and, for repeated radii, in the basis of the repeated axes.
///
/// Method: [`SymmetricEigen`] of the symmetric part of `cov`.
///
/// # Accuracy
///
/// `R·diag(radii²)·Rᵀ` reproduces `cov` to `O(ε·‖cov‖)` (observed on the golden files,
/// relative to `max(1, max|cov|)`: 1.9·10⁻¹⁵ in f64, 7·10⁻⁷ in f32).
///
/// # Example
///
/// ```
/// use ppoe::{surface::to_ellipsoid, Mat3, Vec3};
/// let cov = Mat3::from_rows([[4.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 9.0]]);
/// let (frame, radii) = to_ellipsoid(&Vec3::new(1.0, 2.0, 3.0), &cov)?;
/// approx::assert_abs_diff_eq!(radii, Vec3::new(1.0, 2.0, 3.0), epsilon = 1e-15); // σ, ascending
/// let (r, r2) = (frame.rotation, Mat3::from_diagonal(&radii.map(|x| x * x)));
/// approx::assert_abs_diff_eq!(r * r2 * r.transpose(), cov, epsilon = 1e-14); // R·diag(r²)·Rᵀ
/// # Ok::<(), ppoe::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::NonFinite`] if an input contains NaN or ±∞.
pub fn to_ellipsoid<T: Real>(
    mean: &Vec3<T>,
    cov: &Mat3<T>,
) -> Result<(Transform<T>, Vec3<T>), Error> {
    if !mean.is_finite() {
        return Err(Error::NonFinite);
    }
    let eig = SymmetricEigen::new(cov)?;
    let mut rotation = Mat3::zeros();
    let mut radii = Vec3::zeros();
    for k in 0..3 {
        let src = 2 - k;
        radii.0[k] = eig.values.0[src].max(T::ZERO).sqrt();
        for (row, vrow) in rotation.0.iter_mut().zip(eig.vectors.0.iter()) {
            row[k] = vrow[src];
        }
    }
    if rotation.determinant() < T::ZERO {
        rotation = -rotation;
    }
    Ok((
        Transform {
            rotation,
            translation: *mean,
        },
        radii,
    ))
}

/// pytransform3d's projected ellipsoid of an uncertain pose: the grid of points
/// `y = R̄·(R(E)ᵀ·p(E)) + t̄`, `E = Exp(V₃·diag(factor·√λ₃)·u)`, over the unit-sphere grid
/// `u` (see the [module docs](self)), where λ₃, V₃ are the three **largest** eigenvalues of
/// `cov` (descending) and their eigenvectors. Writes `n_steps²` points row-major into
/// `out` and returns their number.
///
/// Corresponds to pytransform3d's `to_projected_ellipsoid(mean, cov, factor, n_steps)`
/// which returns the same points as three `n × n` arrays x, y, z:
/// `out[i·n + j] = (x[i][j], y[i][j], z[i][j])`. Its conventions are kept, quirks
/// included: the three largest eigenvalues are used whatever their units (rad² or m²),
/// and the transpose `R(E)ᵀ·p(E)` makes the surface the right-perturbation projection of
/// `D·Σ·D`, `D = diag(−1, −1, −1, 1, 1, 1)` (neither the left nor the right
/// perturbation's surface). It is **not** an equiprobable
/// surface of the tool position: see the [module docs](self) and use [`lift_surface`].
///
/// Differences: negative eigenvalues are clamped to 0 (the reference takes `sqrt` of
/// rounding-noise negatives and returns an all-NaN grid for covariances of rank < 3;
/// ours never does); `p(E)` is [`se3::exp_translation`] (the translation of [`se3::exp`]),
/// accurate for tiny rotations (the reference's batch exp divides by ‖ω‖ and loses
/// `ε·‖v‖/‖ω‖`); the eigenvectors are ours, so the grid points are those of the reference up to
/// the eigenvector signs (the surface is the same). [`to_projected_ellipsoid_from_eigen`]
/// takes a given eigen basis.
///
/// # Accuracy
///
/// Relative to `max(1, max|y|)`, given the reference's eigen basis: f64
/// ≤ 10⁻¹² (observed 7.4·10⁻¹⁵ on the 200 golden cases; the reference's batch-exp
/// error never showed there); f32 ≤ 8·ε₃₂·(1 + r), r = factor·√λ₀ the largest
/// perturbation (its rounding enters sin/cos), observed 1.0·10⁻⁶. With our own eigen
/// basis add the eigenvector error `ε·‖Σ‖/gap` times r.
///
/// # Errors
///
/// [`Error::NonFinite`] (any input), [`Error::GridSize`] for
/// `n_steps < 2`, [`Error::BufferTooSmall`] if `out.len() < n_steps²`, [`Error::Overflow`]
/// if a point is not finite (the points are written).
pub fn to_projected_ellipsoid<T: Real>(
    mean: &Transform<T>,
    cov: &Mat6<T>,
    factor: T,
    n_steps: usize,
    out: &mut [Vec3<T>],
) -> Result<usize, Error> {
    grid_len(n_steps, out.len())?;
    let eig = SymmetricEigen::new(cov)?;
    to_projected_ellipsoid_from_eigen(mean, &eig.values, &eig.vectors, factor, n_steps, out)
}

/// The body of [`to_projected_ellipsoid`] after the eigen-decomposition: `values` are the
/// eigenvalues in **descending** order and `vectors` the matching eigenvectors as columns
/// (only the first three of each are used). This lets a caller reproduce the reference's
/// grid points with the reference's own (LAPACK-specific) eigenvectors.
///
/// Negative values are clamped to 0.
///
/// # Errors
///
/// As [`to_projected_ellipsoid`].
pub fn to_projected_ellipsoid_from_eigen<T: Real>(
    mean: &Transform<T>,
    values: &Vec6<T>,
    vectors: &Mat6<T>,
    factor: T,
    n_steps: usize,
    out: &mut [Vec3<T>],
) -> Result<usize, Error> {
    if !mean.rotation.is_finite()
        || !mean.translation.is_finite()
        || !values.is_finite()
        || !vectors.is_finite()
        || !factor.is_finite()
    {
        return Err(Error::NonFinite);
    }
    let n = grid_len(n_steps, out.len())?;
    let mut radii = [T::ZERO; 3];
    for (r, l) in radii.iter_mut().zip(values.0.iter()) {
        *r = factor * l.max(T::ZERO).sqrt();
    }
    // ξ(u) = V₃·diag(radii)·u, with the rotation rows negated (exactly) for the (−ω, v)
    // below: one 6×3 product per point.
    let mut basis = Matrix::<T, 6, 3>::zeros();
    for (r, (brow, vrow)) in basis.0.iter_mut().zip(vectors.0.iter()).enumerate() {
        let sign = if r < 3 { -T::ONE } else { T::ONE };
        for (c, b) in brow.iter_mut().enumerate() {
            *b = sign * (radii[c] * vrow[c]);
        }
    }
    fill_grid(n_steps, out, |u| {
        // R(E)ᵀ·p(E) = Exp(ω)ᵀ·J(ω)·v = J(−ω)·v: the translation of Exp(−ω, v).
        transform3(mean, &se3::exp_translation(&mul3(&basis, u)))
    });
    finite_points(n, out)
}

/// `m·x` for a matrix of three columns, each element summed as `m₀x₀ + m₁x₁ + m₂x₂`
/// (the per-point products of the surfaces).
#[inline(always)]
fn mul3<T: Real, const R: usize>(m: &Matrix<T, R, 3>, x: &Vec3<T>) -> Vector<T, R> {
    let [x0, x1, x2] = x.0;
    Vector(core::array::from_fn(|r| {
        let [m0, m1, m2] = m.0[r];
        m0 * x0 + m1 * x1 + m2 * x2
    }))
}

/// `R·x + p` ([`Transform::transform_point`] with the sums of [`mul3`]).
#[inline(always)]
fn transform3<T: Real>(t: &Transform<T>, x: &Vec3<T>) -> Vec3<T> {
    mul3(&t.rotation, x) + t.translation
}

/// Checks that a pose and a covariance are finite.
#[inline]
fn check_pose_cov<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Result<(), Error> {
    if mean.rotation.is_finite() && mean.translation.is_finite() && cov.is_finite() {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// The linear (first-order) marginal covariance of the tool position, `R̄·Σ_vv·R̄ᵀ`, in
/// the output frame of `mean`, for the **right** perturbation `T = T̄·Exp(η)`, η ~ N(0, Σ)
/// (rotation first, so `Σ_vv` is the lower-right 3×3 block; only its symmetric part is
/// read). First order because `p(T̄·Exp(η)) = t̄ + R̄·(v + ½ ω×v + …)`.
///
/// # Accuracy
///
/// Exactly symmetric, `O(ε·‖Σ_vv‖)`. As an approximation of the true
/// distribution: good at small noise, a first-order error that grows with the rotational
/// noise (the sampled positions lie on arcs); the second-order mean shift is
/// [`position_mean_second_order`].
#[inline]
pub fn position_covariance<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Mat3<T> {
    symmetric_part(&cov.block(1, 1)).congruence(&mean.rotation)
}

/// The linear marginal ellipsoid of the tool position: [`to_ellipsoid`] of
/// `(t̄, R̄·Σ_vv·R̄ᵀ)` ([`position_covariance`]), for the **right** perturbation
/// `T = T̄·Exp(η)`. Radii ascending, at one standard deviation (multiply by k from
/// [`chi2_3_radius`] for a probability).
///
/// # Errors
///
/// [`Error::NonFinite`].
pub fn position_ellipsoid<T: Real>(
    mean: &Transform<T>,
    cov: &Mat6<T>,
) -> Result<(Transform<T>, Vec3<T>), Error> {
    check_pose_cov(mean, cov)?;
    to_ellipsoid(&mean.translation, &position_covariance(mean, cov))
}

/// The second-order mean of the tool position for the **right** perturbation
/// `T = T̄·Exp(η)`, η = (ω, v) ~ N(0, Σ): `t̄ + ½·R̄·E[ω×v]`, with
/// `E[ω×v]ᵢ = ε_ijk·Σ_{ω_j v_k}` read from the cross-covariance block `Σ_ωv` (upper-right
/// 3×3 block, averaged with the transposed lower-left block).
///
/// Method: `p(Exp(η)) = J(ω)·v = v + ½ ω×v + ⅙ ω×(ω×v) + …`; the first and third-order
/// terms have zero mean for a zero-mean Gaussian, so this is exact up to fourth-order
/// moments. On the seed robot the sampled mean sits 0.10 m from t̄ and this predicts it
/// within about 5 mm, the size of the neglected fourth-order terms
/// (the repository's Monte Carlo test measures 5.3 ± 1.3 mm). Non-finite input gives
/// non-finite output.
#[inline]
pub fn position_mean_second_order<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Vec3<T> {
    let c = symmetric_part(cov).block(0, 1); // c[j][k] = Σ_{ω_j v_k}
    let e = Vec3::new(
        c.0[1][2] - c.0[2][1],
        c.0[2][0] - c.0[0][2],
        c.0[0][1] - c.0[1][0],
    );
    mean.translation + mean.rotation * e.scale(T::HALF)
}

/// The "lift" map of an uncertain pose (the default equiprobable surface,
/// [`Surface::Lift`]): `s ↦ position of T̄·Exp(ξ(s))`, `ξ(s) = Σ[:, v]·Σ_vv^(−½)·s`, for the
/// **right** perturbation `T = T̄·Exp(η)`, η ~ N(0, Σ), rotation first.
///
/// For a whitened tool displacement s (in the tool frame), ξ(s) is the most likely full
/// perturbation η producing the first-order tool displacement `Σ_vv^(½)·s` (the
/// conditional mean `E[η | v] = Σ[:, v]·Σ_vv⁻¹·v`), so `{ξ(s) : ‖s‖ = k}` is the
/// first-order k-σ marginal ellipsoid lifted to 6D and mapped through the exact
/// exponential: it bends like the sampled cloud. See the [module docs](self) for why this
/// is the default (the repository's coverage test: the sampled tool positions inside it are within
/// 0.03 of the Gaussian fractions 0.20 / 0.74 / 0.97 at k = 1 / 2 / 3).
///
/// `Σ_vv^(−½)` is the symmetric pseudo-inverse square root ([`SymmetricEigen::pinv_sqrt`]):
/// a rank-deficient position covariance gives a flat (or degenerate) surface, never NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LiftSurface<T> {
    /// The mean pose T̄.
    pub mean: Transform<T>,
    /// The 6×3 map `B = Σ[:, v]·Σ_vv^(−½)` from whitened tool displacements to
    /// perturbations, rotation first: `ξ(s) = B·s`.
    pub basis: Matrix<T, 6, 3>,
}

impl<T: Real> LiftSurface<T> {
    /// Builds the lift map of `(mean, cov)`; only the symmetric part of `cov` is read.
    ///
    /// Method: `Σ_vv^(−½)` from the Jacobi decomposition of `Σ_vv` ([`SymmetricEigen`]),
    /// eigenvalues at or below `3·ε·λ_max` treated as zero.
    ///
    /// # Accuracy
    ///
    /// `O(ε·κ^½)` relative in B, κ the condition number of `Σ_vv` over its numerical range.
    ///
    /// # Example
    ///
    /// ```
    /// use ppoe::{se3, surface::LiftSurface, Mat6, Vec3, Vector};
    /// let mean = se3::exp(&Vector([0.0, 0.0, 0.5, 1.0, 0.0, 0.0]));
    /// let cov = Mat6::from_diagonal(&Vector([1e-4, 1e-4, 1e-4, 1e-6, 1e-6, 1e-6]));
    /// let lift = LiftSurface::new(&mean, &cov)?;
    /// // Uncorrelated noise: s = (1, 0, 0) is one σ (1 mm) along the tool's own x axis.
    /// let p = mean.transform_point(&Vec3::new(1e-3, 0.0, 0.0));
    /// approx::assert_abs_diff_eq!(lift.point(&Vec3::new(1.0, 0.0, 0.0)), p, epsilon = 1e-15);
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`].
    pub fn new(mean: &Transform<T>, cov: &Mat6<T>) -> Result<Self, Error> {
        check_pose_cov(mean, cov)?;
        let sym = symmetric_part(cov);
        let w = SymmetricEigen::new(&sym.block(1, 1))?.pinv_sqrt();
        let mut basis = Matrix::<T, 6, 3>::zeros();
        for (brow, crow) in basis.0.iter_mut().zip(sym.0.iter()) {
            let cv = Vec3::new(crow[3], crow[4], crow[5]);
            // (Σ[r, v] · W)_k = Σ_m Σ[r, 3+m]·W[m][k]; W is symmetric.
            *brow = w.mul_vec(&cv).0;
        }
        Ok(Self { mean: *mean, basis })
    }

    /// The perturbation `ξ(s) = B·s` (rotation first) for a whitened tool displacement s.
    #[inline]
    pub fn perturbation(&self, s: &Vec3<T>) -> Vec6<T> {
        mul3(&self.basis, s)
    }

    /// The tool position `R̄·p(Exp(ξ(s))) + t̄` of `T̄·Exp(ξ(s))` ([`se3::exp_translation`],
    /// accurate to a few ε·‖v‖).
    #[inline]
    pub fn point(&self, s: &Vec3<T>) -> Vec3<T> {
        transform3(&self.mean, &se3::exp_translation(&self.perturbation(s)))
    }

    /// The surface at radius `k` (`‖s‖ = k`) on the unit-sphere grid (row-major, `n_steps²`
    /// points, see the [module docs](self)): `out[i·n + j] = point(k·u(i, j))`. Returns
    /// the number of points written.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for non-finite k, [`Error::GridSize`] for
    /// `n_steps < 2`, [`Error::BufferTooSmall`] if `out.len() < n_steps²`,
    /// [`Error::Overflow`] if a point is not finite (the points are written).
    pub fn grid(&self, k: T, n_steps: usize, out: &mut [Vec3<T>]) -> Result<usize, Error> {
        if !k.is_finite() {
            return Err(Error::NonFinite);
        }
        let n = grid_len(n_steps, out.len())?;
        fill_grid(n_steps, out, |u| self.point(&u.scale(k)));
        finite_points(n, out)
    }
}

/// The default equiprobable surface of the tool position ([`Surface::Lift`]): the lift
/// surface of [`LiftSurface`] at radius `k`, for the **right** perturbation
/// `T = T̄·Exp(η)`, η ~ N(0, Σ) (rotation first), written row-major into `out`
/// (`n_steps²` points; the number is returned).
///
/// Take k from [`chi2_3_radius`] for a probability (k = 1, 2, 3 hold 20 %, 74 %, 97 % of
/// a 3D Gaussian). Method, accuracy and errors: [`LiftSurface::new`] and
/// [`LiftSurface::grid`]; never NaN for finite input, whatever the rank of Σ.
///
/// ```
/// use ppoe::surface::{chi2_3_radius, lift_surface};
/// use ppoe::{Mat6, Transform, Vec3};
/// let cov = Mat6::<f64>::identity() * 1e-4;
/// let k = chi2_3_radius(0.95).unwrap(); // 2.7955
/// let mut grid = [[Vec3::zeros(); 20]; 20];
/// let n = lift_surface(&Transform::identity(), &cov, k, 20, grid.as_flattened_mut()).unwrap();
/// assert_eq!(n, 400);
/// assert!((grid[0][0].0[2] - k * 1e-2).abs() < 1e-12); // north pole: k·σ_z
/// ```
pub fn lift_surface<T: Real>(
    mean: &Transform<T>,
    cov: &Mat6<T>,
    k: T,
    n_steps: usize,
    out: &mut [Vec3<T>],
) -> Result<usize, Error> {
    grid_len(n_steps, out.len())?;
    LiftSurface::new(mean, cov)?.grid(k, n_steps, out)
}

/// The linear marginal ellipsoid of the tool position at radius `k`, on the same grid
/// and with the same parametrisation as [`lift_surface`] (equal to it at first order,
/// point by point): `y = t̄ + R̄·Σ_vv^(½)·k·u`, for the **right** perturbation
/// `T = T̄·Exp(η)`. Writes `n_steps²` points row-major into `out` and returns their
/// number.
///
/// This is the ellipsoid of [`position_ellipsoid`] (`{y : (y − t̄)ᵀ(R̄Σ_vvR̄ᵀ)⁻¹(y − t̄) =
/// k²}`). It is right at small noise but does not bend with the sampled cloud, so it
/// under-covers at larger rotational noise. Method:
/// [`SymmetricEigen::sqrt`].
///
/// # Errors
///
/// As [`lift_surface`].
pub fn marginal_surface<T: Real>(
    mean: &Transform<T>,
    cov: &Mat6<T>,
    k: T,
    n_steps: usize,
    out: &mut [Vec3<T>],
) -> Result<usize, Error> {
    check_pose_cov(mean, cov)?;
    if !k.is_finite() {
        return Err(Error::NonFinite);
    }
    let n = grid_len(n_steps, out.len())?;
    let a = mean.rotation * SymmetricEigen::new(&symmetric_part(&cov.block(1, 1)))?.sqrt();
    fill_grid(n_steps, out, |u| a.mul_vec(&u.scale(k)) + mean.translation);
    finite_points(n, out)
}

/// The surfaces [`surface_grid`] can draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Surface {
    /// The lift surface ([`lift_surface`]): the default, right coverage also where the
    /// sampled cloud bends.
    #[default]
    Lift,
    /// The linear marginal ellipsoid of the tool position ([`marginal_surface`]).
    Marginal,
    /// pytransform3d's projected ellipsoid ([`to_projected_ellipsoid`] with factor k),
    /// for comparison with the reference; not an equiprobable surface.
    Pytransform3d,
}

/// Draws the chosen [`Surface`] of the uncertain pose `(mean, cov)` at radius `k` on the
/// unit-sphere grid (`n_steps²` points, row-major, see the [module docs](self)); returns
/// the number of points written.
///
/// `cov` is the right (local) perturbation covariance for [`Surface::Lift`] and
/// [`Surface::Marginal`]; [`Surface::Pytransform3d`] uses it as given, as the reference
/// does.
///
/// # Errors
///
/// As the chosen function.
pub fn surface_grid<T: Real>(
    surface: Surface,
    mean: &Transform<T>,
    cov: &Mat6<T>,
    k: T,
    n_steps: usize,
    out: &mut [Vec3<T>],
) -> Result<usize, Error> {
    match surface {
        Surface::Lift => lift_surface(mean, cov, k, n_steps, out),
        Surface::Marginal => marginal_surface(mean, cov, k, n_steps, out),
        Surface::Pytransform3d => to_projected_ellipsoid(mean, cov, k, n_steps, out),
    }
}

/// `P(3/2, k²/2)` in f64: the probability that a 3D standard normal vector has norm ≤ k.
fn chi3_cdf(k: f64) -> f64 {
    if k.is_nan() {
        return f64::NAN;
    }
    if k <= 0.0 {
        return 0.0;
    }
    if k == f64::INFINITY {
        return 1.0;
    }
    let x = 0.5 * k * k;
    if x < 2.0 {
        // Series P(a, x) = x^a e^(−x) Σₙ xⁿ/Γ(a+n+1), a = 3/2, Γ(5/2) = 3√π/4; the terms
        // fall by at least x/(5/2) < 0.8 each, < 170 terms reach ε.
        let mut term = 1.0;
        let mut sum = 1.0;
        let mut den = 2.5;
        for _ in 0..200 {
            term *= x / den;
            sum += term;
            den += 1.0;
            if term <= f64::EPSILON * sum {
                break;
            }
        }
        let gamma_5_2 = 0.75 * libm::sqrt(core::f64::consts::PI);
        libm::pow(x, 1.5) * libm::exp(-x) * sum / gamma_5_2
    } else {
        // erf(k/√2) − √(2/π)·k·e^(−k²/2); no cancellation for k ≥ 2 (P ≥ 0.74).
        let c = libm::sqrt(2.0 / core::f64::consts::PI);
        libm::erf(k * core::f64::consts::FRAC_1_SQRT_2) - c * k * libm::exp(-x)
    }
}

/// The probability that a 3D Gaussian vector lies within Mahalanobis distance `k` of its
/// mean: `P(‖x‖ ≤ k)`, x ~ N(0, I₃), i.e. the χ²₃ CDF at k² — the coverage of an
/// equiprobable 3D ellipsoid drawn at k standard deviations (0.1987, 0.7385, 0.9707 for
/// k = 1, 2, 3). `k ≤ 0` gives 0, `k = +∞` gives 1, NaN gives NaN.
///
/// Method: the regularized incomplete gamma function `P(3/2, k²/2)`, by its power series
/// below k = 2 and as `erf(k/√2) − √(2/π)·k·e^(−k²/2)` above (libm's erf), evaluated in
/// f64 and rounded to T.
///
/// # Accuracy
///
/// A few f64 ulps (relative, also for small k), then the rounding to T.
#[inline]
pub fn chi2_3_probability<T: Real>(k: T) -> T {
    T::lit(chi3_cdf(k.to_f64()))
}

/// The radius k (in standard deviations, i.e. Mahalanobis distance) of the 3D ellipsoid
/// that holds probability `p` of a 3D Gaussian: `k² = χ²₃` quantile of p, the inverse of
/// [`chi2_3_probability`]. `p = 0.95` gives k = 2.7955 (not 1.96, which holds 72 % in
/// 3D); 0.1987 / 0.7385 / 0.9707 give 1 / 2 / 3.
///
/// Returns `None` for p outside `[0, 1)` or NaN (p = 1 needs k = ∞); `Some(0)` for p = 0.
///
/// Method: bisection on [`chi2_3_probability`] (evaluated in f64) over a bracket found by
/// doubling from 1, until the bracket is two adjacent f64 numbers; returns the upper end
/// rounded to T.
///
/// # Accuracy
///
/// `|k − k*| ≲ ε_f64·(1 + 1/(k·pdf))` before the rounding to T,
/// i.e. a few f64 ulps for p in [10⁻¹², 1 − 10⁻¹²].
pub fn chi2_3_radius<T: Real>(p: T) -> Option<T> {
    let p = p.to_f64();
    if !(0.0..1.0).contains(&p) {
        return None;
    }
    if p == 0.0 {
        return Some(T::ZERO);
    }
    let mut lo = 0.0_f64;
    let mut hi = 1.0_f64;
    // P(64) = 1 in f64, so at most 6 doublings.
    while chi3_cdf(hi) < p && hi < 64.0 {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..2100 {
        let mid = lo + 0.5 * (hi - lo);
        if mid <= lo || mid >= hi {
            break;
        }
        if chi3_cdf(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(T::lit(hi))
}

crate::linalg::approx_fields!([T: Real] LiftSurface<T> { mean, basis });

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi2_known_values() {
        // χ²₃ CDF at 1, 4, 9 (scipy.stats.chi2(3).cdf).
        assert!((chi2_3_probability(1.0_f64) - 0.198_748_043_098_799_2).abs() < 1e-15);
        assert!((chi2_3_probability(2.0_f64) - 0.738_535_870_050_889_4).abs() < 1e-15);
        assert!((chi2_3_probability(3.0_f64) - 0.970_709_113_465_111_8).abs() < 1e-15);
        let k = chi2_3_radius(0.95_f64).unwrap();
        assert!((k * k - 7.814_727_903_251_18).abs() < 1e-13);
        assert_eq!(chi2_3_radius(1.0_f64), None);
        assert_eq!(chi2_3_radius(-0.1_f64), None);
        assert_eq!(chi2_3_radius(0.0_f64), Some(0.0));
    }

    #[test]
    fn grids_that_overflow_are_errors() {
        // Finite inputs whose points are not: radii k·√λ (or factor·√λ) beyond the
        // largest float.
        fn check<T: Real>() {
            let (pose, cov) = (
                Transform::<T>::identity(),
                Mat6::<T>::identity() * T::lit(4.0),
            );
            let mut out = [Vec3::zeros(); 16];
            for kind in [Surface::Lift, Surface::Marginal, Surface::Pytransform3d] {
                let got = surface_grid(kind, &pose, &cov, T::max_value(), 4, &mut out);
                assert_eq!(got, Err(Error::Overflow), "{kind:?}");
                assert_eq!(surface_grid(kind, &pose, &cov, T::ONE, 4, &mut out), Ok(16));
            }
            let got = to_projected_ellipsoid(&pose, &cov, T::max_value(), 4, &mut out);
            assert_eq!(got, Err(Error::Overflow));
        }
        check::<f64>();
        check::<f32>();
    }
}
