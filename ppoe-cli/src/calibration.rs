//! The calibration part of `ppoe fit`'s output: the before/after residual table that opens
//! the stderr summary, and the systematic tests' lines; the `calibration` JSON object
//! (below) is written by `ppoe_fit::json::calibration`.
//!
//! ```text
//! "calibration": {
//!   "estimated": ["base", "tip", "offsets", "kinematics"],
//!   "measurement": "pose" | "position",
//!   "base_in_tracker": {"pose": 4×4, "cov": 6×6 | null},   X, right perturbation
//!   "marker_in_tip":   {"pose": 4×4, "cov": 6×6 | null},   Y (position: a point)
//!   "home_correction": [6], "home_correction_se": [6],     μ: M' = M·Exp(μ)
//!   "residual_rms": {"before": {"position_mm", "rotation_mrad"}, "after": {…}},
//!   "undetermined": [names], "null_directions": [[[name, weight], …], …],
//!   "rounds": n
//! }
//! ```
//! with `joints[i].offset`, `offset_se`, `axis_correction` (κᵢ: `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ`,
//! base frame, rotation first) and `axis_correction_se` beside each joint's noise. The
//! noise (`joints[i].cov`) belongs to the chain with these folded in
//! (`ppoe::chain::fold_calibration`), which is what `--noise FILE` and `ppoe table
//! --noise` use.

use ppoe_fit::{Calibration, PoseEstimate, ResidualRms};
use std::io::Write;

/// The residual RMS before and after calibration: the first thing a calibration
/// engineer reads.
pub fn residual_table(e: &mut impl Write, c: &Calibration) {
    let rot = |r: &ResidualRms| r.rotation_mrad.map_or("-".into(), |x| format!("{x:.4}"));
    let what = if c.estimated.is_none() {
        "nothing estimated".to_string()
    } else {
        format!("estimated: {}", c.estimated.names().join(", "))
    };
    let _ = writeln!(e, "residual RMS ({what}):");
    let _ = writeln!(e, "                   position (mm)   rotation (mrad)");
    for (label, r) in [("before", &c.rms_before), ("after", &c.rms_after)] {
        let _ = writeln!(e, "  {label:<16} {:>13.4}   {:>15}", r.position_mm, rot(r));
    }
}

/// The estimated calibration, one line per group.
pub fn lines(e: &mut impl Write, c: &Calibration) {
    let est = c.estimated;
    let t = |p: &PoseEstimate| {
        let m = p.pose.to_matrix4();
        format!("[{:.5}, {:.5}, {:.5}] m", m[0][3], m[1][3], m[2][3])
    };
    if est.base {
        let _ = writeln!(e, "  base in tracker: origin {}", t(&c.base_in_tracker));
    }
    if est.tip {
        let _ = writeln!(e, "  marker in tip:   origin {}", t(&c.marker_in_tip));
    }
    if est.offsets {
        let items: Vec<String> = c
            .offsets
            .iter()
            .zip(&c.offset_se)
            .map(|(d, se)| match se {
                Some(se) => format!("{:.4}±{:.4}", 1e3 * d, 1e3 * se),
                None => format!("{:.4} (not determined)", 1e3 * d),
            })
            .collect();
        let _ = writeln!(e, "  joint offsets (mrad or mm): {}", items.join(", "));
    }
    if !c.undetermined.is_empty() {
        let _ = writeln!(
            e,
            "  not separable by these data (held by the gauge): {}",
            c.undetermined.join(", ")
        );
    }
}
