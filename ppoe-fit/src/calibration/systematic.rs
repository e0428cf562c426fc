//! Tests for systematic errors in the residuals, which the covariance test (Kolmogorov–
//! Smirnov of the Mahalanobis distances) notices only once they rival the noise:
//!
//! * the **mean test**: with zₖ the whitened residuals (zₖ ~ N(0, I_d) under the fitted
//!   model), `K·‖z̄‖²` ~ χ²_d. A constant systematic twist in the marker frame (a marker
//!   off the tool frame) shows up here;
//! * the **calibration score test** (Rao's score / Lagrange-multiplier test) of the
//!   calibration groups not estimated: with the whitened Jacobian J of all estimated and
//!   tested parameters at the fit, g = Jᵀz and N = JᵀJ, `gᵀN⁺g` ~ χ² with
//!   rank(N) − rank(N of the estimated ones) degrees of freedom (the estimated parameters'
//!   part of g is zero at their optimum). Tracker registration, marker and joint-zero
//!   errors all show up here, far below the level where they inflate the fitted
//!   covariances visibly.
//!
//! Both are asymptotic (the noise model is itself estimated from the same residuals).

use libm::lgamma;

/// The result of one test.
#[derive(Clone, Debug, PartialEq)]
pub struct SystematicTest {
    /// What is tested: `"mean"` or the calibration groups (`"base"`, `"tip"`, `"offsets"`).
    pub tested: Vec<String>,
    /// The χ² statistic.
    pub statistic: f64,
    /// Its degrees of freedom.
    pub dof: usize,
    /// The p-value (χ² upper tail).
    pub p_value: f64,
}

impl SystematicTest {
    /// The test at `statistic` with `dof` degrees of freedom.
    pub(crate) fn new(tested: Vec<String>, statistic: f64, dof: usize) -> Self {
        Self {
            tested,
            statistic,
            dof,
            p_value: chi2_sf(statistic, dof),
        }
    }

    /// p ≥ 0.01: no evidence of a systematic error.
    pub fn passes(&self) -> bool {
        self.p_value >= 0.01
    }
}

/// The upper tail `Q(dof/2, x/2)` of χ² with `dof` degrees of freedom (regularised
/// incomplete gamma function: its series below a + 1, Lentz's continued fraction above,
/// as in Numerical Recipes §6.2; relative accuracy ~1e-14).
pub fn chi2_sf(x: f64, dof: usize) -> f64 {
    if dof == 0 || x <= 0.0 || x.is_nan() {
        return 1.0;
    }
    if x.is_infinite() {
        return 0.0;
    }
    let (a, x) = (0.5 * dof as f64, 0.5 * x);
    let prefix = (-x + a * x.ln() - lgamma(a)).exp();
    if x < a + 1.0 {
        let (mut term, mut sum) = (1.0 / a, 1.0 / a);
        for n in 1..1000 {
            term *= x / (a + n as f64);
            sum += term;
            if term < sum * 1e-16 {
                break;
            }
        }
        (1.0 - sum * prefix).clamp(0.0, 1.0)
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            d = if d.abs() < tiny { tiny } else { d };
            c = b + an / c;
            c = if c.abs() < tiny { tiny } else { c };
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (prefix * h).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::chi2_sf;

    /// Against the closed forms of `crate::chi2_cdf` (dof 1…6) and tabulated quantiles.
    #[test]
    fn chi2_tail_matches_closed_forms_and_tables() {
        for dof in 1..=6 {
            for x in [0.01, 0.5, 1.0, 3.0, 6.0, 12.0, 30.0, 80.0] {
                let want = 1.0 - crate::chi2_cdf(x, dof);
                let got = chi2_sf(x, dof);
                assert!(
                    (got - want).abs() < 1e-12 * want.max(1e-3),
                    "{dof} {x}: {got} {want}"
                );
            }
        }
        // 99 % quantiles of χ²₁₀, χ²₃₀, χ²₁₀₀ (standard tables).
        for (dof, q) in [(10, 23.209_25), (30, 50.892_18), (100, 135.806_7)] {
            assert!((chi2_sf(q, dof) - 0.01).abs() < 2e-6, "{dof}");
        }
    }
}
