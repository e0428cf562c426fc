//! The batch PPOE (`batch.rs`) against single calls, on this host, f32 and f64, every
//! convention, with and without the joints' displacement constants, batches whose length
//! is and is not a multiple of the lane count.
//!
//! Oracle: the module's claim is that lane k runs the one-lane schedule's operations in its
//! order, so every result must equal `with_lanes(.., 1)` on its row *bit for bit* (and the
//! rank-one batch `ppoe_rank1` on its row); the default single call (another width on SIMD
//! hosts) within the width tests' bounds (`lane_tests.rs`).

extern crate std;
use std::vec::Vec;

use super::lane_tests::{flat, random_chain, random_cov, rel_to_max, Rng, CONVENTIONS};
use super::schedule::with_lanes;
use super::{BatchError, Convention, UncertainPose};
use crate::error::Error;
use crate::kinematics::ChainView;
use crate::linalg::Mat6;
use crate::scalar::Real;
use crate::se3::Transform;

/// Batch lengths: one, the lane counts and neighbours (tails of every size).
const LENGTHS: [usize; 6] = [1, 2, 3, 4, 5, 9];

fn blank<T: Real>(n: usize) -> Vec<UncertainPose<T>> {
    std::vec![UncertainPose::certain(Transform::identity()); n]
}

/// A covariance per joint, every third one zero (skipped joints).
fn covs<T: Real>(rng: &mut Rng, n: usize) -> Vec<Mat6<T>> {
    (0..n)
        .map(|i| {
            let c = random_cov(rng);
            if i % 3 == 1 {
                Mat6::zeros()
            } else {
                c
            }
        })
        .collect()
}

fn batch_matches_single_calls<T: Real>(bound: f64) {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    for n in 1..=9 {
        for prepared in [false, true] {
            let (joints, home) = random_chain::<T>(&mut rng, n, prepared);
            let chain = ChainView {
                joints: &joints,
                home,
            };
            for len in LENGTHS {
                let th: Vec<T> = (0..n * len).map(|_| T::lit(3.0 * rng.next())).collect();
                let shared = covs::<T>(&mut rng, n);
                let each: Vec<Mat6<T>> = (0..len).flat_map(|_| covs::<T>(&mut rng, n)).collect();
                for conv in CONVENTIONS {
                    let mut a = blank(len);
                    chain.ppoe_batch(&th, &shared, conv, &mut a).unwrap();
                    let mut b = blank(len);
                    chain
                        .ppoe_batch_per_config(&th, &each, conv, &mut b)
                        .unwrap();
                    for k in 0..len {
                        let row = &th[k * n..(k + 1) * n];
                        let one = with_lanes(&chain, row, &shared, conv, 1);
                        assert_eq!(a[k], one, "{n} joints, {len} configs, #{k}, {conv:?}");
                        let own = &each[k * n..(k + 1) * n];
                        let one = with_lanes(&chain, row, own, conv, 1);
                        assert_eq!(b[k], one, "per config: {n} joints, #{k}, {conv:?}");
                        let default = chain.ppoe(row, &shared, conv).unwrap();
                        let [ap, ac] = flat(&a[k].pose, &a[k].cov);
                        let [dp, dc] = flat(&default.pose, &default.cov);
                        let e = rel_to_max(&ap, &dp).max(rel_to_max(&ac, &dc));
                        assert!(e <= bound, "{n} joints {conv:?}: {e:.2e} > {bound:.0e}");
                    }
                }
            }
        }
    }
}

#[test]
fn batch_matches_single_calls_f64() {
    batch_matches_single_calls::<f64>(1e-14);
}

#[test]
fn batch_matches_single_calls_f32() {
    batch_matches_single_calls::<f32>(1e-5);
}

fn rank1_batch_is_bitwise<T: Real>() {
    let mut rng = Rng(0x0bad_cafe_f00d_d00d);
    for n in 1..=8 {
        let (joints, home) = random_chain::<T>(&mut rng, n, n % 2 == 0);
        let chain = ChainView {
            joints: &joints,
            home,
        };
        for len in LENGTHS {
            let th: Vec<T> = (0..n * len).map(|_| T::lit(3.0 * rng.next())).collect();
            let s2: Vec<T> = (0..n).map(|i| T::lit(1e-4 * (i % 3) as f64)).collect();
            for conv in CONVENTIONS {
                let mut a = blank(len);
                chain.ppoe_rank1_batch(&th, &s2, conv, &mut a).unwrap();
                for (k, got) in a.iter().enumerate() {
                    let row = &th[k * n..(k + 1) * n];
                    let one = chain.ppoe_rank1(row, &s2, conv).unwrap();
                    assert_eq!(*got, one, "{n} joints, {len} configs, #{k}, {conv:?}");
                }
            }
        }
    }
}

#[test]
fn rank1_batch_is_bitwise_f64() {
    rank1_batch_is_bitwise::<f64>();
}

#[test]
fn rank1_batch_is_bitwise_f32() {
    rank1_batch_is_bitwise::<f32>();
}

/// Wrong lengths are errors; the checked calls name the configuration of a bad θ, a bad
/// per-configuration covariance and an overflowing result.
#[test]
fn batch_errors_name_the_configuration() {
    let mut rng = Rng(7);
    let (joints, home) = random_chain::<f64>(&mut rng, 3, true);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let covs = covs::<f64>(&mut rng, 3);
    let mut out = blank(4);
    let mut th: Vec<f64> = (0..12).map(|_| rng.next()).collect();
    let conv = Convention::Right;
    let mismatch = Err(Error::LengthMismatch);
    assert_eq!(chain.ppoe_batch(&th[..11], &covs, conv, &mut out), mismatch);
    assert_eq!(chain.ppoe_batch(&th, &covs[..2], conv, &mut out), mismatch);
    assert_eq!(
        chain.ppoe_batch_per_config(&th, &covs, conv, &mut out),
        mismatch
    );
    assert_eq!(
        chain.ppoe_rank1_batch(&th, &[1e-4; 2], conv, &mut out),
        mismatch
    );
    assert!(chain.ppoe_batch_checked(&th, &covs, conv, &mut out).is_ok());
    th[7] = f64::NAN;
    let nan = BatchError {
        config: Some(2),
        error: Error::NonFinite,
    };
    assert_eq!(
        chain.ppoe_batch_checked(&th, &covs, conv, &mut out),
        Err(nan)
    );
    assert_eq!(
        chain.ppoe_rank1_batch_checked(&th, &[1e-4; 3], conv, &mut out),
        Err(nan)
    );
    th[7] = 0.1;
    let mut each: Vec<Mat6<f64>> = (0..4).flat_map(|_| covs.clone()).collect();
    each[5].0[0][0] = -1.0;
    let bad = chain.ppoe_batch_per_config_checked(&th, &each, conv, &mut out);
    assert_eq!(bad.map_err(|e| e.config), Err(Some(1)));
    // A covariance equal to the previous configuration's shares its check: a bad one
    // repeated is reported at its first configuration, and NaN (never equal) each time.
    let mut repeated = each.clone();
    (repeated[8], repeated[11]) = (repeated[5], repeated[5]);
    let bad = chain.ppoe_batch_per_config_checked(&th, &repeated, conv, &mut out);
    assert_eq!(bad.map_err(|e| e.config), Err(Some(1)));
    let mut nan_late = each.clone();
    (nan_late[5], nan_late[8]) = (covs[2], covs[2]);
    nan_late[11].0[1][1] = f64::NAN;
    let bad = chain.ppoe_batch_per_config_checked(&th, &nan_late, conv, &mut out);
    let nan = BatchError {
        config: Some(3),
        error: Error::NonFinite,
    };
    assert_eq!(bad, Err(nan));
    let mut huge = covs.clone();
    huge[0] = Mat6::identity() * f64::MAX;
    let mut huge_each = each.clone();
    huge_each[5] = covs[2];
    huge_each[9] = huge[0];
    let over = chain.ppoe_batch_per_config_checked(&th, &huge_each, conv, &mut out);
    assert_eq!(
        over,
        Err(BatchError {
            config: Some(3),
            error: Error::Overflow
        })
    );
    let shown = std::format!("{}", over.unwrap_err());
    assert_eq!(
        shown,
        "configuration 3: result is not finite: an intermediate overflowed"
    );
}
