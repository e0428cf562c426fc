//! The firmware's rank-one PPOE cases (`Chain::ppoe_rank1`: one variance per joint value
//! along its screw axis) and their expected results, on the host in f64 (build.rs writes
//! them as consts).
//!
//! The expectation comes from the other algorithm: the dense PPOE (`ChainView::ppoe`) with
//! the covariances `σᵢ²·SᵢSᵢᵀ` (`chain::screw_noise`) the rank-one path stands for. So the
//! device's rank-one result is checked against a different computation of the same model,
//! not against itself.

use crate::cases::{Case, N};
use ppoe::chain::{screw_noise, ChainView, Convention};
use ppoe::Mat6;

/// One rank-one case and its expected result.
pub struct Rank1Case {
    /// Its name in the firmware output (the dense case it shares its joint values with).
    pub name: String,
    /// Joint values.
    pub thetas: [f64; N],
    /// Variance of each joint value (rad²).
    pub sigma2: [f64; N],
    /// The expected pose (4×4), right convention.
    pub pose: [[f64; 4]; 4],
    /// The expected covariance, right convention.
    pub cov: [[f64; 6]; 6],
}

/// The seed example's variances (0.05 rad² on joints 1, 2, 3 and 5, none on 4 and 6): the
/// joints the seed example's covariances perturb.
const SEED_SIGMA2: [f64; N] = [0.05, 0.05, 0.05, 0.0, 0.05, 0.0];

/// Variances of case `k`: the seed example's for the seed states (`initial`, `frame*`),
/// otherwise standard deviations 0.0025…0.035 rad varied over joints and cases, with one
/// joint (a different one per case) without noise.
fn variances(k: usize, name: &str) -> [f64; N] {
    if name == "initial" || name.starts_with("frame") {
        return SEED_SIGMA2;
    }
    std::array::from_fn(|i| {
        let sigma = 0.005 * (1 + (3 * i + 5 * k) % 7) as f64;
        if i == k % N {
            0.0
        } else {
            sigma * sigma
        }
    })
}

/// One rank-one case per dense case (same joint values), with the dense PPOE of
/// `screw_noise` covariances as the expectation (module docs).
pub fn expected_rank1(robot: &ppoe_build::RobotChain, dense: &[Case]) -> Vec<Rank1Case> {
    let joints = robot.to_core_joints();
    assert_eq!(joints.len(), N, "the seed robot has 6 moving joints");
    let chain = ChainView {
        joints: &joints,
        home: robot.home_transform(),
    };
    let mut out = Vec::new();
    for (k, c) in dense.iter().enumerate() {
        let sigma2 = variances(k, &c.name);
        let covs: Vec<Mat6<f64>> = joints
            .iter()
            .zip(&sigma2)
            .map(|(j, s)| screw_noise(&j.screw, *s))
            .collect();
        let r = chain
            .ppoe(&c.thetas, &covs, Convention::Right)
            .unwrap_or_else(|e| panic!("host PPOE failed for rank-1 case {}: {e:?}", c.name));
        out.push(Rank1Case {
            name: c.name.clone(),
            thetas: c.thetas,
            sigma2,
            pose: r.pose.to_matrix4(),
            cov: r.cov.0,
        });
    }
    out
}
