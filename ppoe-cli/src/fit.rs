//! `ppoe fit`: per-joint noise covariances fitted by maximum likelihood (`ppoe-fit`) from
//! joint values recorded with tool poses measured by a tracker (its output is read back
//! by `--noise FILE`, [`crate::noise`]).

use anyhow::{bail, Context};
use ppoe_build::RobotChain;
use ppoe_fit::{CampaignFit, CampaignSample, Estimate, Fit, Measurement, MeasurementCov, Model};
use serde_json::{json, Value};
use std::io::Write;
use std::time::Instant;

/// The parsed input: the samples and the tracker's noise.
type FitInput = (Vec<CampaignSample>, Option<MeasurementCov>);

/// One sample's measurement: `"pose"` (4×4) or `"position"` ([x, y, z]), never both.
fn measurement(i: usize, s: &Value) -> anyhow::Result<Measurement> {
    match (s.get("pose"), s.get("position")) {
        (Some(_), Some(_)) => bail!("sample {i}: both \"pose\" and \"position\" (give one)"),
        (Some(p), None) => Ok(Measurement::Pose(matrix::<4>(Some(p)).with_context(
            || format!("sample {i}: \"pose\" must be 4 rows of 4 numbers"),
        )?)),
        (None, Some(p)) => {
            let v = p.as_array().filter(|v| v.len() == 3).and_then(|v| {
                let x: Option<Vec<f64>> = v.iter().map(Value::as_f64).collect();
                x
            });
            let v = v.with_context(|| format!("sample {i}: \"position\" must be 3 numbers"))?;
            Ok(Measurement::Position([v[0], v[1], v[2]]))
        }
        (None, None) => bail!("sample {i}: no \"pose\" (4×4) or \"position\" ([x, y, z])"),
    }
}

/// Parses the input `{"samples":[{"thetas":[N],"pose":[[4×4]]} or
/// {"thetas":[N],"position":[x,y,z]}], "measurement_cov": 6×6 (poses) or 3×3
/// (positions)}`; errors name the sample, and a file mixing poses and positions is one.
pub fn parse_input(text: &str) -> anyhow::Result<FitInput> {
    let v: Value = crate::input::parse_json(text).context(concat!(
        "malformed input JSON (expected {\"samples\":[{\"thetas\":[N numbers],",
        "\"pose\":[[4×4]] or \"position\":[x, y, z]}], \"measurement_cov\": optional 6×6 ",
        "or 3×3})"
    ))?;
    let Some(list) = v.get("samples").and_then(Value::as_array) else {
        bail!("the input has no \"samples\" array");
    };
    let mut samples = Vec::with_capacity(list.len());
    for (i, s) in list.iter().enumerate() {
        let thetas = s
            .get("thetas")
            .and_then(Value::as_array)
            .with_context(|| format!("sample {i}: no \"thetas\" array"))?
            .iter()
            .enumerate()
            .map(|(j, x)| {
                x.as_f64()
                    .with_context(|| format!("sample {i}: thetas[{j}] is not a number"))
            })
            .collect::<anyhow::Result<Vec<f64>>>()?;
        let measurement = measurement(i, s)?;
        if let Some(first) = samples.first().map(|f: &CampaignSample| &f.measurement) {
            if std::mem::discriminant(first) != std::mem::discriminant(&measurement) {
                bail!(
                    "sample {i}: a {} where sample 0 has a {} (a campaign's samples are all \
                     poses or all positions)",
                    kind(&measurement),
                    kind(first)
                );
            }
        }
        samples.push(CampaignSample {
            thetas,
            measurement,
        });
    }
    let position = matches!(
        samples.first().map(|s| &s.measurement),
        Some(Measurement::Position(_))
    );
    let r = match v.get("measurement_cov") {
        None | Some(Value::Null) => None,
        Some(m) if position => Some(MeasurementCov::Position(
            matrix::<3>(Some(m))
                .context("\"measurement_cov\" must be 3 rows of 3 numbers for position samples")?,
        )),
        Some(m) => Some(MeasurementCov::Pose(matrix::<6>(Some(m)).context(
            "\"measurement_cov\" must be 6 rows of 6 numbers for pose samples",
        )?)),
    };
    Ok((samples, r))
}

/// For a chain with mimic joints, the samples give the independent joint values
/// ([`RobotChain::input_names`]); the fit needs every chain joint's, mimic ones included.
fn expand_mimic(robot: &RobotChain, samples: &mut [CampaignSample]) -> anyhow::Result<()> {
    if robot.coupling.is_none() {
        return Ok(());
    }
    for (i, s) in samples.iter_mut().enumerate() {
        s.thetas = robot
            .expand_thetas(&s.thetas)
            .with_context(|| format!("sample {i}"))?;
    }
    Ok(())
}

fn kind(m: &Measurement) -> &'static str {
    match m {
        Measurement::Pose(_) => "pose",
        Measurement::Position(_) => "position",
    }
}

fn matrix<const N: usize>(v: Option<&Value>) -> anyhow::Result<[[f64; N]; N]> {
    let rows = v.and_then(Value::as_array).filter(|r| r.len() == N);
    let Some(rows) = rows else {
        bail!("expected {N} rows");
    };
    let mut m = [[0.0; N]; N];
    for (r, (out, row)) in m.iter_mut().zip(rows).enumerate() {
        let row = row.as_array().filter(|x| x.len() == N);
        let Some(row) = row else {
            bail!("row {r} does not hold {N} numbers");
        };
        for (c, (o, x)) in out.iter_mut().zip(row).enumerate() {
            *o = x
                .as_f64()
                .with_context(|| format!("[{r}][{c}] is not a number"))?;
        }
    }
    Ok(m)
}

/// Runs the fit for `robot` with the calibration groups `estimate` and returns the output
/// JSON; progress and the summary go to stderr.
pub fn run(
    robot: &RobotChain,
    text: &str,
    model: Model,
    estimate: Estimate,
) -> anyhow::Result<Value> {
    let (mut samples, r) = parse_input(text)?;
    expand_mimic(robot, &mut samples)?;
    let (joints, home) = crate::eval::core_joints::<f64>(robot);
    let start = Instant::now();
    let mut last = Instant::now();
    let mut progress = |it: usize, l: f64| {
        if last.elapsed().as_secs_f64() > 0.5 {
            eprintln!("fit: step {it}, log-likelihood {l:.6e}");
            last = Instant::now();
        }
    };
    let out = ppoe_fit::fit_campaign(
        &joints,
        &home,
        &samples,
        r.as_ref(),
        model,
        estimate,
        &mut progress,
    )?;
    summary(&out, start.elapsed().as_secs_f64());
    Ok(to_json(robot, &out, r))
}

/// The output JSON (see `ppoe fit --help`): [`ppoe_fit::json::campaign`] with the chain's
/// names.
pub fn to_json(robot: &RobotChain, out: &CampaignFit, r: Option<MeasurementCov>) -> Value {
    let chain = json!({"base": robot.base, "tip": robot.tip, "joints": robot.joint_names()});
    ppoe_fit::json::campaign(chain, out, r.as_ref())
}

/// The human-readable summary on stderr: the residuals before and after calibration,
/// then per joint estimate ± standard error, the quality figures and the warnings.
fn summary(out: &CampaignFit, seconds: f64) {
    let f = &out.fit;
    let mut e = std::io::stderr().lock();
    crate::calibration::residual_table(&mut e, &out.calibration);
    let _ = writeln!(
        e,
        "fit: model {}, {} samples, log-likelihood {:.6e}, {} ({} steps, {} rounds, {seconds:.2} s)",
        f.model.name(),
        f.samples,
        f.log_likelihood,
        if f.converged {
            "converged"
        } else {
            "NOT converged"
        },
        f.iterations,
        out.calibration.rounds
    );
    joint_lines(&mut e, f);
    crate::calibration::lines(&mut e, &out.calibration);
    quality_lines(&mut e, f);
    for w in &f.warnings {
        let _ = writeln!(e, "warning: {w}");
    }
}

/// Per joint: σ² ± standard error (joint model) or the diagonal ± standard errors.
fn joint_lines(e: &mut impl Write, f: &Fit) {
    for j in &f.joints {
        match (j.sigma2, j.sigma2_se) {
            (Some(s), se) => {
                let se = se.map_or("undetermined".into(), |x| format!("{x:.2e}"));
                let _ = writeln!(
                    e,
                    "  {:<16} sigma² = {s:.3e} ± {se}  (sigma = {:.3e})",
                    j.name,
                    s.sqrt()
                );
            }
            _ => {
                let d: Vec<String> = (0..6)
                    .map(|k| match j.cov_se[k][k] {
                        Some(se) => format!("{:.2e}±{se:.1e}", j.cov[k][k]),
                        None => format!("{:.2e}±?", j.cov[k][k]),
                    })
                    .collect();
                let _ = writeln!(e, "  {:<16} diag = [{}]", j.name, d.join(", "));
            }
        }
    }
}

/// The residual floor, identifiability, goodness of fit and prediction error.
fn quality_lines(e: &mut impl Write, f: &Fit) {
    if let Some([r, t]) = f.residual_floor {
        let _ = writeln!(
            e,
            "  residual floor: {r:.2e} rad², {t:.2e} m² (not part of the joints' noise)"
        );
    }
    let id = &f.identifiability;
    let _ = writeln!(
        e,
        "  determined: {} of {} parameters ({} determinable at best)",
        id.determined, id.parameters, id.determinable
    );
    let g = &f.goodness_of_fit;
    let _ = writeln!(
        e,
        "  goodness of fit: mean Mahalanobis² {:.2}, {:.1} % beyond the 99 % quantile, KS p = \
         {:.3} -> {}",
        g.mean_mahalanobis,
        100.0 * g.beyond_99,
        g.p_value,
        if g.fits {
            "consistent with the model"
        } else {
            "the model does NOT fit"
        }
    );
    let p = &f.prediction_error;
    let _ = writeln!(
        e,
        "  predicted tool covariance: ±{:.1} % (median standard error over {} configurations, \
         worst {:.1} %); about {} samples for ±5 %",
        100.0 * p.median,
        p.configurations,
        100.0 * p.worst,
        ppoe_fit::samples_for(f.samples, p.median, 0.05)
    );
}
