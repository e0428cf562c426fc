//! Build script (runs on the host, std):
//! 1. the seed robot's tables (`SEED: Chain<f64, 6>`, `SEED_F32: Chain<f32, 6>`) from
//!    `test_data/urdf/seed.urdf` through `ppoe-build`;
//! 2. the expected results: each test case's PPOE (right convention) computed here in f64
//!    with the runtime chain from `ppoe-build` and the same `ppoe` crate, written as consts;
//! 3. the `memory.x` of the QEMU board for `$TARGET`, and `-Tlink.x` for the binary.

use ppoe::chain::{ChainView, Convention};
use ppoe::Mat6;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::{env, fs};

const URDF: &str = "../../test_data/urdf/seed.urdf";
const N: usize = 6;

struct CaseIn {
    name: String,
    thetas: [f64; N],
    covs: [[[f64; 6]; 6]; N],
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
                let mut acc = 0.0;
                for k in 0..6 {
                    acc += a[i][k] * a[j][k];
                }
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

fn cases() -> Vec<CaseIn> {
    let seed_thetas = [1.0, 1.0, 1.0, 0.0, 1.0, 0.0];
    let mut out = Vec::new();
    // The seed's initial state: -0.5 * thetas (note the -0.0).
    out.push(CaseIn {
        name: "initial".into(),
        thetas: seed_thetas.map(|t: f64| -0.5 * t),
        covs: seed_covs(),
    });
    // Animation frames: angle = 0.5 cos(2π(0.5 + step/200)), thetas_t = angle * thetas.
    for step in [0u32, 50, 100, 150] {
        let angle =
            0.5 * (2.0 * std::f64::consts::PI * (0.5 + f64::from(step) / 200.0)).cos();
        out.push(CaseIn {
            name: format!("frame{step}"),
            thetas: seed_thetas.map(|t| angle * t),
            covs: seed_covs(),
        });
    }
    // Random cases (fixed seed): joint values over the whole circle (joint limits clip some),
    // dense covariances; one with tiny angles (series path), one with angles near ±π.
    let mut rng = Lcg(0x5eed_0005_ba5e_f00d);
    for k in 0..4 {
        let thetas = std::array::from_fn(|_| rng.uniform(-3.1, 3.1));
        let s = [0.01, 0.05, 0.1, 0.2][k];
        let covs = std::array::from_fn(|_| rng.cov(s));
        out.push(CaseIn { name: format!("random{k}"), thetas, covs });
    }
    let thetas = std::array::from_fn(|_| rng.uniform(-1e-7, 1e-7));
    let covs = std::array::from_fn(|_| rng.cov(0.02));
    out.push(CaseIn { name: "tiny".into(), thetas, covs });
    let thetas = std::array::from_fn(|i| {
        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
        sign * rng.uniform(3.1, 3.14159)
    });
    let covs = std::array::from_fn(|_| rng.cov(0.05));
    out.push(CaseIn { name: "near_pi".into(), thetas, covs });
    out
}

fn lit_row(out: &mut String, row: &[f64]) {
    out.push('[');
    for (i, x) in row.iter().enumerate() {
        assert!(x.is_finite(), "non-finite value in the expectations");
        if i > 0 {
            out.push_str(", ");
        }
        let _ = write!(out, "{x:?}");
    }
    out.push(']');
}

fn lit_mat<const C: usize>(out: &mut String, m: &[[f64; C]]) {
    out.push('[');
    for (i, row) in m.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        lit_row(out, row);
    }
    out.push(']');
}

fn main() {
    let out_dir = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let target = env::var("TARGET").unwrap_or_default();

    // 1. The tables.
    let mut cfg = ppoe_build::Config::new(URDF);
    cfg.base("linkmount")
        .tip("tcp")
        .scalar(ppoe_build::Scalar::Both)
        .name("SEED");
    if let Err(e) = cfg.write_to_out_dir("seed_table.rs") {
        panic!("ppoe-build: {e}");
    }

    // 2. The expectations, on the host in f64, with the values the f64 table holds.
    let robot = cfg.chain().unwrap_or_else(|e| panic!("ppoe-build: {e}"));
    let joints = robot.to_core_joints();
    assert_eq!(joints.len(), N, "the seed robot has 6 moving joints");
    let chain = ChainView {
        joints: &joints,
        home: robot.home_transform(),
    };
    let cases = cases();
    let mut src = String::new();
    src.push_str(
        "// Generated by build.rs: PPOE (Convention::Right) of the seed robot in f64 on the host.\n",
    );
    let _ = writeln!(src, "pub const EXPECTED: [Case; {}] = [", cases.len());
    for c in &cases {
        let covs: Vec<Mat6<f64>> = c.covs.iter().map(|m| ppoe::Matrix(*m)).collect();
        let r = chain
            .ppoe(&c.thetas, &covs, Convention::Right)
            .unwrap_or_else(|e| panic!("host PPOE failed for case {}: {e:?}", c.name));
        let _ = write!(src, "    Case {{\n        name: {:?},\n        thetas: ", c.name);
        lit_row(&mut src, &c.thetas);
        src.push_str(",\n        covs: [");
        for (i, m) in c.covs.iter().enumerate() {
            if i > 0 {
                src.push_str(", ");
            }
            lit_mat(&mut src, m);
        }
        src.push_str("],\n        pose: ");
        lit_mat(&mut src, &r.pose.to_matrix4());
        src.push_str(",\n        cov: ");
        lit_mat(&mut src, &r.cov.0);
        src.push_str(",\n    },\n");
    }
    src.push_str("];\n");
    let path = out_dir.join("expected.rs");
    if fs::read(&path).ok().as_deref() != Some(src.as_bytes()) {
        fs::write(&path, src).expect("write expected.rs");
    }

    // 3. Memory layout of the QEMU board for this target, and the linker script.
    let mem = if target.starts_with("thumbv6m") {
        "memory/microbit.x"
    } else if target.starts_with("thumbv8m") {
        "memory/mps2-an505.x"
    } else {
        "memory/lm3s6965evb.x" // thumbv7m (lm3s6965evb) and thumbv7em (mps2-an386)
    };
    fs::copy(mem, out_dir.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out_dir.display());
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed={mem}");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=TARGET");
}
