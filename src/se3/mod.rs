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
//!
//! ```
//! use ppoe::{se3, Transform, Vector};
//! // Exp and Log are inverse for rotation angles below π.
//! let xi = Vector([0.3, -0.2, 0.9, 1.0, 2.0, -0.5]);
//! let t = se3::exp(&xi);
//! approx::assert_abs_diff_eq!(se3::log(&t), xi, epsilon = 1e-14);
//! // A transform composed with its inverse is the identity.
//! approx::assert_abs_diff_eq!(t * t.inverse(), Transform::identity(), epsilon = 1e-15);
//! ```

use crate::error::Error;
use crate::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use crate::scalar::Real;
use crate::so3;

pub(crate) mod congruence;
use congruence::{mirror_lower, Congruence};

/// A rigid transform stored as rotation R and translation p: `x ↦ R·x + p`.
///
/// Composition is `*`: `(a * b).transform_point(x) = a.transform_point(b.transform_point(x))`,
/// so `b2c * a2b` is `a2b` then `b2c`, i.e. `A2C`.
///
/// ```
/// use ppoe::{Transform, Vec3};
/// let a2b = Transform::from_parts([[0., -1., 0.], [1., 0., 0.], [0., 0., 1.]], [1., 0., 0.]);
/// let b2c = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0., 0., 2.]);
/// let x_a = Vec3::new(1.0, 0.0, 0.0);
/// // x_A = (1, 0, 0) → x_B = R·x + p = (0, 1, 0) + (1, 0, 0) → x_C = x_B + (0, 0, 2).
/// assert_eq!((b2c * a2b).transform_point(&x_a), Vec3::new(1.0, 1.0, 2.0));
/// ```
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

    /// The transform `t`, computed in f64, in scalar T: every value rounded to T, then in
    /// the rotation and in the translation separately the elements below ε²·max set to zero
    /// (see [`crate::chain::Joint::from_f64`]).
    pub fn from_f64(t: &Transform<f64>) -> Self {
        Self {
            rotation: Matrix(t.rotation.0.map(|r| r.map(T::lit))).without_negligible(),
            translation: Vector(t.translation.0.map(T::lit)).without_negligible(),
        }
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
    ///
    /// ```
    /// use ppoe::{Transform, Vec3};
    /// let t = Transform::from_parts([[0., -1., 0.], [1., 0., 0.], [0., 0., 1.]], [1., 2., 3.]);
    /// let x = Vec3::new(0.5, -1.0, 4.0);
    /// // The inverse maps the output frame back into the input frame, exactly here.
    /// assert_eq!(t.inverse().transform_point(&t.transform_point(&x)), x);
    /// ```
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
    ///
    /// ```
    /// use ppoe::{se3, Vector};
    /// let t = se3::exp(&Vector([0.1, 0.5, -0.3, 1.0, 0.0, 2.0]));
    /// let xi = Vector([-0.4, 0.2, 0.7, 0.3, -1.0, 0.5]);
    /// // Conjugation moves a twist between frames: T·Exp(ξ)·T⁻¹ = Exp(Ad(T)·ξ).
    /// let lhs = t * se3::exp(&xi) * t.inverse();
    /// approx::assert_abs_diff_eq!(lhs, se3::exp(&(t.adjoint() * xi)), epsilon = 1e-14);
    /// ```
    #[inline]
    pub fn adjoint(&self) -> Mat6<T> {
        let r = self.rotation;
        let pr = so3::hat(&self.translation) * r;
        Mat6::from_blocks(&r, &Mat3::zeros(), &pr, &r)
    }

    /// Moves a covariance of exponential coordinates (rotation first) through the adjoint:
    /// `Ad(T)·Σ·Ad(T)ᵀ`, e.g. from the input frame of `T` to its output frame.
    ///
    /// Method: `Ad(T) = diag(R, R)·[[I, 0], [Q, I]]` with `Q = [Rᵀp]×`, so the product is
    /// a shear whose products with the skew Q are cross products, followed by a block
    /// rotation `R·X·Rᵀ` of the three blocks: ≈ 200 multiplications instead of the 342 of
    /// a dense congruence (and none of the 216 zeros of Ad). The upper-right block of Σ is
    /// not read; the result is exactly symmetric. Σ is assumed symmetric.
    #[inline]
    pub fn transport_covariance(&self, cov: &Mat6<T>) -> Mat6<T> {
        let mut acc = [[T::ZERO; 6]; 6];
        self.add_transported_lower(cov, &mut acc);
        mirror_lower(acc)
    }

    /// Adds the lower triangle (row ≥ column) of `Ad(T)·Σ·Ad(T)ᵀ` to that of `acc` (see
    /// [`Transform::transport_covariance`]); the upper triangle of `acc` is not touched.
    #[inline(always)]
    pub(crate) fn add_transported_lower(&self, cov: &Mat6<T>, acc: &mut [[T; 6]; 6]) {
        Congruence::of(self).add_lower(cov, acc);
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

    /// Checks the transform with tolerance [`Real::TOL`] (see [`Transform::is_valid`]).
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] or [`Error::NotARotation`].
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

impl<T: Real> Transform<T> {
    /// `self · rhs`, always inlined (the PPOE's loops; elsewhere `*`).
    #[inline(always)]
    pub(crate) fn compose(&self, rhs: &Self) -> Self {
        Self {
            rotation: self.rotation * rhs.rotation,
            translation: self.rotation * rhs.translation + self.translation,
        }
    }
}

impl<T: Real> core::ops::Mul for Transform<T> {
    type Output = Self;
    /// Composition `self · rhs` (apply `rhs` first).
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        self.compose(&rhs)
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
/// Taylor series below [`Real::SERIES`].
///
/// # Accuracy
///
/// A few ε in R and ε·‖v‖ in p for any ω (8 ε·‖v‖ just above the series cut-off,
/// measured by the repository's numerical robustness tests).
///
/// # Example
///
/// ```
/// use ppoe::{se3, Vec3, Vector};
/// // ω = (0, 0, θ), v = (0, 0, d): a screw motion, θ about z and d along z.
/// let t = se3::exp(&Vector([0.0, 0.0, 1.2, 0.0, 0.0, 0.4]));
/// approx::assert_abs_diff_eq!(t.translation, Vec3::new(0.0, 0.0, 0.4), epsilon = 1e-16);
/// // v is *not* the translation when ω ≠ 0: a half turn with v = (0, π, 0) moves the
/// // origin on a half circle of radius 1, to (−2, 0, 0).
/// let pi = core::f64::consts::PI;
/// let t = se3::exp(&Vector([0.0, 0.0, pi, 0.0, pi, 0.0]));
/// approx::assert_abs_diff_eq!(t.translation, Vec3::new(-2.0, 0.0, 0.0), epsilon = 1e-15);
/// ```
#[inline]
pub fn exp<T: Real>(xi: &Vec6<T>) -> Transform<T> {
    let w = xi.rotation();
    let parts = so3::ExpParts::new(&w);
    Transform {
        rotation: parts.rotation(),
        translation: parts.jacobian() * xi.translation(),
    }
}

/// The translation part `J(ω)·v` of [`exp`]`(ξ)` alone (no rotation matrix), ξ = (ω, v)
/// rotation first: for surfaces that map many perturbations to positions.
///
/// Method: the left Jacobian of SO(3) ([`so3::left_jacobian`]) applied to v with two
/// cross products, `J(ω)·v = v + a·(ω×v) + b·(ω×(ω×v))`, `a = (1 − cos t)/t²`,
/// `b = (t − sin t)/t³`, t = ‖ω‖.
/// * `t² ≤ 4` (the switch point): a and b from their Maclaurin series in t² (those of
///   cos and sin divided by t² and t³), `a = Σₖ (−t²)ᵏ/(2k+2)!`, `b = Σₖ (−t²)ᵏ/(2k+3)!`,
///   k = 0..=11: no square root, trigonometric function or division. Both series
///   alternate with terms falling by at least 3× for t² ≤ 4, so the truncation error is
///   below the first dropped term, `4¹²/26! = 4.2·10⁻²⁰` in a and `4¹²/27! = 1.5·10⁻²¹`
///   in b (11 terms would leave `4¹¹/25! = 2.7·10⁻¹⁹` in b); the same polynomials serve
///   f32. Evaluation: even and odd k separately (Knuth, TAOCP vol. 2, §4.6.4, the
///   second-order Horner rule), `a = Eₐ(t⁴) − t²·Oₐ(t⁴)` and b alike, the four
///   polynomials of degree 5 side by side by Estrin's scheme (Estrin 1960; ibid.): their
///   terms are all positive and the final subtraction loses at most a factor 1.5, so a
///   and b are accurate to a few ε relative.
/// * `t² > 4` (including t² = ∞ for huge ω): the unit-axis form that [`exp`] uses, with
///   `u = ω/t`: `J(ω)·v = v + ((1 − cos t)/t)·(u×v) + ((t − sin t)/t)·(u×(u×v))`, one
///   [`Real::sin_cos_r`]; no cancellation in `t − sin t` for t > 2, and no t² that could
///   overflow.
/// * A result that is not finite (an intermediate overflowed, e.g. ‖v‖ near the largest
///   finite number, or a non-finite input), and NaN t², go to [`exp`]'s matrix form, so
///   the result is finite wherever [`exp`]'s translation is, and NaN only where it is.
///
/// # Accuracy
///
/// A few ε·‖v‖ absolute for every ω (the rounding of the cross products, whose
/// weights relative to ‖v‖, `a·t = (1 − cos t)/t ≤ 0.73` and `b·t² = (t − sin t)/t ≤
/// 1.22`, are bounded for all t). Measured against an independent f64 reference over t from 10⁻³⁰ to
/// 10²⁰⁰ (f32: 10³⁰), including t² within a few ulps of 4 (`tests/surface_props.rs`,
/// shipped with this package):
/// ≤ 4.7·ε·‖v‖ in f64 and ≤ 4.2·ε·‖v‖ in f32 (≤ 1.7 and ≤ 1.2 ε·‖v‖·max(1, t)), the
/// same order as [`exp`]'s translation.
#[inline(always)]
pub fn exp_translation<T: Real>(xi: &Vec6<T>) -> Vec3<T> {
    // The coefficients 1/(2k+2)! of a and 1/(2k+3)! of b, k = 0..=11, split by the parity
    // of k: row m holds [1/(4m+2)!, 1/(4m+4)!, 1/(4m+3)!, 1/(4m+5)!], the coefficients of
    // y^m, y = t⁴, in a = Eₐ(y) − t²·Oₐ(y) and b = E_b(y) − t²·O_b(y). The factorials up to
    // 22! are exact in f64; 23!..25! round, which moves those coefficients by an ulp, and
    // T::lit rounds all of them once more for f32 (≤ 1 ulp, far below the rounding of the
    // sums).
    const C: [[f64; 4]; 6] = [
        [1.0 / 2.0, 1.0 / 24.0, 1.0 / 6.0, 1.0 / 120.0],
        [1.0 / 720.0, 1.0 / 40320.0, 1.0 / 5040.0, 1.0 / 362880.0],
        [
            1.0 / 3628800.0,
            1.0 / 479001600.0,
            1.0 / 39916800.0,
            1.0 / 6227020800.0,
        ],
        [
            1.0 / 87178291200.0,
            1.0 / 20922789888000.0,
            1.0 / 1307674368000.0,
            1.0 / 355687428096000.0,
        ],
        [
            1.0 / 6402373705728000.0,
            1.0 / 2432902008176640000.0,
            1.0 / 121645100408832000.0,
            1.0 / 51090942171709440000.0,
        ],
        [
            1.0 / 1124000727777607680000.0,
            1.0 / 620448401733239439360000.0,
            1.0 / 25852016738884976640000.0,
            1.0 / 15511210043330985984000000.0,
        ],
    ];
    let (w, v) = (xi.rotation(), xi.translation());
    let t2 = w.norm_squared();
    if t2 <= T::lit(4.0) {
        // The four polynomials side by side (one SIMD vector in f32, two in f64), each by
        // Estrin's scheme (c₀ + c₁y) + y²·((c₂ + c₃y) + y²·(c₄ + c₅y)): sums of positive
        // terms. Then a and b lose at most a factor 1.5 to the subtraction (t²·Oₐ ≤
        // 0.33·Eₐ, t²·O_b ≤ 0.2·E_b): a few ε relative. y is kept ≥ 8ε so that no product
        // is subnormal for small t (slow on most FPUs; in f32, y²·(c₄ + c₅y) would be for
        // t < 5·10⁻³); this moves a and b by at most 8ε·c₁/c₀ ≤ 0.03 ε relative.
        let y = (t2 * t2).max(T::lit(8.0) * T::EPS);
        let y2 = y * y;
        let pair = |m: usize| -> [T; 4] {
            core::array::from_fn(|l| T::lit(C[m][l]) + y * T::lit(C[m + 1][l]))
        };
        let (p0, p1, p2) = (pair(0), pair(2), pair(4));
        let s: [T; 4] = core::array::from_fn(|l| p0[l] + y2 * (p1[l] + y2 * p2[l]));
        let (a, b) = (s[0] - t2 * s[1], s[2] - t2 * s[3]);
        let wv = w.cross(&v);
        let out = v + wv.scale(a) + w.cross(&wv).scale(b);
        // One test for all three: a sum of finite numbers is finite or (rarely) overflows,
        // which only sends a good result down the slow path.
        if (out.0[0] + out.0[1] + out.0[2]).is_finite() {
            return out;
        }
    }
    exp_translation_general(&w, &v)
}

/// The rest of [`exp_translation`], kept out of line so that the series branch inlines
/// into the surface loops: the unit-axis closed form for `t² > 4`, and the matrix form of
/// [`exp`] for NaN ω and for results that are not finite.
#[inline(never)]
fn exp_translation_general<T: Real>(w: &Vec3<T>, v: &Vec3<T>) -> Vec3<T> {
    if w.norm_squared() > T::lit(4.0) {
        let t = w.norm();
        let (s, c) = t.sin_cos_r();
        let u = w.map(|x| x / t);
        let uv = u.cross(v);
        let out = *v + uv.scale((T::ONE - c) / t) + u.cross(&uv).scale((t - s) / t);
        if out.is_finite() {
            return out;
        }
    }
    so3::ExpParts::new(w).jacobian() * *v
}

/// Logarithm: exponential coordinates ξ = (ω, v), ‖ω‖ ∈ [0, π], with `Exp(ξ) = T`.
///
/// Corresponds to pytransform3d's `exponential_coordinates_from_transform`. Method: ω
/// from [`so3::log`], `v = J⁻¹(ω)·p`.
///
/// # Accuracy
///
/// A few ε (relative to ‖p‖ for v) away from π; ω to a few ε at any angle up to π (see
/// [`so3::log_axis_angle`]).
///
/// # Example
///
/// ```
/// use ppoe::{se3, Transform, Vector};
/// // A pure translation: ω = 0, v = p.
/// let t = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., -2., 3.]);
/// assert_eq!(se3::log(&t), Vector([0.0, 0.0, 0.0, 1.0, -2.0, 3.0]));
/// // Log inverts Exp (rotation angles below π).
/// let xi = Vector([-1.0, 0.5, 2.0, 0.1, 0.2, 0.3]);
/// approx::assert_abs_diff_eq!(se3::log(&se3::exp(&xi)), xi, epsilon = 1e-14);
/// ```
#[inline]
pub fn log<T: Real>(t: &Transform<T>) -> Vec6<T> {
    let w = so3::log(&t.rotation);
    let v = so3::left_jacobian_inv(&w) * t.translation;
    Vec6::from_parts(w, v)
}

/// The coefficients m₂, m₃, m₄ of the Q block (Barfoot's "Q" of the SE(3) Jacobian),
/// with pytransform3d's Horner polynomials below 0.5 (precision-independent: their
/// truncation error is < 10⁻¹⁶ there). Out of line: inlined into [`q_matrix`], both
/// branches' code made `se3::left_jacobian` slower in f32 (register pressure).
#[inline(never)]
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
/// Matches pytransform3d's internal Q (the one its `left_jacobian_SE3_inv` and
/// `pose_fusion` use), including its Horner-polynomial branch below ‖φ‖ = 0.5.
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
/// `screw_axis_from_screw_parameters`. s is divided by its largest component before it
/// is normalised, so any nonzero finite s works, subnormal or huge; ŝ is a unit vector
/// to a few ε.
///
/// # Errors
///
/// [`Error::ZeroAxis`] if s = 0, [`Error::NonFinite`] for NaN anywhere or non-finite q,
/// s, [`Error::Overflow`] if `q × ŝ + h·ŝ` overflows.
///
/// # Example
///
/// ```
/// use ppoe::{se3::screw_axis, Error, Vec3, Vector};
/// // Revolute (h = 0) about z through (1, 0, 0); the direction is normalised.
/// let s = screw_axis(&Vec3::new(1.0, 0.0, 0.0), &Vec3::new(0.0, 0.0, 2.0), 0.0)?;
/// assert_eq!(s, Vector([0.0, 0.0, 1.0, 0.0, -1.0, 0.0])); // (ŝ, q × ŝ)
/// // Prismatic (h = ∞) along x: no rotation, and q does not matter.
/// let s = screw_axis(&Vec3::new(5.0, 5.0, 5.0), &Vec3::new(3.0, 0.0, 0.0), f64::INFINITY)?;
/// assert_eq!(s, Vector([0.0, 0.0, 0.0, 1.0, 0.0, 0.0]));
/// assert_eq!(screw_axis(&Vec3::zeros(), &Vec3::zeros(), 0.0), Err(Error::ZeroAxis));
/// # Ok::<(), Error>(())
/// ```
pub fn screw_axis<T: Real>(q: &Vec3<T>, s: &Vec3<T>, h: T) -> Result<Vec6<T>, Error> {
    if !s.is_finite() || h.is_nan() || (h.is_finite() && !q.is_finite()) {
        return Err(Error::NonFinite);
    }
    let m = s.amax();
    if m == T::ZERO {
        return Err(Error::ZeroAxis);
    }
    // Divided (1/m overflows for subnormal m): one component ±1, so ‖s‖ ∈ [1, √3].
    let s = s.map(|x| x / m);
    let s = s.scale(T::ONE / s.norm());
    if h.is_infinite() {
        return Ok(Vec6::from_parts(Vec3::zeros(), s));
    }
    let screw = Vec6::from_parts(s, q.cross(&s) + s.scale(h));
    screw.is_finite().then_some(screw).ok_or(Error::Overflow)
}
