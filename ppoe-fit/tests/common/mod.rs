//! Shared by the fit tests and `examples/fit_accuracy.rs` (which includes this file): the
//! project's test robots, true noise models, exact Monte Carlo samples, and the error of
//! the fitted model's predictions at held-out configurations.
#![allow(dead_code)]

pub mod campaign;

use ppoe::chain::{bending_noise, screw_noise, ChainView, Convention, Joint, JointKind};
use ppoe::{Mat3, Mat6, Transform, Vec3};
use ppoe_fit::{fit, simulate, Fit, Model};

/// A robot of `test_data/urdf`: (file, base, tip).
pub const ROBOTS: [(&str, &str, &str); 6] = [
    ("seed.urdf", "linkmount", "tcp"),
    ("prismatic.urdf", "base_link", "tool0"),
    ("rpy_everywhere.urdf", "base", "tool"),
    ("continuous.urdf", "base", "ee"),
    ("tree.urdf", "base_footprint", "left_tip"),
    ("arm7.urdf", "base", "tool"),
];

/// The chain of a test robot as `ppoe eval` builds it.
pub fn robot(file: &str, base: &str, tip: &str) -> (Vec<Joint<f64>>, Transform<f64>) {
    let path = format!("{}/../test_data/urdf/{file}", env!("CARGO_MANIFEST_DIR"));
    let chain = ppoe_build::Config::new(path)
        .base(base)
        .tip(tip)
        .chain()
        .expect("test robot");
    let joints = chain.to_core_joints().iter().map(Joint::from_f64).collect();
    (joints, Transform::from_f64(&chain.home_transform()))
}

/// True joint-value variances: 1–4·10⁻⁴ rad² (1–2 cm at 1 m), 1–4·10⁻⁶ m² for
/// prismatic joints, scaled by `scale`.
pub fn joint_truth(joints: &[Joint<f64>], scale: f64) -> Vec<f64> {
    joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let base = 1.0 + (i * 7 % 4) as f64;
            let unit = if j.kind == JointKind::Prismatic {
                1e-6
            } else {
                1e-4
            };
            base * unit * scale
        })
        .collect()
}

/// True full covariances: joint-value noise plus bending about a pivot on the joint's
/// axis (anisotropic) plus a small full-rank term, scaled by `scale`.
pub fn full_truth(joints: &[Joint<f64>], scale: f64) -> Vec<Mat6<f64>> {
    joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let s2 = joint_truth(joints, scale)[i];
            let w = j.screw.rotation();
            let pivot = if w.norm() > 0.0 {
                w.cross(&j.screw.translation())
            } else {
                Vec3::zeros()
            };
            let a = 0.5 + 0.25 * (i % 3) as f64;
            let bend = Mat3::from([
                [a, 0.1, 0.0],
                [0.1, 0.6, -0.05],
                [0.0, -0.05, 1.1 - 0.3 * a],
            ]);
            let small = Mat6::from_diagonal(&ppoe::Vec6::from([0.2, 0.1, 0.15, 0.3, 0.2, 0.25]));
            screw_noise(&j.screw, s2)
                + bending_noise(&pivot, &bend.scale(1e-4 * scale))
                + small.scale(1e-6 * scale)
        })
        .collect()
}

/// The dense covariances of joint variances `s2`.
pub fn joint_covs(joints: &[Joint<f64>], s2: &[f64]) -> Vec<Mat6<f64>> {
    joints
        .iter()
        .zip(s2)
        .map(|(j, s)| screw_noise(&j.screw, *s))
        .collect()
}

/// A tracker's noise: 0.5 mrad and 0.2 mm standard deviations (tip frame).
pub fn tracker() -> Mat6<f64> {
    Mat6::from_diagonal(&ppoe::Vec6::from([
        2.5e-7, 2.5e-7, 2.5e-7, 4e-8, 4e-8, 4e-8,
    ]))
}

fn frob(m: &Mat6<f64>) -> f64 {
    m.0.iter().flatten().map(|x| x * x).sum::<f64>().sqrt()
}

/// Relative Frobenius errors of the predicted tool covariance (Right convention, the
/// core's PPOE) at `count` held-out configurations (the same for every call), in their
/// order.
pub fn heldout_errors(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    truth: &[Mat6<f64>],
    fitted: &[Mat6<f64>],
    count: usize,
) -> Vec<f64> {
    let chain = ChainView {
        joints,
        home: *home,
    };
    simulate::configurations(joints, count, 0xbeef)
        .iter()
        .map(|th| {
            let t = chain.ppoe(th, truth, Convention::Right).unwrap().cov;
            let f = chain.ppoe(th, fitted, Convention::Right).unwrap().cov;
            frob(&(f - t)) / frob(&t)
        })
        .collect()
}

/// The fitted covariances as core matrices.
pub fn fitted_covs(f: &Fit) -> Vec<Mat6<f64>> {
    f.joints.iter().map(|j| Mat6::from(j.cov)).collect()
}

/// One scenario's figures.
pub struct Outcome {
    pub fit: Fit,
    pub median: f64,
    pub worst: f64,
    /// The errors at the 200 held-out configurations, in their order.
    pub errors: Vec<f64>,
    /// Joint model: the largest |σ̂² − σ²| / σ² and the largest |σ̂² − σ²| / se.
    pub var_rel: f64,
    pub var_z: f64,
}

/// Samples the exact model on a robot, fits, and compares on 200 held-out
/// configurations.
pub fn scenario(
    robot_index: usize,
    model: Model,
    scale: f64,
    with_tracker: bool,
    count: usize,
    seed: u64,
) -> Outcome {
    let (file, base, tip) = ROBOTS[robot_index];
    let (joints, home) = robot(file, base, tip);
    let s2 = joint_truth(&joints, scale);
    let truth = match model {
        Model::Joint => joint_covs(&joints, &s2),
        Model::Full => full_truth(&joints, scale),
    };
    let r = tracker();
    let meas = with_tracker.then_some(&r);
    let samples = simulate::samples(&joints, &home, &truth, meas, count, seed);
    let r_arr = r.0;
    let f = fit(
        &joints,
        &home,
        &samples,
        with_tracker.then_some(&r_arr),
        model,
        &mut |_, _| {},
    )
    .unwrap_or_else(|e| panic!("{file}: {e}"));
    let errors = heldout_errors(&joints, &home, &truth, &fitted_covs(&f), 200);
    let mut e = errors.clone();
    e.sort_by(f64::total_cmp);
    let (mut var_rel, mut var_z) = (0.0f64, 0.0f64);
    if model == Model::Joint {
        for (j, s) in f.joints.iter().zip(&s2) {
            let (v, se) = (j.sigma2.unwrap(), j.sigma2_se.unwrap());
            var_rel = var_rel.max((v - s).abs() / s);
            var_z = var_z.max((v - s).abs() / se);
        }
    }
    Outcome {
        median: e[e.len() / 2],
        worst: e[e.len() - 1],
        errors,
        fit: f,
        var_rel,
        var_z,
    }
}
