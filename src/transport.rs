//! The PPOE's instruction schedule: the covariance transports `Ad·Σ·Adᵀ` of the joints,
//! W at a time, side by side in the lanes of SIMD registers. Private: only the order in
//! which the same operations run depends on it, never what is computed.
//!
//! Why lanes: each joint's transport is independent of the others' (the sum of the
//! transported covariances is only formed at the end), so W of them can run as one
//! computation on [`Pack`]s of W scalars, which the optimiser maps to SIMD registers
//! where the target has them (SSE2, NEON, wasm simd128): no shuffle is needed inside a
//! transport. [`lanes`] chooses W per scalar and target: as many as fill one 128-bit
//! vector where the target has them (f64: 2, f32: 4), else 1 (Cortex-M: a scalar FPU,
//! where lanes would only add register pressure).
//!
//! Why f32 fills the whole register: two f32 lanes are computed in 4-lane registers
//! whose other two lanes the program leaves undefined (leftovers of earlier code). On a
//! core with a slow path for subnormals, the two-lane f32 PPOE ran 1.2-1.3x slower than
//! f64, and 0.9x with flush-to-zero set; the one- and four-lane schedules, whose lanes
//! hold the same values as the two defined lanes, ran at full speed. So the subnormals
//! are in the undefined lanes (f32's narrow range underflows where f64's does not). Four
//! lanes leave no lane undefined (BENCHMARKS.md, shipped with this package, gives the ratios).
//!
//! Why groups are built as locals: the joints go in groups of W, and each group's W
//! congruences and covariances are built as local values, then gathered into lanes
//! whole. Queuing them in a buffer until W were pending made the lane gathers load
//! what had just been stored field by field (store-forwarding stalls); filling a zeroed
//! buffer lane by lane compiled to a `memset` call and scalar stores that the vector
//! loads then waited on.
//!
//! Why a one-lane tail: when the joint count is not a multiple of W, the last group's
//! joints are transported one lane at a time (the code path of the one-lane targets)
//! rather than in W lanes with zero covariances padding the empty ones: with two lanes
//! a padded lane costs a whole transport, and its result is zero. With four lanes one
//! packed transport costs fewer instructions than three scalar ones (a 7-joint f32 chain
//! 5228 instead of 5579 per PPOE under callgrind) but more than two, so a last group
//! more than half full runs in all W lanes, its empty lanes zero (exactly zero results).
//!
//! Why joints with a zero covariance are skipped: fixed or noiseless joints are common,
//! and their transport adds exactly zero; the check (a scan that stops at the first
//! non-zero entry) costs far less than a transport. The groups are filled with the
//! joints that have a covariance only, so skipping one also saves lanes.
//!
//! Why the schedule is split into a base-frame and a tip-frame function: one function
//! holding both loops left the optimiser more live values than registers, and it
//! spilled; each loop on its own compiles to fewer instructions.
//!
//! Why no closures in the per-joint loops: `core::array::from_fn` and closures there were
//! left as calls by the optimiser, and each call spilled every live register. The loops
//! over the lanes are written out; the closures that remain ([`Pack::gather`]) are
//! always inlined.
//!
//! The rounding: with W lanes the transported covariances are summed in W partial sums,
//! added at the end (`Sums::total`), so results of different widths differ by a few ε of
//! the covariance's size (the repository's lane tests compare widths 1, 2 and 4).

use crate::chain::ChainView;
use crate::linalg::{Mat6, Matrix};
use crate::ppoe::{Convention, UncertainPose};
use crate::scalar::Real;
use crate::se3::Transform;

/// Whether the target has 128-bit SIMD registers for floats.
const SIMD128: bool = cfg!(any(
    target_feature = "sse2",
    target_feature = "neon",
    target_feature = "simd128"
));

/// How many transports the PPOE computes side by side for scalar `T` on this target (see
/// the module doc): as many as fill one 128-bit SIMD register (f32: 4, f64: 2), else 1.
pub(crate) const fn lanes<T: Real>() -> usize {
    match core::mem::size_of::<T>() {
        4 if SIMD128 => 4,
        8 if SIMD128 => 2,
        _ => 1,
    }
}

/// The PPOE of `chain` after the length check, W transports at a time: the joints go in
/// groups of W, each group's W congruences and covariances are built as locals and
/// transported in the W lanes together; a last group of fewer than W joints is
/// transported one lane at a time unless it fills more than half of W > 2 lanes (see
/// [`Sums::add`]).
#[inline(always)]
pub(crate) fn ppoe_lanes<T: Real, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    convention: Convention,
) -> UncertainPose<T> {
    let mut sums = Sums {
        lanes: [[Pack([T::ZERO; W]); 6]; 6],
        tail: [[T::ZERO; 6]; 6],
    };
    let pose = if convention == Convention::Left {
        base_frame(chain, thetas, covs, &mut sums) * chain.home
    } else {
        let start = if convention == Convention::Right {
            chain.home
        } else {
            Transform::identity()
        };
        let clip_continuous = convention == Convention::Pytransform3d;
        let g = tip_frame(chain, thetas, covs, clip_continuous, start, &mut sums);
        if convention == Convention::Right {
            g
        } else {
            g * chain.home
        }
    };
    let cov = sums.total();
    let cov = if convention == Convention::Pytransform3d {
        chain.home.transport_covariance(&cov)
    } else {
        cov
    };
    UncertainPose { pose, cov }
}

/// The lower triangles of the transported covariances, summed: W partial sums in lanes,
/// and one for the joints of the last, incomplete group.
struct Sums<T, const W: usize> {
    lanes: [[Pack<T, W>; 6]; 6],
    tail: [[T; 6]; 6],
}

impl<T: Real, const W: usize> Sums<T, W> {
    /// Adds the transports of `group`'s first `filled` entries: in lanes together when
    /// all W are filled or, with more than two lanes, more than half of them (the empty
    /// slots hold zero congruences and covariances); else one lane at a time.
    #[inline(always)]
    fn add(&mut self, group: &[(Congruence<T>, &Mat6<T>); W], filled: usize) {
        if filled == W || (W > 2 && 2 * filled > W) {
            Congruence::add_lower_packed(group, &mut self.lanes);
        } else if W > 1 {
            for (c, cov) in group.iter().take(filled) {
                c.add_lower(cov, &mut self.tail);
            }
        }
    }

    /// The sum over the lanes and the tail, mirrored: exactly symmetric.
    #[inline(always)]
    fn total(&self) -> Mat6<T> {
        // With one lane there is no tail (every group is full): starting from zeros lets
        // the optimiser drop it.
        let mut acc = [[T::ZERO; 6]; 6];
        for ((arow, lrow), trow) in acc.iter_mut().zip(&self.lanes).zip(&self.tail) {
            for ((a, l), t) in arow.iter_mut().zip(lrow).zip(trow) {
                // All 36, only the lower triangle is kept.
                let start = if W > 1 { *t } else { T::ZERO };
                *a = l.0.iter().fold(start, |s, x| s + *x);
            }
        }
        mirror_lower(acc)
    }
}

/// Base frame: Σ_left = Σᵢ Ad(Pᵢ)·covᵢ·Ad(Pᵢ)ᵀ, Pᵢ = D₁…Dᵢ (the reference's sum moved by
/// Ad(Pₙ)); one transport per joint and none at the end. Returns Pₙ.
#[inline(always)]
fn base_frame<T: Real, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    sums: &mut Sums<T, W>,
) -> Transform<T> {
    let n = chain.joints.len();
    let zero = Mat6::zeros();
    let mut p = Transform::identity();
    let mut i = 0;
    while i < n {
        let mut group = [(Congruence::ZERO, &zero); W];
        let mut filled = 0;
        for slot in group.iter_mut() {
            // The next joint with a covariance, moving P along the joints skipped.
            while let (Some(j), Some(t), Some(cov)) =
                (chain.joints.get(i), thetas.get(i), covs.get(i))
            {
                i += 1;
                p = p.compose(&j.displacement(j.clip(*t, false)));
                if !is_zero(cov) {
                    *slot = (Congruence::of(&p), cov);
                    filled += 1;
                    break;
                }
            }
        }
        sums.add(&group, filled);
    }
    p
}

/// Tip frame, from the tip backwards: Σ_right = Σᵢ Ad(Gᵢ⁻¹)·covᵢ·Ad(Gᵢ⁻¹)ᵀ with
/// Gᵢ = Dᵢ₊₁…Dₙ·`start` (the reference's recursion unrolled, then moved by Ad(M⁻¹) for
/// `start` = M). One transport per joint and none at the end, and each uses the lever arm
/// from joint i to the tip, not through the base and back. The reference's variant starts
/// from I and moves the sum by Ad(M) instead. Returns G₀.
#[inline(always)]
fn tip_frame<T: Real, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    clip_continuous: bool,
    start: Transform<T>,
    sums: &mut Sums<T, W>,
) -> Transform<T> {
    let zero = Mat6::zeros();
    let mut g = start;
    let mut left = chain.joints.len();
    while left > 0 {
        let mut group = [(Congruence::ZERO, &zero); W];
        let mut filled = 0;
        for slot in group.iter_mut() {
            // The next joint towards the base with a covariance, moving G along the
            // joints skipped.
            while let Some(i) = left.checked_sub(1) {
                left = i;
                let (Some(j), Some(t), Some(cov)) =
                    (chain.joints.get(i), thetas.get(i), covs.get(i))
                else {
                    break;
                };
                let c = Congruence::of_inverse(&g);
                g = j.displacement(j.clip(*t, clip_continuous)).compose(&g);
                if !is_zero(cov) {
                    *slot = (c, cov);
                    filled += 1;
                    break;
                }
            }
        }
        sums.add(&group, filled);
    }
    g
}

/// Whether every entry of `cov` is zero (a joint without noise): its transport adds
/// nothing. NaN is not zero, so a non-finite covariance is still transported.
#[inline(always)]
fn is_zero<T: Real>(cov: &Mat6<T>) -> bool {
    // The diagonal first: a joint with noise has a non-zero variance, so the scan
    // usually stops within six entries.
    cov.0
        .iter()
        .enumerate()
        .all(|(i, r)| r.get(i).is_none_or(|x| *x == T::ZERO))
        && cov.0.iter().flatten().all(|x| *x == T::ZERO)
}

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
    fn gather(f: impl Fn(usize) -> T) -> Self {
        let mut a = [T::ZERO; W];
        for k in 0..W {
            a[k] = f(k);
        }
        Pack(a)
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
    const ZERO: Self = Self {
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

    /// W congruences side by side: adds the lower triangle of congruence k applied to
    /// covariance k to lane k of `acc`. The same operations on [`Pack`] lanes, which the
    /// optimiser maps to SIMD where the target has it. Every pack is built whole from its
    /// W lanes (see the module doc).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // a gather: lane k of every element, by index
    pub(crate) fn add_lower_packed<const W: usize>(
        items: &[(Self, &Mat6<T>); W],
        acc: &mut [[Pack<T, W>; 6]; 6],
    ) {
        let mut r = [[Pack::zero(); 3]; 3];
        let mut q = [Pack::zero(); 3];
        let mut c = [[Pack::zero(); 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = Pack::gather(|k| items[k].0.r[i][j]);
            }
            q[i] = Pack::gather(|k| items[k].0.q[i]);
        }
        for i in 0..6 {
            for j in 0..6 {
                c[i][j] = Pack::gather(|k| items[k].1 .0[i][j]);
            }
        }
        transport_lower(&r, &q, &c, acc);
    }
}

/// The lower triangle of `diag(R, R)·S·Σ·Sᵀ·diag(R, R)ᵀ`, `S = [[I, 0], [Q, I]]`,
/// `Q = [q]×`, added to `acc`. Shear first (its products with the skew Q are cross
/// products), then the block rotations; every stage writes its block out before the next
/// starts, which keeps few values live (fewer register spills than rotating first).
#[inline(always)]
fn transport_lower<L: Lane>(r: &[[L; 3]; 3], q: &[L; 3], c: &[[L; 6]; 6], acc: &mut [[L; 6]; 6]) {
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
