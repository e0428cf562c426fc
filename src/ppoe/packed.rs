//! Rigid transforms of W configurations side by side, for the batch PPOE (`batch.rs`):
//! lane k of every [`Pack`] belongs to configuration k. Every operation is the scalar
//! one of [`Transform`] and [`JointConstants::displacement`] written lane by lane with
//! the same operations in the same order, so lane k's result is bit-identical to the
//! scalar computation on configuration k (Rust does not contract `a·b + c` into a fused
//! multiply-add, and starting each sum from its first product as the scalar code does
//! keeps even the sign of a zero). The batch's unit tests (`batch_tests.rs`) compare them
//! bit for bit.

use crate::joint::{Joint, JointConstants};
use crate::scalar::Real;
use crate::se3::congruence::Pack;
use crate::se3::Transform;

/// W rigid transforms (R, p) in lanes.
#[derive(Clone, Copy, Debug)]
pub(super) struct Poses<T, const W: usize> {
    /// Rotation entries, row-major.
    pub(super) r: [[Pack<T, W>; 3]; 3],
    /// Translation.
    pub(super) p: [Pack<T, W>; 3],
}

impl<T: Real, const W: usize> Poses<T, W> {
    /// `t` in every lane.
    #[inline(always)]
    pub(super) fn splat(t: &Transform<T>) -> Self {
        Self::gather(|_| *t)
    }

    /// Lane k is `f(k)`.
    #[inline(always)]
    pub(super) fn gather(f: impl Fn(usize) -> Transform<T>) -> Self {
        let mut out = Self {
            r: [[Pack::splat(T::ZERO); 3]; 3],
            p: [Pack::splat(T::ZERO); 3],
        };
        for k in 0..W {
            let t = f(k);
            for (orow, trow) in out.r.iter_mut().zip(&t.rotation.0) {
                for (o, x) in orow.iter_mut().zip(trow) {
                    set(o, k, *x);
                }
            }
            for (o, x) in out.p.iter_mut().zip(&t.translation.0) {
                set(o, k, *x);
            }
        }
        out
    }

    /// The transform in lane k (zeros beyond W).
    #[inline(always)]
    pub(super) fn lane(&self, k: usize) -> Transform<T> {
        let mut t = Transform::identity();
        for (orow, row) in t.rotation.0.iter_mut().zip(&self.r) {
            for (o, x) in orow.iter_mut().zip(row) {
                *o = get(x, k);
            }
        }
        for (o, x) in t.translation.0.iter_mut().zip(&self.p) {
            *o = get(x, k);
        }
        t
    }

    /// `self · rhs` lane by lane, as [`Transform::compose`]: `R·R'` and `R·p' + p`, every
    /// sum from its first product in the order of `Matrix::mul_mat` and `Matrix::mul_vec`.
    #[inline(always)]
    pub(super) fn compose(&self, rhs: &Self) -> Self {
        let zero = Pack::splat(T::ZERO);
        let mut r = [[zero; 3]; 3];
        for (orow, arow) in r.iter_mut().zip(&self.r) {
            for (c, (a, brow)) in arow.iter().zip(&rhs.r).enumerate() {
                for (o, b) in orow.iter_mut().zip(brow) {
                    *o = if c == 0 { *a * *b } else { *o + *a * *b };
                }
            }
        }
        let mut p = mat_vec(&self.r, &rhs.p);
        for (o, t) in p.iter_mut().zip(&self.p) {
            *o += *t;
        }
        Self { r, p }
    }

    /// Rᵀ.
    #[inline(always)]
    pub(super) fn rotation_transposed(&self) -> [[Pack<T, W>; 3]; 3] {
        let r = &self.r;
        [
            [r[0][0], r[1][0], r[2][0]],
            [r[0][1], r[1][1], r[2][1]],
            [r[0][2], r[1][2], r[2][2]],
        ]
    }

    /// Rᵀ·p (the lever arm of `Congruence::of`), as `Matrix::transpose` then `mul_vec`.
    #[inline(always)]
    pub(super) fn rotated_back_translation(&self) -> [Pack<T, W>; 3] {
        mat_vec(&self.rotation_transposed(), &self.p)
    }

    /// `Ad(self)·s` lane by lane: `(R·ω, p × R·ω + R·v)`, as the rank-one
    /// PPOE's `adjoint_apply`.
    #[inline(always)]
    pub(super) fn adjoint_apply(&self, s: &[Pack<T, W>; 6]) -> [Pack<T, W>; 6] {
        let (w, v) = parts(s);
        let w = mat_vec(&self.r, &w);
        let c = cross(&self.p, &w);
        let rv = mat_vec(&self.r, &v);
        [w[0], w[1], w[2], c[0] + rv[0], c[1] + rv[1], c[2] + rv[2]]
    }

    /// `Ad(self⁻¹)·s` lane by lane: `(Rᵀ·ω, Rᵀ·(v − p × ω))`, as the
    /// rank-one PPOE's `inverse_adjoint_apply`.
    #[inline(always)]
    pub(super) fn inverse_adjoint_apply(&self, s: &[Pack<T, W>; 6]) -> [Pack<T, W>; 6] {
        let (w, v) = parts(s);
        let c = cross(&self.p, &w);
        let v = [v[0] - c[0], v[1] - c[1], v[2] - c[2]];
        let rt = self.rotation_transposed();
        let (w, v) = (mat_vec(&rt, &w), mat_vec(&rt, &v));
        [w[0], w[1], w[2], v[0], v[1], v[2]]
    }
}

/// Lane k of `x` (zero beyond W: never reached, the callers' k < W).
#[inline(always)]
fn get<T: Real, const W: usize>(x: &Pack<T, W>, k: usize) -> T {
    x.0.get(k).copied().unwrap_or(T::ZERO)
}

/// Sets lane k of `x` (no effect beyond W).
#[inline(always)]
fn set<T: Real, const W: usize>(x: &mut Pack<T, W>, k: usize, v: T) {
    if let Some(slot) = x.0.get_mut(k) {
        *slot = v;
    }
}

/// The rotation and translation parts of a 6-vector (rotation first).
#[inline(always)]
fn parts<L: Copy>(s: &[L; 6]) -> ([L; 3], [L; 3]) {
    ([s[0], s[1], s[2]], [s[3], s[4], s[5]])
}

/// `m·v`, every sum from its first product as `Matrix::mul_vec`.
#[inline(always)]
fn mat_vec<T: Real, const W: usize>(
    m: &[[Pack<T, W>; 3]; 3],
    v: &[Pack<T, W>; 3],
) -> [Pack<T, W>; 3] {
    let mut out = [Pack::splat(T::ZERO); 3];
    for (o, row) in out.iter_mut().zip(m) {
        *o = row[0] * v[0] + row[1] * v[1] + row[2] * v[2];
    }
    out
}

/// `a × b`, as `Vector::cross`.
#[inline(always)]
fn cross<T: Real, const W: usize>(a: &[Pack<T, W>; 3], b: &[Pack<T, W>; 3]) -> [Pack<T, W>; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Joint `j`'s displacement `Exp(S·θ)` for the W joint values `theta` (already clipped):
/// [`JointConstants::displacement`] lane by lane with the joint's constants (derived here
/// once for the W lanes when the joint has none, as [`Joint::displacement`] derives them
/// per call); the degenerate joints without constants (ω = 0, or 1/‖ω‖ not finite) go
/// through [`Joint::displacement`] one lane at a time.
#[inline(always)]
pub(super) fn displacement<T: Real, const W: usize>(
    j: &Joint<T>,
    theta: Pack<T, W>,
) -> Poses<T, W> {
    if let Some(k) = j.constants_ref() {
        return constants_displacement(k, theta);
    }
    match JointConstants::of(&j.screw) {
        Some(k) => constants_displacement(&k, theta),
        None => Poses::gather(|k| j.displacement(get(&theta, k))),
    }
}

/// [`JointConstants::displacement`] lane by lane: the same expressions in the same order.
#[inline(always)]
fn constants_displacement<T: Real, const W: usize>(
    k: &JointConstants<T>,
    theta: Pack<T, W>,
) -> Poses<T, W> {
    let sp = Pack::splat;
    let t = theta * sp(k.scale);
    // The scalar's own way of filling whole packs (`Sealed::sin_cos_lanes` says why).
    let (s, c) = T::sin_cos_lanes(t.0);
    let (s, c) = (Pack(s), Pack(c));
    let one = sp(T::ONE);
    let omc = one - c;
    let ([x, y, z], [dx, dy, dz], [xy, xz, yz]) = (k.axis, k.axis_sq, k.axis_prod);
    let r = [
        [
            one - omc * sp(dx),
            omc * sp(xy) - s * sp(z),
            omc * sp(xz) + s * sp(y),
        ],
        [
            omc * sp(xy) + s * sp(z),
            one - omc * sp(dy),
            omc * sp(yz) - s * sp(x),
        ],
        [
            omc * sp(xz) - s * sp(y),
            omc * sp(yz) + s * sp(x),
            one - omc * sp(dz),
        ],
    ];
    let tms = t - s;
    let (v, cv, av) = (k.v, k.axis_cross_v, k.axial_v);
    let p = [
        s * sp(v[0]) + omc * sp(cv[0]) + tms * sp(av[0]),
        s * sp(v[1]) + omc * sp(cv[1]) + tms * sp(av[1]),
        s * sp(v[2]) + omc * sp(cv[2]) + tms * sp(av[2]),
    ];
    Poses { r, p }
}
