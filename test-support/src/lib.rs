//! Shared helpers of `ppoe`'s integration tests and of `examples/accuracy.rs`:
//! golden-file loading, the error measures, Gaussian sampling and the Monte Carlo models.
//!
//! # Why a crate that depends on `ppoe`
//!
//! A dev-dependency that itself depends on `ppoe` would give *unit* tests (`src/**`, built
//! with `--test`) a second, incompatible copy of ppoe's types. This crate is used only by
//! integration tests (`tests/*.rs`) and examples, which link the ordinary `ppoe` library:
//! the same crate this one links, so the types here (`Transform`, `Mat6`, `ChainView`, …)
//! are the ones the tests use. That is what lets the chain loader, the samplers and the
//! Monte Carlo models live here instead of being split into a ppoe-free part and a
//! `#[path]`-included rest. Do not use it from `src/`.
//!
//! It is not published: the packaged `ppoe` ships only the tests that need no golden data
//! and no helper (see the root `Cargo.toml`'s `include`), and `cargo package` drops this
//! path-only dev-dependency.
//!
//! The golden data are read from the repository's `test_data/` (this crate's parent
//! directory). Failures panic with the file and the reason: these are test helpers.
#![deny(missing_docs)]

pub mod fixtures;

use ppoe::uncertainty::{self, Order};
use ppoe::{se3, Mat6, Matrix, Transform, Vec6, Vector};
use rand::Rng;
use rand_distr::StandardNormal;
use serde_json::Value;
use std::path::PathBuf;

/// The golden PPOE files (`test_data/golden/ppoe/{name}.json`), one per test chain.
pub const PPOE_FILES: [&str; 8] = [
    "seed_linkmount_tcp",
    "prismatic_base_link_tool0",
    "fixed_between_world_tool_tip",
    "continuous_base_ee",
    "rpy_everywhere_base_tool",
    "rpy_everywhere_link2_tool",
    "tree_base_footprint_left_tip",
    "tree_base_footprint_right_tip",
];

/// Path of a file below the repository's `test_data/`.
pub fn data_path(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("test_data")
        .join(rel)
}

/// Parses a golden JSON file below `test_data/golden/`.
pub fn golden(rel: &str) -> Value {
    let path = data_path(&format!("golden/{rel}"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read {}: {e} (regenerate with test_data/reference)",
            path.display()
        )
    });
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A float from the golden encoding: a number, or "inf", "-inf", "nan".
pub fn num(v: &Value) -> f64 {
    match v {
        Value::Number(n) => n.as_f64().expect("number"),
        Value::String(s) => match s.as_str() {
            "inf" => f64::INFINITY,
            "-inf" => f64::NEG_INFINITY,
            "nan" => f64::NAN,
            other => panic!("bad float string {other:?}"),
        },
        Value::Null => f64::NAN,
        other => panic!("not a float: {other}"),
    }
}

/// A JSON array of exactly N floats.
pub fn vec_n<const N: usize>(v: &Value) -> [f64; N] {
    let a = v.as_array().expect("array");
    assert_eq!(a.len(), N, "length");
    std::array::from_fn(|i| num(&a[i]))
}

/// A JSON array of floats, any length.
pub fn vecf(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(num).collect()
}

/// A JSON R×C array of floats (rows).
pub fn mat_n<const R: usize, const C: usize>(v: &Value) -> [[f64; C]; R] {
    let a = v.as_array().expect("array");
    assert_eq!(a.len(), R, "rows");
    std::array::from_fn(|i| vec_n::<C>(&a[i]))
}

/// A 4×4 homogeneous matrix (JSON rows) as a `Transform`.
pub fn transform(v: &Value) -> Transform<f64> {
    Transform::from_matrix4(&mat_n::<4, 4>(v))
}

/// A 6×6 matrix (JSON rows).
pub fn mat6(v: &Value) -> Mat6<f64> {
    Matrix(mat_n::<6, 6>(v))
}

/// The project's error measure: `max|a − b| / max(1, max|b|)`.
pub fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let diff = a.iter().zip(b).fold(0.0f64, |m, (x, y)| {
        if x.is_nan() || y.is_nan() {
            f64::INFINITY
        } else {
            m.max((x - y).abs())
        }
    });
    diff / scale
}

/// The entries of a matrix, row by row.
pub fn flat<const R: usize, const C: usize>(m: &Matrix<f64, R, C>) -> Vec<f64> {
    m.0.iter().flatten().copied().collect()
}

/// The 16 entries of a transform's 4×4 matrix, row by row.
pub fn flat_t(t: &Transform<f64>) -> Vec<f64> {
    t.to_matrix4().iter().flatten().copied().collect()
}

/// Relative Frobenius error ‖a − b‖ / ‖b‖.
pub fn frob_rel(a: &Mat6<f64>, b: &Mat6<f64>) -> f64 {
    let d: f64 = flat(&(*a - *b)).iter().map(|x| x * x).sum();
    let n: f64 = flat(b).iter().map(|x| x * x).sum();
    (d / n).sqrt()
}

/// The diagonal 6×6 matrix of `d`.
pub fn diag(d: [f64; 6]) -> Mat6<f64> {
    Mat6::from_diagonal(&Vector(d))
}

/// A sampler of N(0, Σ) for a PSD Σ: Cholesky of Σ + (1e-14·max|Σ| + 1e-300)·I (exact for
/// PD Σ; rank-deficient Σ get a diagonal shift far below the sampling error).
pub struct Gaussian6 {
    l: Mat6<f64>,
    box_muller: bool,
}

impl Gaussian6 {
    /// Standard normals from `rand_distr::StandardNormal`.
    pub fn new(cov: &Mat6<f64>) -> Self {
        Self::with_normals(cov, false)
    }

    /// Standard normals by Box–Muller with the `libm` crate's `log`/`sincos` (pure Rust, so
    /// the sample stream does not depend on the platform's math library).
    pub fn box_muller(cov: &Mat6<f64>) -> Self {
        Self::with_normals(cov, true)
    }

    fn with_normals(cov: &Mat6<f64>, box_muller: bool) -> Self {
        let shift = cov.amax() * 1e-14 + 1e-300;
        let l = (*cov + Mat6::identity() * shift)
            .cholesky()
            .expect("PSD covariance");
        Self { l, box_muller }
    }

    /// One draw of N(0, Σ).
    pub fn sample(&self, rng: &mut impl Rng) -> Vec6<f64> {
        let z: Vec6<f64> = if self.box_muller {
            let mut z = [0.0; 6];
            for pair in z.chunks_exact_mut(2) {
                let u1 = 1.0 - rng.gen::<f64>(); // (0, 1]
                let u2 = rng.gen::<f64>();
                let r = (-2.0 * libm::log(u1)).sqrt();
                let (s, c) = libm::sincos(2.0 * std::f64::consts::PI * u2);
                pair[0] = r * c;
                pair[1] = r * s;
            }
            Vector(z)
        } else {
            Vector(std::array::from_fn(|_| rng.sample(StandardNormal)))
        };
        self.l * z
    }
}

/// Sample covariance (divisor N − 1) and mean of 6-vectors.
pub fn sample_cov(samples: &[Vec6<f64>]) -> (Vec6<f64>, Mat6<f64>) {
    let n = samples.len() as f64;
    let mut mean = Vec6::zeros();
    for s in samples {
        mean += *s;
    }
    mean = mean.scale(1.0 / n);
    let mut cov = Mat6::zeros();
    for s in samples {
        let d = *s - mean;
        cov += d.outer(&d);
    }
    (mean, cov.scale(1.0 / (n - 1.0)))
}

/// Second moment E[x xᵀ] about zero (the covariance of a perturbation whose mean is the
/// nominal pose).
pub fn second_moment(samples: &[Vec6<f64>]) -> Mat6<f64> {
    let mut m = Mat6::zeros();
    for s in samples {
        m += s.outer(s);
    }
    m.scale(1.0 / samples.len() as f64)
}

/// Converts an f64 matrix to the scalar under test.
pub fn cast_m<T: ppoe::Real, const R: usize, const C: usize>(
    m: &Matrix<f64, R, C>,
) -> Matrix<T, R, C> {
    Matrix(m.0.map(|r| r.map(T::lit)))
}

/// Converts an f64 vector to the scalar under test.
pub fn cast_v<T: ppoe::Real, const N: usize>(v: &Vector<f64, N>) -> Vector<T, N> {
    Vector(v.0.map(T::lit))
}

/// Converts an f64 transform to the scalar under test.
pub fn cast_t<T: ppoe::Real>(t: &Transform<f64>) -> Transform<T> {
    Transform {
        rotation: cast_m(&t.rotation),
        translation: cast_v(&t.translation),
    }
}

/// Back to f64 (exact).
pub fn up_m<T: ppoe::Real, const R: usize, const C: usize>(
    m: &Matrix<T, R, C>,
) -> Matrix<f64, R, C> {
    Matrix(m.0.map(|r| r.map(|x| x.to_f64())))
}

/// Back to f64 (exact).
pub fn up_v<T: ppoe::Real, const N: usize>(v: &Vector<T, N>) -> Vector<f64, N> {
    Vector(v.0.map(|x| x.to_f64()))
}

/// Back to f64 (exact).
pub fn up_t<T: ppoe::Real>(t: &Transform<T>) -> Transform<f64> {
    Transform {
        rotation: up_m(&t.rotation),
        translation: up_v(&t.translation),
    }
}

/// Tracks the worst error over the cases of one golden file.
pub struct Worst {
    /// The golden file's name.
    pub name: String,
    /// The worst error so far (NaN if any error was NaN).
    pub max: f64,
    /// The case of the worst error.
    pub label: String,
    /// How many cases were added.
    pub count: usize,
}

impl Worst {
    /// No cases yet.
    pub fn new(name: &str) -> Self {
        Self {
            name: name.into(),
            max: 0.0,
            label: String::new(),
            count: 0,
        }
    }
    /// Records the error of the case `label`.
    pub fn add(&mut self, err: f64, label: &str) {
        self.count += 1;
        if err.is_nan() || err > self.max {
            self.max = err;
            self.label = label.into();
        }
    }
    /// Prints the worst error and asserts it is within `tol`.
    pub fn check(&self, tol: f64) {
        println!(
            "{:<40} {:>5} cases, worst {:.3e} ({})",
            self.name, self.count, self.max, self.label
        );
        assert!(self.count > 0, "{}: no cases", self.name);
        assert!(
            self.max <= tol,
            "{}: worst error {:.3e} > {:.1e} at case {}",
            self.name,
            self.max,
            tol,
            self.label
        );
    }
}

/// A chain from a golden PPOE file in scalar T: joints (kinds from `joint_types`, names
/// leaked to `'static` as the const tables have them) and home pose.
pub fn chain_from_golden<T: ppoe::Real>(g: &Value) -> (Vec<ppoe::chain::Joint<T>>, Transform<T>) {
    use ppoe::chain::{Joint, JointKind};
    let joints = g["joints"]
        .as_array()
        .expect("joints")
        .iter()
        .zip(g["joint_types"].as_array().expect("joint_types"))
        .zip(g["screw_axes"].as_array().expect("screw_axes"))
        .zip(g["limits"].as_array().expect("limits"))
        .map(|(((n, k), s), l)| {
            let name: &'static str =
                Box::leak(n.as_str().expect("name").to_string().into_boxed_str());
            let kind = match k.as_str().expect("type") {
                "revolute" => JointKind::Revolute,
                "continuous" => JointKind::Continuous,
                "prismatic" => JointKind::Prismatic,
                other => panic!("joint type {other}"),
            };
            let l = vec_n::<2>(l);
            Joint::new(
                name,
                kind,
                vec_n::<6>(s).map(T::lit),
                T::lit(l[0]),
                T::lit(l[1]),
            )
        })
        .collect();
    (joints, cast_t(&transform(&g["home"])))
}

/// The seed example's joint covariances (pytransform3d's PPOE example, as
/// `test_data/reference/generate_ppoe.py` uses them) scaled by `scale`: 0.05 rad² about
/// the base z axis for joint 1 and about the base y axis for joints 2, 3 and 5.
pub fn seed_covs(scale: f64) -> Vec<Mat6<f64>> {
    let z = Mat6::from_diagonal(&Vector([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]));
    let y = Mat6::from_diagonal(&Vector([0.0, 1.0, 0.0, 0.0, 0.0, 0.0]));
    [z, y, y, Matrix::zeros(), y, Matrix::zeros()]
        .iter()
        .map(|c| *c * (0.05 * scale))
        .collect()
}

/// The seed animation's joint values at frame k (pytransform3d's PPOE example, as
/// `test_data/reference/generate_ppoe.py` computes them).
pub fn seed_frame(k: usize) -> Vec<f64> {
    let angle = 0.5 * (2.0 * std::f64::consts::PI * (0.5 + k as f64 / 200.0)).cos();
    [1.0, 1.0, 1.0, 0.0, 1.0, 0.0]
        .iter()
        .map(|t| angle * t)
        .collect()
}

/// The joint part of the PPOE model `T = D₁Exp(ξ₁)…DₙExp(ξₙ)·M` at fixed joint values:
/// the displacements `Dᵢ` and samplers of ξᵢ ~ N(0, covsᵢ).
pub struct ChainModel {
    ds: Vec<Transform<f64>>,
    gs: Vec<Gaussian6>,
}

impl ChainModel {
    /// `sampler` is [`Gaussian6::new`] or [`Gaussian6::box_muller`].
    pub fn new(
        chain: &ppoe::chain::ChainView<f64>,
        thetas: &[f64],
        covs: &[Mat6<f64>],
        sampler: fn(&Mat6<f64>) -> Gaussian6,
    ) -> Self {
        let gs = covs.iter().map(sampler).collect();
        let ds = chain
            .joints
            .iter()
            .zip(thetas)
            .map(|(j, t)| j.displacement(j.clip(*t, false)))
            .collect();
        Self { ds, gs }
    }

    /// One draw of `D₁Exp(ξ₁)…DₙExp(ξₙ)` (without the home pose `M`).
    pub fn draw(&self, rng: &mut impl Rng) -> Transform<f64> {
        let mut t = Transform::identity();
        for (d, g) in self.ds.iter().zip(&self.gs) {
            t = t * *d * se3::exp(&g.sample(rng));
        }
        t
    }
}

/// `n` draws of the PPOE model `T = D₁Exp(ξ₁)…DₙExp(ξₙ)·M`, ξᵢ ~ N(0, covsᵢ), with a
/// fixed seed.
pub fn sample_chain_poses(
    chain: &ppoe::chain::ChainView<f64>,
    thetas: &[f64],
    covs: &[Mat6<f64>],
    seed: u64,
    n: usize,
) -> Vec<Transform<f64>> {
    use rand::SeedableRng;
    let model = ChainModel::new(chain, thetas, covs, Gaussian6::new);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| model.draw(&mut rng) * chain.home).collect()
}

/// Barfoot & Furgale (IEEE T-RO 2014, §IV.C) two-pose compounding: T₁ = Exp(ξ₁),
/// T₂ = Exp(ξ₂), ξ₁ = (π/6,0,0 | 0,2,0), ξ₂ = (0,π/4,0 | 0,0,1), Σ₁ = Σ₂ = Σ; global model
/// Exp(ξ')·T̄ = Exp(ζ₂)·T₂·Exp(ζ₁)·T₁, ζᵢ ~ N(0, Σ), T̄ = T₂·T₁.
pub struct TwoPose {
    /// T₁ = Exp(ξ₁).
    pub t1: Transform<f64>,
    /// T₂ = Exp(ξ₂).
    pub t2: Transform<f64>,
    /// T̄⁻¹.
    inv: Transform<f64>,
}

impl TwoPose {
    /// The paper's two poses.
    pub fn barfoot_furgale() -> Self {
        use std::f64::consts::{FRAC_PI_4, FRAC_PI_6};
        let t1 = se3::exp(&Vector([FRAC_PI_6, 0.0, 0.0, 0.0, 2.0, 0.0]));
        let t2 = se3::exp(&Vector([0.0, FRAC_PI_4, 0.0, 0.0, 0.0, 1.0]));
        let inv = (t2 * t1).inverse();
        Self { t1, t2, inv }
    }

    /// Σ = α·diag(½, 1, ½ | 10, 5, 5).
    pub fn cov(alpha: f64) -> Mat6<f64> {
        diag([0.5, 1.0, 0.5, 10.0, 5.0, 5.0]) * alpha
    }

    /// One draw of ξ' = Log(Exp(ζ₂)·T₂·Exp(ζ₁)·T₁·T̄⁻¹) (ζ₁ drawn first).
    pub fn draw(&self, g: &Gaussian6, rng: &mut impl Rng) -> Vec6<f64> {
        let x1 = g.sample(rng);
        let x2 = g.sample(rng);
        se3::log(&(se3::exp(&x2) * self.t2 * se3::exp(&x1) * self.t1 * self.inv))
    }

    /// The covariance of ξ' from `uncertainty::concat_globally`: (second, fourth) order.
    pub fn concat(&self, s: &Mat6<f64>) -> (Mat6<f64>, Mat6<f64>) {
        let (t1, t2) = (&self.t1, &self.t2);
        let (_, c2) = uncertainty::concat_globally(t1, s, t2, s, Order::Second);
        let (_, c4) = uncertainty::concat_globally(t1, s, t2, s, Order::Fourth);
        (c2, c4)
    }
}
