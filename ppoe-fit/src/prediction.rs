//! How well the fitted model predicts the tool covariance: the standard error of Σ(θ)
//! that follows from the standard errors of the fitted covariances.

use crate::design::Design;
use nalgebra::{DMatrix, Matrix6};

/// The most configurations the prediction error is evaluated at (a spread-out subset of
/// the samples'): its cost is that of a few Fisher-scoring steps, and its median and
/// maximum change little beyond this many.
const CONFIGURATIONS: usize = 200;

/// The relative standard error of the fitted model's predicted tool covariance.
///
/// At a configuration θ of the samples, Σ(θ) = Σᵢ Ad(Gᵢ⁻¹)·Cᵢ·Ad(Gᵢ⁻¹)ᵀ (tip frame, right
/// perturbation: what `ChainView::ppoe` with `Convention::Right` returns for the fitted
/// covariances, without the tracker's noise or the joint model's residual floor). Its
/// error ΔΣ is linear in the errors of the fitted Cᵢ, whose covariance is the inverse
/// Fisher information (on the combinations the data determine; the others do not change
/// any prediction). The figure is `√E‖ΔΣ‖²_F / ‖Σ‖_F`.
///
/// # Accuracy
/// First order in the estimation error, and sampling error only: it does not include the
/// second-order model's bias, which grows with the noise (see the crate's Accuracy
/// section). The `fit_validation` tests compare it with the spread of fits over
/// independent datasets (within 25 %). Sampling error shrinks as 1/√samples: about
/// `samples·(median/target)²` samples bring the median to `target` ([`crate::samples_for`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PredictionError {
    /// The median over the configurations.
    pub median: f64,
    /// The largest.
    pub worst: f64,
    /// How many of the samples' configurations were evaluated (at most 200, spread
    /// evenly over the samples).
    pub configurations: usize,
}

/// The prediction error of the coefficients `x` (one per term of the design, a residual
/// floor's set to zero; the first `joint_terms` are the joints') with `unit_cov`, the
/// covariance of the unit coefficients (`Design::units` order).
pub(crate) fn prediction_error(
    design: &Design,
    x: &[Matrix6<f64>],
    joint_terms: usize,
    unit_cov: &DMatrix<f64>,
) -> PredictionError {
    let samples = design.eta.len();
    let stride = samples.div_ceil(CONFIGURATIONS).max(1);
    let mut errors: Vec<f64> = (0..samples)
        .step_by(stride)
        .map(|k| relative_error(design, k, x, joint_terms, unit_cov))
        .collect();
    errors.sort_by(f64::total_cmp);
    PredictionError {
        median: errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN),
        worst: errors.last().copied().unwrap_or(f64::NAN),
        configurations: errors.len(),
    }
}

/// `√E‖ΔΣ‖²_F / ‖Σ‖_F` at sample `k`: with g_a = vec(∂Σ/∂x_a), E‖ΔΣ‖²_F = Σ_ab g_a·g_b·cov_ab.
fn relative_error(
    design: &Design,
    k: usize,
    x: &[Matrix6<f64>],
    joint_terms: usize,
    unit_cov: &DMatrix<f64>,
) -> f64 {
    let units = &design.units;
    // ∂Σ/∂x_a = Aₜ·Sₚq·Aₜᵀ = aₚa_qᵀ + a_qaₚᵀ (p < q) or aₚaₚᵀ, aₚ the p-th column of Aₜ.
    let g = DMatrix::from_fn(36, units.len(), |e, ia| {
        let u = units[ia];
        if u.term >= joint_terms {
            return 0.0;
        }
        let a = &design.a[k][u.term];
        let (r, c) = (e / 6, e % 6);
        let d = a[(r, u.p)] * a[(c, u.q)];
        if u.p == u.q {
            d
        } else {
            d + a[(r, u.q)] * a[(c, u.p)]
        }
    });
    let expected = (&g * unit_cov).component_mul(&g).sum().max(0.0);
    // A fit whose joints' Σ vanished (a floor took every residual) predicts nothing: a
    // huge finite figure says so, where a division by zero would make the report ∞.
    expected.sqrt() / (design.sigma(k, x) - design.r).norm().max(1e-300)
}
