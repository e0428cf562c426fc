//! The PPOE's instruction schedule: the covariance transports `Ad·Σ·Adᵀ` of the joints,
//! W at a time, side by side in the lanes of SIMD registers. Private: only the order in
//! which the same operations run depends on it, never what is computed.
//!
//! Why lanes: each joint's transport is independent of the others' (the sum of the
//! transported covariances is only formed at the end), so W of them can run as one
//! computation on [`Pack`]s of W scalars, which the optimiser maps to SIMD registers
//! where the target has them (SSE2, NEON, wasm simd128): no shuffle is needed inside a
//! transport. [`lanes`] chooses W per scalar and target: f64 as many as fill one
//! 128-bit vector where the target has them (2), f32 two on x86 and four (a whole
//! vector) on the other SIMD targets, else 1 (Cortex-M: a scalar FPU, where lanes would
//! only add register pressure).
//!
//! Why f32 runs two lanes on x86: measured. On x86-64 the four-lane f32 PPOE executes
//! fewer instructions than the two-lane one but ran slower, and slower than f64 (the
//! `lanes_ratio` benchmark times every width; BENCHMARKS.md, shipped with this package,
//! gives the figures). Its groups gather every covariance entry of four joints into a
//! register (four loads and three shuffles each, where two lanes need two), the likely
//! cost; it was not isolated. Two f32 lanes are
//! computed in 4-lane registers whose other two lanes the program does not define. When
//! the congruences were gathered into lanes from registers, those lanes held leftovers
//! of earlier code, which underflowed into subnormals: on a core with a slow path for
//! them the two-lane f32 PPOE ran 1.2-1.3x slower than f64 (0.9x with flush-to-zero
//! set), and f32 ran one lane on x86 instead. Packs now reach the registers from memory
//! ([`PackedCongruence`] below, the covariances loaded entry by entry), and loads fill
//! the other lanes with zeros: the test `tests/subnormal_lanes.rs` checks that an f32
//! and f64 PPOE raise no subnormal-operand and no underflow flag in any lane (x86-64's
//! MXCSR), and `lanes_ratio` with `LANES_RATIO_FLAGS` set shows the same per width.
//!
//! Not kept: two f32 joints in four lanes whose other two are zero (a prototype with
//! packed congruences, not kept, so no command here reproduces it, executed 5408
//! instructions for the seed's dense f32 PPOE instead of two lanes' 4152 under
//! `lanes_ratio`'s callgrind mode, and ran 1.5x slower); one transport with its
//! matrices' rows in lanes (`Ad·Σ` as combinations of Σ's rows, then `(Ad·Σ)·Adᵀ` as
//! combinations of Adᵀ's): the optimiser splits such packs into scalars and regroups
//! them with shuffles, and the PPOE executed more instructions; the rows of the 3×3
//! blocks in four-lane packs (three entries and a zero, one SSE register each): every
//! product needs an entry broadcast to all lanes (a shuffle) and, in SSE's two-operand
//! form, a copy; a prototype (not kept) executed 5710 instructions for the seed's dense
//! f32 PPOE instead of 4859 (one lane, then) under `lanes_ratio`'s callgrind mode.
//!
//! Why congruences are written into packs, one group ahead: the joints go in groups of
//! W, and each joint's congruence is written into lane k of the group's packs
//! ([`PackedCongruence`]) as soon as it is made, so the transport reads every pack whole
//! from where it was written, as a memory operand. Built as W local values and gathered
//! into lanes instead, the transport loaded each entry of each congruence separately,
//! shuffled the lanes together and spilled the packs to the stack for later use (on the
//! seed's dense f64 PPOE this and the padded tail below cut its instructions from 4418
//! to 4268 under `lanes_ratio`'s callgrind mode, and more so its loads and stores to the
//! stack; on x86-64 the time followed the loads and stores more than the instruction
//! count). Written lane by lane, a pack is loaded whole right after its lanes were
//! stored one at a time, which stalls (the store buffer cannot forward one load from
//! two stores); so group k + 1 is made before group k is transported ([`Sums::run`]),
//! and the stores have long left the store buffer when the transport loads them. The
//! forward kinematics of the next group, a chain of dependent products, also runs
//! beside the transports, which do not depend on it. One lane is the exception: there
//! each joint goes from the walk to its transport through a one-slot group (nothing to
//! pack; [`Sums::run_one_lane`]).
//!
//! Why the last group is padded: when the joint count is not a multiple of W, the empty
//! lanes of the last group get zero congruences and covariances (exactly zero results).
//! With two lanes a padded lane costs a whole transport, but so did the alternative, its
//! joint transported alone one lane at a time (a scalar transport executes as many
//! instructions as a two-lane one, and on x86-64 `lanes_ratio`'s f64 7-joint chain ran
//! slower than its 8-joint one with packed congruences and a one-lane tail, a variant
//! not kept, so no command here reproduces it). With four lanes one packed transport costs fewer
//! instructions than three scalar ones (a 7-joint f32 chain 5228 instead of 5579 per
//! PPOE under callgrind, measured with the gathered form) but more than two, so a last
//! group at most half full runs one lane at a time (the code path of the one-lane
//! targets). Also not kept (no command here reproduces it): a lone joint in two lanes
//! by blocks (the sandwiches of its upper-left and sheared lower-right blocks side by
//! side, the lower-left block's columns 0 and 1 in lanes; entry by entry the same
//! operations). Under `lanes_ratio`'s callgrind mode, as a branch in [`Sums::add`] it
//! cost the seed's dense f64 PPOE 4270 instructions instead of 4099 and the 7-joint arm
//! 5368 instead of 5267; with the last group taken out of the loop the arm executed 5140
//! (5539 padded in that loop), yet ran slower than the padded loop here (`lanes_ratio`
//! `61 2000`, three runs alternating with the kept code: 375, 378 and 527 ns per call
//! against 356, 346 and 348; the third under load, the closed-form port there 1299 ns
//! against 1007-1046 in the others), and slower still when the lone joint was
//! transported first.
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
//! tests (`lane_tests.rs` beside this file), so the one-lane schedule of the scalar-FPU
//! targets is tested by `cargo test` on the host too (and runs in QEMU); the
//! `lanes_ratio` benchmark times them (built with `--cfg ppoe_bench_lanes`, see
//! `with_lanes`).
//!
//! Private because it is a performance decision with no effect on the result's
//! definition: the public entry points and their accuracy do not change when it changes;
//! the benchmarks and the firmware's instruction counts are where a new schedule must
//! prove itself.

use super::{Convention, UncertainPose};
use crate::kinematics::ChainView;
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::congruence::{mirror_lower, Congruence, Pack, PackedCongruence};
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
/// target (see the module doc): [`simd_lanes`], except f32 on x86 (two lanes).
const fn lanes<T: Real>() -> usize {
    const X86: bool = cfg!(any(target_arch = "x86", target_arch = "x86_64"));
    match core::mem::size_of::<T>() {
        4 if X86 && SIMD128 => 2,
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
/// groups of W, each group's W congruences written into the lanes of packs and
/// transported in the W lanes together; a last group of fewer than W joints is padded
/// with zeros, except one at most half full of W > 2 lanes, which is transported one
/// lane at a time (see [`Sums::add`]).
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
    let zero = Mat6::zeros();
    let pose = if convention == Convention::Left {
        let mut walk = BaseWalk {
            chain,
            thetas,
            covs,
            p: Transform::identity(),
            i: 0,
        };
        sums.run(&mut walk, &zero);
        walk.p * chain.home
    } else {
        let start = if convention == Convention::Right {
            chain.home
        } else {
            Transform::identity()
        };
        let mut walk = TipWalk {
            chain,
            thetas,
            covs,
            clip_continuous: convention == Convention::Pytransform3d,
            g: start,
            left: chain.joints.len(),
        };
        sums.run(&mut walk, &zero);
        let g = walk.g;
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
/// and one for the joints transported one lane at a time (with four lanes, those of a
/// last group at most half full).
struct Sums<T, const W: usize> {
    lanes: [[Pack<T, W>; 6]; 6],
    tail: [[T; 6]; 6],
}

impl<T: Real, const W: usize> Sums<T, W> {
    /// Whether the tail is ever added to: with more than two lanes (a last group at most
    /// half full). Else it stays zero, and is not read.
    const TAIL: bool = W > 2;

    /// Runs `walk` to its end. One lane: each joint's transport as it comes
    /// ([`Self::run_one_lane`]). More: one group at a time, each group's transports after
    /// the next group has been made (the module doc says why).
    #[inline(always)]
    fn run<'c, K: Walk<'c, T>>(&mut self, walk: &mut K, zero: &'c Mat6<T>) {
        if W == 1 {
            return self.run_one_lane(walk, zero);
        }
        let mut a = Group::new(zero);
        let mut b = Group::new(zero);
        a.fill(walk);
        while a.filled > 0 {
            b.fill(walk);
            self.add(&mut a, zero);
            if b.filled == 0 {
                break;
            }
            a.fill(walk);
            self.add(&mut b, zero);
        }
    }

    /// [`Self::run`] with one lane (the scalar-FPU targets): each joint through a
    /// one-slot group, gathered into one-lane packs. The slot is the form the firmware's
    /// budgets were set with; handing each joint from the walk straight to its transport
    /// compiled to more stack on the Cortex-M targets with an FPU (the M4F's f32 PPOE 428
    /// bytes instead of 352, `scripts/firmware.sh`, with a variant not kept).
    #[inline(always)]
    fn run_one_lane<'c, K: Walk<'c, T>>(&mut self, walk: &mut K, zero: &'c Mat6<T>) {
        loop {
            let mut group = [(Congruence::ZERO, zero); W];
            let mut filled = 0;
            for slot in group.iter_mut() {
                if let Some(next) = walk.next() {
                    *slot = next;
                    filled += 1;
                }
            }
            if filled == 0 {
                return;
            }
            Congruence::add_lower_packed(&group, &mut self.lanes);
        }
    }

    /// Adds the transports of `group`'s joints (W > 1; [`Self::run`] passes only groups
    /// with at least one): in the W lanes together, the empty lanes of an incomplete
    /// group set to zero congruences and covariances, or, with more than two lanes and at
    /// most half of them filled, one lane at a time.
    #[inline(always)]
    fn add<'c>(&mut self, group: &mut Group<'c, T, W>, zero: &'c Mat6<T>) {
        let filled = group.filled;
        if W == 2 || 2 * filled > W {
            for k in filled..W {
                group.congruences.set_lane(k, &Congruence::ZERO);
                if let Some(slot) = group.covs.get_mut(k) {
                    *slot = zero;
                }
            }
            group.congruences.add_lower(&group.covs, &mut self.lanes);
        } else {
            for (k, cov) in group.covs.iter().enumerate().take(filled) {
                group.congruences.lane(k).add_lower(cov, &mut self.tail);
            }
        }
        group.filled = 0;
    }

    /// The sum over the lanes and the tail, mirrored: exactly symmetric.
    #[inline(always)]
    fn total(&self) -> Mat6<T> {
        let mut acc = [[T::ZERO; 6]; 6];
        for ((arow, lrow), trow) in acc.iter_mut().zip(&self.lanes).zip(&self.tail) {
            for ((a, l), t) in arow.iter_mut().zip(lrow).zip(trow) {
                // All 36, only the lower triangle is kept. Starting from zero where the
                // tail is unused lets the optimiser drop it.
                let start = if Self::TAIL { *t } else { T::ZERO };
                *a = l.0.iter().fold(start, |s, x| s + *x);
            }
        }
        mirror_lower(acc)
    }
}

/// Up to W joints' congruences in the lanes of packs, and their covariances: the first
/// `filled` lanes hold joints, the others what an earlier group left (set to zero before
/// they are transported, [`Sums::add`]).
struct Group<'c, T, const W: usize> {
    congruences: PackedCongruence<T, W>,
    covs: [&'c Mat6<T>; W],
    filled: usize,
}

impl<'c, T: Real, const W: usize> Group<'c, T, W> {
    /// An empty group.
    #[inline(always)]
    fn new(zero: &'c Mat6<T>) -> Self {
        Self {
            congruences: PackedCongruence::ZERO,
            covs: [zero; W],
            filled: 0,
        }
    }

    /// Fills the lanes with `walk`'s next joints (fewer at the chain's end).
    #[inline(always)]
    fn fill<K: Walk<'c, T>>(&mut self, walk: &mut K) {
        for _ in 0..W {
            let Some((c, cov)) = walk.next() else {
                break;
            };
            self.congruences.set_lane(self.filled, &c);
            if let Some(slot) = self.covs.get_mut(self.filled) {
                *slot = cov;
            }
            self.filled += 1;
        }
    }
}

/// A walk along the chain, one joint with a covariance at a time.
trait Walk<'c, T: Real> {
    /// The next joint that has a covariance: its congruence and covariance (`None` at the
    /// chain's end).
    fn next(&mut self) -> Option<(Congruence<T>, &'c Mat6<T>)>;
}

/// Base frame: Σ_left = Σᵢ Ad(Pᵢ)·covᵢ·Ad(Pᵢ)ᵀ, Pᵢ = D₁…Dᵢ (the reference's sum moved by
/// Ad(Pₙ)); one transport per joint and none at the end. `p` ends as Pₙ.
struct BaseWalk<'a, 'c, T> {
    chain: &'a ChainView<'a, T>,
    thetas: &'a [T],
    covs: &'c [Mat6<T>],
    p: Transform<T>,
    i: usize,
}

impl<'c, T: Real> Walk<'c, T> for BaseWalk<'_, 'c, T> {
    #[inline(always)]
    fn next(&mut self) -> Option<(Congruence<T>, &'c Mat6<T>)> {
        // Moving P along the joints skipped.
        while let (Some(j), Some(t), Some(cov)) = (
            self.chain.joints.get(self.i),
            self.thetas.get(self.i),
            self.covs.get(self.i),
        ) {
            self.i += 1;
            self.p = self.p.compose(&j.displacement(j.clip(*t, false)));
            if !is_zero(cov) {
                return Some((Congruence::of(&self.p), cov));
            }
        }
        None
    }
}

/// Tip frame, from the tip backwards: Σ_right = Σᵢ Ad(Gᵢ⁻¹)·covᵢ·Ad(Gᵢ⁻¹)ᵀ with
/// Gᵢ = Dᵢ₊₁…Dₙ·`start` (the reference's recursion unrolled, then moved by Ad(M⁻¹) for
/// `start` = M). One transport per joint and none at the end, and each uses the lever arm
/// from joint i to the tip, not through the base and back. The reference's variant starts
/// from I and moves the sum by Ad(M) instead. `g` ends as G₀.
struct TipWalk<'a, 'c, T> {
    chain: &'a ChainView<'a, T>,
    thetas: &'a [T],
    covs: &'c [Mat6<T>],
    clip_continuous: bool,
    g: Transform<T>,
    left: usize,
}

impl<'c, T: Real> Walk<'c, T> for TipWalk<'_, 'c, T> {
    #[inline(always)]
    fn next(&mut self) -> Option<(Congruence<T>, &'c Mat6<T>)> {
        // Towards the base, moving G along the joints skipped.
        while let Some(i) = self.left.checked_sub(1) {
            self.left = i;
            let (Some(j), Some(t), Some(cov)) = (
                self.chain.joints.get(i),
                self.thetas.get(i),
                self.covs.get(i),
            ) else {
                break;
            };
            let c = Congruence::of_inverse(&self.g);
            self.g = j
                .displacement(j.clip(*t, self.clip_continuous))
                .compose(&self.g);
            if !is_zero(cov) {
                return Some((c, cov));
            }
        }
        None
    }
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
