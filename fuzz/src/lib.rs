//! Shared input types and oracles of the ppoe fuzz targets (see FUZZING.md).
//!
//! Every fuzz input is decoded into structured values with `arbitrary`. Scalars are
//! [`FVal`]s: either a raw bit pattern (NaN, ±∞, subnormals, huge, tiny — anything), an
//! ordinary small value, or one of a table of special values, so that the fuzzer reaches
//! both the invalid inputs and the valid domain where the output properties are checked.

#![forbid(unsafe_code)]

pub mod core_checks;
pub mod eigen_checks;
pub mod mesh_checks;
pub mod noise_checks;
pub mod table_checks;
pub mod urdf_checks;

use arbitrary::Arbitrary;
use num_traits::Float;
use ppoe::linalg::{Mat3, Mat6, Matrix, Vec3, Vec6, Vector};
use ppoe::{so3, Real, Transform};

/// One fuzzed scalar.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum FVal {
    /// Any bit pattern (the low 32 bits for f32).
    Bits(u64),
    /// `i / 1024`: ordinary values in [−32, 32).
    Small(i16),
    /// `i / 128`: values in [−1, 1).
    Unit(i8),
    /// An entry of [`special`].
    Special(u8),
}

/// The scalar types under test, with what the fuzz targets need on top of [`Real`].
pub trait Fz: Real + Float {
    /// The value with these bits (f32: the low 32 bits).
    fn from_bits64(u: u64) -> Self;
    /// Bound of the "valid domain" of the output oracles: inputs within it must give
    /// finite, symmetric, PSD outputs (see FUZZING.md for why a bound is needed).
    const BOUND: f64;
    /// The smallest positive subnormal.
    fn denorm_min() -> Self;
    /// Name for messages.
    const NAME: &'static str;
}

impl Fz for f64 {
    fn from_bits64(u: u64) -> Self {
        f64::from_bits(u)
    }
    const BOUND: f64 = 1e3;
    fn denorm_min() -> Self {
        f64::from_bits(1)
    }
    const NAME: &'static str = "f64";
}

impl Fz for f32 {
    fn from_bits64(u: u64) -> Self {
        f32::from_bits(u as u32)
    }
    const BOUND: f64 = 10.0;
    fn denorm_min() -> Self {
        f32::from_bits(1)
    }
    const NAME: &'static str = "f32";
}

/// The special values.
pub fn special<T: Fz>(i: u8) -> T {
    let table: [T; 24] = [
        T::ZERO,
        -T::ZERO,
        T::ONE,
        -T::ONE,
        T::nan(),
        T::infinity(),
        T::neg_infinity(),
        T::min_positive_value(),
        T::denorm_min(),
        T::max_value(),
        T::min_value(),
        T::EPS,
        T::PI(),
        T::PI() - T::lit(1e-7),
        T::PI() + T::lit(1e-7),
        T::lit(2.0) * T::PI(),
        T::lit(1e-300),
        T::lit(1e300),
        T::TOL,
        T::SERIES,
        T::lit(0.5),
        T::lit(1e-3),
        T::lit(1e3),
        -T::nan(),
    ];
    table[i as usize % table.len()]
}

impl FVal {
    /// The value as `T`.
    pub fn get<T: Fz>(self) -> T {
        match self {
            FVal::Bits(u) => T::from_bits64(u),
            FVal::Small(i) => T::lit(i as f64 / 1024.0),
            FVal::Unit(i) => T::lit(i as f64 / 128.0),
            FVal::Special(i) => special(i),
        }
    }
}

/// N values.
pub fn vals<T: Fz, const N: usize>(v: &[FVal; N]) -> Vector<T, N> {
    Vector(v.map(|x| x.get()))
}

/// A rotation: raw 3×3 values or Exp of a rotation vector.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum RotIn {
    /// Nine raw values (usually not a rotation).
    Raw([FVal; 9]),
    /// `so3::exp(w)`.
    Exp([FVal; 3]),
    /// The identity.
    Identity,
}

/// A transform.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct TransformIn {
    /// The rotation.
    pub rot: RotIn,
    /// The translation.
    pub p: [FVal; 3],
}

impl TransformIn {
    /// The transform.
    pub fn get<T: Fz>(&self) -> Transform<T> {
        let rotation = match &self.rot {
            RotIn::Raw(v) => {
                let v: [T; 9] = v.map(|x| x.get());
                Mat3::from_rows([[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]])
            }
            RotIn::Exp(w) => so3::exp(&vals(w)),
            RotIn::Identity => Mat3::identity(),
        };
        Transform {
            rotation,
            translation: vals(&self.p),
        }
    }
}

/// A 6×6 covariance.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum CovIn {
    /// 36 raw values (usually not symmetric).
    Raw([FVal; 36]),
    /// The lower triangle (21 values), mirrored: exactly symmetric, maybe indefinite.
    Sym([FVal; 21]),
    /// `A·Aᵀ` of the 6×k matrix A (k = 1..6, the values padded with 0), mirrored: PSD up
    /// to rounding, any rank.
    Gram(u8, [FVal; 36]),
    /// A diagonal matrix.
    Diag([FVal; 6]),
    /// `s·I`.
    Scaled(FVal),
}

/// A symmetric N×N matrix from its lower triangle given row by row.
pub fn mirror<T: Fz, const N: usize>(lower: &[T]) -> Matrix<T, N, N> {
    let mut m = Matrix::<T, N, N>::zeros();
    let mut k = 0;
    for i in 0..N {
        for j in 0..=i {
            let x = lower.get(k).copied().unwrap_or(T::ZERO);
            m.0[i][j] = x;
            m.0[j][i] = x;
            k += 1;
        }
    }
    m
}

/// `A·Aᵀ` for the N×N matrix with the first `rank` columns from `v`, exactly symmetric.
pub fn gram<T: Fz, const N: usize>(rank: u8, v: &[T]) -> Matrix<T, N, N> {
    let rank = (rank as usize % N) + 1;
    let mut a = Matrix::<T, N, N>::zeros();
    for i in 0..N {
        for j in 0..rank {
            a.0[i][j] = v.get(i * N + j).copied().unwrap_or(T::ZERO);
        }
    }
    Matrix::<T, N, N>::identity().congruence(&a)
}

impl CovIn {
    /// Positive semi-definite by construction (up to the rounding of `A·Aᵀ`): a Gram
    /// matrix, a diagonal with no negative or NaN entry, or `s·I` with s ≥ 0. Raw and
    /// mirrored inputs may be indefinite, however small their negative eigenvalue.
    pub fn psd_by_construction<T: Fz>(&self) -> bool {
        match self {
            CovIn::Raw(_) | CovIn::Sym(_) => false,
            CovIn::Gram(..) => true,
            CovIn::Diag(v) => v.iter().all(|x| x.get::<T>() >= T::ZERO),
            CovIn::Scaled(s) => s.get::<T>() >= T::ZERO,
        }
    }

    /// The matrix.
    pub fn get<T: Fz>(&self) -> Mat6<T> {
        match self {
            CovIn::Raw(v) => {
                let v: [T; 36] = v.map(|x| x.get());
                let mut m = Mat6::zeros();
                for i in 0..6 {
                    for j in 0..6 {
                        m.0[i][j] = v[i * 6 + j];
                    }
                }
                m
            }
            CovIn::Sym(v) => mirror::<T, 6>(&v.map(|x| x.get())),
            CovIn::Gram(r, v) => gram::<T, 6>(*r, &v.map(|x| x.get())),
            CovIn::Diag(v) => Mat6::from_diagonal(&vals(v)),
            CovIn::Scaled(s) => Mat6::<T>::identity() * s.get::<T>(),
        }
    }
}

/// Largest absolute value of a slice of scalars (NaN counts as +∞).
pub fn amax_of<T: Fz>(xs: impl IntoIterator<Item = T>) -> T {
    xs.into_iter().fold(T::ZERO, |m, x| {
        if x.is_nan() {
            T::infinity()
        } else {
            m.max(x.abs())
        }
    })
}

/// `max |m_ij|` (NaN → ∞).
pub fn mat_amax<T: Fz, const R: usize, const C: usize>(m: &Matrix<T, R, C>) -> T {
    amax_of(m.0.iter().flatten().copied())
}

/// `max |v_i|` (NaN → ∞).
pub fn vec_amax<T: Fz, const N: usize>(v: &Vector<T, N>) -> T {
    amax_of(v.0.iter().copied())
}

/// `‖RᵀR − I‖_max`, computed here (not by the library).
pub fn ortho_error<T: Fz>(r: &Mat3<T>) -> T {
    let mut e = T::ZERO;
    for i in 0..3 {
        for j in 0..3 {
            let mut s = T::ZERO;
            for k in 0..3 {
                s += r.0[k][i] * r.0[k][j];
            }
            let d = if i == j { s - T::ONE } else { s };
            e = e.max(d.abs());
            if d.is_nan() {
                return T::infinity();
            }
        }
    }
    e
}

/// `det R`, computed here.
pub fn det3<T: Fz>(r: &Mat3<T>) -> T {
    let m = r.0;
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// `true` if every element is finite.
pub fn transform_finite<T: Fz>(t: &Transform<T>) -> bool {
    t.rotation.is_finite() && t.translation.is_finite()
}

/// Asserts that `t` is finite with an orthonormal rotation (`‖RᵀR − I‖ ≤ tol`, det > 0).
#[track_caller]
pub fn assert_rigid<T: Fz>(what: &str, t: &Transform<T>, tol: T) {
    assert!(
        transform_finite(t),
        "{what} ({}): not finite: {t:?}",
        T::NAME
    );
    let e = ortho_error(&t.rotation);
    assert!(
        e <= tol,
        "{what} ({}): ‖RᵀR − I‖ = {:e} > {:e}: {t:?}",
        T::NAME,
        e.to_f64(),
        tol.to_f64()
    );
    assert!(
        det3(&t.rotation) > T::ZERO,
        "{what} ({}): det R ≤ 0: {t:?}",
        T::NAME
    );
}

/// Asserts that a covariance output is finite and exactly symmetric.
#[track_caller]
pub fn assert_sym<T: Fz, const N: usize>(what: &str, c: &Matrix<T, N, N>) {
    assert!(c.is_finite(), "{what} ({}): not finite: {c:?}", T::NAME);
    assert_sym_bits(what, c);
}

/// Asserts that a matrix is exactly symmetric (NaN matches NaN; for outputs of inputs
/// outside the valid domain, which may overflow).
#[track_caller]
pub fn assert_sym_bits<T: Fz, const N: usize>(what: &str, c: &Matrix<T, N, N>) {
    for i in 0..N {
        for j in 0..i {
            assert!(
                c.0[i][j].to_bits_eq(c.0[j][i]),
                "{what} ({}): not exactly symmetric at ({i}, {j}): {:e} vs {:e}",
                T::NAME,
                c.0[i][j].to_f64(),
                c.0[j][i].to_f64()
            );
        }
    }
}

/// Bitwise-equal comparison that treats +0 and −0 as equal.
pub trait BitsEq {
    /// `self == other` or both NaN.
    fn to_bits_eq(self, other: Self) -> bool;
}
impl<T: Fz> BitsEq for T {
    fn to_bits_eq(self, other: T) -> bool {
        self == other || (self.is_nan() && other.is_nan())
    }
}

/// Asserts that a covariance output is finite, exactly symmetric and passes
/// `check_covariance` (PSD within the library's tolerance).
#[track_caller]
pub fn assert_cov<T: Fz, const N: usize>(what: &str, c: &Matrix<T, N, N>) {
    assert_sym(what, c);
    if let Err(e) = ppoe::uncertainty::check_covariance(c) {
        let eig = ppoe::linalg::SymmetricEigen::new(c).map(|e| e.values);
        panic!(
            "{what} ({}): output covariance fails check_covariance: {e:?}; eigenvalues {eig:?}; {c:?}",
            T::NAME
        );
    }
}

/// A 3-vector of this kind is used as is.
pub type V3<T> = Vec3<T>;
/// A 6-vector.
pub type V6<T> = Vec6<T>;
