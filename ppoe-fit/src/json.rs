//! The fit as JSON (feature `json`): the content of `ppoe fit`'s output file, written by the
//! `ppoe` command and returned by the Python package's `ppoe.fit` from this one function,
//! so the two cannot drift apart.
//!
//! ```text
//! {"model", "chain": {"base", "tip", "joints"}, "joints": [{"name", "cov", "cov_se",
//!  "sigma2", "sigma2_se", "sigma", "offset", "offset_se", "axis_correction",
//!  "axis_correction_se"}], "log_likelihood", "samples", "converged", "iterations",
//!  "measurement", "measurement_cov", "residual_floor", "identifiability",
//!  "goodness_of_fit": {…, "mean_test", "calibration_test"}, "prediction_error",
//!  "calibration": {"estimated", "measurement", "base_in_tracker", "marker_in_tip",
//!  "home_correction", "home_correction_se", "residual_rms", "undetermined",
//!  "null_directions", "rounds"}, "warnings"}
//! ```
//! Poses are 4×4 row-major matrices; covariances rotation first; absent values `null`.
//! The noise (`joints[i].cov`) belongs to the chain with the calibration folded in
//! (`ppoe::chain::fold_calibration`).

use crate::{samples_for, Calibration, CampaignFit, MeasurementCov, PoseEstimate};
use crate::{ResidualRms, SystematicTest};
use serde_json::{json, Value};

/// The whole output of a campaign fit; `chain` is the `"chain"` object (the caller's names
/// of the base, the tip and the joints), `r` the measurement covariance the fit was given
/// (zeros of the measurement's size when `None`).
pub fn campaign(chain: Value, out: &CampaignFit, r: Option<&MeasurementCov>) -> Value {
    let (f, c) = (&out.fit, &out.calibration);
    let joints: Vec<Value> = f
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            json!({
                "name": j.name, "cov": j.cov, "cov_se": j.cov_se,
                "sigma2": j.sigma2, "sigma2_se": j.sigma2_se,
                "sigma": j.sigma2.map(f64::sqrt),
                "offset": c.offsets.get(i), "offset_se": c.offset_se.get(i),
                "axis_correction": c.axis_corrections.get(i),
                "axis_correction_se": c.axis_correction_se.get(i),
            })
        })
        .collect();
    let (id, g, p) = (&f.identifiability, &f.goodness_of_fit, &f.prediction_error);
    let r = match r {
        None if c.position_only => json!([[0.0f64; 3]; 3].to_vec()),
        None => json!([[0.0f64; 6]; 6].to_vec()),
        Some(MeasurementCov::Pose(m)) => json!(m),
        Some(MeasurementCov::Position(m)) => json!(m),
    };
    json!({
        "model": f.model.name(),
        "chain": chain,
        "joints": joints,
        "log_likelihood": f.log_likelihood,
        "samples": f.samples,
        "converged": f.converged,
        "iterations": f.iterations,
        "measurement": if c.position_only { "position" } else { "pose" },
        "measurement_cov": r,
        "residual_floor": f.residual_floor.map(|[a, b]| json!({"rotation": a, "translation": b})),
        "identifiability": {
            "parameters": id.parameters, "determined": id.determined,
            "determinable": id.determinable, "undetermined": id.undetermined,
            "null_directions": id.null_directions,
        },
        "goodness_of_fit": {
            "mean_mahalanobis": g.mean_mahalanobis, "beyond_99": g.beyond_99,
            "ks_statistic": g.ks_statistic, "p_value": g.p_value, "fits": g.fits,
            "mean_test": systematic_test(&out.mean_test),
            "calibration_test": out.calibration_test.as_ref().map(systematic_test),
        },
        "prediction_error": {
            "median": p.median, "worst": p.worst, "configurations": p.configurations,
            "samples_for_5_percent": samples_for(f.samples, p.median, 0.05),
        },
        "calibration": calibration(c),
        "warnings": f.warnings,
    })
}

/// A systematic test: `{"tested", "statistic", "dof", "p_value", "passes"}`.
pub fn systematic_test(t: &SystematicTest) -> Value {
    json!({
        "tested": t.tested, "statistic": t.statistic, "dof": t.dof,
        "p_value": t.p_value, "passes": t.passes(),
    })
}

/// The `"calibration"` object (see the module doc).
pub fn calibration(c: &Calibration) -> Value {
    let pose = |p: &PoseEstimate| json!({"pose": p.pose.to_matrix4(), "cov": p.cov});
    let rms =
        |r: &ResidualRms| json!({"position_mm": r.position_mm, "rotation_mrad": r.rotation_mrad});
    json!({
        "estimated": c.estimated.names(),
        "measurement": if c.position_only { "position" } else { "pose" },
        "base_in_tracker": pose(&c.base_in_tracker),
        "marker_in_tip": pose(&c.marker_in_tip),
        "home_correction": c.home_correction,
        "home_correction_se": c.home_correction_se,
        "residual_rms": {"before": rms(&c.rms_before), "after": rms(&c.rms_after)},
        "undetermined": c.undetermined,
        "null_directions": c.null_directions,
        "rounds": c.rounds,
    })
}
