//! Fixed-size vectors and matrices: [`Vector`] and [`Matrix`], with the aliases used
//! throughout the crate ([`Vec3`], [`Vec6`], [`Mat3`], [`Mat6`]).
//!
//! Storage is a plain array (row-major for matrices) in a public field, so data goes in
//! and out without our types: `Mat6::from(array)`, `m.0[i][j]`, `<[[T; 6]; 6]>::from(m)`.
//! All loops have compile-time bounds, so indexing cannot panic and is unrolled by the
//! optimiser.
//!
//! ```
//! use ppoe::{Mat3, Mat6, Vec3, Vec6, Vector};
//! let a = Vec3::new(1.0, 2.0, 2.0);
//! assert_eq!(a.norm(), 3.0);
//! assert_eq!(a.cross(&Vec3::new(0.0, 0.0, 1.0)), Vec3::new(2.0, -1.0, 0.0));
//! let m = Mat3::from_rows([[2.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 4.0]]);
//! assert_eq!(m * a, Vec3::new(2.0, 6.0, 8.0)); // matrix times column vector
//! assert_eq!(m.determinant(), 24.0);
//! // 6-vectors and 6×6 blocks are rotation first: (ω, v) and [[ωω, ωv], [vω, vv]].
//! let xi: Vec6<f64> = Vector([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
//! assert_eq!(xi.translation(), Vec3::new(4.0, 5.0, 6.0));
//! let c = Mat6::from_blocks(&m, &Mat3::zeros(), &Mat3::zeros(), &Mat3::identity());
//! assert_eq!(c.block(0, 0), m);
//! assert_eq!(<[[f64; 6]; 6]>::from(c)[5][5], 1.0); // plain arrays in and out
//! ```

mod approx_eq;
mod cholesky;
mod eigen;

pub(crate) use approx_eq::approx_fields;
pub(crate) use eigen::symmetric_part;
pub use eigen::{SymmetricEigen, MAX_SWEEPS};

use crate::scalar::Real;
use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A column vector of `N` scalars.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vector<T, const N: usize>(pub [T; N]);

/// An `R`×`C` matrix stored row-major: `self.0[row][column]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Matrix<T, const R: usize, const C: usize>(pub [[T; C]; R]);

/// A 3-vector (a point, a translation, a rotation vector ω).
pub type Vec3<T> = Vector<T, 3>;
/// A 6-vector in rotation-first order (ω, v): a twist, a screw axis or exponential
/// coordinates of SE(3).
pub type Vec6<T> = Vector<T, 6>;
/// A 3×3 matrix (a rotation, a 3D covariance).
pub type Mat3<T> = Matrix<T, 3, 3>;
/// A 6×6 matrix in rotation-first block order (a covariance, an adjoint, a Jacobian).
pub type Mat6<T> = Matrix<T, 6, 6>;

impl<T: Real, const N: usize> Default for Vector<T, N> {
    fn default() -> Self {
        Self::zeros()
    }
}

impl<T: Real, const N: usize> Vector<T, N> {
    /// The zero vector.
    #[inline]
    pub fn zeros() -> Self {
        Vector([T::ZERO; N])
    }

    /// Applies `f` to every element.
    #[inline]
    pub fn map(self, mut f: impl FnMut(T) -> T) -> Self {
        let mut out = self;
        for x in out.0.iter_mut() {
            *x = f(*x);
        }
        out
    }

    /// Combines two vectors element by element.
    #[inline]
    pub fn zip_map(self, other: Self, mut f: impl FnMut(T, T) -> T) -> Self {
        let mut out = self;
        for (x, y) in out.0.iter_mut().zip(other.0.iter()) {
            *x = f(*x, *y);
        }
        out
    }

    /// Dot product, summed from the first product in index order (not from zero: the
    /// optimiser may not drop an added zero, which would turn a −0 sum into +0).
    #[inline]
    pub fn dot(&self, other: &Self) -> T {
        let mut terms = self.0.iter().zip(other.0.iter()).map(|(x, y)| *x * *y);
        let first = terms.next().unwrap_or(T::ZERO);
        terms.fold(first, |s, t| s + t)
    }

    /// Squared Euclidean norm.
    #[inline]
    pub fn norm_squared(&self) -> T {
        self.dot(self)
    }

    /// Euclidean norm (computed without overflow or underflow for any finite input).
    #[inline]
    pub fn norm(&self) -> T {
        let n2 = self.norm_squared();
        if n2.is_finite() && n2 >= T::min_positive_value() {
            return n2.sqrt();
        }
        self.norm_rescaled()
    }

    /// [`Vector::norm`]'s rare path, out of line so the common one stays small enough to
    /// inline: rescale so squares neither overflow nor underflow.
    #[cold]
    #[inline(never)]
    fn norm_rescaled(&self) -> T {
        let scale = self.amax();
        if scale == T::ZERO || !scale.is_finite() {
            return scale;
        }
        (self.map(|x| x / scale).norm_squared()).sqrt() * scale
    }

    /// Largest absolute value of an element (NaN if any element is NaN).
    #[inline]
    pub fn amax(&self) -> T {
        let mut m = T::ZERO;
        for x in self.0.iter() {
            let a = x.abs();
            if a > m || a.is_nan() {
                m = a;
            }
        }
        m
    }

    /// The vector with every element below `ε² · amax` set to zero (ε = [`Real::EPS`]).
    ///
    /// Such an element changes no result by more than ε² relative to the largest one, far
    /// below the rounding of any input, but its products with other small values land in the
    /// subnormal range, where x86 cores take a slow microcode path (as the f32 seed
    /// robot's `−1.9·10⁻²³` screw entries did). Unchanged if `amax` is zero or not
    /// finite.
    pub fn without_negligible(self) -> Self {
        let m = self.amax();
        if !m.is_finite() || m == T::ZERO {
            return self;
        }
        let cut = T::EPS * T::EPS * m;
        self.map(|x| if x.abs() < cut { T::ZERO } else { x })
    }

    /// Multiplies every element by `s`.
    #[inline]
    pub fn scale(self, s: T) -> Self {
        self.map(|x| x * s)
    }

    /// `true` if every element is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|x| x.is_finite())
    }

    /// Outer product `self · otherᵀ`.
    #[inline]
    pub fn outer<const M: usize>(&self, other: &Vector<T, M>) -> Matrix<T, N, M> {
        let mut out = Matrix::zeros();
        for (row, a) in out.0.iter_mut().zip(self.0.iter()) {
            for (x, b) in row.iter_mut().zip(other.0.iter()) {
                *x = *a * *b;
            }
        }
        out
    }
}

impl<T: Real> Vec3<T> {
    /// Creates a 3-vector.
    #[inline]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Vector([x, y, z])
    }

    /// Cross product `self × other`.
    #[inline]
    pub fn cross(&self, o: &Self) -> Self {
        let [a0, a1, a2] = self.0;
        let [b0, b1, b2] = o.0;
        Vector([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])
    }
}

impl<T: Real> Vec6<T> {
    /// Builds a 6-vector from its rotation part ω and translation part v (rotation first).
    #[inline]
    pub fn from_parts(omega: Vec3<T>, v: Vec3<T>) -> Self {
        let [a, b, c] = omega.0;
        let [d, e, f] = v.0;
        Vector([a, b, c, d, e, f])
    }

    /// The rotation part ω (first three elements).
    #[inline]
    pub fn rotation(&self) -> Vec3<T> {
        Vector([self.0[0], self.0[1], self.0[2]])
    }

    /// The translation part v (last three elements).
    #[inline]
    pub fn translation(&self) -> Vec3<T> {
        Vector([self.0[3], self.0[4], self.0[5]])
    }
}

impl<T: Real, const R: usize, const C: usize> Default for Matrix<T, R, C> {
    fn default() -> Self {
        Self::zeros()
    }
}

impl<T: Real, const R: usize, const C: usize> Matrix<T, R, C> {
    /// The zero matrix.
    #[inline]
    pub fn zeros() -> Self {
        Matrix([[T::ZERO; C]; R])
    }

    /// Applies `f` to every element.
    #[inline]
    pub fn map(self, mut f: impl FnMut(T) -> T) -> Self {
        let mut out = self;
        for row in out.0.iter_mut() {
            for x in row.iter_mut() {
                *x = f(*x);
            }
        }
        out
    }

    /// Combines two matrices element by element.
    #[inline]
    pub fn zip_map(self, other: &Self, mut f: impl FnMut(T, T) -> T) -> Self {
        let mut out = self;
        for (row, orow) in out.0.iter_mut().zip(other.0.iter()) {
            for (x, y) in row.iter_mut().zip(orow.iter()) {
                *x = f(*x, *y);
            }
        }
        out
    }

    /// Transpose.
    #[inline]
    pub fn transpose(&self) -> Matrix<T, C, R> {
        let mut out = Matrix::zeros();
        for (i, row) in self.0.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                if let Some(slot) = out.0.get_mut(j).and_then(|r| r.get_mut(i)) {
                    *slot = *x;
                }
            }
        }
        out
    }

    /// Multiplies every element by `s`.
    #[inline]
    pub fn scale(self, s: T) -> Self {
        self.map(|x| x * s)
    }

    /// Largest absolute value of an element (NaN if any element is NaN).
    #[inline]
    pub fn amax(&self) -> T {
        let mut m = T::ZERO;
        for row in self.0.iter() {
            for x in row.iter() {
                let a = x.abs();
                if a > m || a.is_nan() {
                    m = a;
                }
            }
        }
        m
    }

    /// The matrix with every element below `ε² · amax` set to zero: see
    /// [`Vector::without_negligible`].
    pub fn without_negligible(self) -> Self {
        let m = self.amax();
        if !m.is_finite() || m == T::ZERO {
            return self;
        }
        let cut = T::EPS * T::EPS * m;
        self.map(|x| if x.abs() < cut { T::ZERO } else { x })
    }

    /// `true` if every element is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|r| r.iter().all(|x| x.is_finite()))
    }

    /// Matrix-vector product `self · v`.
    #[inline]
    pub fn mul_vec(&self, v: &Vector<T, C>) -> Vector<T, R> {
        let mut out = Vector::zeros();
        for (o, row) in out.0.iter_mut().zip(self.0.iter()) {
            *o = Vector(*row).dot(v);
        }
        out
    }

    /// Transposed matrix-vector product `selfᵀ · v`.
    #[inline]
    pub fn tr_mul_vec(&self, v: &Vector<T, R>) -> Vector<T, C> {
        let mut out = Vector::<T, C>::zeros();
        for (row, s) in self.0.iter().zip(v.0.iter()) {
            for (o, x) in out.0.iter_mut().zip(row.iter()) {
                *o += *x * *s;
            }
        }
        out
    }

    /// Matrix product `self · rhs`, each entry summed from its first product in index
    /// order (as [`Vector::dot`]).
    #[inline]
    pub fn mul_mat<const K: usize>(&self, rhs: &Matrix<T, C, K>) -> Matrix<T, R, K> {
        let mut out = Matrix::<T, R, K>::zeros();
        for (orow, arow) in out.0.iter_mut().zip(self.0.iter()) {
            for (c, (a, brow)) in arow.iter().zip(rhs.0.iter()).enumerate() {
                for (o, b) in orow.iter_mut().zip(brow.iter()) {
                    *o = if c == 0 { *a * *b } else { *o + *a * *b };
                }
            }
        }
        out
    }

    /// Product with a transposed right factor, `self · rhsᵀ`.
    #[inline]
    pub fn mul_tr<const K: usize>(&self, rhs: &Matrix<T, K, C>) -> Matrix<T, R, K> {
        let mut out = Matrix::<T, R, K>::zeros();
        for (orow, arow) in out.0.iter_mut().zip(self.0.iter()) {
            for (o, brow) in orow.iter_mut().zip(rhs.0.iter()) {
                *o = Vector(*arow).dot(&Vector(*brow));
            }
        }
        out
    }

    /// Row `i` as a vector (`None` if out of range).
    #[inline]
    pub fn row(&self, i: usize) -> Option<Vector<T, C>> {
        self.0.get(i).map(|r| Vector(*r))
    }

    /// Column `j` as a vector (zeros if out of range).
    #[inline]
    pub fn column(&self, j: usize) -> Vector<T, R> {
        let mut out = Vector::zeros();
        for (o, row) in out.0.iter_mut().zip(self.0.iter()) {
            *o = row.get(j).copied().unwrap_or(T::ZERO);
        }
        out
    }
}

impl<T: Real, const N: usize> Matrix<T, N, N> {
    /// The identity matrix.
    #[inline]
    pub fn identity() -> Self {
        Self::from_diagonal(&Vector([T::ONE; N]))
    }

    /// A diagonal matrix.
    #[inline]
    pub fn from_diagonal(d: &Vector<T, N>) -> Self {
        let mut out = Self::zeros();
        for (i, (row, x)) in out.0.iter_mut().zip(d.0.iter()).enumerate() {
            if let Some(slot) = row.get_mut(i) {
                *slot = *x;
            }
        }
        out
    }

    /// The diagonal.
    #[inline]
    pub fn diagonal(&self) -> Vector<T, N> {
        let mut out = Vector::zeros();
        for (i, (o, row)) in out.0.iter_mut().zip(self.0.iter()).enumerate() {
            *o = row.get(i).copied().unwrap_or(T::ZERO);
        }
        out
    }

    /// Sum of the diagonal.
    #[inline]
    pub fn trace(&self) -> T {
        self.diagonal().0.iter().fold(T::ZERO, |s, x| s + *x)
    }

    /// `(self + selfᵀ) / 2`.
    #[inline]
    pub fn symmetrize(&self) -> Self {
        let t = self.transpose();
        self.zip_map(&t, |a, b| (a + b) * T::HALF)
    }

    /// Largest absolute difference between `self` and its transpose.
    #[inline]
    pub fn asymmetry(&self) -> T {
        (*self - self.transpose()).amax()
    }

    /// Congruence `a · self · aᵀ` for symmetric `self`, computed on one triangle and
    /// mirrored, so the result is exactly symmetric.
    #[inline]
    pub fn congruence<const M: usize>(&self, a: &Matrix<T, M, N>) -> Matrix<T, M, M> {
        let tmp = a.mul_mat(self); // M×N
        let mut out = Matrix::<T, M, M>::zeros();
        for i in 0..M {
            for j in 0..=i {
                let v = Vector(tmp.0[i]).dot(&Vector(a.0[j]));
                out.0[i][j] = v;
                out.0[j][i] = v;
            }
        }
        out
    }
}

impl<T: Real> Mat3<T> {
    /// Creates a 3×3 matrix from its rows.
    #[inline]
    pub const fn from_rows(rows: [[T; 3]; 3]) -> Self {
        Matrix(rows)
    }

    /// Determinant.
    #[inline]
    pub fn determinant(&self) -> T {
        let r0 = Vector(self.0[0]);
        let r1 = Vector(self.0[1]);
        let r2 = Vector(self.0[2]);
        r0.dot(&r1.cross(&r2))
    }
}

impl<T: Real> Mat6<T> {
    /// Assembles a 6×6 matrix from four 3×3 blocks `[[a, b], [c, d]]`.
    #[inline]
    pub fn from_blocks(a: &Mat3<T>, b: &Mat3<T>, c: &Mat3<T>, d: &Mat3<T>) -> Self {
        let mut out = Self::zeros();
        for i in 0..3 {
            for j in 0..3 {
                out.0[i][j] = a.0[i][j];
                out.0[i][j + 3] = b.0[i][j];
                out.0[i + 3][j] = c.0[i][j];
                out.0[i + 3][j + 3] = d.0[i][j];
            }
        }
        out
    }

    /// The 3×3 block at block row `bi` and block column `bj` (each 0 or 1; other values
    /// are taken modulo 2).
    #[inline]
    pub fn block(&self, bi: usize, bj: usize) -> Mat3<T> {
        let (r, c) = ((bi % 2) * 3, (bj % 2) * 3);
        let mut out = Mat3::zeros();
        for i in 0..3 {
            for j in 0..3 {
                out.0[i][j] = self.0[r + i][c + j];
            }
        }
        out
    }
}

macro_rules! elementwise_ops {
    ($ty:ident < $($c:ident),+ >, $map:ident) => {
        impl<T: Real, $(const $c: usize),+> Add for $ty<T, $($c),+> {
            type Output = Self;
            #[inline]
            fn add(self, rhs: Self) -> Self {
                self.$map(&rhs, |a, b| a + b)
            }
        }
        impl<T: Real, $(const $c: usize),+> Sub for $ty<T, $($c),+> {
            type Output = Self;
            #[inline]
            fn sub(self, rhs: Self) -> Self {
                self.$map(&rhs, |a, b| a - b)
            }
        }
        impl<T: Real, $(const $c: usize),+> AddAssign for $ty<T, $($c),+> {
            #[inline]
            fn add_assign(&mut self, rhs: Self) {
                *self = *self + rhs;
            }
        }
        impl<T: Real, $(const $c: usize),+> SubAssign for $ty<T, $($c),+> {
            #[inline]
            fn sub_assign(&mut self, rhs: Self) {
                *self = *self - rhs;
            }
        }
        impl<T: Real, $(const $c: usize),+> Neg for $ty<T, $($c),+> {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                self.map(|a| -a)
            }
        }
        impl<T: Real, $(const $c: usize),+> Mul<T> for $ty<T, $($c),+> {
            type Output = Self;
            #[inline]
            fn mul(self, s: T) -> Self {
                self.scale(s)
            }
        }
    };
}

impl<T: Real, const N: usize> Vector<T, N> {
    #[inline]
    fn zip_ref(self, other: &Self, f: impl FnMut(T, T) -> T) -> Self {
        self.zip_map(*other, f)
    }
}

elementwise_ops!(Vector<N>, zip_ref);
elementwise_ops!(Matrix<R, C>, zip_map);

impl<T: Real, const R: usize, const C: usize, const K: usize> Mul<Matrix<T, C, K>>
    for Matrix<T, R, C>
{
    type Output = Matrix<T, R, K>;
    #[inline]
    fn mul(self, rhs: Matrix<T, C, K>) -> Matrix<T, R, K> {
        self.mul_mat(&rhs)
    }
}

impl<T: Real, const R: usize, const C: usize> Mul<Vector<T, C>> for Matrix<T, R, C> {
    type Output = Vector<T, R>;
    #[inline]
    fn mul(self, rhs: Vector<T, C>) -> Vector<T, R> {
        self.mul_vec(&rhs)
    }
}

impl<T, const N: usize> From<[T; N]> for Vector<T, N> {
    fn from(a: [T; N]) -> Self {
        Vector(a)
    }
}

impl<T, const N: usize> From<Vector<T, N>> for [T; N] {
    fn from(v: Vector<T, N>) -> Self {
        v.0
    }
}

impl<T, const R: usize, const C: usize> From<[[T; C]; R]> for Matrix<T, R, C> {
    fn from(a: [[T; C]; R]) -> Self {
        Matrix(a)
    }
}

impl<T, const R: usize, const C: usize> From<Matrix<T, R, C>> for [[T; C]; R] {
    fn from(m: Matrix<T, R, C>) -> Self {
        m.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negligible_elements_are_zeroed_relative_to_the_largest() {
        // f32: ε² = 1.42e-14; the seed robot's 1.9e-23 goes, 3.3e-7 stays.
        let v: Vec3<f32> = Vector([-1.864_253e-23, 1.0, -3.267_949e-7]);
        assert_eq!(v.without_negligible().0, [0.0, 1.0, -3.267_949e-7]);
        // Relative, not absolute: the same tiny values survive among tiny values.
        let t: Vec3<f32> = Vector([1e-23, 2e-23, 0.0]);
        assert_eq!(t.without_negligible(), t);
        // f64: 1.9e-23 is above ε²·1 = 4.9e-32 and stays.
        let w: Vec3<f64> = Vector([-1.864_252_887_470_2e-23, 1.0, 0.0]);
        assert_eq!(w.without_negligible(), w);
        // Just below and at the cut.
        let cut = f64::EPSILON * f64::EPSILON * 4.0;
        let c: Vec3<f64> = Vector([4.0, cut * 0.99, cut]);
        assert_eq!(c.without_negligible().0, [4.0, 0.0, cut]);
        // Non-finite or zero maximum: unchanged (NaN compared by bits).
        for bad in [f32::NAN, f32::INFINITY] {
            let b: Vec3<f32> = Vector([bad, 1e-30, 1.0]);
            let out = b.without_negligible().0.map(f32::to_bits);
            assert_eq!(out, b.0.map(f32::to_bits));
        }
        assert_eq!(Vec3::<f32>::zeros().without_negligible(), Vec3::zeros());
        let m: Mat3<f32> = Matrix([
            [1.0, 0.0, 0.0],
            [0.0, 1.0, -1.864_253e-23],
            [0.0, 2e-23, 1.0],
        ]);
        assert_eq!(m.without_negligible(), Mat3::identity());
    }

    #[test]
    fn spd_inverse_and_solve() {
        let a: Mat3<f64> = Matrix([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]]);
        let inv = a.inverse_spd().unwrap();
        approx::assert_relative_eq!(a * inv, Mat3::identity(), epsilon = 1e-14);
        let b = Vector([1.0, 2.0, 3.0]);
        let x = a.solve_spd(&b).unwrap();
        approx::assert_relative_eq!(a * x, b, epsilon = 1e-14);
        let singular: Mat3<f64> = Matrix([[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        assert!(singular.cholesky().is_none());
    }

    #[test]
    fn norm_does_not_overflow() {
        let v = Vec3::new(1e300_f64, 1e300, 0.0);
        assert!((v.norm() / 1.414_213_562_373_095e300 - 1.0).abs() < 1e-15);
        assert_eq!(Vec3::new(0.0_f32, 0.0, 0.0).norm(), 0.0);
    }
}
