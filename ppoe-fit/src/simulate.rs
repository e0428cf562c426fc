//! Samples of the exact product model, for tests, reports and trying the estimator on a
//! robot before recording data: θ uniform within the joint limits (±π, or ±1 m for a
//! prismatic joint, where a limit is infinite), ξᵢ ~ N(0, Cᵢ), ν ~ N(0, R), composed
//! exactly as `T = D₁·Exp(ξ₁)···Dₙ·Exp(ξₙ)·M·Exp(ν)` (no second-order approximation).

use crate::samples::Sample;
use nalgebra::Matrix6;
use ppoe::chain::{Joint, JointKind};
use ppoe::{se3, Mat6, Transform, Vec6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// `count` joint configurations spread uniformly over the limits, from `seed`.
pub fn configurations(joints: &[Joint<f64>], count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            joints
                .iter()
                .map(|j| uniform_in_limits(j, &mut rng))
                .collect()
        })
        .collect()
}

fn uniform_in_limits(j: &Joint<f64>, rng: &mut impl Rng) -> f64 {
    let wide = if j.kind == JointKind::Prismatic {
        1.0
    } else {
        std::f64::consts::PI
    };
    let lo = if j.lower.is_finite() { j.lower } else { -wide };
    let hi = if j.upper.is_finite() { j.upper } else { wide };
    if hi > lo {
        rng.gen_range(lo..hi)
    } else {
        lo
    }
}

/// A square-root factor F with F·Fᵀ = C for a symmetric PSD C (eigen-decomposition;
/// negative rounding-level eigenvalues count as zero).
fn sqrt_factor(c: &Mat6<f64>) -> Matrix6<f64> {
    let m = Matrix6::from_fn(|r, k| 0.5 * (c.0[r][k] + c.0[k][r]));
    let e = m.symmetric_eigen();
    let d = e.eigenvalues.map(|v| v.max(0.0).sqrt());
    e.eigenvectors * Matrix6::from_diagonal(&d)
}

fn gaussian(f: &Matrix6<f64>, rng: &mut impl Rng) -> Vec6<f64> {
    let w = nalgebra::Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
    let x = f * w;
    Vec6::from(std::array::from_fn(|i| x[i]))
}

/// `count` samples of the exact model at random configurations (see the module docs),
/// deterministic for a given `seed`.
pub fn samples(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    covs: &[Mat6<f64>],
    measurement_cov: Option<&Mat6<f64>>,
    count: usize,
    seed: u64,
) -> Vec<Sample> {
    let configs = configurations(joints, count, seed);
    samples_at(
        joints,
        home,
        covs,
        measurement_cov,
        &configs,
        seed ^ 0x9e37_79b9,
    )
}

/// Samples of the exact model at the given configurations.
pub fn samples_at(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    covs: &[Mat6<f64>],
    measurement_cov: Option<&Mat6<f64>>,
    configs: &[Vec<f64>],
    seed: u64,
) -> Vec<Sample> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let factors: Vec<Matrix6<f64>> = covs.iter().map(sqrt_factor).collect();
    let meas = measurement_cov.map(sqrt_factor);
    configs
        .iter()
        .map(|thetas| {
            let mut t = Transform::identity();
            for ((j, th), f) in joints.iter().zip(thetas).zip(&factors) {
                t = t * j.displacement(j.clip(*th, false)) * se3::exp(&gaussian(f, &mut rng));
            }
            t = t * *home;
            if let Some(f) = &meas {
                t = t * se3::exp(&gaussian(f, &mut rng));
            }
            Sample {
                thetas: thetas.clone(),
                pose: t.to_matrix4(),
            }
        })
        .collect()
}

/// The systematic errors of a simulated measurement campaign (see [`campaign`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Systematic {
    /// X: the robot base in the tracker's frame.
    pub base_in_tracker: Transform<f64>,
    /// Y: the marker in the tip frame (position-only campaigns measure its origin).
    pub marker_in_tip: Transform<f64>,
    /// The true joint zero offsets δᵢ.
    pub offsets: Vec<f64>,
    /// The true axis errors κᵢ (base-frame twists, `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ`; empty: none).
    pub axis_errors: Vec<Vec6<f64>>,
    /// The true home error μ (`M' = M·Exp(μ)`).
    pub home_error: Vec6<f64>,
}

/// `count` samples of a campaign with systematic errors `sys`, from `seed`:
/// `T = X·D₁'·Exp(ξ₁)···Dₙ'·Exp(ξₙ)·M'·Y·Exp(ν)` with the true kinematics `D', M'` (the
/// nominal `joints`, `home` with `sys`'s offsets and errors folded by
/// [`ppoe::chain::fold_calibration`]), ξᵢ ~ N(0, `covs[i]`) (covariances of the *true*
/// chain's joints), ν ~ N(0, `measurement_cov`) in the marker frame. Returns the samples
/// as `(thetas, T)` — the joint values as the encoders read them (θ, not θ + δ) — and the
/// true chain and home pose (without Y). Take `T`'s translation for position-only data.
///
/// # Panics
/// If `sys` does not fold (wrong lengths or non-finite values): a test helper's misuse.
pub fn campaign(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    covs: &[Mat6<f64>],
    measurement_cov: Option<&Mat6<f64>>,
    sys: &Systematic,
    count: usize,
    seed: u64,
) -> (Vec<Sample>, Vec<Joint<f64>>, Transform<f64>) {
    let mut truth = joints.to_vec();
    let mut true_home = *home;
    ppoe::chain::fold_calibration(
        &mut truth,
        &mut true_home,
        &sys.offsets,
        &sys.axis_errors,
        &sys.home_error,
    )
    .expect("the systematic errors fold into the chain");
    let marked = true_home * sys.marker_in_tip;
    let mut samples = samples(&truth, &marked, covs, measurement_cov, count, seed);
    for s in &mut samples {
        s.pose = (sys.base_in_tracker * Transform::from_matrix4(&s.pose)).to_matrix4();
    }
    (samples, truth, true_home)
}
