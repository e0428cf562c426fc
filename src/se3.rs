//! SE(3): rigid transforms, their exponential coordinates, adjoint and Jacobians.
//!
//! Conventions (those of pytransform3d):
//! * A [`Transform`] `A2B` maps coordinates in frame A to frame B: `x_B = R·x_A + p`.
//!   `a * b` is the matrix product: apply `b` first, then `a`
//!   (pytransform3d's `concat(b, a)`).
//! * Exponential coordinates, twists and screw axes are **rotation first**: ξ = (ω, v).
//!   `Exp(ξ) = [[Exp(ω), J(ω)·v], [0, 1]]`.
//! * The adjoint is `Ad(T) = [[R, 0], [[p]×R, R]]`, so `T·Exp(ξ)·T⁻¹ = Exp(Ad(T)·ξ)`.
//! * Jacobians are *left* Jacobians: `Exp(ξ + δ) ≈ Exp(J(ξ)·δ)·Exp(ξ)`.

use crate::error::Error;
use crate::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::so3;

/// A rigid transform stored as rotation R and translation p: `x ↦ R·x + p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform<T> {
    /// The rotation R (orthonormal, det +1).
    pub rotation: Mat3<T>,
    /// The translation p.
    pub translation: Vec3<T>,
}

impl<T: Real> Default for Transform<T> {
    fn default() -> Self {
        Self::identity()
    }
}

impl<T: Real> Transform<T> {
    /// The identity transform.
    #[inline]
    pub fn identity() -> Self {
        Self {
            rotation: Mat3::identity(),
            translation: Vec3::zeros(),
        }
    }

    /// A transform from rotation rows and translation; usable in `const` items.
    #[inline]
    pub const fn from_parts(rotation: [[T; 3]; 3], translation: [T; 3]) -> Self {
        Self {
            rotation: Matrix(rotation),
            translation: Vector(translation),
        }
    }

    /// A transform from a row-major homogeneous 4×4 matrix (the last row is ignored).
    #[inline]
    pub fn from_matrix4(m: &[[T; 4]; 4]) -> Self {
        let mut out = Self::identity();
        for (i, row) in m.iter().take(3).enumerate() {
            out.rotation.0[i] = [row[0], row[1], row[2]];
            out.translation.0[i] = row[3];
        }
        out
    }

    /// The row-major homogeneous 4×4 matrix.
    #[inline]
    pub fn to_matrix4(&self) -> [[T; 4]; 4] {
        let (r, p) = (self.rotation.0, self.translation.0);
        let (o, l) = (T::ZERO, T::ONE);
        [
            [r[0][0], r[0][1], r[0][2], p[0]],
            [r[1][0], r[1][1], r[1][2], p[1]],
            [r[2][0], r[2][1], r[2][2], p[2]],
            [o, o, o, l],
        ]
    }

    /// The inverse `[[Rᵀ, −Rᵀp], [0, 1]]` (closed form; assumes R orthonormal).
    #[inline]
    pub fn inverse(&self) -> Self {
        let rt = self.rotation.transpose();
        Self {
            rotation: rt,
            translation: -(rt * self.translation),
        }
    }

    /// Applies the transform to a point: `R·x + p`.
    #[inline]
    pub fn transform_point(&self, x: &Vec3<T>) -> Vec3<T> {
        self.rotation * *x + self.translation
    }

    /// Applies the rotation only (to a direction): `R·x`.
    #[inline]
    pub fn transform_vector(&self, x: &Vec3<T>) -> Vec3<T> {
        self.rotation * *x
    }

    /// The adjoint `Ad(T) = [[R, 0], [[p]×R, R]]` (rotation-first), which maps twists and
    /// exponential coordinates from the input frame of `T` to its output frame.
    ///
    /// Corresponds to pytransform3d's `adjoint_from_transform`.
    #[inline]
    pub fn adjoint(&self) -> Mat6<T> {
        let r = self.rotation;
        let pr = so3::hat(&self.translation) * r;
        Mat6::from_blocks(&r, &Mat3::zeros(), &pr, &r)
    }

    /// Moves a covariance of exponential coordinates (rotation first) through the adjoint:
    /// `Ad(T)·Σ·Ad(T)ᵀ`, e.g. from the input frame of `T` to its output frame.
    ///
    /// Method: `Ad(T) = [[I, 0], [P, I]]·diag(R, R)` with `P = [p]×`, so the product is a
    /// block rotation `R·X·Rᵀ` of the three blocks of Σ followed by a shear whose products
    /// with the skew P are cross products: ≈ 200 multiplications instead of the 342 of a
    /// dense congruence (and none of the 216 zeros of Ad). Only one triangle of Σ is read;
    /// the result is exactly symmetric. Σ is assumed symmetric.
    #[inline]
    pub fn transport_covariance(&self, cov: &Mat6<T>) -> Mat6<T> {
        let r = &self.rotation.0;
        let p = &self.translation.0;
        let c = &cov.0;
        let block = |bi: usize, bj: usize| -> [[T; 3]; 3] {
            core::array::from_fn(|i| core::array::from_fn(|j| c[bi + i][bj + j]))
        };
        // Rotate the blocks: A' = R A Rᵀ, B' = R B Rᵀ, D' = R D Rᵀ.
        let a = sandwich(r, &block(0, 0), true);
        let b = sandwich(r, &block(0, 3), false);
        let d = sandwich(r, &block(3, 3), true);
        // Shear by [[I, 0], [P, I]], P = [p]×: E = P·A' + B'ᵀ is the lower-left block and
        // P·A'·Pᵀ + P·B' + B'ᵀ·Pᵀ + D' = E·Pᵀ + P·B' + D' the lower-right one.
        let mut out = [[T::ZERO; 6]; 6];
        let mut e = [[T::ZERO; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                e[i][j] = cross_component(p, [a[0][j], a[1][j], a[2][j]], i) + b[j][i];
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                out[i][j] = a[i][j];
                out[3 + i][j] = e[i][j];
                out[j][3 + i] = e[i][j];
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                // Lower triangle computed, mirrored: exactly symmetric.
                if j <= i {
                    let v = cross_component(p, e[i], j)
                        + cross_component(p, [b[0][j], b[1][j], b[2][j]], i)
                        + d[i][j];
                    out[3 + i][3 + j] = v;
                    out[3 + j][3 + i] = v;
                }
            }
        }
        Matrix(out)
    }

    /// The exponential map of exponential coordinates ξ = (ω, v), rotation first.
    /// See [`exp`].
    #[inline]
    pub fn exp(xi: &Vec6<T>) -> Self {
        exp(xi)
    }

    /// The logarithm: exponential coordinates ξ = (ω, v) with ‖ω‖ ∈ [0, π]. See [`log`].
    #[inline]
    pub fn log(&self) -> Vec6<T> {
        log(self)
    }

    /// `true` if all elements are finite, R is orthonormal within `tol`
    /// (`‖RᵀR − I‖_max ≤ tol`) and `det R > 0`.
    #[inline]
    pub fn is_valid(&self, tol: T) -> bool {
        self.translation.is_finite() && so3::is_rotation(&self.rotation, tol)
    }

    /// Checks the transform with tolerance [`Real::TOL`]: [`Error::NonFinite`] or
    /// [`Error::NotARotation`].
    pub fn check(&self) -> Result<(), Error> {
        if !self.rotation.is_finite() || !self.translation.is_finite() {
            Err(Error::NonFinite)
        } else if !self.is_valid(T::TOL) {
            Err(Error::NotARotation)
        } else {
            Ok(())
        }
    }
}

/// `R·X·Rᵀ` on plain arrays (the constant loop bounds let the optimiser unroll it); for
/// symmetric X the lower triangle is computed and mirrored, so the result is exactly
/// symmetric.
#[inline(always)]
fn sandwich<T: Real>(r: &[[T; 3]; 3], x: &[[T; 3]; 3], symmetric: bool) -> [[T; 3]; 3] {
    let mut rx = [[T::ZERO; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            rx[i][j] = r[i][0] * x[0][j] + r[i][1] * x[1][j] + r[i][2] * x[2][j];
        }
    }
    let mut out = [[T::ZERO; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            if !symmetric || j <= i {
                out[i][j] = rx[i][0] * r[j][0] + rx[i][1] * r[j][1] + rx[i][2] * r[j][2];
            }
        }
    }
    if symmetric {
        (out[0][1], out[0][2], out[1][2]) = (out[1][0], out[2][0], out[2][1]);
    }
    out
}

/// Component `i` of `p × x`.
#[inline(always)]
fn cross_component<T: Real>(p: &[T; 3], x: [T; 3], i: usize) -> T {
    match i {
        0 => p[1] * x[2] - p[2] * x[1],
        1 => p[2] * x[0] - p[0] * x[2],
        _ => p[0] * x[1] - p[1] * x[0],
    }
}

impl<T: Real> core::ops::Mul for Transform<T> {
    type Output = Self;
    /// Composition `self · rhs` (apply `rhs` first).
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        Self {
            rotation: self.rotation * rhs.rotation,
            translation: self.rotation * rhs.translation + self.translation,
        }
    }
}

impl<T: Real> From<[[T; 4]; 4]> for Transform<T> {
    fn from(m: [[T; 4]; 4]) -> Self {
        Self::from_matrix4(&m)
    }
}

impl<T: Real> From<Transform<T>> for [[T; 4]; 4] {
    fn from(t: Transform<T>) -> Self {
        t.to_matrix4()
    }
}

crate::linalg::approx_fields!([T: Real] Transform<T> { rotation, translation });

/// The 4×4 matrix form `[[ [ω]×, v ], [0, 0]]` of a twist ξ = (ω, v) (an element of se(3)).
#[inline]
pub fn hat<T: Real>(xi: &Vec6<T>) -> [[T; 4]; 4] {
    let w = so3::hat(&xi.rotation()).0;
    let v = xi.translation().0;
    let o = T::ZERO;
    [
        [w[0][0], w[0][1], w[0][2], v[0]],
        [w[1][0], w[1][1], w[1][2], v[1]],
        [w[2][0], w[2][1], w[2][2], v[2]],
        [o, o, o, o],
    ]
}

/// The inverse of [`hat`]: (ω, v) from a 4×4 se(3) matrix (skew part averaged).
#[inline]
pub fn vee<T: Real>(m: &[[T; 4]; 4]) -> Vec6<T> {
    let w = Matrix([
        [m[0][0], m[0][1], m[0][2]],
        [m[1][0], m[1][1], m[1][2]],
        [m[2][0], m[2][1], m[2][2]],
    ]);
    Vec6::from_parts(so3::vee(&w), Vector([m[0][3], m[1][3], m[2][3]]))
}

/// The 6×6 adjoint of a twist ("curly hat"), rotation first: `ad(ξ) = [[[ω]×, 0], [[v]×,
/// [ω]×]]`, so that `ad(ξ₁)·ξ₂` is the Lie bracket.
#[inline]
pub fn curly_hat<T: Real>(xi: &Vec6<T>) -> Mat6<T> {
    let w = so3::hat(&xi.rotation());
    let v = so3::hat(&xi.translation());
    Mat6::from_blocks(&w, &Mat3::zeros(), &v, &w)
}

/// Exponential map: the transform `Exp(ξ) = [[Exp(ω), J(ω)·v], [0, 1]]` of exponential
/// coordinates ξ = (ω, v), rotation first.
///
/// Corresponds to pytransform3d's `transform_from_exponential_coordinates` (the
/// single-instance version). Method: one sin/cos and the coefficients of
/// `I + aW + bW²` (rotation) and `I + bW + cW²` (left Jacobian, applied to v), with
/// Taylor series below [`Real::SERIES`]. Accuracy: a few ε absolute in R and
/// ε·‖v‖ in p, for any ω including tiny ones (pytransform3d's batch formula loses
/// ε·‖v‖/‖ω‖ there).
#[inline]
pub fn exp<T: Real>(xi: &Vec6<T>) -> Transform<T> {
    let w = xi.rotation();
    let parts = so3::ExpParts::new(&w);
    Transform {
        rotation: parts.rotation(),
        translation: parts.jacobian() * xi.translation(),
    }
}

/// The translation part `J(ω)·v` of [`exp`]`(ξ)` alone (no rotation matrix): for surfaces
/// that map many perturbations to positions. Same method and accuracy as [`exp`].
#[inline]
pub fn exp_translation<T: Real>(xi: &Vec6<T>) -> Vec3<T> {
    so3::ExpParts::new(&xi.rotation()).jacobian() * xi.translation()
}

/// Logarithm: exponential coordinates ξ = (ω, v), ‖ω‖ ∈ [0, π], with `Exp(ξ) = T`.
///
/// Corresponds to pytransform3d's `exponential_coordinates_from_transform`. Method: ω
/// from [`so3::log`], `v = J⁻¹(ω)·p`. Accuracy: a few ε (relative to ‖p‖ for v) away from
/// π; near π the axis is accurate to ε/(π − θ) at worst (see [`so3::log_axis_angle`]).
#[inline]
pub fn log<T: Real>(t: &Transform<T>) -> Vec6<T> {
    let w = so3::log(&t.rotation);
    let v = so3::left_jacobian_inv(&w) * t.translation;
    Vec6::from_parts(w, v)
}

/// The coefficients m₂, m₃, m₄ of the Q block (Barfoot's "Q" of the SE(3) Jacobian),
/// with pytransform3d's Horner polynomials below 0.5 (precision-independent: their
/// truncation error is < 10⁻¹⁶ there).
fn q_coefficients<T: Real>(ph: T) -> (T, T, T) {
    let p2 = ph * ph;
    if ph < T::HALF {
        let l = T::lit;
        let m2 = l(1.0 / 6.0)
            - p2 * (l(1.0 / 120.0)
                - p2 * (l(1.0 / 5040.0)
                    - p2 * (l(1.0 / 362880.0)
                        - p2 * (l(1.0 / 39916800.0) - p2 / l(6227020800.0)))));
        let m3 = l(-1.0 / 24.0)
            + p2 * (l(1.0 / 720.0)
                - p2 * (l(1.0 / 40320.0)
                    - p2 * (l(1.0 / 3628800.0)
                        - p2 * (l(1.0 / 479001600.0) - p2 / l(87178291200.0)))));
        let m4 = l(-1.0 / 120.0)
            + p2 * (l(1.0 / 2520.0)
                - p2 * (l(1.0 / 120960.0)
                    - p2 * (l(1.0 / 9979200.0)
                        - p2 * (l(1.0 / 1245404160.0) - p2 / l(217945728000.0)))));
        (m2, m3, m4)
    } else {
        let (s, c) = ph.sin_cos_r();
        let p3 = p2 * ph;
        let p4 = p2 * p2;
        let m2 = (ph - s) / p3;
        let m3 = (T::ONE - p2 * T::HALF - c) / p4;
        let m4 = (m3 - T::lit(3.0) * (ph - s - p3 / T::lit(6.0)) / (p4 * ph)) * T::HALF;
        (m2, m3, m4)
    }
}

/// The Q block of the SE(3) left Jacobian, `J₆ = [[J, 0], [Q, J]]`, for ξ = (φ, ρ)
/// (Barfoot, *State Estimation for Robotics*, eq. 7.86b).
///
/// Matches pytransform3d's internal Q (MATH.md §2.6), including its polynomial branch
/// below ‖φ‖ = 0.5.
pub fn q_matrix<T: Real>(xi: &Vec6<T>) -> Mat3<T> {
    let phi = xi.rotation();
    let p = so3::hat(&phi);
    let r = so3::hat(&xi.translation());
    let (m2, m3, m4) = q_coefficients(phi.norm());
    let pr = p * r;
    let rp = r * p;
    let prp = pr * p;
    let ppr = p * pr;
    let rpp = rp * p;
    let prpp = prp * p;
    let pprp = p * prp;
    r * T::HALF + (pr + rp + prp) * m2 - (ppr + rpp - prp * T::lit(3.0)) * m3 - (prpp + pprp) * m4
}

/// Left Jacobian of SE(3), rotation first: `J₆(ξ) = [[J(ω), 0], [Q(ξ), J(ω)]]`.
///
/// Corresponds to pytransform3d's `left_jacobian_SE3`.
pub fn left_jacobian<T: Real>(xi: &Vec6<T>) -> Mat6<T> {
    let j = so3::left_jacobian(&xi.rotation());
    Mat6::from_blocks(&j, &Mat3::zeros(), &q_matrix(xi), &j)
}

/// Inverse left Jacobian of SE(3): `[[J⁻¹, 0], [−J⁻¹·Q·J⁻¹, J⁻¹]]`.
///
/// Corresponds to pytransform3d's `left_jacobian_SE3_inv` (which switches to a 10-term
/// series for ‖ω‖ < √(6ε); the closed form here is exact there too, since J⁻¹(0) = I
/// and Q has its polynomial branch).
pub fn left_jacobian_inv<T: Real>(xi: &Vec6<T>) -> Mat6<T> {
    let ji = so3::left_jacobian_inv(&xi.rotation());
    let lower = -(ji * q_matrix(xi) * ji);
    Mat6::from_blocks(&ji, &Mat3::zeros(), &lower, &ji)
}

/// Screw axis S (rotation first) from screw parameters: a point `q` on the axis, the
/// direction `s` (normalised here) and the pitch `h`.
///
/// `S = (ŝ, q × ŝ + h·ŝ)` for finite h (h = 0: revolute), `S = (0, ŝ)` for h = ±∞
/// (prismatic; q is ignored). Corresponds to pytransform3d's
/// `screw_axis_from_screw_parameters`. Errors: [`Error::ZeroAxis`] if ‖s‖ = 0,
/// [`Error::NonFinite`] for NaN anywhere or non-finite q, s.
pub fn screw_axis<T: Real>(q: &Vec3<T>, s: &Vec3<T>, h: T) -> Result<Vec6<T>, Error> {
    if !s.is_finite() || h.is_nan() || (h.is_finite() && !q.is_finite()) {
        return Err(Error::NonFinite);
    }
    let n = s.norm();
    if n == T::ZERO {
        return Err(Error::ZeroAxis);
    }
    let s = s.scale(T::ONE / n);
    if h.is_infinite() {
        return Ok(Vec6::from_parts(Vec3::zeros(), s));
    }
    Ok(Vec6::from_parts(s, q.cross(&s) + s.scale(h)))
}
