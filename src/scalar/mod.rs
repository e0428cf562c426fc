//! The scalar abstraction: one trait, [`Real`], implemented for `f32` and `f64`.
//!
//! Every algorithm in this crate is written once, generically over [`Real`]. The trait
//! carries the precision-dependent constants (series cut-offs, near-π thresholds,
//! tolerances), each derived from the type's machine epsilon, so that `f32` users do not
//! inherit thresholds tuned for `f64` (which in f32 makes series cut-offs too small and
//! tolerances unreachable).
//! It is also the single place where the elementary functions (sin, cos, sqrt, atan2)
//! are chosen per precision.
//!
//! ```
//! use ppoe::{so3, Real, Vec3};
//! // Written once, run in f32 and f64: T's own ε and tolerances come with it.
//! fn angle<T: Real>(w: &Vec3<T>) -> T {
//!     so3::log_axis_angle(&so3::exp(w)).1
//! }
//! assert!((angle(&Vec3::new(0.0_f32, 0.0, 0.5)) - 0.5).abs() <= 4.0 * f32::EPS);
//! assert!((angle(&Vec3::new(0.0_f64, 0.0, 0.5)) - 0.5).abs() <= 4.0 * f64::EPS);
//! assert!(f64::from(f32::TOL) > 1e4 * f64::TOL); // √ε of each type: 3.5e-4, 1.5e-8
//! ```

use core::fmt::{Debug, Display};
use core::ops::{AddAssign, DivAssign, MulAssign, SubAssign};
use num_traits::{Float, FloatConst};

mod sincos;

mod sealed {
    /// Seals [`Real`](super::Real), and holds the per-type kernels the crate picks by scalar
    /// without making them public API.
    pub trait Sealed: Sized + Copy {
        /// `(sin, cos)` of every lane, as [`Real::sin_cos_r`](super::Real::sin_cos_r) of
        /// each, for the batch PPOE's packs (the same bits). f64 writes the lanes in a
        /// loop: its inlined sin/cos is large enough that `array::from_fn` around it stays
        /// a call, which clobbers every SSE register of the caller. f32 builds the arrays
        /// with `from_fn`, which stays inlined there; its lanes written one by one into an
        /// array would make the vector reads after it wait on the scalar writes.
        fn sin_cos_lanes<const W: usize>(x: [Self; W]) -> ([Self; W], [Self; W]);
    }

    impl Sealed for f64 {
        #[inline(always)]
        fn sin_cos_lanes<const W: usize>(x: [f64; W]) -> ([f64; W], [f64; W]) {
            let (mut s, mut c) = ([0.0; W], [0.0; W]);
            for ((s, c), x) in s.iter_mut().zip(c.iter_mut()).zip(x) {
                (*s, *c) = super::sincos::sin_cos_f64(x);
            }
            (s, c)
        }
    }

    impl Sealed for f32 {
        #[inline(always)]
        fn sin_cos_lanes<const W: usize>(x: [f32; W]) -> ([f32; W], [f32; W]) {
            let sc: [(f32, f32); W] = core::array::from_fn(|l| {
                super::sincos::sin_cos_f32(x.get(l).copied().unwrap_or(0.0))
            });
            (sc.map(|v| v.0), sc.map(|v| v.1))
        }
    }
}

/// A floating-point scalar: `f32` or `f64`.
///
/// The trait is sealed: the constants below are tuned and tested for these two types.
///
/// | constant | f64 | f32 | derivation |
/// |---|---|---|---|
/// | [`EPS`](Real::EPS) | 2⁻⁵² | 2⁻²³ | machine epsilon |
/// | [`SERIES`](Real::SERIES) | 2⁻¹³ | 2⁻⁶ | ≈ ε^¼: below it the 3-term Taylor series of the SO(3)/SE(3) coefficients is exact to ε |
/// | [`TOL`](Real::TOL) | ≈1.5·10⁻⁸ | ≈3.5·10⁻⁴ | √ε: default relative tolerance of the input checks |
pub trait Real:
    Float
    + FloatConst
    + Debug
    + Display
    + Default
    + Send
    + Sync
    + 'static
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + approx::AbsDiffEq<Epsilon = Self>
    + approx::RelativeEq
    + approx::UlpsEq
    + sealed::Sealed
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 0.5.
    const HALF: Self;
    /// Machine epsilon (the difference between 1 and the next larger number).
    const EPS: Self;
    /// Angle below which exp/log/Jacobian coefficients use their Taylor series (≈ ε^¼).
    const SERIES: Self;
    /// Default relative tolerance of the checked entry points (√ε): symmetry and
    /// positive semi-definiteness of covariances, orthonormality of rotations.
    const TOL: Self;

    /// Converts an `f64` constant to this type (rounding to nearest for `f32`).
    fn lit(x: f64) -> Self;

    /// Converts to `f64` (exact for both types).
    fn to_f64(self) -> f64;

    /// Converts a small count to this type (exact up to 2²⁴).
    fn from_usize(n: usize) -> Self;

    /// Sine and cosine of `self`.
    ///
    /// Method and accuracy: libm's `sin`/`cos` (musl/FreeBSD, < 1 ulp).
    #[inline]
    fn sin_cos_r(self) -> (Self, Self) {
        Float::sin_cos(self)
    }
}

impl Real for f64 {
    const ZERO: f64 = 0.0;
    const ONE: f64 = 1.0;
    const TWO: f64 = 2.0;
    const HALF: f64 = 0.5;
    const EPS: f64 = f64::EPSILON;
    const SERIES: f64 = 1.220_703_125e-4; // 2^-13 ≈ eps^(1/4) = 1.22e-4
    const TOL: f64 = 1.490_116_119_384_765_6e-8; // sqrt(eps) = 2^-26

    #[inline]
    fn lit(x: f64) -> f64 {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn from_usize(n: usize) -> f64 {
        n as f64
    }

    /// libm's `sincos` (FreeBSD msun; one shared range reduction; < 1 ulp), bit for bit:
    /// on targets with 128-bit SIMD (x86-64, AArch64) its branches for |x| ≲ 5π/4 (a
    /// revolute joint's angles within ±225°, except within 2⁻²⁰ relative of ±π/2 and ±π)
    /// are inlined, elsewhere those for |x| ≤ π/4; the rest stays a call. A call
    /// clobbers every SSE register, so the caller would spill its live values around
    /// each joint's sin/cos; inlined, the polynomials also overlap the neighbouring
    /// joints' work.
    #[inline(always)]
    fn sin_cos_r(self) -> (f64, f64) {
        sincos::sin_cos_f64(self)
    }
}

impl Real for f32 {
    const ZERO: f32 = 0.0;
    const ONE: f32 = 1.0;
    const TWO: f32 = 2.0;
    const HALF: f32 = 0.5;
    const EPS: f32 = f32::EPSILON;
    const SERIES: f32 = 0.015_625; // 2^-6 ≈ eps^(1/4) = 1.86e-2
    const TOL: f32 = 3.452_669_8e-4; // sqrt(eps) = 2^-11.5

    #[inline]
    fn lit(x: f64) -> f32 {
        x as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn from_usize(n: usize) -> f32 {
        n as f32
    }

    /// f32-native sine and cosine, in f32 and integer arithmetic only (libm's `sinf`/`cosf`
    /// compute in f64, which an M4F emulates in software).
    ///
    /// Method: for |x| ≤ π/4 the Cephes minimax polynomials for sin and cos (Moshier,
    /// *Methods and Programs for Mathematical Functions*, 1989) directly, evaluated by
    /// Estrin's scheme, and `(x, 1)` for |x| ≤ 2⁻¹² (the polynomials' own bits there); up
    /// to |x| = 10⁴ a Cody–Waite reduction by π/2 with a three-part constant (exact
    /// products for |k| < 2¹⁵) first; beyond, a Payne–Hanek reduction in 64-bit integers
    /// (`reduce_pio2_f32`).
    ///
    /// # Accuracy
    ///
    /// Against f64: absolute error ≤ 10⁻⁷ everywhere —
    /// measured 7.8·10⁻⁸ (0.65 ulp of 1) on a fine sweep of |x| ≤ 10⁴, and 7.9·10⁻⁸ on
    /// *every* f32 above 10⁴ (an exhaustive test, `--ignored`). NaN and ±∞ give NaN.
    #[inline(always)]
    fn sin_cos_r(self) -> (f32, f32) {
        sincos::sin_cos_f32(self)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::Real;

    fn check_derivations<T: Real>() {
        let eps = T::EPS.to_f64();
        let series = T::SERIES.to_f64();
        // Within a factor 2 of eps^(1/4), and the dropped Taylor term t^6/5040 is below eps.
        assert!(series <= eps.powf(0.25) * 2.0 && series >= eps.powf(0.25) / 2.0);
        assert!(series.powi(6) / 5040.0 < eps);
        let tol = T::TOL.to_f64();
        assert!((tol - eps.sqrt()).abs() / eps.sqrt() < 1e-6);
    }

    #[test]
    fn constants_follow_epsilon() {
        check_derivations::<f32>();
        check_derivations::<f64>();
    }
}
