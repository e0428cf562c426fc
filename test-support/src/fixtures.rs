//! The benchmark fixtures shared by `benches/*.rs` and `examples/ppoe_icount.rs`, so that
//! timings and instruction counts of different harnesses are of the same inputs.

use crate::{chain_from_golden, golden};
use ppoe::chain::{Joint, JointKind};
use ppoe::{se3, Mat6, Real, Transform, Vec3, Vector};

/// Joints, home pose, joint values and joint covariances of one benchmark case.
pub type Case<T> = (Vec<Joint<T>>, Transform<T>, Vec<T>, Vec<Mat6<T>>);

/// The seed robot's chain from the oracle's golden file, converted as ppoe-build's tables
/// are (`Joint::from_f64`, `Transform::from_f64`: displacement constants computed in f64,
/// elements below ε²·max zeroed).
pub fn seed_chain<T: Real>() -> (Vec<Joint<T>>, Transform<T>) {
    let (joints, home) = chain_from_golden::<f64>(&golden("ppoe/seed_linkmount_tcp.json"));
    (
        joints.iter().map(Joint::from_f64).collect(),
        Transform::from_f64(&home),
    )
}

/// The seed example's initial joint values and joint covariances: 0.05 rad² about the base
/// z axis (joint 1) and the base y axis (joints 2, 3 and 5); joints 4 and 6 have none.
pub fn seed_state<T: Real>() -> (Vec<T>, Vec<Mat6<T>>) {
    let mut covs = vec![Mat6::zeros(); 6];
    covs[0].0[2][2] = T::lit(0.05);
    for i in [1, 2, 4] {
        covs[i].0[1][1] = T::lit(0.05);
    }
    (
        [-0.5, -0.5, -0.5, 0.0, -0.5, 0.0].map(T::lit).to_vec(),
        covs,
    )
}

/// The seed robot at the seed example's initial state ([`seed_chain`], [`seed_state`]).
pub fn seed_case<T: Real>() -> Case<T> {
    let (joints, home) = seed_chain();
    let (thetas, covs) = seed_state();
    (joints, home, thetas, covs)
}

/// A synthetic chain of `n` revolute joints with varied axes (`joint i`: direction
/// `(0.3 sin 0.7i, 0.4 cos 0.7i, 0.866)` through `(0.1i, 0.05, 0.2i)`), limits ±3, home
/// `(0.1, 0, 0.2n)`, joint values `0.3 + 0.1i` and the same full-rank diagonal covariance
/// on every joint; converted with `Joint::from_f64`.
pub fn synthetic_case<T: Real>(n: usize) -> Case<T> {
    let joints = (0..n)
        .map(|i| {
            let a = i as f64 * 0.7;
            let s = Vec3::<f64>::new(a.sin() * 0.3, a.cos() * 0.4, 0.866);
            let q = Vec3::new(0.1 * i as f64, 0.05, 0.2 * i as f64);
            let screw = se3::screw_axis(&q, &s, 0.0).expect("a valid screw axis");
            Joint::from_f64(&Joint::new("j", JointKind::Revolute, screw.0, -3.0, 3.0))
        })
        .collect();
    let home = Transform::from_parts(
        [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]].map(|r| r.map(T::lit)),
        [0.1, 0.0, 0.2 * n as f64].map(T::lit),
    );
    let thetas = (0..n).map(|i| T::lit(0.3 + 0.1 * i as f64)).collect();
    let cov = Mat6::from_diagonal(&Vector([1e-4, 2e-4, 1e-4, 1e-6, 2e-6, 1e-6].map(T::lit)));
    (joints, home, thetas, vec![cov; n])
}
