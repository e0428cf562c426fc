//! Monte Carlo checks of the *true* distribution: sample each perturbation model with a
//! fixed seed and compare the analytic covariance with the sampled second moment of the
//! perturbation (relative Frobenius error). With N = 10⁵ samples the sampling error of a
//! covariance is ≈ √(2/N) ≈ 0.45 % (one standard error).

mod common;
use common::*;
use ppoe::chain::{ChainView, Convention};
use ppoe::uncertainty;
use ppoe::{se3, Mat6, Transform, Vec3, Vec6, Vector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const N: usize = 100_000;

/// Barfoot & Furgale (2014) two-pose compounding ([`TwoPose::barfoot_furgale`]),
/// Σ = α·diag(½,1,½ | 10,5,5) for both: the (2nd, 4th)-order errors.
fn bf_errors(alpha: f64, seed: u64) -> (f64, f64) {
    let bf = TwoPose::barfoot_furgale();
    let s = TwoPose::cov(alpha);
    let g = Gaussian6::new(&s);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let samples: Vec<Vec6<f64>> = (0..N).map(|_| bf.draw(&g, &mut rng)).collect();
    let mc = second_moment(&samples);
    let (c2, c4) = bf.concat(&s);
    (frob_rel(&c2, &mc), frob_rel(&c4, &mc))
}

#[test]
fn concat_globally_matches_sampling_and_fourth_order_helps() {
    let (e2, e4) = bf_errors(0.001, 1);
    println!("alpha 0.001: 2nd {e2:.4}, 4th {e4:.4}");
    assert!(e2 < 0.015 && e4 < 0.015, "small noise: {e2} {e4}");
    let (e2, e4) = bf_errors(1.0, 2);
    println!("alpha 1: 2nd {e2:.4}, 4th {e4:.4}");
    assert!(e4 < e2, "4th order must be closer than 2nd at large noise");
    assert!(e2 > 0.1 && e4 < 0.04, "large noise: 2nd {e2}, 4th {e4}");
}

#[test]
fn concat_locally_matches_sampling() {
    let a2b = se3::exp(&Vector([0.3, -0.2, 0.5, 0.4, 0.1, -0.3]));
    let b2c = se3::exp(&Vector([-0.6, 0.1, 0.2, 0.0, 0.7, 0.2]));
    let ca = diag([1e-3, 2e-3, 5e-4, 1e-3, 3e-3, 2e-3]);
    let cb = diag([2e-3, 5e-4, 1e-3, 4e-3, 1e-3, 1e-3]);
    let (mean, cov) = uncertainty::concat_locally(&a2b, &b2c, &ca, &cb);
    let (ga, gb) = (Gaussian6::new(&ca), Gaussian6::new(&cb));
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let inv = mean.inverse();
    // Local model: T̄·Exp(ξ') = T_BC·Exp(ξ_B)·T_AB·Exp(ξ_A).
    let samples: Vec<Vec6<f64>> = (0..N)
        .map(|_| {
            let xa = ga.sample(&mut rng);
            let xb = gb.sample(&mut rng);
            se3::log(&(inv * b2c * se3::exp(&xb) * a2b * se3::exp(&xa)))
        })
        .collect();
    let e = frob_rel(&cov, &second_moment(&samples));
    println!("concat_locally: {e:.4}");
    assert!(e < 0.015, "{e}");
}

/// Samples the PPOE model and returns the right perturbations η = Log(T̄⁻¹·T).
fn sample_chain(
    chain: &ChainView<f64>,
    thetas: &[f64],
    covs: &[Mat6<f64>],
    seed: u64,
) -> Vec<Vec6<f64>> {
    let mean_inv = chain.forward_kinematics(thetas).unwrap().inverse();
    sample_chain_poses(chain, thetas, covs, seed, N)
        .iter()
        .map(|t| se3::log(&(mean_inv * *t)))
        .collect()
}

fn seed_chain() -> (Vec<ppoe::chain::Joint<f64>>, Transform<f64>) {
    chain_from_golden(&golden("ppoe/seed_linkmount_tcp.json"))
}

/// Seed-animation joint values at frame k.
fn frame(k: usize) -> Vec<f64> {
    seed_frame(k)
}

#[test]
fn ppoe_right_convention_matches_sampling_on_seed_robot() {
    let (joints, home) = seed_chain();
    let chain = ChainView {
        joints: &joints,
        home,
    };
    for (k, seed) in [(0usize, 10u64), (100, 11)] {
        let th = frame(k);
        for (scale, bound) in [(1.0 / 16.0, 0.015), (1.0, 0.06)] {
            let covs = seed_covs(scale);
            let mc = second_moment(&sample_chain(&chain, &th, &covs, seed));
            let right = chain.ppoe(&th, &covs, Convention::Right).unwrap();
            let compat = chain.ppoe(&th, &covs, Convention::Pytransform3d).unwrap();
            let (e, ec) = (frob_rel(&right.cov, &mc), frob_rel(&compat.cov, &mc));
            println!("frame {k}, noise x{scale}: right {e:.4}, pytransform3d-compatible {ec:.3}");
            assert!(e < bound, "frame {k} x{scale}: {e} >= {bound}");
            assert!(ec > 0.3, "the compatible variant should be far off: {ec}");
            // Left convention: the same distribution seen from the base frame.
            let left = chain.ppoe(&th, &covs, Convention::Left).unwrap();
            let mc_left: Vec<Vec6<f64>> = sample_chain(&chain, &th, &covs, seed + 100)
                .iter()
                .map(|eta| right.pose.adjoint() * *eta)
                .collect();
            let el = frob_rel(&left.cov, &second_moment(&mc_left));
            assert!(el < bound, "left: {el}");
        }
    }
}

#[test]
fn fourth_order_ppoe_is_closer_at_large_noise() {
    let (joints, home) = seed_chain();
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let th = frame(0);
    let covs = seed_covs(4.0);
    let mc = second_moment(&sample_chain(&chain, &th, &covs, 21));
    let e2 = frob_rel(&chain.ppoe(&th, &covs, Convention::Right).unwrap().cov, &mc);
    let e4 = frob_rel(
        &chain
            .ppoe_fourth_order(&th, &covs, Convention::Right)
            .unwrap()
            .cov,
        &mc,
    );
    println!("seed x4 noise: 2nd order {e2:.4}, 4th order {e4:.4}");
    assert!(
        e4 < e2 / 4.0,
        "4th order {e4} not clearly closer than 2nd {e2}"
    );
    assert!(e4 < 0.015, "{e4}");
}

/// The second-order mean of the tool position predicts the sampled mean, which on the seed
/// robot at its noise sits about 0.10 m from the rigid tool position (printed below).
#[test]
fn second_order_mean_of_tool_position() {
    let (joints, home) = seed_chain();
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let th = frame(0);
    let covs = seed_covs(1.0);
    let tip = chain.ppoe(&th, &covs, Convention::Right).unwrap();
    let etas = sample_chain(&chain, &th, &covs, 31);
    let mut mean = Vec3::<f64>::zeros();
    for eta in &etas {
        mean += (tip.pose * se3::exp(eta)).translation;
    }
    mean = mean.scale(1.0 / etas.len() as f64);
    let predicted = ppoe::surface::position_mean_second_order(&tip.pose, &tip.cov);
    let shift = (mean - tip.pose.translation).norm();
    let miss = (mean - predicted).norm();
    // Standard error of the sampled mean: √(tr Cov(position) / N).
    let var: f64 = etas
        .iter()
        .map(|eta| ((tip.pose * se3::exp(eta)).translation - mean).norm_squared())
        .sum::<f64>()
        / (etas.len() as f64 - 1.0);
    let se = (var / etas.len() as f64).sqrt();
    println!("sampled mean {shift:.4} m from t̄; second-order mean misses it by {miss:.4} m (standard error {se:.4} m)");
    assert!(shift > 0.05, "{shift}");
    // The neglected fourth-order terms are ≈ 5 mm here: the prediction must
    // explain over 90 % of the shift, and miss by less than 5 mm plus 3 standard errors.
    assert!(miss < 0.005 + 3.0 * se, "{miss}");
}
