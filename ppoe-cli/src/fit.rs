//! `ppoe fit`: per-joint noise covariances fitted by maximum likelihood (`ppoe-fit`) from
//! joint values recorded with tool poses measured by a tracker; and `--noise FILE`, the
//! fit's output read back by `eval`, `render`, `mesh` and `demo`.

use anyhow::{bail, Context};
use ppoe_build::noise::NoiseModel;
use ppoe_build::RobotChain;
use ppoe_fit::{Fit, Model, Sample};
use serde_json::{json, Value};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// The parsed input: the samples and the tracker's noise.
type FitInput = (Vec<Sample>, Option<[[f64; 6]; 6]>);

/// Parses the input `{"samples":[{"thetas":[N],"pose":[[4×4]]}],"measurement_cov":6×6}`;
/// errors name the sample.
pub fn parse_input(text: &str) -> anyhow::Result<FitInput> {
    let v: Value = serde_json::from_str(text).context(concat!(
        "malformed input JSON (expected {\"samples\":[{\"thetas\":[N numbers],",
        "\"pose\":[[4×4]]}], \"measurement_cov\": optional 6×6})"
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
        let pose = matrix::<4>(s.get("pose"))
            .with_context(|| format!("sample {i}: \"pose\" must be 4 rows of 4 numbers"))?;
        samples.push(Sample { thetas, pose });
    }
    let r = match v.get("measurement_cov") {
        None | Some(Value::Null) => None,
        Some(m) => {
            Some(matrix::<6>(Some(m)).context("\"measurement_cov\" must be 6 rows of 6 numbers")?)
        }
    };
    Ok((samples, r))
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

/// Runs the fit for `robot` and returns the output JSON; progress and the summary go to
/// stderr.
pub fn run(robot: &RobotChain, text: &str, model: Model) -> anyhow::Result<Value> {
    let (samples, r) = parse_input(text)?;
    let (joints, home) = crate::eval::core_joints::<f64>(robot);
    let start = Instant::now();
    let mut last = Instant::now();
    let mut progress = |it: usize, l: f64| {
        if last.elapsed().as_secs_f64() > 0.5 {
            eprintln!("fit: step {it}, log-likelihood {l:.6e}");
            last = Instant::now();
        }
    };
    let fit = ppoe_fit::fit(&joints, &home, &samples, r.as_ref(), model, &mut progress)?;
    summary(&fit, start.elapsed().as_secs_f64());
    Ok(to_json(robot, &fit, r))
}

/// The output JSON (see `ppoe fit --help`).
pub fn to_json(robot: &RobotChain, f: &Fit, r: Option<[[f64; 6]; 6]>) -> Value {
    let joints: Vec<Value> = f
        .joints
        .iter()
        .map(|j| {
            json!({
                "name": j.name, "cov": j.cov, "cov_se": j.cov_se,
                "sigma2": j.sigma2, "sigma2_se": j.sigma2_se,
                "sigma": j.sigma2.map(f64::sqrt),
            })
        })
        .collect();
    let id = &f.identifiability;
    let g = &f.goodness_of_fit;
    let p = &f.prediction_error;
    json!({
        "model": f.model.name(),
        "chain": {"base": robot.base, "tip": robot.tip, "joints": robot.joint_names()},
        "joints": joints,
        "log_likelihood": f.log_likelihood,
        "samples": f.samples,
        "converged": f.converged,
        "iterations": f.iterations,
        "measurement_cov": r.unwrap_or([[0.0; 6]; 6]),
        "residual_floor": f.residual_floor.map(|[a, b]| json!({"rotation": a, "translation": b})),
        "identifiability": {
            "parameters": id.parameters, "determined": id.determined,
            "determinable": id.determinable, "undetermined": id.undetermined,
            "null_directions": id.null_directions,
        },
        "goodness_of_fit": {
            "mean_mahalanobis": g.mean_mahalanobis, "beyond_99": g.beyond_99,
            "ks_statistic": g.ks_statistic, "p_value": g.p_value, "fits": g.fits,
        },
        "prediction_error": {
            "median": p.median, "worst": p.worst, "configurations": p.configurations,
            "samples_for_5_percent": ppoe_fit::samples_for(f.samples, p.median, 0.05),
        },
        "warnings": f.warnings,
    })
}

/// The human-readable summary on stderr: per joint, estimate ± standard error.
fn summary(f: &Fit, seconds: f64) {
    let mut e = std::io::stderr().lock();
    let _ = writeln!(
        e,
        "fit: model {}, {} samples, log-likelihood {:.6e}, {} ({} steps, {seconds:.2} s)",
        f.model.name(),
        f.samples,
        f.log_likelihood,
        if f.converged {
            "converged"
        } else {
            "NOT converged"
        },
        f.iterations
    );
    joint_lines(&mut e, f);
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
        "  goodness of fit: mean Mahalanobis² {:.2} (6 expected), {:.1} % beyond the 99 % \
         quantile, KS p = {:.3} -> {}",
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

/// The noise model of `--noise FILE`, checked against the chain.
pub fn read_noise(path: &Path, robot: &RobotChain) -> anyhow::Result<Vec<[[f64; 6]; 6]>> {
    let model = NoiseModel::read(path)?;
    model
        .check_against(robot)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok(model.joints.iter().map(|j| j.cov).collect())
}

/// The cases of `eval`/`render`/`mesh`, read once from `path` (`None` or `-`: standard
/// input); with a noise model (`--noise`), every case gets its covariances, and a case
/// that gives its own is an error (one source of covariances).
///
/// # Errors
/// Unreadable or malformed input or noise model, naming it; a case with its own covs.
pub fn cases(
    path: Option<&Path>,
    noise: Option<&Path>,
    robot: &RobotChain,
) -> anyhow::Result<crate::eval::Input> {
    let Some(noise) = noise else {
        return crate::load::cases(path);
    };
    let covs = read_noise(noise, robot)?;
    let input = crate::load::read(path.unwrap_or(Path::new("-")), "input file")?;
    let bytes = input
        .bytes
        .strip_prefix("\u{feff}".as_bytes())
        .unwrap_or(&input.bytes);
    let mut v: Value = serde_json::from_slice(bytes)
        .with_context(|| format!("{}: malformed input JSON", input.name))?;
    if let Some(cases) = v.get_mut("cases").and_then(Value::as_array_mut) {
        for (i, c) in cases.iter_mut().enumerate() {
            let Some(obj) = c.as_object_mut() else {
                continue; // the typed parse reports it
            };
            if obj.contains_key("covs") {
                bail!("case {i} gives \"covs\" and --noise is set: give the covariances one way");
            }
            obj.insert("covs".into(), json!(covs));
        }
    }
    crate::eval::parse_input_bytes(v.to_string().as_bytes())
        .map_err(|e| anyhow::anyhow!("{}: malformed input JSON: {e:#}", input.name))
}

/// The seed robot's covariances from a noise model (`demo --noise`), checked against the
/// seed table's joint names.
pub fn seed_noise(path: &Path) -> anyhow::Result<[ppoe::Mat6<f64>; 6]> {
    let model = NoiseModel::read(path)?;
    let names: Vec<&str> = crate::seed::SEED.joints.iter().map(|j| j.name).collect();
    let mine: Vec<&str> = model.joints.iter().map(|j| j.name.as_str()).collect();
    if names != mine {
        bail!(
            "{}: the noise model's joints [{}] are not the seed robot's [{}]",
            path.display(),
            mine.join(", "),
            names.join(", ")
        );
    }
    let covs = model.covs();
    Ok(std::array::from_fn(|i| covs[i]))
}
