//! Calibration-grade fits (`fit_campaign`) on simulated campaigns of the exact product
//! model with every systematic error of a real campaign at once: the tracker metres away
//! at an arbitrary orientation, a marker centimetres off the tool frame, joint zero
//! offsets of milliradians, axis errors of a millimetre; a precise robot (0.07–0.2 mrad
//! per joint). The fitted tool covariance at held-out configurations (each chain its own:
//! the fitted calibrated one against the true one) against the truth, the offsets against
//! their standard errors, and the systematic tests.

mod common;
use common::*;
use ppoe::chain::{screw_noise, ChainView, Convention, Joint};
use ppoe::{se3, Mat6, Transform, Vec6};
use ppoe_fit::simulate::{self, Systematic};
use ppoe_fit::{
    fit_campaign, CampaignFit, CampaignSample, Estimate, Measurement, MeasurementCov, Model,
};

/// Precise joint noise: σ from 0.07 to 0.2 mrad (prismatic: µm).
fn precise(joints: &[Joint<f64>]) -> Vec<f64> {
    (0..joints.len())
        .map(|i| {
            let s = 0.07e-3 + 0.13e-3 * ((i * 5) % 7) as f64 / 6.0;
            s * s
        })
        .collect()
}

/// Every systematic error at once, sized by `size` (1: the sizes; the marker 9 cm
/// from the tip frame's origin, 7 cm from its z axis, whatever the size).
fn systematic(joints: &[Joint<f64>], size: f64, seed: u64) -> Systematic {
    let f = |k: u64| ((seed * 7919 + k * 104_729) % 1000) as f64 / 500.0 - 1.0;
    let n = joints.len();
    Systematic {
        base_in_tracker: se3::exp(&Vec6::from([
            2.0 * f(1),
            2.5 * f(2),
            3.0 * f(3),
            3.0 + f(4),
            -1.5 + f(5),
            0.8 * f(6),
        ])),
        marker_in_tip: se3::exp(&Vec6::from([
            0.5 * f(7),
            0.4 * f(8),
            1.2 * f(9),
            0.05f64.copysign(f(10)),
            0.045f64.copysign(f(11)),
            0.06,
        ])),
        offsets: (0..n).map(|i| 3e-3 * size * f(20 + i as u64)).collect(),
        axis_errors: (0..n)
            .map(|i| {
                let g = |k: u64| 1e-3 * size * f(40 + 6 * i as u64 + k);
                Vec6::from([0.0, 0.0, 0.0, g(3), g(4), g(5)])
            })
            .collect(),
        home_error: Vec6::from([1e-3 * size * f(90), 0.0, 0.0, 0.0, 5e-4 * size * f(91), 0.0]),
    }
}

/// The relative Frobenius errors of the fitted tool covariance at 200 held-out
/// configurations, each chain its own.
fn heldout(
    truth: (&[Joint<f64>], &Transform<f64>, &[Mat6<f64>]),
    fitted: (&[Joint<f64>], &Transform<f64>, &[Mat6<f64>]),
) -> Vec<f64> {
    let t = ChainView {
        joints: truth.0,
        home: *truth.1,
    };
    let f = ChainView {
        joints: fitted.0,
        home: *fitted.1,
    };
    let frob = |m: &Mat6<f64>| m.0.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    let mut e: Vec<f64> = simulate::configurations(truth.0, 200, 0xbeef)
        .iter()
        .map(|th| {
            let a = t.ppoe(th, truth.2, Convention::Right).unwrap().cov;
            let b = f.ppoe(th, fitted.2, Convention::Right).unwrap().cov;
            frob(&(b - a)) / frob(&a)
        })
        .collect();
    e.sort_by(f64::total_cmp);
    e
}

struct Run {
    out: CampaignFit,
    median: f64,
    worst: f64,
    /// Largest |δ̂ − δ| / se over the determined offsets.
    offset_z: f64,
    truth_offsets: Vec<f64>,
}

/// One simulated campaign.
#[derive(Clone, Copy)]
struct Setup {
    robot: usize,
    model: Model,
    estimate: Estimate,
    position: bool,
    tracker: bool,
    /// Size of the systematic errors (1: the issue's; 0: none).
    size: f64,
    samples: usize,
    seed: u64,
}

const BASE: Setup = Setup {
    robot: 0,
    model: Model::Joint,
    estimate: Estimate::ALL,
    position: false,
    tracker: false,
    size: 1.0,
    samples: 2000,
    seed: 3,
};

/// The true noise: precise joint-value noise, or for the full model that plus bending
/// and a full-rank part at the same scale (`full_truth` scaled down to ~0.1 mrad).
fn true_covs(model: Model, joints: &[Joint<f64>]) -> Vec<Mat6<f64>> {
    match model {
        Model::Joint => joints
            .iter()
            .zip(precise(joints))
            .map(|(j, s)| screw_noise(&j.screw, s))
            .collect(),
        Model::Full => full_truth(joints, 1e-4),
    }
}

/// The tracker's noise for poses (0.05 mrad, 0.03 mm) or positions (0.03 mm).
fn tracker_cov(position: bool) -> Mat6<f64> {
    let (r, t) = (2.5e-9, 9e-10);
    let rot = if position { 0.0 } else { r };
    Mat6::from_diagonal(&Vec6::from([rot, rot, rot, t, t, t]))
}

fn run(s: Setup) -> Run {
    let (file, base, tip) = ROBOTS[s.robot];
    let (joints, home) = common::robot(file, base, tip);
    let mut sys = systematic(&joints, s.size, s.seed);
    if s.size == 0.0 {
        sys.base_in_tracker = Transform::identity();
        sys.marker_in_tip = Transform::identity();
    }
    if s.position {
        // A retroreflector: a point, the tip's axes, on a 12 cm bracket: the last joint's
        // noise is seen only through the marker's lever arm about its axis.
        sys.marker_in_tip = Transform::from_parts(
            [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            [0.1, -0.06, 0.04],
        );
    }
    // The truth's covariances belong to the true (calibrated) chain's axes.
    let zero = vec![Mat6::zeros(); joints.len()];
    let (_, true_joints, true_home) = simulate::campaign(&joints, &home, &zero, None, &sys, 1, 0);
    let covs = true_covs(s.model, &true_joints);
    let r = tracker_cov(s.position);
    let meas = s.tracker.then_some(&r);
    let (samples, _, _) = simulate::campaign(&joints, &home, &covs, meas, &sys, s.samples, s.seed);
    let samples: Vec<CampaignSample> = samples
        .into_iter()
        .map(|x| CampaignSample {
            measurement: if s.position {
                Measurement::Position([x.pose[0][3], x.pose[1][3], x.pose[2][3]])
            } else {
                Measurement::Pose(x.pose)
            },
            thetas: x.thetas,
        })
        .collect();
    let cov = s.tracker.then(|| {
        if s.position {
            MeasurementCov::Position(std::array::from_fn(|i| {
                std::array::from_fn(|j| r.0[3 + i][3 + j])
            }))
        } else {
            MeasurementCov::Pose(r.0)
        }
    });
    let out = fit_campaign(
        &joints,
        &home,
        &samples,
        cov.as_ref(),
        s.model,
        s.estimate,
        &mut |_, _| {},
    )
    .unwrap_or_else(|e| panic!("{file}: {e}"));
    let fitted: Vec<Mat6<f64>> = out.fit.joints.iter().map(|j| Mat6::from(j.cov)).collect();
    let c = &out.calibration;
    let e = heldout(
        (&true_joints, &true_home, &covs),
        (&c.joints, &c.home, &fitted),
    );
    let mut offset_z = 0.0f64;
    for ((d, se), t) in c.offsets.iter().zip(&c.offset_se).zip(&sys.offsets) {
        if let Some(se) = se {
            offset_z = offset_z.max((d - t).abs() / se);
        }
    }
    Run {
        median: e[e.len() / 2],
        worst: e[e.len() - 1],
        offset_z,
        truth_offsets: sys.offsets.clone(),
        out,
    }
}

fn show(label: &str, r: &Run) {
    let c = &r.out.calibration;
    eprintln!(
        "{label}: median {:.3}, worst {:.3}, offsets within {:.2} se, KS p {:.3}, fits {}, \
         rounds {}, rms {:.3} mm → {:.3} mm, undetermined {:?}",
        r.median,
        r.worst,
        r.offset_z,
        r.out.fit.goodness_of_fit.p_value,
        r.out.fit.goodness_of_fit.fits,
        c.rounds,
        c.rms_before.position_mm,
        c.rms_after.position_mm,
        c.undetermined
    );
}

fn accepts(label: &str, r: &Run, median: f64, worst: f64) {
    show(label, r);
    assert!(
        r.out.fit.goodness_of_fit.fits,
        "{label}: {:?}",
        r.out.fit.warnings
    );
    assert!(r.median <= median && r.worst <= worst, "{label}");
    assert!(r.offset_z <= 3.0, "{label}");
}

/// Every systematic error at once, the joint model from poses: within 10 % median, 20 %
/// worst, on the seed robot and the 7-joint arm, with and without tracker noise.
#[test]
fn joint_model_from_poses_with_every_systematic_error() {
    for (robot, tracker, seed) in [(0, false, 3), (5, false, 4), (0, true, 5), (5, true, 6)] {
        let r = run(Setup {
            robot,
            tracker,
            seed,
            ..BASE
        });
        accepts(&format!("robot {robot}, tracker {tracker}"), &r, 0.10, 0.20);
    }
}

/// The same from a laser tracker's positions only: 15 % / 25 %.
#[test]
fn joint_model_from_positions_with_every_systematic_error() {
    for (robot, tracker, seed) in [(0, true, 7), (5, false, 8)] {
        let r = run(Setup {
            robot,
            tracker,
            seed,
            position: true,
            ..BASE
        });
        accepts(&format!("positions, robot {robot}"), &r, 0.15, 0.25);
    }
}

/// The full model: 15 % / 30 %.
#[test]
fn full_model_with_every_systematic_error() {
    let r = run(Setup {
        model: Model::Full,
        tracker: true,
        seed: 9,
        ..BASE
    });
    accepts("full model, seed robot", &r, 0.15, 0.30);
}

/// Without `--estimate`, in the silent zone (joint zeros off by 0.05 mrad on a precise
/// robot: the covariance test still accepts while the covariances are too large), the
/// calibration score test fires, names calibration, and the fit counts as rejected; with
/// the offsets estimated the same data pass and the offsets are recovered.
#[test]
fn silent_zone_is_caught_without_calibration() {
    let (joints, home) = common::robot(ROBOTS[5].0, ROBOTS[5].1, ROBOTS[5].2);
    let sys = Systematic {
        base_in_tracker: Transform::identity(),
        marker_in_tip: Transform::identity(),
        offsets: (0..joints.len())
            .map(|i| if i % 2 == 0 { 5e-5 } else { -5e-5 })
            .collect(),
        axis_errors: Vec::new(),
        home_error: Vec6::zeros(),
    };
    let covs = true_covs(Model::Joint, &joints);
    let (samples, _, _) = simulate::campaign(&joints, &home, &covs, None, &sys, 2000, 12);
    let samples: Vec<CampaignSample> = samples
        .into_iter()
        .map(|x| CampaignSample {
            measurement: Measurement::Pose(x.pose),
            thetas: x.thetas,
        })
        .collect();
    let none = Estimate::NONE;
    let out = fit_campaign(
        &joints,
        &home,
        &samples,
        None,
        Model::Joint,
        none,
        &mut |_, _| {},
    )
    .unwrap();
    let t = out.calibration_test.as_ref().unwrap();
    eprintln!(
        "silent zone: KS p {:.3}, score χ² {:.1} on {}, p {:.1e}",
        out.fit.goodness_of_fit.p_value, t.statistic, t.dof, t.p_value
    );
    assert!(!t.passes());
    assert!(!out.fit.goodness_of_fit.fits);
    assert!(out
        .fit
        .warnings
        .iter()
        .any(|w| w.contains("--estimate base,tip,offsets")));
    let est = Estimate {
        offsets: true,
        ..Estimate::NONE
    };
    let out = fit_campaign(
        &joints,
        &home,
        &samples,
        None,
        Model::Joint,
        est,
        &mut |_, _| {},
    )
    .unwrap();
    assert!(out.fit.goodness_of_fit.fits, "{:?}", out.fit.warnings);
    let c = &out.calibration;
    for ((d, se), t) in c.offsets.iter().zip(&c.offset_se).zip(&sys.offsets) {
        assert!((d - t).abs() < 3.0 * se.unwrap(), "{d} vs {t}");
    }
}

/// A campaign without systematic errors: neither test fires (fixed seeds), and the noise
/// model keeps its accuracy.
#[test]
fn ideal_campaign_passes_the_systematic_tests() {
    for robot in [0, 5] {
        let r = run(Setup {
            robot,
            size: 0.0,
            estimate: Estimate::NONE,
            seed: 13,
            ..BASE
        });
        show(&format!("ideal, robot {robot}"), &r);
        assert!(r.out.mean_test.passes());
        assert!(r.out.calibration_test.as_ref().unwrap().passes());
        assert!(r.out.fit.goodness_of_fit.fits);
        assert!(r.median < 0.1);
    }
}

/// The reported standard errors of the offsets are the spread of independent fits (12
/// campaigns of 600 samples, the 7-joint arm, base, tip and offsets estimated): per
/// determined offset the ratio of the spread to the mean reported error within [0.6, 1.5]
/// (the spread of 12 values is itself uncertain by ±20 %), their median within 25 % of 1.
#[test]
fn reported_standard_errors_are_the_spread_of_fits() {
    let est = Estimate {
        kinematics: false,
        ..Estimate::ALL
    };
    let runs: Vec<Run> = (0..12)
        .map(|k| {
            let s = Setup {
                robot: 5,
                estimate: est,
                samples: 600,
                seed: 100 + k,
                size: 0.0,
                ..BASE
            };
            run(s)
        })
        .collect();
    let n = runs[0].out.calibration.offsets.len();
    let mut ratios = Vec::new();
    for i in 1..n - 1 {
        let v: Vec<f64> = runs
            .iter()
            .map(|r| r.out.calibration.offsets[i] - r.truth_offsets[i])
            .collect();
        let m = v.iter().sum::<f64>() / v.len() as f64;
        let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64;
        let se = runs
            .iter()
            .map(|r| r.out.calibration.offset_se[i].unwrap())
            .sum::<f64>()
            / runs.len() as f64;
        ratios.push(var.sqrt() / se);
    }
    eprintln!("offset spread / reported se: {ratios:.2?}");
    assert!(ratios.iter().all(|r| (0.6..=1.5).contains(r)));
    ratios.sort_by(f64::total_cmp);
    assert!((ratios[ratios.len() / 2] - 1.0).abs() < 0.25);
}
