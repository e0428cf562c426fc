//! Cholesky factorisation of symmetric positive definite matrices, and the solves and
//! inverse built on it.

use super::{Matrix, Vector};
use crate::scalar::Real;

impl<T: Real, const N: usize> Matrix<T, N, N> {
    /// Cholesky factor L (lower triangular, `self = L Lᵀ`) of a symmetric positive
    /// definite matrix; `None` if a pivot is not positive or not finite.
    ///
    /// Method: the Cholesky–Banachiewicz recurrence (Golub & Van Loan, Alg. 4.2.1); only
    /// the lower triangle of `self` is read.
    pub fn cholesky(&self) -> Option<Self> {
        let mut l = Self::zeros();
        for i in 0..N {
            for j in 0..=i {
                let mut s = self.0[i][j];
                for k in 0..j {
                    s -= l.0[i][k] * l.0[j][k];
                }
                if i == j {
                    if s.is_nan() || s <= T::ZERO || !s.is_finite() {
                        return None;
                    }
                    l.0[i][i] = s.sqrt();
                } else {
                    l.0[i][j] = s / l.0[j][j];
                }
            }
        }
        Some(l)
    }

    /// Solves `self · x = b` for symmetric positive definite `self` (Cholesky);
    /// `None` if `self` is not positive definite.
    pub fn solve_spd(&self, b: &Vector<T, N>) -> Option<Vector<T, N>> {
        let l = self.cholesky()?;
        Some(cholesky_solve(&l, b))
    }

    /// Inverse of a symmetric positive definite matrix (Cholesky), exactly symmetric;
    /// `None` if not positive definite.
    pub fn inverse_spd(&self) -> Option<Self> {
        let l = self.cholesky()?;
        let mut inv = Self::zeros();
        for j in 0..N {
            let mut e = Vector::zeros();
            e.0[j] = T::ONE;
            let col = cholesky_solve(&l, &e);
            for i in 0..N {
                inv.0[i][j] = col.0[i];
            }
        }
        Some(inv.symmetrize())
    }
}

/// Forward and back substitution with a Cholesky factor.
fn cholesky_solve<T: Real, const N: usize>(l: &Matrix<T, N, N>, b: &Vector<T, N>) -> Vector<T, N> {
    let mut y = *b;
    for i in 0..N {
        let mut s = y.0[i];
        for k in 0..i {
            s -= l.0[i][k] * y.0[k];
        }
        y.0[i] = s / l.0[i][i];
    }
    for i in (0..N).rev() {
        let mut s = y.0[i];
        for k in i + 1..N {
            s -= l.0[k][i] * y.0[k];
        }
        y.0[i] = s / l.0[i][i];
    }
    y
}
