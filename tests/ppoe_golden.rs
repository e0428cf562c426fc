//! Golden tests of the PPOE on our test robots, against `test_data/reference/generate_ppoe.py`
//! (pytransform3d 3.17.0's example `ProbabilisticRobotKinematics`): the pytransform3d-compatible variant must
//! reproduce the example's pose and covariance; the right and left conventions must match
//! `Ad(M⁻¹)·C·Ad(M⁻¹)ᵀ` and `Ad(T̄)·Σ_R·Ad(T̄)ᵀ` computed by the oracle script from the
//! same C.
//!
//! Error measure `max|a − b| / max(1, max|b|)`: f64 ≤ 1e-12. f32 ≤ [`F32_BOUND`] for joint
//! values up to 10 rad (f32 rounds an angle θ by θ·6·10⁻⁸, so the 1000-rad cases of
//! continuous joints carry an input error of 6·10⁻⁵ and are excluded from the f32 check).

mod common;
use common::*;
use ppoe::chain::{ChainView, Convention};
use ppoe::uncertainty::check_covariance;
use ppoe::{Mat6, Real, Vec6, Vector};

const F64_BOUND: f64 = 1e-12;
/// Six joints, each an exp (≈ 20 roundings) and a 6×6 congruence (≈ 12 roundings per
/// element) on values of order 1: typically 1e-6 (worst seen 1.7e-6), bound 1e-5.
const F32_BOUND: f64 = 1e-5;

/// The golden files: one per test chain.
const FILES: [&str; 8] = PPOE_FILES;

/// `prepared`: the joints with their displacement constants (what `ppoe-build`'s tables
/// and `Joint::from_f64` hold), else as `Joint::new` makes them (derived per call).
fn run<T: Real>(bound: f64, file: &str, prepared: bool) {
    let g = golden(&format!("ppoe/{file}.json"));
    let (mut joints, home) = chain_from_golden::<T>(&g);
    if prepared {
        joints = joints.into_iter().map(|j| j.prepared()).collect();
        assert!(joints.iter().any(|j| j.constants().is_some()));
    }
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let ty = if prepared {
        format!("{} prepared", core::any::type_name::<T>())
    } else {
        core::any::type_name::<T>().to_string()
    };
    let mut w = [
        Worst::new(&format!("{file} clip {ty}")),
        Worst::new(&format!("{file} pose {ty}")),
        Worst::new(&format!("{file} cov pytransform3d {ty}")),
        Worst::new(&format!("{file} cov right {ty}")),
        Worst::new(&format!("{file} cov left {ty}")),
    ];
    let is_f32 = Real::to_f64(T::EPS) > 1e-10;
    let (mut psd_checked, mut n) = (0usize, 0usize);
    for c in g["cases"].as_array().unwrap() {
        let l = c["label"].as_str().unwrap();
        let thetas = vecf(&c["thetas"]);
        if is_f32 && thetas.iter().any(|t| t.abs() > 10.0) {
            continue;
        }
        let th: Vec<T> = thetas.iter().map(|x| T::lit(*x)).collect();
        let covs: Vec<Mat6<T>> = c["covs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| cast_m(&mat6(m)))
            .collect();
        let mut clipped = vec![T::ZERO; th.len()];
        chain.clip(&th, &mut clipped, true).unwrap();
        let clipped64: Vec<f64> = clipped.iter().map(|x| Real::to_f64(*x)).collect();
        w[0].add(rel_err(&clipped64, &vecf(&c["thetas_clipped"])), l);
        let compat = chain.ppoe(&th, &covs, Convention::Pytransform3d).unwrap();
        w[1].add(
            rel_err(
                &flat_t(&up_t(&compat.pose)),
                &flat_t(&transform(&c["pose"])),
            ),
            l,
        );
        w[2].add(
            rel_err(
                &flat(&up_m(&compat.cov)),
                &flat(&mat6(&c["cov_pytransform3d"])),
            ),
            l,
        );
        // Right/left from the clipped values (continuous joints with stated limits are not
        // clipped by the default conventions; the oracle always clips).
        let right = chain.ppoe_checked(&clipped, &covs, Convention::Right);
        let right = right.unwrap_or_else(|e| panic!("{l}: {e}"));
        w[3].add(
            rel_err(&flat(&up_m(&right.cov)), &flat(&mat6(&c["cov_right"]))),
            l,
        );
        let left = chain.ppoe(&clipped, &covs, Convention::Left).unwrap();
        w[4].add(
            rel_err(&flat(&up_m(&left.cov)), &flat(&mat6(&c["cov_left"]))),
            l,
        );
        // Every output covariance is exactly symmetric (one triangle computed, mirrored),
        // and PSD within check_covariance's tolerance when the inputs are PSD to working
        // precision (an input indefinite within tolerance may stay so, see ppoe_checked).
        let inputs_psd = covs.iter().all(psd_to_working_precision);
        for (name, cov) in [
            ("pytransform3d", &compat.cov),
            ("right", &right.cov),
            ("left", &left.cov),
        ] {
            assert_eq!(cov.asymmetry(), T::ZERO, "{file} {l}: {name} not symmetric");
            if inputs_psd {
                check_covariance(cov).unwrap_or_else(|e| panic!("{file} {l}: {name}: {e}"));
            }
        }
        psd_checked += usize::from(inputs_psd);
        n += 1;
    }
    for x in &w {
        x.check(bound);
    }
    println!("{file} {ty}: outputs exactly symmetric; PSD checked in {psd_checked} of {n} cases");
    // The golden set is built from PSD covariances (Gram matrices, diagonal, rank-deficient):
    // the PSD check must not be vacuous.
    assert!(
        psd_checked * 2 > n,
        "{file}: too few PSD input sets ({psd_checked} of {n})"
    );
}

/// `sym(Σ) + (64·ε·‖Σ‖_max + MIN_POSITIVE)·I` has a Cholesky factor: λ_min ≥ −64·ε·‖Σ‖_max.
fn psd_to_working_precision<T: Real>(c: &Mat6<T>) -> bool {
    let shift = T::lit(64.0) * T::EPS * c.amax() + T::min_positive_value();
    (c.symmetrize() + Mat6::identity() * shift)
        .cholesky()
        .is_some()
}

#[test]
fn ppoe_f64_all_robots() {
    for f in FILES {
        run::<f64>(F64_BOUND, f, false);
        run::<f64>(F64_BOUND, f, true);
    }
}

#[test]
fn ppoe_f32_all_robots() {
    for f in FILES {
        run::<f32>(F32_BOUND, f, false);
        run::<f32>(F32_BOUND, f, true);
    }
}

/// The seed example's initial state and all 200 animation frames are in the golden file.
#[test]
fn seed_frames_present() {
    let g = golden("ppoe/seed_linkmount_tcp.json");
    let labels: Vec<&str> = g["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["label"].as_str().unwrap())
        .collect();
    assert!(labels.contains(&"seed_initial"));
    for k in 0..200 {
        assert!(
            labels.contains(&format!("frame_{k}").as_str()),
            "frame_{k} missing"
        );
    }
    let _ = Vec6::<f64>::zeros() + Vector([0.0; 6]);
}
