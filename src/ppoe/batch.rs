//! The PPOE of many configurations of one chain: a trajectory, a planner's candidates, a
//! dataset. [`ChainView::ppoe_batch`] and its variants.
//!
//! Why configurations in the lanes: the single-call schedule (`schedule.rs`) puts W
//! *joints* side by side, which needs gathers of their congruences and covariances and
//! leaves the forward kinematics (a chain of dependent products) and the sin/cos scalar.
//! Here W *configurations* run side by side, W = as many as fill one 128-bit register
//! (f64: 2, f32: 4 where 128-bit SIMD exists, else 1): every value of
//! the computation, the sin/cos, the products of the forward kinematics and the
//! transports, is a [`Pack`] of W independent lanes, built whole, with no gather except
//! the joint values; a covariance shared by every configuration (a robot's noise model)
//! is the same in every lane.
//!
//! Why lane k is bit-identical to a single call: each lane runs the operations of the
//! one-lane schedule (`schedule.rs` with W = 1: the transports summed joint by joint in
//! the order of the chain) in the same order (`packed.rs` says how), so for finite
//! inputs a configuration's result does not depend on its position in the batch, on the
//! batch's length or on W. It equals [`ChainView::ppoe`] exactly where that call runs one
//! lane (Cortex-M, RISC-V without vector units); elsewhere the single call
//! sums its joint lanes separately, and the two differ by a few ε of ‖Σ‖ (the unit tests in
//! `batch_tests.rs` beside this file check both statements). A last group of fewer than
//! W configurations fills its empty lanes with its last configuration, whose duplicates
//! are computed and discarded.
//!
//! Joints whose covariance is exactly zero in every lane are skipped, as in the single
//! call; a zero covariance in some lanes only is transported there and adds exactly zero
//! (for finite inputs).
//!
//! Why the chain's last joint is transported once per batch (tip frame, shared
//! covariances): its congruence is constant (Ad(M⁻¹), or the identity in the
//! pytransform3d convention), so its term is the same in every configuration; computed
//! by the scalar operations each lane would run into zeros, it starts every group's sum
//! with the same bits, one transport of n saved per configuration.

use super::packed::{displacement, Poses};
use super::schedule::{is_zero, simd_lanes};
use super::{Convention, UncertainPose};
use crate::error::Error;
use crate::joint::Joint;
use crate::kinematics::ChainView;
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::congruence::{mirror_lower, transport_lower, Congruence, Pack};
use crate::se3::Transform;
use crate::uncertainty::check_covariance;

/// Why a checked batch call failed: the error, and the configuration (row of `thetas`,
/// entry of `out`) it concerns; `None` when it concerns no one configuration (the chain,
/// the lengths, a covariance shared by all).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BatchError {
    /// The configuration's index, if the error is one configuration's.
    pub config: Option<usize>,
    /// What went wrong.
    pub error: Error,
}

impl From<Error> for BatchError {
    fn from(error: Error) -> Self {
        Self {
            config: None,
            error,
        }
    }
}

impl core::fmt::Display for BatchError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.config {
            Some(i) => write!(f, "configuration {i}: {}", self.error),
            None => write!(f, "{}", self.error),
        }
    }
}

impl core::error::Error for BatchError {}

/// The error `error` of configuration `config`.
fn at(config: usize, error: Error) -> BatchError {
    BatchError {
        config: Some(config),
        error,
    }
}

/// Which configurations a group's lanes hold: lane k holds `first + k`, or `last` (the
/// batch's last one) where that is beyond the batch.
#[derive(Clone, Copy)]
struct Group {
    first: usize,
    last: usize,
}

impl Group {
    /// The configuration in lane k.
    #[inline(always)]
    fn config(&self, k: usize) -> usize {
        (self.first + k).min(self.last)
    }

    /// Joint i's values in the lanes, clipped as [`Joint::clip`], from row-major `thetas`
    /// with n joints per row.
    #[inline(always)]
    fn thetas<T: Real, const W: usize>(
        &self,
        thetas: &[T],
        n: usize,
        i: usize,
        j: &Joint<T>,
        clip_continuous: bool,
    ) -> Pack<T, W> {
        Pack::gather(|k| {
            let t = thetas.get(self.config(k) * n + i).copied();
            j.clip(t.unwrap_or(T::ZERO), clip_continuous)
        })
    }
}

/// Where the lanes' joint covariances come from.
trait CovLanes<T: Real, const W: usize> {
    /// Writes joint i's covariances in the lanes of `group` to `c`; `false` (and `c`
    /// unspecified) when they are zero in every lane.
    fn lanes(&self, i: usize, group: &Group, c: &mut Acc<T, W>) -> bool;

    /// Joint i's covariance if it is the same in every configuration: `Some(None)` when
    /// it is zero, `None` when it may differ between configurations.
    fn common(&self, i: usize) -> Option<Option<&Mat6<T>>>;
}

/// One covariance per joint, shared by every configuration, with which of the first 64
/// are zero found once per batch (a zero covariance is scanned whole, and a robot's noise
/// model often has joints without noise).
struct Shared<'a, T> {
    covs: &'a [Mat6<T>],
    /// Bit i: joint i < 64 has a non-zero covariance.
    nonzero: u64,
}

impl<'a, T: Real> Shared<'a, T> {
    fn new(covs: &'a [Mat6<T>]) -> Self {
        let nonzero = covs
            .iter()
            .take(64)
            .enumerate()
            .filter(|(_, c)| !is_zero(c))
            .fold(0u64, |m, (i, _)| {
                m | u32::try_from(i).map_or(0, |b| 1u64 << (b & 63))
            });
        Self { covs, nonzero }
    }

    /// Joint i's covariance, `None` if it is zero (or absent).
    #[inline(always)]
    fn get(&self, i: usize) -> Option<&Mat6<T>> {
        let cov = self.covs.get(i)?;
        let zero = match u32::try_from(i)
            .ok()
            .and_then(|b| self.nonzero.checked_shr(b))
        {
            Some(bits) if i < 64 => bits & 1 == 0,
            _ => is_zero(cov),
        };
        (!zero).then_some(cov)
    }
}

impl<T: Real, const W: usize> CovLanes<T, W> for Shared<'_, T> {
    #[inline(always)]
    fn lanes(&self, i: usize, _: &Group, c: &mut Acc<T, W>) -> bool {
        let Some(cov) = self.get(i) else {
            return false;
        };
        for (crow, row) in c.iter_mut().zip(&cov.0) {
            for (x, v) in crow.iter_mut().zip(row) {
                *x = Pack::splat(*v);
            }
        }
        true
    }

    #[inline(always)]
    fn common(&self, i: usize) -> Option<Option<&Mat6<T>>> {
        Some(self.get(i))
    }
}

/// One covariance per joint and configuration, row-major (configurations × joints).
struct PerConfig<'a, T> {
    covs: &'a [Mat6<T>],
    n: usize,
}

impl<T: Real, const W: usize> CovLanes<T, W> for PerConfig<'_, T> {
    #[inline(always)]
    fn lanes(&self, i: usize, group: &Group, c: &mut Acc<T, W>) -> bool {
        let zero = Mat6::zeros();
        let cov = |k: usize| self.covs.get(group.config(k) * self.n + i).unwrap_or(&zero);
        if (0..W).all(|k| is_zero(cov(k))) {
            return false;
        }
        for (r, crow) in c.iter_mut().enumerate() {
            for (col, x) in crow.iter_mut().enumerate() {
                *x = Pack::gather(|k| cov(k).0[r][col]);
            }
        }
        true
    }

    #[inline(always)]
    fn common(&self, _: usize) -> Option<Option<&Mat6<T>>> {
        None
    }
}

/// Lower triangles of the transported covariances of the W lanes, summed.
type Acc<T, const W: usize> = [[Pack<T, W>; 6]; 6];

/// Lane k of `acc`, each entry plus `start`.
#[inline(always)]
fn lane<T: Real, const W: usize>(acc: &Acc<T, W>, k: usize, start: T) -> [[T; 6]; 6] {
    let mut out = [[T::ZERO; 6]; 6];
    for (orow, row) in out.iter_mut().zip(acc) {
        for (o, x) in orow.iter_mut().zip(row) {
            *o = start + x.0.get(k).copied().unwrap_or(T::ZERO);
        }
    }
    out
}

/// The dense batch after the length checks, in the target's lane count.
fn dense<T: Real, C: CovLanes<T, 4> + CovLanes<T, 2> + CovLanes<T, 1>>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &C,
    convention: Convention,
    out: &mut [UncertainPose<T>],
) {
    match const { simd_lanes::<T>() } {
        4 => dense_lanes::<T, C, 4>(chain, thetas, covs, convention, out),
        2 => dense_lanes::<T, C, 2>(chain, thetas, covs, convention, out),
        _ => dense_lanes::<T, C, 1>(chain, thetas, covs, convention, out),
    }
}

/// The dense batch, W configurations at a time.
#[inline(always)]
fn dense_lanes<T: Real, C: CovLanes<T, W>, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &C,
    convention: Convention,
    out: &mut [UncertainPose<T>],
) {
    let last = out.len().saturating_sub(1);
    let first = hoisted_first::<T, C, W>(chain, covs, convention);
    let start = first
        .unwrap_or([[T::ZERO; 6]; 6])
        .map(|row| row.map(Pack::splat));
    for (g, chunk) in out.chunks_mut(W).enumerate() {
        let group = Group { first: g * W, last };
        let mut acc: Acc<T, W> = start;
        let pose = if convention == Convention::Left {
            base_frame(chain, thetas, covs, &group, &mut acc)
        } else {
            let skip_first = first.is_some();
            tip_frame(
                chain, thetas, covs, convention, &group, skip_first, &mut acc,
            )
        };
        if convention == Convention::Pytransform3d {
            acc = moved_to_tip(&chain.home, &acc);
        }
        for (k, o) in chunk.iter_mut().enumerate() {
            *o = UncertainPose {
                pose: pose.lane(k),
                // `0 + x`, as the one-lane schedule's final sum.
                cov: mirror_lower(lane(&acc, k, T::ZERO)),
            };
        }
    }
}

/// The tip-frame sum's first term, computed once per batch: the loop's first joint (the
/// chain's last) is transported by a constant congruence, Ad(M⁻¹) (Right) or the identity
/// (Pytransform3d, whose M comes at the end), so where its covariance is shared the term
/// is the same in every configuration. It is the scalar transport into zeros that every
/// lane would run (the same operations, so the same bits); zeros where the covariance is
/// zero (the lanes skip it). `None` where nothing is hoisted: the base frame (whose first
/// congruence varies), covariances per configuration, no joints.
fn hoisted_first<T: Real, C: CovLanes<T, W>, const W: usize>(
    chain: &ChainView<'_, T>,
    covs: &C,
    convention: Convention,
) -> Option<[[T; 6]; 6]> {
    if convention == Convention::Left {
        return None;
    }
    let last = chain.joints.len().checked_sub(1)?;
    let cov = covs.common(last)?;
    let mut acc = [[T::ZERO; 6]; 6];
    if let Some(cov) = cov {
        let g = if convention == Convention::Right {
            chain.home
        } else {
            Transform::identity()
        };
        let c = Congruence::of_inverse(&g);
        c.add_lower(cov, &mut acc);
    }
    Some(acc)
}

/// Pytransform3d's sums moved by Ad(M), `M` = `home`, in every lane: lane k is the one-lane
/// schedule's `home.transport_covariance` of `mirror_lower(0 + Σₖ)` (the same operations:
/// `0 + x` mirrored into whole matrices, then [`Congruence::add_lower_splat`] into zeros).
#[inline(always)]
fn moved_to_tip<T: Real, const W: usize>(home: &Transform<T>, acc: &Acc<T, W>) -> Acc<T, W> {
    let zero = Pack::splat(T::ZERO);
    let mut full = [[zero; 6]; 6];
    for (i, row) in full.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            let (r, c) = if i >= j { (i, j) } else { (j, i) };
            *x = zero + acc.get(r).and_then(|a| a.get(c)).copied().unwrap_or(zero);
        }
    }
    let mut out = [[zero; 6]; 6];
    Congruence::of(home).add_lower_splat(&full, &mut out);
    out
}

/// Base frame, as the schedule's `base_frame` per lane: Σ_left = Σᵢ Ad(Pᵢ)·covᵢ·Ad(Pᵢ)ᵀ,
/// Pᵢ = D₁…Dᵢ. Returns the poses Pₙ·M.
#[inline(always)]
fn base_frame<T: Real, C: CovLanes<T, W>, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &C,
    group: &Group,
    acc: &mut Acc<T, W>,
) -> Poses<T, W> {
    let n = chain.joints.len();
    let mut c = [[Pack::splat(T::ZERO); 6]; 6];
    let mut p = Poses::splat(&Transform::identity());
    for (i, j) in chain.joints.iter().enumerate() {
        p = p.compose(&displacement(j, group.thetas(thetas, n, i, j, false)));
        if covs.lanes(i, group, &mut c) {
            transport_lower(&p.r, &p.rotated_back_translation(), &c, acc);
        }
    }
    p.compose(&Poses::splat(&chain.home))
}

/// Tip frame, as the schedule's `tip_frame` per lane: Σ = Σᵢ Ad(Gᵢ⁻¹)·covᵢ·Ad(Gᵢ⁻¹)ᵀ,
/// Gᵢ = Dᵢ₊₁…Dₙ·M (Right) or Dᵢ₊₁…Dₙ (Pytransform3d, whose sum the caller moves by Ad(M)).
/// `skip_first`: the chain's last joint's term is already in `acc` ([`hoisted_first`]).
/// Returns the poses.
#[inline(always)]
fn tip_frame<T: Real, C: CovLanes<T, W>, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    covs: &C,
    convention: Convention,
    group: &Group,
    skip_first: bool,
    acc: &mut Acc<T, W>,
) -> Poses<T, W> {
    let n = chain.joints.len();
    let mut c = [[Pack::splat(T::ZERO); 6]; 6];
    let right = convention == Convention::Right;
    let mut g = Poses::splat(&if right {
        chain.home
    } else {
        Transform::identity()
    });
    for (i, j) in chain.joints.iter().enumerate().rev() {
        // The congruence by Ad(G⁻¹): Rᵀ and −p.
        let (r, q) = (g.rotation_transposed(), [-g.p[0], -g.p[1], -g.p[2]]);
        g = displacement(j, group.thetas(thetas, n, i, j, !right)).compose(&g);
        if !(skip_first && i + 1 == n) && covs.lanes(i, group, &mut c) {
            transport_lower(&r, &q, &c, acc);
        }
    }
    if right {
        g
    } else {
        g.compose(&Poses::splat(&chain.home))
    }
}

/// The rank-one batch after the length checks, in the target's lane count.
fn rank1<T: Real>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    sigma2: &[T],
    convention: Convention,
    out: &mut [UncertainPose<T>],
) {
    match const { simd_lanes::<T>() } {
        4 => rank1_lanes::<T, 4>(chain, thetas, sigma2, convention, out),
        2 => rank1_lanes::<T, 2>(chain, thetas, sigma2, convention, out),
        _ => rank1_lanes::<T, 1>(chain, thetas, sigma2, convention, out),
    }
}

/// The rank-one batch, W configurations at a time: the rank-one PPOE (`rank1.rs`) per lane.
#[inline(always)]
fn rank1_lanes<T: Real, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    sigma2: &[T],
    convention: Convention,
    out: &mut [UncertainPose<T>],
) {
    let last = out.len().saturating_sub(1);
    for (g, chunk) in out.chunks_mut(W).enumerate() {
        let group = Group { first: g * W, last };
        let mut acc: Acc<T, W> = [[Pack::splat(T::ZERO); 6]; 6];
        let pose = rank1_group(chain, thetas, sigma2, convention, &group, &mut acc);
        for (k, o) in chunk.iter_mut().enumerate() {
            *o = UncertainPose {
                pose: pose.lane(k),
                cov: mirror_lower(lane(&acc, k, T::ZERO)),
            };
        }
    }
}

/// One group of the rank-one batch: `Σ = J·diag(σ²)·Jᵀ` with the space Jacobian (Left) or
/// the body Jacobian (Right; Pytransform3d's moved by Ad(M)), as `rank1.rs`. Returns the
/// poses.
#[inline(always)]
fn rank1_group<T: Real, const W: usize>(
    chain: &ChainView<'_, T>,
    thetas: &[T],
    sigma2: &[T],
    convention: Convention,
    group: &Group,
    acc: &mut Acc<T, W>,
) -> Poses<T, W> {
    let n = chain.joints.len();
    let clip_continuous = convention == Convention::Pytransform3d;
    let splat = |s: &crate::linalg::Vec6<T>| s.0.map(Pack::splat);
    let home = Poses::splat(&chain.home);
    if convention == Convention::Left {
        let mut p = Poses::splat(&Transform::identity());
        for ((i, j), s2) in chain.joints.iter().enumerate().zip(sigma2) {
            add_rank1_lower(&p.adjoint_apply(&splat(&j.screw)), *s2, acc);
            p = p.compose(&displacement(j, group.thetas(thetas, n, i, j, false)));
        }
        return p.compose(&home);
    }
    let right = convention == Convention::Right;
    let mut g = if right {
        home
    } else {
        Poses::splat(&Transform::identity())
    };
    for ((i, j), s2) in chain.joints.iter().enumerate().zip(sigma2).rev() {
        let u = g.inverse_adjoint_apply(&splat(&j.screw));
        let u = if right { u } else { home.adjoint_apply(&u) };
        add_rank1_lower(&u, *s2, acc);
        g = displacement(j, group.thetas(thetas, n, i, j, clip_continuous)).compose(&g);
    }
    if right {
        g
    } else {
        g.compose(&home)
    }
}

/// `acc += σ²·u·uᵀ` (lower triangle), as `rank1.rs`'s `add_rank1_lower`.
#[inline(always)]
fn add_rank1_lower<T: Real, const W: usize>(u: &[Pack<T, W>; 6], sigma2: T, acc: &mut Acc<T, W>) {
    let su = u.map(|x| x * Pack::splat(sigma2));
    for (r, row) in acc.iter_mut().enumerate() {
        for (c, a) in row.iter_mut().enumerate().take(r + 1) {
            if let (Some(s), Some(x)) = (su.get(r), u.get(c)) {
                *a += *s * *x;
            }
        }
    }
}

impl<T: Real> ChainView<'_, T> {
    /// The PPOE of many configurations, unchecked: `out[k]` is [`ChainView::ppoe`] of row k
    /// of `thetas` (row-major, `out.len()` rows of one value per joint) with the joint
    /// covariances `covs` (one per joint) shared by every configuration, in `convention`.
    ///
    /// Method: as [`ChainView::ppoe`], with the configurations rather than the joints in
    /// the lanes of SIMD registers (the module `batch.rs` of this package says why). The
    /// result of a configuration is bit-identical for finite inputs wherever it stands in
    /// any batch; it equals a single [`ChainView::ppoe`] call exactly where that call
    /// runs one lane (Cortex-M, RISC-V) and within a few ε of ‖Σ‖ elsewhere
    /// (the single call sums its lanes in another order). Same accuracy as
    /// [`ChainView::ppoe`].
    ///
    /// ```
    /// use ppoe::chain::{screw_noise, Chain, Convention, Joint, JointKind, UncertainPose};
    /// use ppoe::Transform;
    /// const INF: f64 = f64::INFINITY;
    /// // The planar 2-link arm of `Chain::ppoe`.
    /// const ARM: Chain<f64, 2> = Chain::new("base", "tip", [
    ///     Joint::new("j1", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
    ///     Joint::new("j2", JointKind::Revolute, [0., 0., 1., 0., -0.5, 0.], -INF, INF),
    /// ], Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [1., 0., 0.]));
    /// let covs = ARM.joints.map(|j| screw_noise(&j.screw, 1e-4));
    /// // Three configurations, one row of two joint values each.
    /// let thetas = [0.3, -0.2, 0.0, 0.0, 1.0, 0.5];
    /// let mut out = [UncertainPose::certain(Transform::identity()); 3];
    /// ARM.as_ref().ppoe_batch(&thetas, &covs, Convention::Right, &mut out)?;
    /// let single = ARM.ppoe(&[1.0, 0.5], &covs, Convention::Right);
    /// approx::assert_abs_diff_eq!(out[2], single, epsilon = 1e-15);
    /// # Ok::<(), ppoe::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `covs` has one entry per joint and `thetas` one row
    /// per entry of `out`.
    pub fn ppoe_batch(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
        out: &mut [UncertainPose<T>],
    ) -> Result<(), Error> {
        let n = self.joints.len();
        if covs.len() != n || out.len().checked_mul(n) != Some(thetas.len()) {
            return Err(Error::LengthMismatch);
        }
        dense(self, thetas, &Shared::new(covs), convention, out);
        Ok(())
    }

    /// [`ChainView::ppoe_batch`] with one covariance per joint *and configuration*: `covs`
    /// row-major like `thetas` (`out.len()` rows of one 6×6 per joint). Same method and
    /// bit-identity; the covariances are gathered into the lanes, which costs more than
    /// shared ones.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `thetas` and `covs` both have one row per entry
    /// of `out`.
    pub fn ppoe_batch_per_config(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
        out: &mut [UncertainPose<T>],
    ) -> Result<(), Error> {
        let n = self.joints.len();
        let rows = out.len().checked_mul(n);
        if rows != Some(thetas.len()) || rows != Some(covs.len()) {
            return Err(Error::LengthMismatch);
        }
        dense(self, thetas, &PerConfig { covs, n }, convention, out);
        Ok(())
    }

    /// [`ChainView::ppoe_batch`] with input checks, as [`ChainView::ppoe_checked`]: the
    /// chain, every θ finite, every covariance checked ([`check_covariance`], once: they
    /// are shared), then every result finite ([`Error::Overflow`] otherwise).
    ///
    /// # Errors
    ///
    /// A [`BatchError`] with the configuration concerned (`None` for the lengths, the
    /// chain and the shared covariances). On an error from the result checks, `out`
    /// holds every result, valid or not; on an input error it is untouched.
    pub fn ppoe_batch_checked(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
        out: &mut [UncertainPose<T>],
    ) -> Result<(), BatchError> {
        self.check_batch_thetas(thetas, out.len())?;
        for c in covs {
            check_covariance(c)?;
        }
        self.ppoe_batch(thetas, covs, convention, out)?;
        validate_all(out)
    }

    /// [`ChainView::ppoe_batch_per_config`] with the input and result checks of
    /// [`ChainView::ppoe_batch_checked`], every covariance checked (a covariance equal to
    /// the same joint's in the previous configuration shares its check: a repeated noise
    /// model costs one factorisation per joint).
    ///
    /// # Errors
    ///
    /// As [`ChainView::ppoe_batch_checked`]; a covariance's error names its configuration.
    pub fn ppoe_batch_per_config_checked(
        &self,
        thetas: &[T],
        covs: &[Mat6<T>],
        convention: Convention,
        out: &mut [UncertainPose<T>],
    ) -> Result<(), BatchError> {
        self.check_batch_thetas(thetas, out.len())?;
        let n = self.joints.len().max(1);
        for (i, c) in covs.iter().enumerate() {
            // Equal to the same joint's covariance one configuration earlier, which
            // passed: the same check would pass (±0 aside, equal values give the same
            // result; NaN is never equal). A noise model repeated over the batch is
            // factorised once per joint instead of once per configuration.
            if i.checked_sub(n).and_then(|p| covs.get(p)) == Some(c) {
                continue;
            }
            check_covariance(c).map_err(|e| at(i / n, e))?;
        }
        self.ppoe_batch_per_config(thetas, covs, convention, out)?;
        validate_all(out)
    }

    /// The rank-one PPOE ([`ChainView::ppoe_rank1`]: one variance per joint along its
    /// screw axis) of many configurations: `sigma2` one variance per joint, shared by every
    /// configuration, `thetas` and `out` as [`ChainView::ppoe_batch`]. Lane k is
    /// bit-identical to [`ChainView::ppoe_rank1`] on row k for finite inputs, on every
    /// target (the single rank-one call has no lanes).
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] unless `sigma2` has one entry per joint and `thetas` one
    /// row per entry of `out`.
    pub fn ppoe_rank1_batch(
        &self,
        thetas: &[T],
        sigma2: &[T],
        convention: Convention,
        out: &mut [UncertainPose<T>],
    ) -> Result<(), Error> {
        let n = self.joints.len();
        if sigma2.len() != n || out.len().checked_mul(n) != Some(thetas.len()) {
            return Err(Error::LengthMismatch);
        }
        rank1(self, thetas, sigma2, convention, out);
        Ok(())
    }

    /// [`ChainView::ppoe_rank1_batch`] with the checks of [`ChainView::ppoe_rank1_checked`]
    /// (the chain, finite θ and σ², no negative σ²) and every result finite.
    ///
    /// # Errors
    ///
    /// As [`ChainView::ppoe_batch_checked`]; a bad σ² is `config: None`
    /// ([`Error::NonFinite`], [`Error::NotPositiveSemidefinite`]).
    pub fn ppoe_rank1_batch_checked(
        &self,
        thetas: &[T],
        sigma2: &[T],
        convention: Convention,
        out: &mut [UncertainPose<T>],
    ) -> Result<(), BatchError> {
        self.check_batch_thetas(thetas, out.len())?;
        if !sigma2.iter().all(|s| s.is_finite()) {
            return Err(Error::NonFinite.into());
        }
        if sigma2.iter().any(|s| *s < T::ZERO) {
            return Err(Error::NotPositiveSemidefinite.into());
        }
        self.ppoe_rank1_batch(thetas, sigma2, convention, out)?;
        validate_all(out)
    }

    /// The checks shared by the checked batch calls before any computation: the lengths of
    /// `thetas` (`rows` rows), the chain, every θ finite.
    fn check_batch_thetas(&self, thetas: &[T], rows: usize) -> Result<(), BatchError> {
        let n = self.joints.len();
        if rows.checked_mul(n) != Some(thetas.len()) {
            return Err(Error::LengthMismatch.into());
        }
        self.check()?;
        match thetas.iter().position(|t| !t.is_finite()) {
            Some(i) => Err(at(i / n.max(1), Error::NonFinite)),
            None => Ok(()),
        }
    }
}

/// Every result finite and a valid pose (`checks::validate_uncertain_pose`).
fn validate_all<T: Real>(out: &[UncertainPose<T>]) -> Result<(), BatchError> {
    for (i, o) in out.iter().enumerate() {
        crate::checks::validate_uncertain_pose(&o.pose, &o.cov).map_err(|e| at(i, e))?;
    }
    Ok(())
}
