//! Weighted least squares of the deterministic parameters for a given noise model: the
//! residuals of every sample, whitened by the noise model's covariance (Σₖ = LₖLₖᵀ,
//! zₖ = Lₖ⁻¹rₖ), minimised by Gauss–Newton with the pseudo-inverse on the combinations
//! the data determine (the others do not move: the gauge is the starting point's), and
//! the parameters' covariance `(JᵀJ)⁺` of the whitened problem — the inverse Fisher
//! information of the mean parameters, which for a Gaussian is orthogonal to that of the
//! covariance parameters except through Σ's weak dependence on the marker's lever arm and
//! the corrected axes.
//!
//! The Jacobian is by central differences (step `H`): the residual is a composition of
//! exponentials, logarithms and the chain's fold, smooth at the scale of any real
//! calibration, and the columns are independent, so they are computed in parallel.

use super::layout::{Layout, Point};
use crate::report::information;
use nalgebra::{DMatrix, DVector, Matrix6};
use ppoe::chain::Joint;
use ppoe::{se3, Transform, Vec3};

/// The central-difference step (rad, m): truncation error O(H²) ≈ 1e-12 relative,
/// rounding ε·|r|/H far below it for residuals under a metre.
const H: f64 = 1e-6;
const MAX_ITERATIONS: usize = 30;
/// Stop when the predicted decrease of the whitened sum of squares is below this (a χ²
/// change of 1e-6: the parameters move by a thousandth of their standard errors).
const DECREASE_TOL: f64 = 1e-6;

/// The measurements, checked: the tracker's poses or points.
pub(crate) enum Data {
    Poses(Vec<Transform<f64>>),
    Positions(Vec<Vec3<f64>>),
}

impl Data {
    /// Residual components per sample.
    pub fn dim(&self) -> usize {
        match self {
            Data::Poses(_) => 6,
            Data::Positions(_) => 3,
        }
    }
}

/// A campaign: the nominal chain, the joint values and the measurements.
pub(crate) struct Campaign<'a> {
    pub joints: &'a [Joint<f64>],
    pub home: &'a Transform<f64>,
    pub thetas: Vec<Vec<f64>>,
    pub data: Data,
}

/// The tip pose of a chain at θ (clipped to the limits, as the PPOE clips).
pub(crate) fn tip(joints: &[Joint<f64>], home: &Transform<f64>, thetas: &[f64]) -> Transform<f64> {
    let mut t = Transform::identity();
    for (j, th) in joints.iter().zip(thetas) {
        t = t * j.displacement(j.clip(*th, false));
    }
    t * *home
}

impl Campaign<'_> {
    /// Every sample's residual at `at`, concatenated: `Log((X·T̄·Y)⁻¹·Tₖ)` (marker frame,
    /// rotation first) or `R_T̄ᵀ·(X⁻¹·pₖ − T̄·m)` (tip-frame axes at the marker point).
    pub fn residuals(&self, at: &Point) -> Option<Vec<f64>> {
        let (joints, home) = at.chain(self.joints, self.home)?;
        let xi = at.x.inverse();
        let mut out = Vec::with_capacity(self.thetas.len() * self.data.dim());
        for (k, th) in self.thetas.iter().enumerate() {
            let f = tip(&joints, &home, th);
            match &self.data {
                Data::Poses(t) => {
                    let e = se3::log(&((f * at.y).inverse() * xi * t[k]));
                    out.extend_from_slice(&e.0);
                }
                Data::Positions(p) => {
                    let local = xi.transform_point(&p[k]) - f.transform_point(&at.y.translation);
                    let e = f.rotation.transpose().mul_vec(&local);
                    out.extend_from_slice(&e.0);
                }
            }
        }
        out.iter().all(|x| x.is_finite()).then_some(out)
    }
}

/// Per sample, the inverse of Σₖ's lower Cholesky factor (d×d in the top-left corner).
pub(crate) struct Whitening(pub Vec<Matrix6<f64>>);

impl Whitening {
    /// The same isotropic weights for every sample: rotation components with variance
    /// `vr`, translation ones `vt`.
    pub fn isotropic(k: usize, dim: usize, vr: f64, vt: f64) -> Self {
        let mut w = Matrix6::zeros();
        for i in 0..dim {
            let v = if dim == 6 && i < 3 { vr } else { vt };
            w[(i, i)] = 1.0 / v.sqrt();
        }
        Self(vec![w; k])
    }

    /// From per-sample covariances (d×d in the top-left corner); `None` if one is not
    /// positive definite.
    pub fn of(sigmas: &[Matrix6<f64>], dim: usize) -> Option<Self> {
        let mut out = Vec::with_capacity(sigmas.len());
        for s in sigmas {
            let block = DMatrix::from_fn(dim, dim, |r, c| s[(r, c)]);
            let l = block.cholesky()?.l();
            let inv = l.solve_lower_triangular(&DMatrix::identity(dim, dim))?;
            out.push(Matrix6::from_fn(|r, c| {
                if r < dim && c < dim {
                    inv[(r, c)]
                } else {
                    0.0
                }
            }));
        }
        Some(Self(out))
    }

    /// The whitened residuals.
    pub fn apply(&self, r: &[f64], dim: usize) -> DVector<f64> {
        let mut z = DVector::zeros(r.len());
        for (k, w) in self.0.iter().enumerate() {
            for i in 0..dim {
                z[dim * k + i] = (0..=i).map(|j| w[(i, j)] * r[dim * k + j]).sum();
            }
        }
        z
    }
}

/// The whitened residuals and Jacobian at `at`.
pub(crate) fn linearise(
    c: &Campaign,
    layout: &Layout,
    at: &Point,
    w: &Whitening,
) -> Option<(DVector<f64>, DMatrix<f64>)> {
    let d = c.data.dim();
    let r = w.apply(&c.residuals(at)?, d);
    let p = layout.len();
    let column = |j: usize| -> Option<DVector<f64>> {
        let mut e = vec![0.0; p];
        e[j] = H;
        let plus = c.residuals(&layout.apply(&e, at))?;
        e[j] = -H;
        let minus = c.residuals(&layout.apply(&e, at))?;
        let diff: Vec<f64> = plus
            .iter()
            .zip(&minus)
            .map(|(a, b)| (a - b) / (2.0 * H))
            .collect();
        Some(w.apply(&diff, d))
    };
    let parts =
        crate::parallel::chunks_from(p, 2, |range| range.map(column).collect::<Option<Vec<_>>>());
    let cols: Vec<DVector<f64>> = parts.into_iter().collect::<Option<Vec<_>>>()?.concat();
    let j = DMatrix::from_fn(r.len(), p, |i, k| cols[k][i]);
    Some((r, j))
}

/// Gauss–Newton from `start` with the weights `w` to where the predicted decrease is
/// negligible or no halved step decreases the sum of squares; `None` if a residual is not
/// finite.
pub(crate) fn solve(c: &Campaign, layout: &Layout, start: &Point, w: &Whitening) -> Option<Point> {
    let mut at = start.clone();
    for _ in 0..MAX_ITERATIONS {
        if layout.len() == 0 {
            break;
        }
        let (r, j) = linearise(c, layout, &at, w)?;
        let g = j.transpose() * &r;
        let info = information(&(j.transpose() * &j));
        let step = -(&info.cov * &g);
        if -g.dot(&step) < DECREASE_TOL {
            break;
        }
        let sse = r.norm_squared();
        let mut t = 1.0;
        loop {
            let cand = layout.apply((&step * t).as_slice(), &at);
            let better = c
                .residuals(&cand)
                .is_some_and(|rc| w.apply(&rc, c.data.dim()).norm_squared() < sse);
            if better {
                at = cand;
                break;
            }
            t *= 0.5;
            if t < 1e-4 {
                return Some(at);
            }
        }
    }
    Some(at)
}
