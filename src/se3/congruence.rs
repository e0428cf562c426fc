//! The covariance congruence `Σ ↦ Ad(T)·Σ·Ad(T)ᵀ` of a rigid transform, structured:
//! `Ad(T) = diag(R, R)·[[I, 0], [Q, I]]` with `Q = [Rᵀp]×`, so the product is a shear
//! whose products with the skew Q are cross products, followed by the block rotations
//! `R·X·Rᵀ`; only the lower triangle is accumulated. [`Transform::transport_covariance`]
//! applies one; the PPOE's schedule applies W at a time in the lanes of a [`Pack`] (the
//! schedule's module says why and when).
//!
//! [`Transform::transport_covariance`]: super::Transform::transport_covariance

use super::Transform;
use crate::linalg::{Mat6, Matrix};
use crate::scalar::Real;

/// The arithmetic of the structured transport: a scalar, or W scalars in lanes ([`Pack`]).
pub(crate) trait Lane:
    Copy
    + core::ops::Add<Output = Self>
    + core::ops::Sub<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::AddAssign
{
    /// Zero in every lane.
    fn zero() -> Self;
}

impl<T: Real> Lane for T {
    #[inline(always)]
    fn zero() -> Self {
        T::ZERO
    }
}

/// W independent values side by side with element-wise arithmetic: W transports in the
/// lanes of SIMD registers (see [`Congruence::add_lower_packed`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pack<T, const W: usize>(pub(crate) [T; W]);

/// Element-wise `Pack ∘ Pack` operators, lane by lane.
macro_rules! pack_ops {
    ($($trait:ident $method:ident $assign:tt),*) => {$(
        impl<T: Real, const W: usize> core::ops::$trait for Pack<T, W> {
            type Output = Self;
            #[inline(always)]
            fn $method(mut self, o: Self) -> Self {
                for (a, b) in self.0.iter_mut().zip(o.0) {
                    *a $assign b;
                }
                self
            }
        }
    )*};
}

pack_ops!(Add add +=, Sub sub -=, Mul mul *=);

impl<T: Real, const W: usize> core::ops::AddAssign for Pack<T, W> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<T: Real, const W: usize> Pack<T, W> {
    /// The pack whose lane k is `f(k)`.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane k from f(k)
    pub(crate) fn gather(f: impl Fn(usize) -> T) -> Self {
        let mut a = [T::ZERO; W];
        for k in 0..W {
            a[k] = f(k);
        }
        Pack(a)
    }
}

impl<T: Real, const W: usize> Pack<T, W> {
    /// `x` in every lane.
    #[inline(always)]
    pub(crate) fn splat(x: T) -> Self {
        Pack([x; W])
    }
}

impl<T: Real, const W: usize> core::ops::Neg for Pack<T, W> {
    type Output = Self;
    /// Lane-wise negation (exact, as the scalar's: `-0` for `0`).
    #[inline(always)]
    fn neg(mut self) -> Self {
        for a in self.0.iter_mut() {
            *a = -*a;
        }
        self
    }
}

impl<T: Real, const W: usize> Lane for Pack<T, W> {
    #[inline(always)]
    fn zero() -> Self {
        Pack([T::ZERO; W])
    }
}

/// The congruence `Σ ↦ Ad(T)·Σ·Ad(T)ᵀ` of a transform T = (R, p), factored as
/// `Ad(T) = diag(R, R)·[[I, 0], [Q, I]]`, `Q = [q]×`, `q = Rᵀp`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Congruence<T> {
    r: [[T; 3]; 3],
    q: [T; 3],
}

impl<T: Real> Congruence<T> {
    /// A placeholder for the unfilled slots of a group (never transported).
    pub(crate) const ZERO: Self = Self {
        r: [[T::ZERO; 3]; 3],
        q: [T::ZERO; 3],
    };

    /// The congruence by `Ad(t)`.
    #[inline(always)]
    pub(crate) fn of(t: &Transform<T>) -> Self {
        let q = t.rotation.transpose() * t.translation;
        Self {
            r: t.rotation.0,
            q: q.0,
        }
    }

    /// The congruence by `Ad(t⁻¹)`: R → Rᵀ and q = R·(−Rᵀp) = −p, no product needed.
    #[inline(always)]
    pub(crate) fn of_inverse(t: &Transform<T>) -> Self {
        Self {
            r: t.rotation.transpose().0,
            q: (-t.translation).0,
        }
    }

    /// Adds the lower triangle of `Ad·Σ·Adᵀ` to `acc`.
    #[inline(always)]
    pub(crate) fn add_lower(&self, cov: &Mat6<T>, acc: &mut [[T; 6]; 6]) {
        transport_lower(&self.r, &self.q, &cov.0, acc);
    }

    /// This congruence in every lane: adds the lower triangle of `Ad·Σₖ·Adᵀ` to lane k of
    /// `acc`, Σₖ lane k of `c` (every entry read: `c` holds whole symmetric matrices). Lane
    /// k is bit-identical to [`Congruence::add_lower`] on Σₖ (the same operations).
    #[inline(always)]
    pub(crate) fn add_lower_splat<const W: usize>(
        &self,
        c: &[[Pack<T, W>; 6]; 6],
        acc: &mut [[Pack<T, W>; 6]; 6],
    ) {
        let r = self.r.map(|row| row.map(Pack::splat));
        transport_lower(&r, &self.q.map(Pack::splat), c, acc);
    }

    /// W congruences side by side: adds the lower triangle of congruence k applied to
    /// covariance k to lane k of `acc`. The same operations on [`Pack`] lanes, every pack
    /// gathered whole from its W lanes. The PPOE's one-lane schedule on the scalar-FPU
    /// targets uses it (W = 1); with more lanes the schedule writes its congruences into
    /// a [`PackedCongruence`] instead (its module doc says why).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // a gather: lane k of every element, by index
    pub(crate) fn add_lower_packed<const W: usize>(
        items: &[(Self, &Mat6<T>); W],
        acc: &mut [[Pack<T, W>; 6]; 6],
    ) {
        let mut r = [[Pack::zero(); 3]; 3];
        let mut q = [Pack::zero(); 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = Pack::gather(|k| items[k].0.r[i][j]);
            }
            q[i] = Pack::gather(|k| items[k].0.q[i]);
        }
        let c = gather_covariances(|k| items[k].1);
        transport_lower(&r, &q, &c, acc);
    }
}

/// W congruences in the lanes of packs (lane k holds congruence k), written lane by
/// lane as they are made and transported together by [`PackedCongruence::add_lower`]:
/// the transport reads each pack whole from where it was written, with no gather.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PackedCongruence<T, const W: usize> {
    r: [[Pack<T, W>; 3]; 3],
    q: [Pack<T, W>; 3],
}

impl<T: Real, const W: usize> PackedCongruence<T, W> {
    /// Zero congruences in every lane.
    pub(crate) const ZERO: Self = Self {
        r: [[Pack([T::ZERO; W]); 3]; 3],
        q: [Pack([T::ZERO; W]); 3],
    };

    /// Writes `c` into lane `k` (nothing if `k` ≥ W).
    #[inline(always)]
    pub(crate) fn set_lane(&mut self, k: usize, c: &Congruence<T>) {
        for (prow, crow) in self.r.iter_mut().zip(&c.r) {
            for (p, x) in prow.iter_mut().zip(crow) {
                if let Some(l) = p.0.get_mut(k) {
                    *l = *x;
                }
            }
        }
        for (p, x) in self.q.iter_mut().zip(&c.q) {
            if let Some(l) = p.0.get_mut(k) {
                *l = *x;
            }
        }
    }

    /// The congruence in lane `k` (zero if `k` ≥ W).
    #[inline(always)]
    pub(crate) fn lane(&self, k: usize) -> Congruence<T> {
        let at = |p: &Pack<T, W>| p.0.get(k).copied().unwrap_or(T::ZERO);
        Congruence {
            r: self.r.map(|row| row.map(|p| at(&p))),
            q: self.q.map(|p| at(&p)),
        }
    }

    /// Adds the lower triangle of congruence k applied to `covs[k]` to lane k of `acc`:
    /// [`transport_lower`] on the packs, the covariances gathered into lanes.
    #[inline(always)]
    pub(crate) fn add_lower(&self, covs: &[&Mat6<T>; W], acc: &mut [[Pack<T, W>; 6]; 6]) {
        let c = gather_covariances(|k| covs[k]);
        transport_lower(&self.r, &self.q, &c, acc);
    }
}

/// The W covariances `cov(0)`, …, `cov(W − 1)` side by side: entry (i, j) of covariance k
/// in lane k of pack (i, j).
#[inline(always)]
#[allow(clippy::needless_range_loop)] // a gather: lane k of every element, by index
fn gather_covariances<'c, T: Real + 'c, const W: usize>(
    cov: impl Fn(usize) -> &'c Mat6<T>,
) -> [[Pack<T, W>; 6]; 6] {
    let mut c = [[Pack::zero(); 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            c[i][j] = Pack::gather(|k| cov(k).0[i][j]);
        }
    }
    c
}

/// The lower triangle of `diag(R, R)·S·Σ·Sᵀ·diag(R, R)ᵀ`, `S = [[I, 0], [Q, I]]`,
/// `Q = [q]×`, added to `acc`. Shear first (its products with the skew Q are cross
/// products), then the block rotations; every stage writes its block out before the next
/// starts, which keeps few values live (fewer register spills than rotating first).
#[inline(always)]
pub(crate) fn transport_lower<L: Lane>(
    r: &[[L; 3]; 3],
    q: &[L; 3],
    c: &[[L; 6]; 6],
    acc: &mut [[L; 6]; 6],
) {
    // Shear: E = Q·A + Bᵀ (lower left) and E·Qᵀ + Q·B + D (lower right) for the blocks
    // Σ = [[A, B], [Bᵀ, D]]; B is read from the upper-right block.
    let mut x = [[L::zero(); 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            x[3 + i][j] = cross_component(q, [c[0][j], c[1][j], c[2][j]], i) + c[j][3 + i];
        }
    }
    for i in 0..3 {
        for j in 0..=i {
            let v = cross_component(q, [x[3 + i][0], x[3 + i][1], x[3 + i][2]], j)
                + cross_component(q, [c[0][3 + j], c[1][3 + j], c[2][3 + j]], i)
                + c[3 + i][3 + j];
            x[3 + i][3 + j] = v;
            x[3 + j][3 + i] = v;
        }
    }
    // Rotate the three blocks: R·A·Rᵀ, R·E·Rᵀ, R·(lower right)·Rᵀ.
    sandwich_add(r, c, 0, 0, acc, true);
    sandwich_add(r, &x, 3, 0, acc, false);
    sandwich_add(r, &x, 3, 3, acc, true);
}

/// Adds `R·X·Rᵀ` for the 3×3 block X of `c` at (bi, bj) to the same block of `acc` (lower
/// triangle only if `symmetric`). Column by column, `y = X·rⱼ` then `rᵢ·y`, so that
/// only R, y and one sum are live (few register spills).
#[inline(always)]
fn sandwich_add<L: Lane>(
    r: &[[L; 3]; 3],
    c: &[[L; 6]; 6],
    bi: usize,
    bj: usize,
    acc: &mut [[L; 6]; 6],
    symmetric: bool,
) {
    for j in 0..3 {
        let mut y = [L::zero(); 3];
        for (k, yk) in y.iter_mut().enumerate() {
            let row = &c[bi + k];
            *yk = row[bj] * r[j][0] + row[bj + 1] * r[j][1] + row[bj + 2] * r[j][2];
        }
        for i in 0..3 {
            if !symmetric || i >= j {
                acc[bi + i][bj + j] += r[i][0] * y[0] + r[i][1] * y[1] + r[i][2] * y[2];
            }
        }
    }
}

/// The symmetric matrix whose lower triangle (row ≥ column) is that of `m`: exactly
/// symmetric by construction.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // a transposition: m[j][i] from m[i][j]
pub(crate) fn mirror_lower<T: Real>(mut m: [[T; 6]; 6]) -> Mat6<T> {
    for i in 0..6 {
        for j in 0..i {
            m[j][i] = m[i][j];
        }
    }
    Matrix(m)
}

/// Component `i` of `p × x`.
#[inline(always)]
fn cross_component<L: Lane>(p: &[L; 3], x: [L; 3], i: usize) -> L {
    match i {
        0 => p[1] * x[2] - p[2] * x[1],
        1 => p[2] * x[0] - p[0] * x[2],
        _ => p[0] * x[1] - p[1] * x[0],
    }
}
