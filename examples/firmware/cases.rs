//! The firmware's test cases and their expected PPOE results on the host in f64 (the same
//! `ppoe` crate, the runtime chain from `ppoe-build`). Shared by build.rs here (Rust
//! consts) and by examples/c-firmware/gen (a C header): both firmwares check the same cases.

use ppoe::chain::{ChainView, Convention};
use ppoe::Mat6;

/// The seed robot, relative to examples/firmware and examples/c-firmware/gen.
pub const URDF: &str = "../../test_data/urdf/seed.urdf";
/// Moving joints of the seed robot.
pub const N: usize = 6;

/// One test case and its expected result.
pub struct Case {
    /// Its name in the firmware output.
    pub name: String,
    /// Joint values.
    pub thetas: [f64; N],
    /// Joint covariances.
    pub covs: [[[f64; 6]; 6]; N],
    /// The expected pose (4×4) of the right-convention PPOE.
    pub pose: [[f64; 4]; 4],
    /// The expected covariance.
    pub cov: [[f64; 6]; 6],
}

impl Case {
    /// A case without its expectation (filled by [`expected`]).
    fn input(name: String, thetas: [f64; N], covs: [[[f64; 6]; 6]; N]) -> Self {
        let (pose, cov) = ([[0.0; 4]; 4], [[0.0; 6]; 6]);
        Case {
            name,
            thetas,
            covs,
            pose,
            cov,
        }
    }
}

/// Knuth's MMIX LCG; the top 53 bits give a uniform f64 in [0, 1). Fixed seed: the cases are
/// the same on every build.
struct Lcg(u64);
impl Lcg {
    fn next_f64(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
    /// A random covariance `s²·A·Aᵀ/6`, A with entries uniform in [−1, 1): dense, PSD.
    fn cov(&mut self, s: f64) -> [[f64; 6]; 6] {
        let mut a = [[0.0; 6]; 6];
        for row in a.iter_mut() {
            for x in row.iter_mut() {
                *x = self.uniform(-1.0, 1.0);
            }
        }
        let mut c = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                let acc: f64 = a[i].iter().zip(&a[j]).map(|(x, y)| x * y).sum();
                c[i][j] = s * s * acc / 6.0;
            }
        }
        c
    }
}

/// The seed example's joint covariances (MATH.md §5.3): 0.05 variance about base z for
/// joint 1, about base y for joints 2, 3 and 5.
fn seed_covs() -> [[[f64; 6]; 6]; N] {
    let mut covs = [[[0.0; 6]; 6]; N];
    covs[0][2][2] = 0.05;
    for j in [1, 2, 4] {
        covs[j][1][1] = 0.05;
    }
    covs
}

// 3.14159 is the upper end of the near-±π joint values, deliberately just below π.
#[allow(clippy::approx_constant)]
fn inputs() -> Vec<Case> {
    let seed_thetas = [1.0, 1.0, 1.0, 0.0, 1.0, 0.0];
    let mut out = Vec::new();
    // The seed's initial state: -0.5 * thetas (note the -0.0).
    out.push(Case::input(
        "initial".into(),
        seed_thetas.map(|t: f64| -0.5 * t),
        seed_covs(),
    ));
    // Animation frames: angle = 0.5 cos(2π(0.5 + step/200)), thetas_t = angle * thetas.
    for step in [0u32, 50, 100, 150] {
        let angle = 0.5 * (2.0 * std::f64::consts::PI * (0.5 + f64::from(step) / 200.0)).cos();
        out.push(Case::input(
            format!("frame{step}"),
            seed_thetas.map(|t| angle * t),
            seed_covs(),
        ));
    }
    // Random cases (fixed seed): joint values over the whole circle (joint limits clip some),
    // dense covariances; one with tiny angles (series path), one with angles near ±π.
    let mut rng = Lcg(0x5eed_0005_ba5e_f00d);
    for k in 0..4 {
        let thetas = std::array::from_fn(|_| rng.uniform(-3.1, 3.1));
        let s = [0.01, 0.05, 0.1, 0.2][k];
        let covs = std::array::from_fn(|_| rng.cov(s));
        out.push(Case::input(format!("random{k}"), thetas, covs));
    }
    let thetas = std::array::from_fn(|_| rng.uniform(-1e-7, 1e-7));
    let covs = std::array::from_fn(|_| rng.cov(0.02));
    out.push(Case::input("tiny".into(), thetas, covs));
    let thetas = std::array::from_fn(|i| {
        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
        sign * rng.uniform(3.1, 3.14159)
    });
    let covs = std::array::from_fn(|_| rng.cov(0.05));
    out.push(Case::input("near_pi".into(), thetas, covs));
    out
}

/// The cases with their expected results: the PPOE (right convention) of each, on the host
/// in f64, with the values the f64 table holds (`RobotChain::to_core_joints`).
pub fn expected(robot: &ppoe_build::RobotChain) -> Vec<Case> {
    let joints = robot.to_core_joints();
    assert_eq!(joints.len(), N, "the seed robot has 6 moving joints");
    let chain = ChainView {
        joints: &joints,
        home: robot.home_transform(),
    };
    let mut cases = inputs();
    for c in &mut cases {
        let covs: Vec<Mat6<f64>> = c.covs.iter().map(|m| ppoe::Matrix(*m)).collect();
        let r = chain
            .ppoe(&c.thetas, &covs, Convention::Right)
            .unwrap_or_else(|e| panic!("host PPOE failed for case {}: {e:?}", c.name));
        c.pose = r.pose.to_matrix4();
        c.cov = r.cov.0;
    }
    cases
}
