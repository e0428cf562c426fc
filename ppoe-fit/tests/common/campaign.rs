//! Simulated measurement campaigns with systematic errors, fitted by `fit_campaign`,
//! compared with the truth at held-out configurations: shared by
//! `tests/calibration_validation.rs`, `examples/fit_accuracy.rs` and `examples/fit_bench.rs`.

use super::*;
use ppoe::chain::{screw_noise, ChainView, Convention, Joint};
use ppoe::{se3, Mat6, Transform, Vec6};
use ppoe_fit::simulate::{self, Systematic};
use ppoe_fit::{
    fit_campaign, CampaignFit, CampaignSample, Estimate, Measurement, MeasurementCov, Model,
};

/// Precise joint noise: σ from 0.07 to 0.2 mrad (prismatic: µm).
pub fn precise(joints: &[Joint<f64>]) -> Vec<f64> {
    (0..joints.len())
        .map(|i| {
            let s = 0.07e-3 + 0.13e-3 * ((i * 5) % 7) as f64 / 6.0;
            s * s
        })
        .collect()
}

/// Every systematic error at once, sized by `size` (1: the sizes; the marker 9 cm
/// from the tip frame's origin, 7 cm from its z axis, whatever the size).
pub fn systematic(joints: &[Joint<f64>], size: f64, seed: u64) -> Systematic {
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
pub fn heldout(
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

pub struct Run {
    pub out: CampaignFit,
    pub median: f64,
    pub worst: f64,
    /// Largest |δ̂ − δ| / se over the determined offsets.
    pub offset_z: f64,
    /// The true offsets.
    pub truth_offsets: Vec<f64>,
    /// Wall time of the fit (s).
    pub seconds: f64,
}

/// One simulated campaign.
#[derive(Clone, Copy)]
pub struct Setup {
    pub robot: usize,
    pub model: Model,
    pub estimate: Estimate,
    pub position: bool,
    pub tracker: bool,
    /// Size of the systematic errors (1: the issue's; 0: none).
    pub size: f64,
    pub samples: usize,
    pub seed: u64,
    /// The data already in the robot's base frame and the marker at the tip frame (no
    /// registration, no marker offset; the other errors as `size` says).
    pub registered: bool,
}

pub const BASE: Setup = Setup {
    robot: 0,
    model: Model::Joint,
    estimate: Estimate::ALL,
    position: false,
    tracker: false,
    size: 1.0,
    samples: 2000,
    seed: 3,
    registered: false,
};

/// The true noise: precise joint-value noise, or for the full model that plus bending
/// and a full-rank part at the same scale (`full_truth` scaled down to ~0.1 mrad).
pub fn true_covs(model: Model, joints: &[Joint<f64>]) -> Vec<Mat6<f64>> {
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
pub fn tracker_cov(position: bool) -> Mat6<f64> {
    let (r, t) = (2.5e-9, 9e-10);
    let rot = if position { 0.0 } else { r };
    Mat6::from_diagonal(&Vec6::from([rot, rot, rot, t, t, t]))
}

pub fn run(s: Setup) -> Run {
    let (file, base, tip) = ROBOTS[s.robot];
    let (joints, home) = super::robot(file, base, tip);
    let mut sys = systematic(&joints, s.size, s.seed);
    if s.size == 0.0 || s.registered {
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
    let start = std::time::Instant::now();
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
    let seconds = start.elapsed().as_secs_f64();
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
        seconds,
        out,
    }
}

pub fn show(label: &str, r: &Run) {
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
