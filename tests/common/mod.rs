//! Shared helpers of the integration tests: golden-file loading and Gaussian sampling.
#![allow(dead_code)]

use ppoe::{Mat6, Matrix, Transform, Vec6, Vector};
use rand::Rng;
use rand_distr::StandardNormal;
use serde_json::Value;
use std::path::PathBuf;

/// Path of a file below `test_data/`.
pub fn data_path(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
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

pub fn vec_n<const N: usize>(v: &Value) -> [f64; N] {
    let a = v.as_array().expect("array");
    assert_eq!(a.len(), N, "length");
    std::array::from_fn(|i| num(&a[i]))
}

pub fn vecf(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(num).collect()
}

pub fn mat_n<const R: usize, const C: usize>(v: &Value) -> [[f64; C]; R] {
    let a = v.as_array().expect("array");
    assert_eq!(a.len(), R, "rows");
    std::array::from_fn(|i| vec_n::<C>(&a[i]))
}

pub fn transform(v: &Value) -> Transform<f64> {
    Transform::from_matrix4(&mat_n::<4, 4>(v))
}

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

pub fn flat<const R: usize, const C: usize>(m: &Matrix<f64, R, C>) -> Vec<f64> {
    m.0.iter().flatten().copied().collect()
}

pub fn flat_t(t: &Transform<f64>) -> Vec<f64> {
    t.to_matrix4().iter().flatten().copied().collect()
}

/// Relative Frobenius error ‖a − b‖ / ‖b‖.
pub fn frob_rel(a: &Mat6<f64>, b: &Mat6<f64>) -> f64 {
    let d: f64 = flat(&(*a - *b)).iter().map(|x| x * x).sum();
    let n: f64 = flat(b).iter().map(|x| x * x).sum();
    (d / n).sqrt()
}

/// A sampler of N(0, Σ) for a PSD Σ (Cholesky of Σ + 1e-300·I, exact for PD Σ; rank-
/// deficient Σ are handled by a tiny diagonal shift far below the sampling error).
pub struct Gaussian6 {
    l: Mat6<f64>,
}

impl Gaussian6 {
    pub fn new(cov: &Mat6<f64>) -> Self {
        let shift = cov.amax() * 1e-14 + 1e-300;
        let l = (*cov + Mat6::identity() * shift)
            .cholesky()
            .expect("PSD covariance");
        Self { l }
    }

    pub fn sample(&self, rng: &mut impl Rng) -> Vec6<f64> {
        let z: Vec6<f64> = Vector(std::array::from_fn(|_| rng.sample(StandardNormal)));
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

pub fn cast_v<T: ppoe::Real, const N: usize>(v: &Vector<f64, N>) -> Vector<T, N> {
    Vector(v.0.map(T::lit))
}

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

pub fn up_v<T: ppoe::Real, const N: usize>(v: &Vector<T, N>) -> Vector<f64, N> {
    Vector(v.0.map(|x| x.to_f64()))
}

pub fn up_t<T: ppoe::Real>(t: &Transform<T>) -> Transform<f64> {
    Transform {
        rotation: up_m(&t.rotation),
        translation: up_v(&t.translation),
    }
}

/// Tracks the worst error over the cases of one golden file.
pub struct Worst {
    pub name: String,
    pub max: f64,
    pub label: String,
    pub count: usize,
}

impl Worst {
    pub fn new(name: &str) -> Self {
        Self {
            name: name.into(),
            max: 0.0,
            label: String::new(),
            count: 0,
        }
    }
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
