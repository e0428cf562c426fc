//! What the fit reports besides the estimate: standard errors from the Fisher information,
//! which combinations the data determine, and the goodness of fit (squared Mahalanobis
//! distances of the residuals under the fitted model against χ²₆).

use nalgebra::DMatrix;

/// Eigenvalues of the scaled Fisher information below this fraction of the largest count
/// as undetermined: exact non-identifiability leaves ~1e-16, data that merely vary little
/// leave far more.
pub const RANK_TOL: f64 = 1e-9;

/// The covariance of the natural parameters (pseudo-inverse of the Fisher information on
/// its determined subspace) and, per parameter, whether it is undetermined; plus the
/// rank and up to 12 null directions as (parameter, weight) lists.
pub(crate) struct Information {
    pub cov: DMatrix<f64>,
    pub undetermined: Vec<bool>,
    pub rank: usize,
    pub null_directions: Vec<Vec<(usize, f64)>>,
}

pub(crate) fn information(f: &DMatrix<f64>) -> Information {
    let p = f.nrows();
    if p == 0 {
        // No parameters (a campaign without calibration): nothing to decompose.
        return Information {
            cov: DMatrix::zeros(0, 0),
            undetermined: Vec::new(),
            rank: 0,
            null_directions: Vec::new(),
        };
    }
    let d: Vec<f64> = (0..p).map(|i| f[(i, i)].max(0.0).sqrt()).collect();
    let inv = |x: f64| if x > 0.0 { 1.0 / x } else { 0.0 };
    let s = DMatrix::from_fn(p, p, |i, j| f[(i, j)] * inv(d[i]) * inv(d[j]));
    let e = s.symmetric_eigen();
    let top = e.eigenvalues.max().max(1e-300);
    let mut cov = DMatrix::zeros(p, p);
    let mut null = vec![0.0; p];
    let mut rank = 0;
    let mut null_directions = Vec::new();
    for (k, &lam) in e.eigenvalues.iter().enumerate() {
        let v = e.eigenvectors.column(k);
        if lam > RANK_TOL * top {
            rank += 1;
            cov += v * v.transpose() / lam;
        } else {
            for i in 0..p {
                null[i] += v[i] * v[i];
            }
            if null_directions.len() < 12 {
                let mut comps: Vec<(usize, f64)> = (0..p).map(|i| (i, v[i])).collect();
                comps.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
                comps.truncate(4);
                comps.retain(|c| c.1.abs() > 0.05);
                null_directions.push(comps);
            }
        }
    }
    let cov = DMatrix::from_fn(p, p, |i, j| cov[(i, j)] * inv(d[i]) * inv(d[j]));
    let undetermined = (0..p).map(|i| d[i] == 0.0 || null[i] > 1e-6).collect();
    Information {
        cov,
        undetermined,
        rank,
        null_directions,
    }
}

/// The goodness of fit: the squared Mahalanobis distances dₖ = ηₖᵀΣₖ⁻¹ηₖ under the fitted
/// model should follow χ²₆. For the joint model, directions where the residual floor
/// dominates the predicted variance (fewer than six joints, singular configurations) are
/// left out and dₖ is compared with χ² of the remaining dimension: the residual there is
/// second order and not Gaussian.
#[derive(Clone, Debug, PartialEq)]
pub struct GoodnessOfFit {
    /// Mean of dₖ (χ²₆: 6; the mean dimension where directions are left out).
    pub mean_mahalanobis: f64,
    /// Fraction of samples with dₖ above χ²₆'s 99 % quantile 16.81 (expected 0.01).
    pub beyond_99: f64,
    /// Kolmogorov–Smirnov statistic of dₖ against χ²₆.
    pub ks_statistic: f64,
    /// Its asymptotic p-value (slightly conservative: the model was fitted to the same
    /// samples).
    pub p_value: f64,
    /// p ≥ 0.01: the residuals are consistent with the fitted model.
    pub fits: bool,
}

/// The CDF of χ² with `dof` = 1…6 degrees of freedom, in closed form: for even dof
/// `1 − e^(−h)·Σₖ hᵏ/k!` (k < dof/2), for odd dof `erf(√h) − e^(−h)·Σₖ h^(k−½)/Γ(k+½)`
/// (1 ≤ k ≤ (dof−1)/2), h = x/2.
pub fn chi2_cdf(x: f64, dof: usize) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let h = 0.5 * x;
    if dof.is_multiple_of(2) {
        let (mut term, mut sum) = (1.0, 0.0);
        for k in 0..dof / 2 {
            sum += term;
            term *= h / (k + 1) as f64;
        }
        1.0 - (-h).exp() * sum
    } else {
        // Γ(3/2) = √π/2, Γ(k+3/2) = (k+½)·Γ(k+½).
        let (mut gamma, mut sum) = (0.5 * std::f64::consts::PI.sqrt(), 0.0);
        let mut power = h.sqrt();
        for k in 1..=(dof - 1) / 2 {
            sum += power / gamma;
            gamma *= k as f64 + 0.5;
            power *= h;
        }
        libm::erf(h.sqrt()) - (-h).exp() * sum
    }
}

/// The Kolmogorov distribution's survival function Q(λ) = 2·Σ (−1)^(j−1)·e^(−2j²λ²).
fn kolmogorov_q(lambda: f64) -> f64 {
    if lambda < 0.2 {
        return 1.0;
    }
    let mut s = 0.0;
    for j in 1..=100 {
        let j = j as f64;
        let t = (-2.0 * j * j * lambda * lambda).exp();
        s += if j as usize % 2 == 1 { t } else { -t };
        if t < 1e-17 {
            break;
        }
    }
    (2.0 * s).clamp(0.0, 1.0)
}

/// The 99 % quantiles of χ² with 1…6 degrees of freedom.
const Q99: [f64; 7] = [
    0.0, 6.634_897, 9.210_340, 11.344_867, 13.276_704, 15.086_272, 16.811_894,
];

/// `d`: (squared Mahalanobis distance, its dimension) per sample.
pub(crate) fn goodness_of_fit(d: &[(f64, usize)]) -> GoodnessOfFit {
    let k = d.len().max(1) as f64;
    let mut u: Vec<f64> = d.iter().map(|(x, r)| chi2_cdf(*x, *r)).collect();
    u.sort_by(f64::total_cmp);
    let ks = u
        .iter()
        .enumerate()
        .map(|(i, ui)| ((i + 1) as f64 / k - ui).max(ui - i as f64 / k))
        .fold(0.0, f64::max);
    let sk = k.sqrt();
    let p_value = kolmogorov_q((sk + 0.12 + 0.11 / sk) * ks);
    GoodnessOfFit {
        mean_mahalanobis: d.iter().map(|x| x.0).sum::<f64>() / k,
        beyond_99: d.iter().filter(|(x, r)| *x > Q99[(*r).min(6)]).count() as f64 / k,
        ks_statistic: ks,
        p_value,
        fits: p_value >= 0.01,
    }
}
