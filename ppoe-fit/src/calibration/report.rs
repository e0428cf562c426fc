//! The calibration's report: estimates with standard errors (none for undetermined
//! combinations), and the warnings of the systematic tests.

use super::layout::{Layout, Point};
use super::{Calibration, CampaignFit, PoseEstimate, ResidualRms};
use crate::report::Information;
use ppoe::chain::Joint;
use ppoe::Transform;

/// The standard error of parameter `i`, `None` if undetermined.
fn se(info: &Information, i: usize) -> Option<f64> {
    (!info.undetermined[i]).then(|| info.cov[(i, i)].max(0.0).sqrt())
}

/// The 6×6 covariance of a pose block starting at `s` of length `l` (6, or 3: the
/// translation block), entries of undetermined parameters `None`.
fn pose_cov(info: &Information, (s, l): (usize, usize)) -> Option<[[Option<f64>; 6]; 6]> {
    if l == 0 {
        return None;
    }
    let off = 6 - l;
    Some(std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            if a < off || b < off {
                return Some(0.0);
            }
            let (i, j) = (s + a - off, s + b - off);
            let det = !info.undetermined[i] && !info.undetermined[j];
            det.then(|| info.cov[(i, j)])
        })
    }))
}

/// Names and weighted combinations, for the report.
type Combinations = Vec<Vec<(String, f64)>>;

/// The names of the undetermined parameters and the null directions, with the offsets of
/// parallel consecutive axes (determined only by the gauge).
fn undetermined(
    info: &Information,
    names: &[String],
    layout: &Layout,
    joints: &[Joint<f64>],
) -> (Vec<String>, Combinations) {
    let (mut undetermined, mut null_directions) = null_space(info, names);
    for &(a, b) in &layout.parallel_pairs {
        let name = |i: usize| format!("offset of joint '{}'", joints[i].name);
        for i in [a, b] {
            if layout.offset_index(i).is_some() && !undetermined.contains(&name(i)) {
                undetermined.push(name(i));
            }
        }
        null_directions.push(vec![
            (name(a), std::f64::consts::FRAC_1_SQRT_2),
            (name(b), -std::f64::consts::FRAC_1_SQRT_2),
            (
                format!(
                    "link length along the arm between joints '{}' and '{}'",
                    joints[a].name, joints[b].name
                ),
                1.0,
            ),
        ]);
    }
    (undetermined, null_directions)
}

/// The undetermined parameters' names and the null directions of `info`.
fn null_space(info: &Information, names: &[String]) -> (Vec<String>, Combinations) {
    let u = (0..names.len())
        .filter(|&i| info.undetermined[i])
        .map(|i| names[i].clone())
        .collect();
    let d = info
        .null_directions
        .iter()
        .map(|d| d.iter().map(|(i, w)| (names[*i].clone(), *w)).collect())
        .collect();
    (u, d)
}

/// The calibration at `at` with the parameters' information `info`.
pub(super) fn calibration(
    layout: &Layout,
    at: &Point,
    info: &Information,
    rms: (ResidualRms, ResidualRms),
    rounds: usize,
    (joints, home): (&[Joint<f64>], &Transform<f64>),
) -> Option<Calibration> {
    let n = joints.len();
    let names = layout.names(joints);
    let paired = |i: usize| layout.parallel_pairs.iter().any(|p| p.0 == i || p.1 == i);
    let offset_se = (0..n)
        .map(|i| {
            let k = layout.offset_index(i).filter(|_| !paired(i))?;
            se(info, k)
        })
        .collect();
    let (undetermined, null_directions) = undetermined(info, &names, layout, joints);
    let axis_correction_se = (0..n)
        .map(|i| {
            if !layout.has_kinematics() {
                return [None; 6];
            }
            let (start, len) = layout.joint_block(i);
            let det = (start..start + len).all(|k| !info.undetermined[k]);
            let c = layout.kappa_cov(&info.cov, i);
            std::array::from_fn(|k| det.then(|| c[(k, k)].max(0.0).sqrt()))
        })
        .collect();
    let (hs, hl) = layout.block("home");
    let home_correction_se = std::array::from_fn(|k| (hl > 0).then(|| se(info, hs + k)).flatten());
    let (cal_joints, cal_home) = at.chain(joints, home)?;
    Some(Calibration {
        estimated: layout.estimate,
        position_only: layout.position,
        base_in_tracker: PoseEstimate {
            pose: at.x,
            cov: pose_cov(info, layout.block("base")),
        },
        marker_in_tip: PoseEstimate {
            pose: at.y,
            cov: pose_cov(info, layout.block("tip")),
        },
        offsets: at.offsets.clone(),
        offset_se,
        axis_corrections: at.kappa.iter().map(|k| k.0).collect(),
        axis_correction_se,
        home_correction: at.mu.0,
        home_correction_se,
        rms_before: rms.0,
        rms_after: rms.1,
        undetermined,
        null_directions,
        rounds,
        joints: cal_joints,
        home: cal_home,
    })
}

/// The systematic tests' verdicts: a failed calibration test rejects the fit, and either
/// test's failure gives a warning naming calibration.
pub(super) fn warn(out: &mut CampaignFit) {
    let m = &out.mean_test;
    if !m.passes() {
        out.fit.warnings.push(format!(
            "the residuals' mean is not zero (χ² = {:.1} on {} degrees of freedom, p = {:.1e}): \
             a systematic error (a marker off the tool frame, a tracker registration, joint \
             zero offsets) inflates the fitted noise; calibrate with --estimate {}",
            m.statistic,
            m.dof,
            m.p_value,
            suggestion(&out.calibration.estimated)
        ));
    }
    if let Some(t) = &out.calibration_test {
        if !t.passes() {
            out.fit.goodness_of_fit.fits = false;
            out.fit.warnings.push(format!(
                "the residuals show systematic errors of the {} (score test χ² = {:.1} on {} \
                 degrees of freedom, p = {:.1e}): they inflate the fitted noise; calibrate \
                 with --estimate {}",
                t.tested.join(", "),
                t.statistic,
                t.dof,
                t.p_value,
                suggestion(&out.calibration.estimated)
            ));
        }
    }
}

/// The `--estimate` list that adds the groups not yet estimated among base, tip, offsets.
fn suggestion(e: &super::Estimate) -> String {
    let mut all = super::Estimate {
        base: true,
        tip: true,
        offsets: true,
        ..*e
    };
    all.kinematics = e.kinematics;
    all.names().join(",")
}
