//! The PPOE's schedules against each other, on this host: the covariance transports run
//! 1, 2 or 4 at a time side by side ([`with_lanes`]). Every Cortex-M target runs the
//! one-lane schedule, hosts with 128-bit SIMD the two- or four-lane one; these tests run
//! all three here, in f32 and f64, for the three conventions, with and without the
//! joints' displacement constants.
//!
//! The chains are random (a fixed seed) with 1 to 9 joints of every kind, so that with
//! two and four lanes the last group is full for some and incomplete, padded or (four
//! lanes, at most half full) transported one lane at a time, for others; a group's lanes
//! are reused, so stale lanes must not leak into the next group's result. Joints with a
//! zero covariance are skipped (`zero_covariances_*`).
//!
//! Oracle: the schedules are the same operations on the same values, except that W lanes
//! sum the transported covariances in W partial sums (added at the end). So pose and
//! covariance of every width must agree with those of one lane to rounding:
//! `max|a − b| / max|b|` ≤ 1e-14 (f64) and 1e-5 (f32). The default `ppoe` must equal one
//! of the widths bit for bit (it is one of these schedules, chosen by the target).

extern crate std;
use std::vec::Vec;

use super::schedule::with_lanes;
use super::Convention;
use crate::joint::{Joint, JointKind};
use crate::kinematics::ChainView;
use crate::linalg::{Mat6, Matrix};
use crate::scalar::Real;
use crate::se3::{self, Transform};

const F64_BOUND: f64 = 1e-14;
const F32_BOUND: f64 = 1e-5;
pub(super) const CONVENTIONS: [Convention; 3] = [
    Convention::Right,
    Convention::Left,
    Convention::Pytransform3d,
];

/// A fixed-seed generator of uniform numbers in [−1, 1) (xorshift64*): the same cases on
/// every run and target.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        x as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// A unit 3-vector (not uniform on the sphere; any direction will do).
    fn unit(&mut self) -> [f64; 3] {
        loop {
            let v = [self.next(), self.next(), self.next()];
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 0.1 {
                return v.map(|x| x / n);
            }
        }
    }
}

/// Joint `i` of a random chain: revolute, continuous or prismatic in turn, its axis
/// through a point within 1 m of the base, limits ±2.5 (values up to ±3 get clipped).
fn random_joint<T: Real>(rng: &mut Rng, i: usize) -> Joint<T> {
    let (w, q) = (rng.unit(), [rng.next(), rng.next(), rng.next()]);
    let kind = [
        JointKind::Revolute,
        JointKind::Continuous,
        JointKind::Prismatic,
    ][i % 3];
    let screw = if kind == JointKind::Prismatic {
        [0.0, 0.0, 0.0, w[0], w[1], w[2]]
    } else {
        // (ω, q × ω): the axis through q.
        let v = [
            q[1] * w[2] - q[2] * w[1],
            q[2] * w[0] - q[0] * w[2],
            q[0] * w[1] - q[1] * w[0],
        ];
        [w[0], w[1], w[2], v[0], v[1], v[2]]
    };
    Joint::new("j", kind, screw.map(T::lit), T::lit(-2.5), T::lit(2.5))
}

/// A random positive semi-definite covariance `L·Lᵀ` of size ~1e-3.
pub(super) fn random_cov<T: Real>(rng: &mut Rng) -> Mat6<T> {
    let l: [[f64; 6]; 6] = core::array::from_fn(|_| core::array::from_fn(|_| rng.next()));
    Matrix(core::array::from_fn(|r| {
        core::array::from_fn(|c| T::lit(1e-3 * (0..6).map(|k| l[r][k] * l[c][k]).sum::<f64>()))
    }))
}

/// A random chain of `n` joints (with their displacement constants if `prepared`) and a
/// home pose within 1 m.
pub(super) fn random_chain<T: Real>(
    rng: &mut Rng,
    n: usize,
    prepared: bool,
) -> (Vec<Joint<T>>, Transform<T>) {
    let joints = (0..n)
        .map(|i| random_joint::<T>(rng, i))
        .map(|j| if prepared { j.prepared() } else { j })
        .collect();
    let xi = crate::linalg::Vector(core::array::from_fn(|_| T::lit(rng.next())));
    (joints, se3::exp(&xi))
}

pub(super) fn flat<T: Real>(pose: &Transform<T>, cov: &Mat6<T>) -> [Vec<f64>; 2] {
    let mut p: Vec<f64> = pose
        .rotation
        .0
        .iter()
        .flatten()
        .map(|x| Real::to_f64(*x))
        .collect();
    p.extend(pose.translation.0.iter().map(|x| Real::to_f64(*x)));
    [
        p,
        cov.0.iter().flatten().map(|x| Real::to_f64(*x)).collect(),
    ]
}

/// `max|a − b| / max|b|`, 0 when both are equal.
pub(super) fn rel_to_max(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if diff == 0.0 {
        0.0
    } else {
        diff / scale
    }
}

/// Widths 2 and 4 against one lane on one chain and state, every convention; asserts that
/// the default is one of the widths and returns the worst relative difference.
fn compare_widths<T: Real>(chain: &ChainView<'_, T>, th: &[T], covs: &[Mat6<T>]) -> f64 {
    let mut worst = 0.0f64;
    for conv in CONVENTIONS {
        let one = with_lanes(chain, th, covs, conv, 1);
        let default = chain.ppoe(th, covs, conv).unwrap();
        let mut default_is_a_width = default == one;
        for w in [2, 4] {
            let other = with_lanes(chain, th, covs, conv, w);
            default_is_a_width |= default == other;
            let [ap, ac] = flat(&other.pose, &other.cov);
            let [bp, bc] = flat(&one.pose, &one.cov);
            for e in [rel_to_max(&ap, &bp), rel_to_max(&ac, &bc)] {
                assert!(e.is_finite(), "{} joints {conv:?} {w} lanes: {e}", th.len());
                worst = worst.max(e);
            }
        }
        assert!(
            default_is_a_width,
            "{conv:?}: ppoe is none of the schedules"
        );
    }
    worst
}

fn lane_widths_agree<T: Real>(bound: f64) {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for n in 1..=9 {
        for prepared in [false, true] {
            let (joints, home) = random_chain::<T>(&mut rng, n, prepared);
            let chain = ChainView {
                joints: &joints,
                home,
            };
            for _ in 0..20 {
                let th: Vec<T> = (0..n).map(|_| T::lit(3.0 * rng.next())).collect();
                let covs: Vec<Mat6<T>> = (0..n).map(|_| random_cov(&mut rng)).collect();
                let worst = compare_widths(&chain, &th, &covs);
                assert!(
                    worst <= bound,
                    "{n} joints prepared={prepared}: {worst:.2e} > {bound:.0e}"
                );
            }
        }
    }
}

#[test]
fn lane_widths_agree_f64() {
    lane_widths_agree::<f64>(F64_BOUND);
}

#[test]
fn lane_widths_agree_f32() {
    lane_widths_agree::<f32>(F32_BOUND);
}

/// `full` with the covariances of the joints not in `mask` scaled by `s`.
fn masked<T: Real>(full: &[Mat6<T>], mask: u32, s: f64) -> Vec<Mat6<T>> {
    let scaled = |m: &Mat6<T>| Matrix(m.0.map(|r| r.map(|x| x * T::lit(s))));
    (0..full.len())
        .map(|i| {
            if mask & (1 << i) != 0 {
                full[i]
            } else {
                scaled(&full[i])
            }
        })
        .collect()
}

/// Joints with a zero covariance are skipped by the schedule; one with a tiny non-zero
/// covariance is transported. The PPOE is linear in the joint covariances, so the two must
/// agree to rounding of the all-joints covariance (the tiny one's contribution, ~1e-200
/// resp. 1e-30 of it, is far below that), at every width, for every pattern of zero
/// joints (every subset: odd and even counts of transported joints, zero joints between,
/// before and after them) and every convention.
fn zero_covariances<T: Real>(tiny: f64, bound: f64) {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for n in [5, 6, 7] {
        let (joints, home) = random_chain::<T>(&mut rng, n, false);
        let chain = ChainView {
            joints: &joints,
            home,
        };
        let th: Vec<T> = (0..n).map(|i| T::lit(0.3 - 0.2 * i as f64)).collect();
        let full: Vec<Mat6<T>> = (0..n).map(|_| random_cov(&mut rng)).collect();
        // Relative to the covariance of all joints' noise: with few (or no) joints
        // transported the result itself can be zero.
        let all = chain.ppoe(&th, &full, Convention::Right).unwrap();
        let scale = rel_scale(&all.cov);
        for mask in 0u32..(1 << n) {
            let (zeroed, tiny_covs) = (masked(&full, mask, 0.0), masked(&full, mask, tiny));
            for conv in CONVENTIONS {
                for w in [1, 2, 4] {
                    let a = with_lanes(&chain, &th, &zeroed, conv, w);
                    let b = with_lanes(&chain, &th, &tiny_covs, conv, w);
                    assert_eq!(a.pose, b.pose, "{n} {mask:b} {conv:?} {w}");
                    let [_, ac] = flat(&a.pose, &a.cov);
                    let [_, bc] = flat(&b.pose, &b.cov);
                    let e = ac
                        .iter()
                        .zip(&bc)
                        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
                    let e = e / scale;
                    assert!(
                        e <= bound,
                        "{n} mask {mask:b} {conv:?} {w} lanes: {e:.2e} > {bound:.0e}"
                    );
                }
            }
        }
    }
}

/// `max|cov|`, which must be positive.
fn rel_scale<T: Real>(cov: &Mat6<T>) -> f64 {
    let s = cov
        .0
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(Real::to_f64(*x).abs()));
    assert!(s > 0.0);
    s
}

#[test]
fn zero_covariances_f64() {
    zero_covariances::<f64>(1e-200, F64_BOUND);
}

#[test]
fn zero_covariances_f32() {
    zero_covariances::<f32>(1e-30, F32_BOUND);
}
