//! The PPOE's schedules against each other, on the host: the covariance transports run 1,
//! 2 or 4 at a time side by side (`ChainView::ppoe_with_lanes`). Every Cortex-M target
//! runs the one-lane schedule, hosts with 128-bit SIMD the two-lane one; this runs both
//! (and four lanes) here, on every golden chain and case, in f32 and f64, for the three
//! conventions, with and without the joints' displacement constants.
//!
//! The golden chains have 5, 6 and 7 joints: with two and four lanes the last group is
//! incomplete for some (transported one lane at a time), full for others. Joints with a
//! zero covariance are skipped (`zero_covariances_*`).
//!
//! Oracle: the schedules are the same operations on the same values, except that W lanes
//! sum the transported covariances in W partial sums (added at the end). So pose and
//! covariance of every width must agree with those of one lane to rounding:
//! `max|a − b| / max|b|` ≤ 1e-14 (f64) and 1e-5 (f32). The default `ppoe` must equal one
//! of the widths bit for bit (it is one of these schedules, chosen by the target).

mod common;
use common::*;
use ppoe::chain::{ChainView, Convention};
use ppoe::{Mat6, Matrix, Real, Transform};

const F64_BOUND: f64 = 1e-14;
const F32_BOUND: f64 = 1e-5;

/// `max|a − b|`.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// `max|a − b| / max|b|`, 0 when both are zero.
fn rel_to_max(a: &[f64], b: &[f64]) -> f64 {
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

fn pose_flat<T: Real>(t: &Transform<T>) -> Vec<f64> {
    flat_t(&up_t(t))
}

fn cov_flat<T: Real>(c: &Mat6<T>) -> Vec<f64> {
    flat(&up_m(c))
}

/// Every case of golden file `file`: returns the worst error seen and the number of
/// comparisons made.
fn run<T: Real>(file: &str, prepared: bool) -> (f64, usize) {
    let g = golden(&format!("ppoe/{file}.json"));
    let (mut joints, home) = chain_from_golden::<T>(&g);
    if prepared {
        joints = joints.into_iter().map(|j| j.prepared()).collect();
    }
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let (mut worst, mut n) = (0.0f64, 0usize);
    for c in g["cases"].as_array().unwrap() {
        let l = c["label"].as_str().unwrap();
        let th: Vec<T> = vecf(&c["thetas"]).iter().map(|x| T::lit(*x)).collect();
        let covs: Vec<Mat6<T>> = c["covs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| cast_m(&mat6(m)))
            .collect();
        for conv in [
            Convention::Right,
            Convention::Left,
            Convention::Pytransform3d,
        ] {
            let one = chain.ppoe_with_lanes(&th, &covs, conv, 1).unwrap();
            let default = chain.ppoe(&th, &covs, conv).unwrap();
            let mut default_is_a_width = default == one;
            for w in [2, 4] {
                let other = chain.ppoe_with_lanes(&th, &covs, conv, w).unwrap();
                default_is_a_width |= default == other;
                for (a, b) in [
                    (pose_flat(&other.pose), pose_flat(&one.pose)),
                    (cov_flat(&other.cov), cov_flat(&one.cov)),
                ] {
                    let e = rel_to_max(&a, &b);
                    assert!(e.is_finite(), "{file} {l} {conv:?} {w} lanes: {e}");
                    worst = worst.max(e);
                    n += 1;
                }
            }
            assert!(
                default_is_a_width,
                "{file} {l} {conv:?}: ppoe is none of the schedules"
            );
        }
    }
    (worst, n)
}

fn all_files<T: Real>(bound: f64) {
    for file in PPOE_FILES {
        for prepared in [false, true] {
            let (worst, n) = run::<T>(file, prepared);
            let ty = core::any::type_name::<T>();
            println!("{file} {ty} prepared={prepared}: {n} comparisons, worst {worst:.2e}");
            assert!(n > 0, "{file}: no cases");
            assert!(worst <= bound, "{file} {ty}: {worst:.2e} > {bound:.0e}");
        }
    }
}

#[test]
fn lane_widths_agree_f64() {
    all_files::<f64>(F64_BOUND);
}

#[test]
fn lane_widths_agree_f32() {
    all_files::<f32>(F32_BOUND);
}

/// Joints with a zero covariance are skipped by the schedule; one with a tiny non-zero
/// covariance is transported. The PPOE is linear in the joint covariances, so the two must
/// agree to rounding of the all-joints covariance (the tiny one's contribution,
/// ~1e-200 resp. 1e-30 of it, is far below that), at every width, for every pattern of zero joints (every subset of the
/// first joints: odd and even counts of transported joints, zero joints between, before and
/// after them) and every convention.
fn zero_covariances<T: Real>(tiny: f64, bound: f64) {
    for file in PPOE_FILES {
        let g = golden(&format!("ppoe/{file}.json"));
        let (joints, home) = chain_from_golden::<T>(&g);
        let chain = ChainView {
            joints: &joints,
            home,
        };
        let n = joints.len();
        let th: Vec<T> = (0..n).map(|i| T::lit(0.3 - 0.2 * i as f64)).collect();
        let full: Vec<Mat6<T>> = (0..n)
            .map(|i| {
                let mut m = Mat6::zeros();
                for (r, row) in m.0.iter_mut().enumerate() {
                    for (c, x) in row.iter_mut().enumerate() {
                        let d = if r == c { 1e-3 } else { 0.0 };
                        *x = T::lit(d + 1e-5 * ((r + c + i) % 4) as f64);
                    }
                }
                m
            })
            .collect();
        // The errors are relative to the covariance of all joints' noise: with few (or
        // no) joints transported the result itself can be zero.
        let all = chain.ppoe(&th, &full, Convention::Right).unwrap().cov;
        let scale = cov_flat(&all).iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut compared = 0;
        for mask in 0u32..(1 << n.min(8)) {
            let pick = |scale: f64| -> Vec<Mat6<T>> {
                (0..n)
                    .map(|i| {
                        if mask & (1 << i) != 0 {
                            full[i]
                        } else {
                            Matrix(full[i].0.map(|r| r.map(|x| x * T::lit(scale))))
                        }
                    })
                    .collect()
            };
            let (zeroed, tiny_covs) = (pick(0.0), pick(tiny));
            for conv in [
                Convention::Right,
                Convention::Left,
                Convention::Pytransform3d,
            ] {
                for w in [1, 2, 4] {
                    let a = chain.ppoe_with_lanes(&th, &zeroed, conv, w).unwrap();
                    let b = chain.ppoe_with_lanes(&th, &tiny_covs, conv, w).unwrap();
                    assert_eq!(a.pose, b.pose, "{file} {mask:b} {conv:?} {w}");
                    let e = max_diff(&cov_flat(&a.cov), &cov_flat(&b.cov)) / scale;
                    assert!(
                        e <= bound,
                        "{file} mask {mask:b} {conv:?} {w} lanes: {e:.2e} > {bound:.0e}"
                    );
                    compared += 1;
                }
            }
        }
        assert!(compared > 0);
    }
}

#[test]
fn zero_covariances_f64() {
    zero_covariances::<f64>(1e-200, F64_BOUND);
}

#[test]
fn zero_covariances_f32() {
    zero_covariances::<f32>(1e-30, F32_BOUND);
}

/// A length mismatch is an error at every width, as for `ppoe`.
#[test]
fn lane_widths_check_lengths() {
    let g = golden("ppoe/seed_linkmount_tcp.json");
    let (joints, home) = chain_from_golden::<f64>(&g);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let th = vec![0.0; joints.len()];
    let covs = vec![Mat6::zeros(); joints.len() - 1];
    for w in [1, 2, 4] {
        assert_eq!(
            chain.ppoe_with_lanes(&th, &covs, Convention::Right, w),
            Err(ppoe::Error::LengthMismatch)
        );
    }
}
