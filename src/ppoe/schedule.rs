//! The PPOE's instruction schedule: the covariance transports `Ad·Σ·Adᵀ` of the joints,
//! W at a time, side by side in the lanes of SIMD registers. Private: only the order in
//! which the same operations run depends on it, never what is computed.
//!
//! Why lanes: each joint's transport is independent of the others' (the sum of the
//! transported covariances is only formed at the end), so W of them can run as one
//! computation on [`Pack`]s of W scalars, which the optimiser maps to SIMD registers
//! where the target has them (SSE2, NEON, wasm simd128): no shuffle is needed inside a
//! transport. [`lanes`] chooses W per scalar and target: f64 as many as fill one
//! 128-bit vector where the target has them (2), f32 one on x86 and four (a whole
//! vector) on the other SIMD targets, else 1 (Cortex-M: a scalar FPU, where lanes would
//! only add register pressure).
//!
//! Why f32 runs one lane on x86: its four-lane groups gather every congruence and
//! covariance entry of four joints into a register (four loads and three shuffles each,
//! where f64's two lanes need two), and on x86-64 the one-lane f32 PPOE ran faster than
//! the four-lane one although it executes more instructions (the `lanes_ratio`
//! benchmark times every width; BENCHMARKS.md, shipped with this package, gives the
//! figures). Never two f32 lanes: they are computed in 4-lane registers whose other two
//! lanes the program leaves undefined (leftovers of earlier code), and on a core with a
//! slow path for subnormals the two-lane f32 PPOE ran 1.2-1.3x slower than f64 (0.9x
//! with flush-to-zero set): f32's narrow range underflows in the undefined lanes.
//! Nor two f32 joints in four lanes whose other two are zero (slower still), nor one
//! transport with its matrices' rows in lanes (`Ad·Σ` as combinations of Σ's rows, then
//! `(Ad·Σ)·Adᵀ` as combinations of Adᵀ's): the optimiser splits such packs into scalars
//! and regroups them with shuffles, and the PPOE executed more instructions. Nor with the
//! rows of the 3×3 blocks in four-lane packs (three entries and a zero, one SSE register
//! each): every product needs an entry broadcast to all lanes (a shuffle) and, in SSE's
//! two-operand form, a copy; a prototype (not kept, so no command here reproduces it)
//! executed 5710 instructions for the seed's dense f32 PPOE instead of 4859 under
//! `lanes_ratio`'s callgrind mode.
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
//! the covariance's size. Every width is compiled and compared on every host by the unit
//! tests (`lane_tests.rs` beside this file), so the one-lane schedule is tested by
//! `cargo test` (in the form of the SIMD hosts, see `Sums::IN_PLACE`; the scalar-FPU targets'
//! form runs in QEMU); the `lanes_ratio` benchmark
//! times them (built with `--cfg ppoe_bench_lanes`, see `with_lanes`).
//!
//! Private because it is a performance decision with no effect on the result's
//! definition: the public entry points and their accuracy do not change when it changes;
//! the benchmarks and the firmware's instruction counts are where a new schedule must
//! prove itself.

use super::{Convention, UncertainPose};
use crate::kinematics::ChainView;
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::congruence::{mirror_lower, Congruence, Pack};
use crate::se3::Transform;

/// Whether the target has 128-bit SIMD registers for floats.
const SIMD128: bool = cfg!(any(
    target_feature = "sse2",
    target_feature = "neon",
    target_feature = "simd128"
));

/// How many values of scalar `T` fill one 128-bit SIMD register on this target (f32: 4,
/// f64: 2), 1 without SIMD: the batch PPOE's lane count (its lanes are configurations).
pub(super) const fn simd_lanes<T: Real>() -> usize {
    match core::mem::size_of::<T>() {
        4 if SIMD128 => 4,
        8 if SIMD128 => 2,
        _ => 1,
    }
}

/// How many transports the single-call PPOE computes side by side for scalar `T` on this
/// target (see the module doc): [`simd_lanes`], except f32 on x86 (one lane).
const fn lanes<T: Real>() -> usize {
    const X86: bool = cfg!(any(target_arch = "x86", target_arch = "x86_64"));
    match core::mem::size_of::<T>() {
        4 if X86 => 1,
        _ => simd_lanes::<T>(),
    }
}

/// The PPOE of `chain` after the length check, with the target's lane count [`lanes`]:
/// a constant of T and the target, so only one arm is compiled in.
#[inline(always)]
pub(super) fn ppoe<T: Real>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    convention: Convention,
) -> UncertainPose<T> {
    match const { lanes::<T>() } {
        4 => ppoe_lanes::<T, 4>(chain, thetas, covs, convention),
        2 => ppoe_lanes::<T, 2>(chain, thetas, covs, convention),
        _ => ppoe_lanes::<T, 1>(chain, thetas, covs, convention),
    }
}

/// [`ppoe`] with `lanes` transports side by side (1, 2 or 4; any other value gives 1)
/// instead of the target's choice: the schedules of other targets run on this one
/// (results differ only in rounding). Compiled for the unit tests, and with
/// `--cfg ppoe_bench_lanes` for the `lanes_ratio` benchmark; in no other build.
#[cfg(any(test, ppoe_bench_lanes))]
pub(super) fn with_lanes<T: Real>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    convention: Convention,
    lanes: usize,
) -> UncertainPose<T> {
    match lanes {
        4 => ppoe_lanes::<T, 4>(chain, thetas, covs, convention),
        2 => ppoe_lanes::<T, 2>(chain, thetas, covs, convention),
        _ => ppoe_lanes::<T, 1>(chain, thetas, covs, convention),
    }
}

/// The PPOE of `chain` after the length check, W transports at a time: the joints go in
/// groups of W, each group's W congruences and covariances are built as locals and
/// transported in the W lanes together; a last group of fewer than W joints is
/// transported one lane at a time unless it fills more than half of W > 2 lanes (see
/// [`Sums::add`]).
#[inline(always)]
fn ppoe_lanes<T: Real, const W: usize>(
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
/// and one for the joints of the last, incomplete group (with one lane on a SIMD target,
/// for every joint).
struct Sums<T, const W: usize> {
    lanes: [[Pack<T, W>; 6]; 6],
    tail: [[T; 6]; 6],
}

impl<T: Real, const W: usize> Sums<T, W> {
    /// One lane on a SIMD target (f32 on x86-64): each transport reads its covariance in
    /// place and goes to the tail, the lanes stay zero. Gathered into one-lane packs, the
    /// covariance was copied to the stack and read back by loads spanning two of the
    /// copy's stores (store-forwarding stalls, every joint). Not on the scalar-FPU
    /// targets: there the gathered form compiled to less stack for software f64 (the
    /// firmware's budgets).
    const IN_PLACE: bool = W == 1 && SIMD128;

    /// Adds the transports of `group`'s first `filled` entries: in place to the tail if
    /// [`Self::IN_PLACE`]; else in lanes together when all W are filled or, with more than
    /// two lanes, more than half of them (the empty slots hold zero congruences and
    /// covariances); else one lane at a time.
    #[inline(always)]
    fn add(&mut self, group: &[(Congruence<T>, &Mat6<T>); W], filled: usize) {
        if Self::IN_PLACE {
            if let (1, Some((c, cov))) = (filled, group.first()) {
                c.add_lower(cov, &mut self.tail);
            }
        } else if filled == W || (W > 2 && 2 * filled > W) {
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
        if Self::IN_PLACE {
            return mirror_lower(self.tail);
        }
        // One lane elsewhere: no tail (every group is full); starting from zeros lets the
        // optimiser drop it.
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
pub(super) fn is_zero<T: Real>(cov: &Mat6<T>) -> bool {
    // The diagonal first: a joint with noise has a non-zero variance, so the scan
    // usually stops within six entries.
    cov.0
        .iter()
        .enumerate()
        .all(|(i, r)| r.get(i).is_none_or(|x| *x == T::ZERO))
        && cov.0.iter().flatten().all(|x| *x == T::ZERO)
}
