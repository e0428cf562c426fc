//! Benchmark robots read from test_data/urdf with ppoe-build, the way a firmware build script
//! reads them, and their inputs. Shared by benches/ops.rs, benches/rank1.rs,
//! benches/lanes_ratio.rs and the Pinocchio export (benches/pinocchio/export.rs), so that
//! every benchmark of a robot runs the same chain.
//!
//! ppoe-build links its own copy of ppoe (a dev-dependency cycle), so only its plain `f64`
//! arrays cross over; the joints are rebuilt here with this crate's types, as the
//! generated tables build them (`Joint::prepared`, then `Joint::from_f64` /
//! `Transform::from_f64` for the scalar).

#![allow(dead_code)] // each bench binary uses a different part

use ppoe::chain::{Joint, JointKind};
use ppoe::{Mat6, Matrix, Real, Transform};

/// A robot of test_data/urdf: file, base link, tip link.
pub struct Robot {
    /// Short name used in benchmark ids and the Pinocchio export.
    pub name: &'static str,
    /// File name under test_data/urdf.
    pub file: &'static str,
    /// Base link.
    pub base: &'static str,
    /// Tip link.
    pub tip: &'static str,
}

/// The seed robot (6 joints; the same chain as the golden file the seed benches read).
pub const SEED: Robot = Robot {
    name: "seed",
    file: "seed.urdf",
    base: "linkmount",
    tip: "tcp",
};

/// The 7-joint arm of test_data/urdf/arm7.urdf.
pub const ARM7: Robot = Robot {
    name: "arm7",
    file: "arm7.urdf",
    base: "base",
    tip: "tool",
};

/// The chain ppoe-build extracts (panics on a broken test file: benchmark set-up).
pub fn robot_chain(r: &Robot) -> ppoe_build::RobotChain {
    let path = format!("{}/test_data/urdf/{}", env!("CARGO_MANIFEST_DIR"), r.file);
    ppoe_build::Config::new(&path)
        .base(r.base)
        .tip(r.tip)
        .chain()
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The chain in this crate's types and scalar T, converted as ppoe-build's tables are.
pub fn core_chain<T: Real>(rc: &ppoe_build::RobotChain) -> (Vec<Joint<T>>, Transform<T>) {
    let joints = rc
        .joints
        .iter()
        .map(|j| {
            let kind = match j.kind {
                ppoe_build::JointKind::Revolute => JointKind::Revolute,
                ppoe_build::JointKind::Continuous => JointKind::Continuous,
                ppoe_build::JointKind::Prismatic => JointKind::Prismatic,
            };
            let name: &'static str = Box::leak(j.name.clone().into_boxed_str());
            Joint::from_f64(&Joint::new(name, kind, j.screw, j.lower, j.upper).prepared())
        })
        .collect();
    let home = Transform::from_f64(&Transform::from_matrix4(&rc.home));
    (joints, home)
}

/// The 7-joint arm's benchmark configuration (inside every limit, no joint at zero).
pub fn arm7_thetas<T: Real>() -> Vec<T> {
    [0.1, -0.4, 0.2, -2.0, 0.3, 1.6, 0.5].map(T::lit).to_vec()
}

/// `count` configurations of `n` joints, row-major, uniform in [−1, 1] (inside every limit
/// of the seed and the 7-joint arm), from a fixed seed: the batch benchmarks' inputs, whose
/// first configuration is also their single-call one.
pub fn batch_thetas<T: Real>(count: usize, n: usize) -> Vec<T> {
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    (0..count * n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            T::lit((x >> 11) as f64 / (1u64 << 52) as f64 - 1.0)
        })
        .collect()
}

/// Full-rank joint covariances for an n-joint chain: standard deviations of 0.8 to 1.5
/// mrad and mm, growing by 10 % per joint along the chain, correlated as ρ^|i−j| with ρ = 0.3 (an AR(1)
/// correlation, positive definite), so no entry is zero and the dense and structured paths
/// both do all their work.
pub fn arm7_covs<T: Real>(n: usize) -> Vec<Mat6<T>> {
    (0..n)
        .map(|k| {
            let g = 1.0 + 0.1 * k as f64;
            let s = [1e-3, 1.2e-3, 0.8e-3, 1e-3, 1.5e-3, 0.9e-3].map(|x| x * g);
            Matrix(std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    T::lit(s[i] * s[j] * 0.3f64.powi((i as i32 - j as i32).abs()))
                })
            }))
        })
        .collect()
}
