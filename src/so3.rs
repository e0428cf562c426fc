//! SO(3): the rotation group. Rotation vectors ω = θ·u (unit axis u, angle θ), the
//! exponential map (Rodrigues), the logarithm and the left Jacobian.
//!
//! Conventions: a rotation matrix R maps vectors of the rotated frame into the reference
//! frame (`x_ref = R · x_rot`, pytransform3d's `A2B`). [`hat`]`(ω)·x = ω × x`.
//! Jacobians are *left* Jacobians: `Exp(ω + δ) ≈ Exp(J(ω)·δ)·Exp(ω)`.
//!
//! ```
//! use ppoe::{so3, Vec3};
//! // A quarter turn about z: the rotated frame's x axis is the reference frame's y axis.
//! let r = so3::exp(&Vec3::new(0.0, 0.0, core::f64::consts::FRAC_PI_2));
//! let x_ref = r * Vec3::new(1.0, 0.0, 0.0);
//! approx::assert_abs_diff_eq!(x_ref, Vec3::new(0.0, 1.0, 0.0), epsilon = 1e-15);
//! // hat(ω)·x is the cross product ω × x.
//! let (w, x) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, 0.5, 2.0));
//! assert_eq!(so3::hat(&w) * x, w.cross(&x));
//! ```

use crate::linalg::{Mat3, Matrix, Vec3, Vector};
use crate::scalar::Real;

/// The skew-symmetric (cross-product) matrix `[ω]×`, with `[ω]× · x = ω × x`.
#[inline]
pub fn hat<T: Real>(w: &Vec3<T>) -> Mat3<T> {
    let [x, y, z] = w.0;
    let o = T::ZERO;
    Matrix([[o, -z, y], [z, o, -x], [-y, x, o]])
}

/// The inverse of [`hat`]: the vector of the skew part, `((M₂₁−M₁₂)/2, (M₀₂−M₂₀)/2,
/// (M₁₀−M₀₁)/2)`. Exact for skew-symmetric input.
#[inline]
pub fn vee<T: Real>(m: &Mat3<T>) -> Vec3<T> {
    let a = m.0;
    Vector([
        (a[2][1] - a[1][2]) * T::HALF,
        (a[0][2] - a[2][0]) * T::HALF,
        (a[1][0] - a[0][1]) * T::HALF,
    ])
}

/// The SO(3)/SE(3) exponential of ω = t·u in the form `I + a·[x]× + b·[x]×²`, for the
/// rotation `Exp(ω)` and for the left Jacobian `J(ω)`.
///
/// Below [`Real::SERIES`]: x = ω with the Taylor series to t⁴ (truncation < ε) of
/// `sin t/t`, `(1 − cos t)/t²`, `(t − sin t)/t³`. Above: x = u (unit axis) with
/// `sin t`, `1 − cos t` and `(1 − cos t)/t`, `(t − sin t)/t`, which never overflow, even
/// for angles whose square does (f32 beyond 10¹⁹). `1 − cos t` is `sin²t/(1 + cos t)`
/// for cos t > 0 (no cancellation: a few ε relative); the cancellation in `t − sin t`
/// near the cut-off costs ≈ ε/t² relative in `(t − sin t)/t ≈ t²/6`, i.e. ε absolute.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ExpParts<T> {
    x: Vec3<T>,
    ra: T,
    rb: T,
    ja: T,
    jb: T,
}

impl<T: Real> ExpParts<T> {
    // Always inlined: once sin/cos is inlined into it the optimiser leaves it as a call,
    // and the callers' live values spill around that call.
    #[inline(always)]
    pub(crate) fn new(w: &Vec3<T>) -> Self {
        let t = w.norm();
        if t < T::SERIES {
            let t2 = t * t;
            let t4 = t2 * t2;
            let b = T::HALF - t2 / T::lit(24.0) + t4 / T::lit(720.0);
            Self {
                x: *w,
                ra: T::ONE - t2 / T::lit(6.0) + t4 / T::lit(120.0),
                rb: b,
                ja: b,
                jb: T::lit(1.0 / 6.0) - t2 / T::lit(120.0) + t4 / T::lit(5040.0),
            }
        } else {
            let (s, c) = t.sin_cos_r();
            // 1 − cos t as sin²t/(1 + cos t) while cos t > 0: no cancellation, so
            // (1 − cos t)/t keeps a few ε relative just above the cut-off (the
            // subtraction lost ε/t there).
            let omc = if c > T::ZERO {
                s * s / (T::ONE + c)
            } else {
                T::ONE - c
            };
            Self {
                x: w.map(|v| v / t),
                ra: s,
                rb: omc,
                ja: omc / t,
                jb: (t - s) / t,
            }
        }
    }

    /// `Exp(ω)`.
    #[inline]
    pub(crate) fn rotation(&self) -> Mat3<T> {
        i_plus_aw_bw2(&self.x, self.ra, self.rb)
    }

    /// The left Jacobian `J(ω)`.
    #[inline]
    pub(crate) fn jacobian(&self) -> Mat3<T> {
        i_plus_aw_bw2(&self.x, self.ja, self.jb)
    }
}

/// `I + a·W + b·W²` for `W = [w]×`, without forming W².
#[inline]
pub(crate) fn i_plus_aw_bw2<T: Real>(w: &Vec3<T>, a: T, b: T) -> Mat3<T> {
    let [x, y, z] = w.0;
    let (xx, yy, zz) = (x * x, y * y, z * z);
    let (xy, xz, yz) = (x * y, x * z, y * z);
    Matrix([
        [T::ONE - b * (yy + zz), b * xy - a * z, b * xz + a * y],
        [b * xy + a * z, T::ONE - b * (xx + zz), b * yz - a * x],
        [b * xz - a * y, b * yz + a * x, T::ONE - b * (xx + yy)],
    ])
}

/// Exponential map `Exp(ω)`: the rotation by angle ‖ω‖ about ω (Rodrigues' formula
/// `R = I + (sin θ/θ)·W + ((1 − cos θ)/θ²)·W²`, `W = [ω]×`).
///
/// Corresponds to pytransform3d's `matrix_from_compact_axis_angle`. Non-finite input
/// gives non-finite output.
///
/// # Accuracy
///
/// Absolute error of a few ε in every element for any ω (no angle wrapping is needed;
/// sin and cos are periodic).
///
/// # Example
///
/// ```
/// use ppoe::{so3, Vec3};
/// // About z by θ: the closed form [[cos θ, −sin θ, 0], [sin θ, cos θ, 0], [0, 0, 1]].
/// let t = 0.7_f64;
/// let r = so3::exp(&Vec3::new(0.0, 0.0, t));
/// let rz = [[t.cos(), -t.sin(), 0.0], [t.sin(), t.cos(), 0.0], [0.0, 0.0, 1.0]];
/// approx::assert_abs_diff_eq!(r, ppoe::Mat3::from_rows(rz), epsilon = 1e-15);
/// // f32 works the same way, with f32's own series cut-off (`Real::SERIES`).
/// let r32 = so3::exp(&Vec3::new(0.0_f32, 0.0, 0.7));
/// assert!((r32.0[1][0] - 0.7_f32.sin()).abs() < 1e-6);
/// ```
#[inline]
pub fn exp<T: Real>(w: &Vec3<T>) -> Mat3<T> {
    ExpParts::new(w).rotation()
}

/// Logarithm as unit axis and angle: `R = Exp(angle · axis)` with angle ∈ [0, π].
///
/// Method: angle = atan2(½‖r‖, (tr R − 1)/2) with r the skew part `(R₂₁−R₁₂, R₀₂−R₂₀,
/// R₁₀−R₀₁)`, as pytransform3d 3.17's `axis_angle_from_matrix`. Axis: r/‖r‖ up to
/// θ = π/2; beyond, where r shrinks towards π and loses its direction to rounding, the
/// row k of `S − cos θ·I` (= (1 − cos θ)·u_k·uᵀ, S = (R + Rᵀ)/2) with the largest
/// diagonal element, normalised, overall sign fixed by r (at exactly π the largest
/// component is positive, as in the reference). Angle 0 returns axis (1, 0, 0).
///
/// Never NaN for finite input; the input need not be exactly orthonormal.
///
/// # Accuracy
///
/// Of the axis, for elements of R accurate to a few ε: ≈ ε/sin θ up to π/2 (the
/// axis's own conditioning for small angles, ≤ √2·ε from π/4 on), a few ε beyond; within
/// 16 ε of the exact axis for θ ∈ [π/2, π] and within 4 ε/sin θ below
/// (the repository's numerical robustness tests). pytransform3d, which switches only 10⁻⁶
/// from π, has
/// an axis error ≈ ε/δ at π − δ outside that band (2·10⁻¹⁰ at its edge) and up to δ/2
/// inside it.
pub fn log_axis_angle<T: Real>(rot: &Mat3<T>) -> (Vec3<T>, T) {
    let m = rot.0;
    let r = Vector([m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]]);
    let cos = ((rot.trace() - T::ONE) * T::HALF).max(-T::ONE).min(T::ONE);
    let rn = r.norm();
    let angle = (rn * T::HALF).atan2(cos);
    let x_axis = Vector([T::ONE, T::ZERO, T::ZERO]);
    if angle == T::ZERO || !angle.is_finite() {
        return (x_axis, angle);
    }
    // Up to π/2 the skew part 2·sin θ·u carries the axis to ε/sin θ ≤ √2·ε; beyond, the
    // symmetric part does better (below).
    if cos >= T::ZERO {
        let inv = T::ONE / rn;
        if inv.is_finite() {
            return (r.scale(inv), angle);
        }
        // A subnormal skew part: 1/‖r‖ overflows, so normalise by division instead.
        let m = r.amax();
        let rs = r.map(|x| x / m);
        return (rs.scale(T::ONE / rs.norm()), angle);
    }
    // Towards π the skew part ≈ 2δ·u (θ = π − δ) loses its direction to rounding (ε/δ);
    // the symmetric part is S = cos θ·I + (1 − cos θ)·u·uᵀ with 1 − cos θ ≥ 1, so the row
    // of B = S − cos θ·I with the largest diagonal element (|u_k| ≥ 1/√3) is
    // (1 − cos θ)·u_k·u: normalised, u to a few ε. (pytransform3d uses the skew part up
    // to 10⁻⁶ from π, then |uᵢ| = √((Sᵢᵢ + 1)/2), off by up to δ/2 in a component near 0.)
    let sym = rot.symmetrize();
    let b = sym - Mat3::identity() * cos;
    let d = b.diagonal();
    let mut k = 0;
    for i in 1..3 {
        if d.0[i] > d.0[k] {
            k = i;
        }
    }
    let row = Vector(b.0[k]);
    let n = row.norm();
    if n.is_nan() || n <= T::ZERO || !n.is_finite() {
        return (x_axis, angle);
    }
    // Row k has the sign of u_k; the skew part fixes the overall sign below π. At
    // exactly π the largest component stays positive, as in the reference.
    let mut a = row.scale(T::ONE / n);
    if angle < T::PI() && a.dot(&r) < T::ZERO {
        a = -a;
    }
    (a, angle)
}

/// Logarithm `Log(R)`: the rotation vector ω = angle · axis with ‖ω‖ ∈ [0, π]
/// (see [`log_axis_angle`] for method and accuracy).
///
/// Corresponds to pytransform3d's `compact_axis_angle_from_matrix`.
///
/// ```
/// use ppoe::{so3, Vec3};
/// // Log inverts Exp up to an angle of π ...
/// let w = Vec3::new(0.3, -1.2, 0.8);
/// approx::assert_abs_diff_eq!(so3::log(&so3::exp(&w)), w, epsilon = 1e-14);
/// // ... and beyond π returns the same rotation with angle 2π − ‖ω‖ about −ω.
/// let w = Vec3::new(0.0, 0.0, 4.0);
/// let expected = Vec3::new(0.0, 0.0, 4.0 - 2.0 * core::f64::consts::PI);
/// approx::assert_abs_diff_eq!(so3::log(&so3::exp(&w)), expected, epsilon = 1e-14);
/// ```
#[inline]
pub fn log<T: Real>(rot: &Mat3<T>) -> Vec3<T> {
    let (axis, angle) = log_axis_angle(rot);
    axis.scale(angle)
}

/// Left Jacobian of SO(3): `J(ω) = I + ((1 − cos θ)/θ²)·W + ((θ − sin θ)/θ³)·W²`.
///
/// Corresponds to pytransform3d's `left_jacobian_SO3`; series below [`Real::SERIES`].
///
/// # Accuracy
///
/// A few ε absolute in every element for any ω, including just above the series
/// cut-off (within 8 ε of a series oracle for θ ∈ [SERIES, 64·SERIES],
/// measured by the repository's numerical robustness tests).
///
/// # Example
///
/// ```
/// use ppoe::{so3, Vec3};
/// let w = Vec3::new(0.4, -0.3, 1.1);
/// let j = so3::left_jacobian(&w);
/// // J(ω)·ω = ω: a step along ω only changes the angle.
/// approx::assert_abs_diff_eq!(j * w, w, epsilon = 1e-15);
/// // The left perturbation: Exp(ω + δ) = Exp(J(ω)·δ)·Exp(ω) + O(‖δ‖²).
/// let d = Vec3::new(1e-6, 2e-6, -1e-6);
/// let lhs = so3::exp(&(w + d));
/// let rhs = so3::exp(&(j * d)) * so3::exp(&w);
/// approx::assert_abs_diff_eq!(lhs, rhs, epsilon = 1e-11);
/// ```
#[inline]
pub fn left_jacobian<T: Real>(w: &Vec3<T>) -> Mat3<T> {
    ExpParts::new(w).jacobian()
}

/// Inverse left Jacobian of SO(3): `J⁻¹(ω) = I − ½W + ((1 − (θ/2)cot(θ/2))/θ²)·W²`.
///
/// Corresponds to pytransform3d's `left_jacobian_SO3_inv`; series below [`Real::SERIES`].
/// Singular (infinite) at θ = 2π·k, k ≠ 0; finite for θ < 2π.
#[inline]
pub fn left_jacobian_inv<T: Real>(w: &Vec3<T>) -> Mat3<T> {
    let t = w.norm();
    if t < T::SERIES {
        // (1 − (t/2)·cot(t/2))/t² = 1/12 + t²/720 + t⁴/30240 + …
        let t2 = t * t;
        let d = T::lit(1.0 / 12.0) + t2 / T::lit(720.0) + t2 * t2 / T::lit(30240.0);
        i_plus_aw_bw2(w, -T::HALF, d)
    } else {
        // Unit-axis form: no t² that could overflow.
        let half = t * T::HALF;
        let (s, c) = half.sin_cos_r();
        i_plus_aw_bw2(&w.map(|v| v / t), -half, T::ONE - half * c / s)
    }
}

/// `true` if `rot` is a rotation within tolerance `tol`: finite, `‖RᵀR − I‖_max ≤ tol` and
/// `det R > 0`.
pub fn is_rotation<T: Real>(rot: &Mat3<T>, tol: T) -> bool {
    rot.is_finite()
        && (rot.transpose() * *rot - Mat3::identity()).amax() <= tol
        && rot.determinant() > T::ZERO
}
