//! Maximum likelihood by Fisher scoring: each step is `Δ = F⁺·g` in the parameters θ
//! (F = Jᵀ·F_x·J, g = Jᵀ·g_x from the design's closed forms; F⁺ the pseudo-inverse on the
//! directions F determines, after scaling F to unit diagonal), followed by step halving
//! until the likelihood does not decrease. Directions the data do not determine (F
//! singular: structural non-identifiability, or a rank-deficient factor L) are left
//! unchanged.

use crate::design::Design;
use crate::error::FitError;
use crate::param::Param;
use nalgebra::{DMatrix, DVector};

/// Stop when the full step's predicted log-likelihood gain is below this: parameters then
/// move by far less than a hundredth of their standard errors.
const GAIN_TOL: f64 = 1e-6;
const MAX_ITERATIONS: usize = 200;
/// EM stops when a cycle gains less than this: a log-likelihood difference of 1e-3 is
/// statistically negligible (a likelihood-ratio χ² of 0.002), and EM's steps shrink
/// slowly near covariances of lower rank.
const EM_GAIN_TOL: f64 = 1e-3;
/// The Fisher information is an expectation: a few hundred samples give the step's
/// metric; the gradient (the fixed point) always uses every sample.
const FISHER_SAMPLES: usize = 600;

pub(crate) struct Outcome {
    pub theta: DVector<f64>,
    pub loglik: f64,
    pub iterations: usize,
    pub converged: bool,
    /// No step improved and the last accepted one gained less than `GAIN_TOL`.
    pub stalled_at_optimum: bool,
}

/// The scaled Fisher information's eigen-decomposition, computed once per iteration and
/// shared by the damped steps tried in it (only μ changes between them).
struct Scoring {
    /// 1/√F_ii (0 where F_ii = 0): the scaling to unit diagonal.
    d: Vec<f64>,
    eigen: nalgebra::SymmetricEigen<f64, nalgebra::Dyn>,
    top: f64,
    /// The scaled gradient.
    gs: DVector<f64>,
}

impl Scoring {
    fn new(f: &DMatrix<f64>, g: &DVector<f64>) -> Self {
        let p = f.nrows();
        let d: Vec<f64> = (0..p)
            .map(|i| {
                let v = f[(i, i)];
                if v > 0.0 {
                    1.0 / v.sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        let s = DMatrix::from_fn(p, p, |i, j| f[(i, j)] * d[i] * d[j]);
        let gs = DVector::from_fn(p, |i, _| g[i] * d[i]);
        let eigen = s.symmetric_eigen();
        let top = eigen.eigenvalues.max().max(1e-300);
        Self { d, eigen, top, gs }
    }

    /// `(F + μ·λ_max)⁺·g` with F scaled to unit diagonal, eigenvalues below 1e-9 of the
    /// largest dropped (as in the rank of the report).
    fn step(&self, mu: f64) -> DVector<f64> {
        let p = self.d.len();
        let mut step = DVector::zeros(p);
        for (k, &lam) in self.eigen.eigenvalues.iter().enumerate() {
            if lam > crate::report::RANK_TOL * self.top {
                let v = self.eigen.eigenvectors.column(k);
                step += v * (v.dot(&self.gs) / (lam + mu * self.top));
            }
        }
        DVector::from_fn(p, |i, _| step[i] * self.d[i])
    }
}

/// Full model: `θ + t·Δ` with t ≤ 1 halved until no term's coefficient matrix changes by more than
/// its own size (relative Frobenius norm): the scoring metric is a local model of the
/// likelihood in the coefficients, and the parameterisations are nonlinear in them (a
/// log-Cholesky entry far below its neighbours can otherwise jump by orders of
/// magnitude).
fn trusted(param: &Param, theta: &DVector<f64>, step: DVector<f64>) -> DVector<f64> {
    if param.model == crate::param::Model::Joint {
        // Log-variances: a step is a factor per variance, at most e³ = 20 per step and
        // parameter. A floor variance near its bound has a vanishing Fisher information
        // and its scoring step alone could overflow; clipped per parameter, so that it
        // cannot shrink every other parameter's step to nothing (scaling the whole step
        // did, and scoring then stalled short of the optimum).
        let mut cand = theta + step.map(|s| s.clamp(-3.0, 3.0));
        param.clamp(&mut cand);
        return cand;
    }
    let x0 = param.coeffs(theta);
    let mut t = 1.0;
    loop {
        let mut cand = theta + &step * t;
        param.clamp(&mut cand);
        let x1 = param.coeffs(&cand);
        let ok = x0
            .iter()
            .zip(&x1)
            .all(|(a, b)| (b - a).norm() <= a.norm().max(1e-300));
        if ok || t < 1e-6 {
            return cand;
        }
        t *= 0.5;
    }
}

/// The gradient and Fisher information in θ; parameters held at their bound leave the
/// step (zero rows, dropped by the scaling in `Scoring`).
fn metric(
    design: &Design,
    param: &Param,
    theta: &DVector<f64>,
    stride: usize,
) -> Result<(DVector<f64>, DMatrix<f64>), FitError> {
    let Some(m) = design.moments(&param.coeffs(theta), stride) else {
        return Err(FitError::Numerical("Σ became singular".into()));
    };
    let j = param.jacobian(theta, design.units.len());
    let mut g = j.transpose() * &m.grad;
    let mut f = j.transpose() * &m.fisher * &j;
    for (k, _) in param.active(theta, &g).iter().enumerate().filter(|a| *a.1) {
        g[k] = 0.0;
        f.row_mut(k).fill(0.0);
        f.column_mut(k).fill(0.0);
    }
    Ok((g, f))
}

/// When to give up on a scoring run that still gains, but slowly: once the last `window`
/// accepted steps together gained less than `gain`. The full model's scoring can crawl
/// for hundreds of steps towards covariances of lower rank (log-Cholesky diagonals
/// heading to −∞) gaining 10⁻³ each; the caller's rounds of EM and scoring decide
/// convergence.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Crawl {
    pub window: usize,
    pub gain: f64,
}

impl Crawl {
    /// Whether `history` (the log-likelihood after each accepted step) ends in a crawl.
    fn crawling(&self, history: &[f64]) -> bool {
        let n = history.len();
        n > self.window && history[n - 1] - history[n - 1 - self.window] < self.gain
    }
}

/// What one iteration's damped steps came to.
enum Trial {
    /// The full step's predicted gain is below `GAIN_TOL`: nothing to do.
    Converged,
    /// A step that does not lower the likelihood (`converged`: it gained next to nothing).
    Moved {
        theta: DVector<f64>,
        loglik: f64,
        converged: bool,
    },
    /// No step up to the largest damping improves.
    Stuck,
}

/// One iteration's damped steps: μ raised tenfold until a step does not lower the
/// likelihood, and lowered tenfold after one that does not (for the next iteration).
fn damped(
    design: &Design,
    param: &Param,
    (theta, loglik): (&DVector<f64>, f64),
    g: &DVector<f64>,
    scoring: &Scoring,
    mu: &mut f64,
) -> Trial {
    while *mu < 1e3 {
        let step = scoring.step(*mu);
        let gain = 0.5 * g.dot(&step);
        let cand = trusted(param, theta, step);
        // The step actually taken (bounds may clip it).
        let gain = gain.min(0.5 * g.dot(&(&cand - theta)));
        if gain < GAIN_TOL && *mu <= 1e-6 {
            return Trial::Converged;
        }
        match design.loglik(&param.coeffs(&cand)) {
            Some(l) if l >= loglik => {
                let converged = l - loglik < GAIN_TOL && gain < GAIN_TOL && *mu <= 1e-6;
                *mu = (*mu * 0.1).max(1e-9);
                return Trial::Moved {
                    theta: cand,
                    loglik: l,
                    converged,
                };
            }
            _ => *mu *= 10.0,
        }
    }
    Trial::Stuck
}

/// Maximises the likelihood from `theta`; `progress(iteration, loglik)` after each step;
/// stops early (not converged) on a `crawl`.
pub(crate) fn maximize(
    design: &Design,
    param: &Param,
    mut theta: DVector<f64>,
    crawl: Option<Crawl>,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<Outcome, FitError> {
    let stride = design.eta.len().div_ceil(FISHER_SAMPLES).max(1);
    let Some(mut loglik) = design.loglik(&param.coeffs(&theta)) else {
        return Err(FitError::Numerical(
            "the starting covariances give a singular Σ for some sample".into(),
        ));
    };
    let (mut converged, mut iterations, mut mu) = (false, 0, 1e-6);
    let mut last_gain = f64::INFINITY;
    let mut stalled_at_optimum = false;
    let mut history = vec![loglik];
    while iterations < MAX_ITERATIONS && !converged {
        iterations += 1;
        let (g, f) = metric(design, param, &theta, stride)?;
        let scoring = Scoring::new(&f, &g);
        match damped(design, param, (&theta, loglik), &g, &scoring, &mut mu) {
            Trial::Converged => converged = true,
            Trial::Moved {
                theta: t,
                loglik: l,
                converged: c,
            } => {
                (last_gain, theta, loglik, converged) = (l - loglik, t, l, c);
                if !c {
                    progress(iterations, loglik);
                    history.push(loglik);
                    if crawl.is_some_and(|cr| cr.crawling(&history)) {
                        break;
                    }
                }
            }
            Trial::Stuck => {
                progress(iterations, loglik);
                // No step improves: at the optimum within rounding if the last one
                // gained next to nothing.
                stalled_at_optimum = last_gain < GAIN_TOL;
                break;
            }
        }
    }
    Ok(Outcome {
        theta,
        loglik,
        iterations,
        converged,
        stalled_at_optimum,
    })
}

type Coeffs = Vec<nalgebra::Matrix6<f64>>;

fn lin(a: &Coeffs, b: &Coeffs, ca: f64, cb: f64) -> Coeffs {
    a.iter().zip(b).map(|(x, y)| x * ca + y * cb).collect()
}

fn dist2(a: &Coeffs, b: &Coeffs) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).norm_squared()).sum()
}

/// Every coefficient matrix PSD (a Cholesky factor of it plus 1e-12 of its trace).
fn all_psd(x: &Coeffs) -> bool {
    x.iter().all(|m| {
        let t = m.trace().max(0.0) * 1e-12 + 1e-300;
        (m + nalgebra::Matrix6::identity() * t).cholesky().is_some()
    })
}

/// EM accelerated by SQUAREM (Varadhan & Roland 2008): two EM steps give r and v, the
/// extrapolation `x − 2αr + α²v` (α = −‖r‖/‖v‖, moved towards −1 until the result is PSD
/// and not worse), then one EM step. Monotone and PSD like plain EM. Stops when a cycle
/// gains less than `GAIN_TOL`; returns the coefficients, the log-likelihood, the cycles
/// and whether it stopped by that test.
pub(crate) fn em(
    design: &Design,
    mut x: Coeffs,
    max: usize,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<(Coeffs, f64, usize, bool), FitError> {
    let singular = || FitError::Numerical("Σ became singular in EM".into());
    let (x1, mut l0) = design.em_step(&x).ok_or_else(singular)?;
    let mut first = Some(x1);
    for it in 0..max {
        let x1 = match first.take() {
            Some(x1) => x1,
            None => design.em_step(&x).ok_or_else(singular)?.0,
        };
        let (x2, _) = design.em_step(&x1).ok_or_else(singular)?;
        let r = lin(&x1, &x, 1.0, -1.0);
        let v = lin(&lin(&x2, &x1, 1.0, -1.0), &r, 1.0, -1.0);
        let mut alpha = -(dist2(&x1, &x) / dist2(&v, &lin(&v, &v, 0.0, 0.0)).max(1e-300)).sqrt();
        let mut next = x2.clone();
        while alpha < -1.0 {
            let cand = lin(&lin(&x, &r, 1.0, -2.0 * alpha), &v, 1.0, alpha * alpha);
            if all_psd(&cand) {
                if let Some((stepped, l)) = design.em_step(&cand) {
                    if l >= l0 {
                        next = stepped;
                        break;
                    }
                }
            }
            alpha = 0.5 * (alpha - 1.0);
        }
        // The step from `next` gives its log-likelihood, and is the next cycle's first.
        let (x1_next, l) = design.em_step(&next).ok_or_else(singular)?;
        progress(it + 1, l);
        let gain = l - l0;
        x = next;
        l0 = l;
        first = Some(x1_next);
        if gain < EM_GAIN_TOL {
            return Ok((x, l0, it + 1, true));
        }
    }
    Ok((x, l0, max, false))
}
