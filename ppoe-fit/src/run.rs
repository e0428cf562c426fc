//! The fit from samples to report: checks, method-of-moments start, identifiability,
//! maximum likelihood, standard errors and goodness of fit.

use crate::design::Design;
use crate::error::FitError;
use crate::optimize::{maximize, Crawl};
use crate::param::{unit_matrix, Model, Param};
use crate::prediction::{prediction_error, PredictionError};
use crate::report::{goodness_of_fit, information, GoodnessOfFit, Information};
use crate::samples::{prepare, to_na, transports, Prepared, Sample};
use nalgebra::{DVector, Matrix6, Vector6};
use ppoe::chain::{Joint, JointKind};
use ppoe::{Mat6, Transform};

/// EM cycles before each round of Fisher scoring (full model), the most rounds, and the
/// log-likelihood gain of a round below which the full model counts as converged: at
/// covariances of lower rank the optimum is on the boundary of the PSD cone, where the
/// gradient does not vanish, and 0.5 is a likelihood-ratio χ² of 1 over all the
/// parameters, statistically nothing.
const EM_CYCLES: usize = 15;
const ROUNDS: usize = 12;
const ROUND_TOL: f64 = 0.5;
/// A round's scoring stops once 10 steps gained less than a tenth of `ROUND_TOL`: at that
/// pace it would need over a hundred steps to gain what counts as nothing.
const CRAWL: Crawl = Crawl {
    window: 10,
    gain: 0.1 * ROUND_TOL,
};

/// The full model: rounds of a few EM cycles (monotone and PSD: they bring a start whose
/// Σ is nearly singular, or a scoring run stalled at covariances of lower rank, to where
/// scoring makes progress) and Fisher scoring, until scoring converges.
fn full_rounds(
    design: &Design,
    param: &Param,
    mut theta: DVector<f64>,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<crate::optimize::Outcome, FitError> {
    let mut iterations = 0;
    let mut last = f64::NEG_INFINITY;
    for round in 0..ROUNDS {
        let (x, _, cycles, _) =
            crate::optimize::em(design, param.coeffs(&theta), EM_CYCLES, progress)?;
        let mut out = maximize(design, param, param.theta_of(&x), Some(CRAWL), progress)?;
        iterations += cycles + out.iterations;
        out.converged |= out.loglik - last < ROUND_TOL;
        if out.converged || round + 1 == ROUNDS {
            out.iterations = iterations;
            return Ok(out);
        }
        last = out.loglik;
        theta = out.theta;
    }
    unreachable!("the last round returns")
}

/// One joint's fitted noise.
#[derive(Clone, Debug, PartialEq)]
pub struct JointFit {
    /// The joint's name.
    pub name: String,
    /// Cᵢ: 6×6 row-major, base-frame screw coordinates, rotation first (exactly what
    /// `ppoe eval` takes as `covs[i]`); symmetric PSD by construction.
    pub cov: [[f64; 6]; 6],
    /// Standard error of each entry of `cov`; `None` where the data do not determine it.
    pub cov_se: [[Option<f64>; 6]; 6],
    /// Joint model: σᵢ², the variance of the joint value (rad² or m²).
    pub sigma2: Option<f64>,
    /// Joint model: the standard error of σᵢ².
    pub sigma2_se: Option<f64>,
}

/// Which combinations of the parameters the data determine.
#[derive(Clone, Debug, PartialEq)]
pub struct Identifiability {
    /// Number of natural parameters (σᵢ² and the two floor variances, or the 21 entries
    /// of each Cᵢ).
    pub parameters: usize,
    /// Rank of the Fisher information: how many combinations the data determine.
    pub determined: usize,
    /// The same rank for configurations spread over the joint limits: what the model
    /// can determine at best (the rest is structural, e.g. a variance along joint i+1's
    /// axis placed on joint i or i+1).
    pub determinable: usize,
    /// Parameters not determined by the data (names).
    pub undetermined: Vec<String>,
    /// Up to 12 undetermined combinations, each as its largest (name, weight) terms.
    pub null_directions: Vec<Vec<(String, f64)>>,
}

/// The result of [`fit`].
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// The model fitted.
    pub model: Model,
    /// Per joint, base to tip.
    pub joints: Vec<JointFit>,
    /// The maximised log-likelihood of the residuals.
    pub log_likelihood: f64,
    /// Number of samples.
    pub samples: usize,
    /// Whether Fisher scoring converged (predicted gain below 1e-6).
    pub converged: bool,
    /// Fisher-scoring iterations.
    pub iterations: usize,
    /// Joint model: the residual floor (τ_rot in rad², τ_trans in m², tip frame), not
    /// part of the joints' noise.
    pub residual_floor: Option<[f64; 2]>,
    /// Which combinations are determined.
    pub identifiability: Identifiability,
    /// Residuals against the fitted model.
    pub goodness_of_fit: GoodnessOfFit,
    /// How precisely the fitted model predicts the tool covariance (standard error from
    /// the Fisher information).
    pub prediction_error: PredictionError,
    /// Things the user should know (not converged, few samples, clipped joint values,
    /// a poor fit, a large residual floor).
    pub warnings: Vec<String>,
}

/// Fits the per-joint noise of the chain (`joints`, `home`: screw axes in the base frame,
/// home pose of the tip) to `samples`, with the tracker's noise `measurement_cov` (tip
/// frame, rotation first; `None` = zero). `progress(iteration, log_likelihood)` is
/// called after each Fisher-scoring step.
///
/// # Errors
/// A [`FitError`] naming the sample for malformed samples (wrong length, NaN/∞, a pose
/// that is not rigid), a bad measurement covariance or chain, fewer samples than the
/// model needs ([`FitError::TooFewSamples`]), configurations that do not vary enough
/// ([`FitError::NotIdentifiable`]), or a likelihood that cannot be evaluated.
pub fn fit(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    samples: &[Sample],
    measurement_cov: Option<&[[f64; 6]; 6]>,
    model: Model,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<Fit, FitError> {
    let r = check_measurement(measurement_cov)?;
    fit_with(joints, home, samples, r, model, None, progress)
}

/// [`fit`] with a checked measurement covariance `r`; `position_pad`: the samples are
/// position-only measurements padded to poses (rotation residual exactly zero, `r`'s
/// rotation block this variance, far above any rotation the model predicts), so the
/// likelihood is the 3-D one of the translations up to a constant (removed from the
/// reported log-likelihood), and the goodness of fit uses 3-D distances.
pub(crate) fn fit_with(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    samples: &[Sample],
    r: Matrix6<f64>,
    model: Model,
    position_pad: Option<f64>,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<Fit, FitError> {
    check_chain(joints, home)?;
    let n = joints.len();
    let needed = check_count(samples.len(), n, model)?;
    let prepared = prepare(joints, home, samples)?;
    // Position-only: the rotation rows of every transport zeroed, so Σ's rotation block is
    // R's alone (the padding) and the likelihood, its moments and the rank are exactly
    // the translations' 3-D ones; the prediction error keeps the whole Σ.
    let (data, unmasked) = match position_pad {
        Some(_) => (translation_rows(&prepared), Some(prepared)),
        None => (prepared, None),
    };
    // The floor only where Σ could be singular: no positive definite R.
    let with_floor = model == Model::Joint && r.cholesky().is_none();
    let param = Param {
        model,
        n,
        floor_min: with_floor.then(|| floor_min(&data)).transpose()?,
    };
    let design = Design::new(&data, model == Model::Joint, with_floor, r);
    let theta0 = start(&design, &param, position_pad);
    let names = natural_names(joints, model, with_floor);
    let (_, determinable) = identifiability_check(
        &design,
        &param,
        &theta0,
        (joints, home),
        (r, position_pad.is_some()),
        &names,
    )?;
    let out = if model == Model::Full {
        full_rounds(&design, &param, theta0, progress)?
    } else {
        let mut out = maximize(&design, &param, theta0, None, progress)?;
        out.converged |= out.stalled_at_optimum;
        out
    };
    let x = param.coeffs(&out.theta);
    let m = design
        .moments(&x, 1)
        .ok_or_else(|| FitError::Numerical("Σ singular at the optimum".into()))?;
    let jn = param.natural_jacobian(design.units.len());
    let info = information(&(jn.transpose() * &m.fisher * &jn));
    let unit_cov = &jn * &info.cov * jn.transpose();
    let joints_only = if with_floor {
        without_floor(&x)
    } else {
        x.clone()
    };
    let prediction = match &unmasked {
        Some(full) => {
            let full = Design::new(full, model == Model::Joint, with_floor, r);
            prediction_error(&full, &joints_only, n, &unit_cov)
        }
        None => prediction_error(&design, &joints_only, n, &unit_cov),
    };
    let d = match position_pad {
        Some(_) => position_distances(&design, &x),
        None => distances(&design, &x, &m.mahalanobis, with_floor),
    };
    let gof = goodness_of_fit(&d);
    // The padded rotation block's constant, −½·ln det(2π·V·I₃) per sample.
    let pad = position_pad.map_or(0.0, |v| {
        1.5 * (2.0 * std::f64::consts::PI * v).ln() * samples.len() as f64
    });
    let joints_out = joint_fits(joints, &data, &param, &x, &info);
    let floor = with_floor.then(|| [x[n][(0, 0)], x[n][(3, 3)]]);
    let mut fit = Fit {
        model,
        joints: joints_out,
        log_likelihood: out.loglik + pad,
        samples: samples.len(),
        converged: out.converged,
        iterations: out.iterations,
        residual_floor: floor,
        identifiability: identifiability(&info, determinable, &names),
        goodness_of_fit: gof,
        prediction_error: prediction,
        warnings: Vec::new(),
    };
    fit.warnings = warnings(&fit, &design, &x, data.clipped, needed);
    check_finite(&fit)?;
    Ok(fit)
}

/// The fewest samples a model of `n` joints needs (returned), or the error for fewer.
pub(crate) fn check_count(samples: usize, n: usize, model: Model) -> Result<usize, FitError> {
    let needed = 10.max(if model == Model::Joint { n + 2 } else { 21 * n });
    if samples < needed {
        return Err(FitError::TooFewSamples {
            got: samples,
            needed,
        });
    }
    Ok(needed)
}

/// The starting parameters: the method of moments' estimates made admissible.
fn start(design: &Design, param: &Param, position_pad: Option<f64>) -> DVector<f64> {
    let mut theta0 = param.start(&method_of_moments(design, param));
    if let (Some(_), Some(min)) = (position_pad, param.floor_min) {
        // Position-only: the floor's rotation variance is invisible beside the padded
        // block; held at its bound (the active set keeps it there), since a step in a
        // direction without information would swamp the step of every other parameter.
        theta0[param.n] = min[0].ln();
    }
    theta0
}

/// A result with a non-finite number in it is an error, not an answer (it would reach the
/// JSON as `null`).
fn check_finite(fit: &Fit) -> Result<(), FitError> {
    let p = &fit.prediction_error;
    let mut numbers = [fit.log_likelihood, p.median, p.worst]
        .into_iter()
        .chain(fit.residual_floor.into_iter().flatten());
    let per_joint = fit.joints.iter().all(|j| {
        j.cov.iter().flatten().all(|x| x.is_finite())
            && j.cov_se.iter().flatten().flatten().all(|x| x.is_finite())
            && [j.sigma2, j.sigma2_se]
                .into_iter()
                .flatten()
                .all(f64::is_finite)
    });
    if per_joint && numbers.all(f64::is_finite) {
        Ok(())
    } else {
        Err(FitError::Numerical(
            "the fitted model holds a non-finite number (overflow)".into(),
        ))
    }
}

fn check_chain(joints: &[Joint<f64>], home: &Transform<f64>) -> Result<(), FitError> {
    home.check()
        .map_err(|e| FitError::BadChain(format!("home pose: {e}")))?;
    if joints.is_empty() {
        return Err(FitError::BadChain("the chain has no moving joint".into()));
    }
    for j in joints {
        let (w, v) = (j.screw.rotation().norm(), j.screw.translation().norm());
        let unit = match j.kind {
            JointKind::Prismatic => w == 0.0 && (v - 1.0).abs() < 1e-9,
            _ => (w - 1.0).abs() < 1e-9,
        };
        if !j.screw.is_finite() || !unit {
            return Err(FitError::BadChain(format!(
                "joint '{}': the screw axis is not finite or not a unit axis",
                j.name
            )));
        }
    }
    Ok(())
}

fn check_measurement(r: Option<&[[f64; 6]; 6]>) -> Result<Matrix6<f64>, FitError> {
    let Some(r) = r else {
        return Ok(Matrix6::zeros());
    };
    ppoe::uncertainty::check_covariance(&Mat6::from(*r))
        .map_err(|e| FitError::BadMeasurementCov(e.to_string()))?;
    Ok(to_na(&Mat6::from(*r)))
}

/// The floor's lower bounds: 1e-12 of the residuals' mean squared rotation and
/// translation components (and an error if the residuals are all zero).
fn floor_min(data: &Prepared) -> Result<[f64; 2], FitError> {
    let k = data.eta.len() as f64;
    let rot = data
        .eta
        .iter()
        .map(|e| e.fixed_rows::<3>(0).norm_squared())
        .sum::<f64>();
    let tra = data
        .eta
        .iter()
        .map(|e| e.fixed_rows::<3>(3).norm_squared())
        .sum::<f64>();
    if rot + tra == 0.0 {
        return Err(FitError::Numerical(
            "every measured pose equals the forward kinematics exactly: no noise to fit".into(),
        ));
    }
    let scale = (rot + tra) / (6.0 * k);
    Ok([
        (1e-12 * rot / (3.0 * k)).max(1e-16 * scale).max(1e-300),
        (1e-12 * tra / (3.0 * k)).max(1e-16 * scale).max(1e-300),
    ])
}

/// The samples with the rotation rows of every transport zeroed: their designs predict
/// the translation block of Σ only.
fn translation_rows(data: &Prepared) -> Prepared {
    Prepared {
        eta: data.eta.clone(),
        transports: data
            .transports
            .iter()
            .map(|ads| {
                ads.iter()
                    .map(|a| {
                        let mut a = *a;
                        a.fixed_rows_mut::<3>(0).fill(0.0);
                        a
                    })
                    .collect()
            })
            .collect(),
        screws: data.screws.clone(),
        clipped: data.clipped,
    }
}

/// The natural parameters that best match Σ(θ) to ηηᵀ in least squares.
fn method_of_moments(design: &Design, param: &Param) -> DVector<f64> {
    let (f, b) = design.normal_equations();
    let jn = param.natural_jacobian(design.units.len());
    let (f, b) = (jn.transpose() * f * &jn, jn.transpose() * b);
    let info = information(&f);
    &info.cov * b
}

/// Names of the natural parameters, for reports.
fn natural_names(joints: &[Joint<f64>], model: Model, floor: bool) -> Vec<String> {
    let floor_names = [
        "residual floor (rotation)".to_string(),
        "residual floor (translation)".to_string(),
    ];
    match model {
        Model::Joint => joints
            .iter()
            .map(|j| format!("sigma2 of joint '{}'", j.name))
            .chain(floor_names.into_iter().filter(|_| floor))
            .collect(),
        Model::Full => joints
            .iter()
            .flat_map(|j| {
                (0..6).flat_map(move |p| {
                    (p..6).map(move |q| format!("cov[{p}][{q}] of joint '{}'", j.name))
                })
            })
            .collect(),
    }
}

/// The Fisher information of the data at the start, and the rank the model reaches on
/// spread-out configurations; an error if the data determine less than that.
fn identifiability_check(
    design: &Design,
    param: &Param,
    theta0: &DVector<f64>,
    (joints, home): (&[Joint<f64>], &Transform<f64>),
    (r, position): (Matrix6<f64>, bool),
    names: &[String],
) -> Result<(Information, usize), FitError> {
    let x0 = param.coeffs(theta0);
    let jn = param.natural_jacobian(design.units.len());
    let natural = |d: &Design| -> Result<Information, FitError> {
        let m = d
            .moments(&x0, 1)
            .ok_or_else(|| FitError::Numerical("the starting Σ is singular".into()))?;
        Ok(information(&(jn.transpose() * &m.fisher * &jn)))
    };
    let data = natural(design)?;
    let configs = crate::simulate::configurations(joints, 300, 0x5eed);
    let spread = Prepared {
        eta: vec![Vector6::zeros(); configs.len()],
        transports: configs
            .iter()
            .map(|t| transports(joints, home, t).0)
            .collect(),
        screws: joints
            .iter()
            .map(|j| Vector6::from_fn(|i, _| j.screw.0[i]))
            .collect(),
        clipped: 0,
    };
    let floor = param.floor_min.is_some();
    let spread = if position {
        translation_rows(&spread)
    } else {
        spread
    };
    let best = natural(&Design::new(&spread, param.model == Model::Joint, floor, r))?;
    if data.rank < best.rank {
        let missing: Vec<&str> = (0..names.len())
            .filter(|&i| data.undetermined[i] && !best.undetermined[i])
            .map(|i| names[i].as_str())
            .collect();
        return Err(FitError::NotIdentifiable(format!(
            "the samples determine {} of the {} combinations the model can determine; \
             undetermined: {}. Record configurations that move every joint over its range",
            data.rank,
            best.rank,
            if missing.is_empty() {
                "combinations of several parameters".to_string()
            } else {
                missing.join(", ")
            }
        )));
    }
    Ok((data, best.rank))
}

/// The per-joint results in base-frame screw coordinates.
fn joint_fits(
    joints: &[Joint<f64>],
    data: &Prepared,
    param: &Param,
    x: &[Matrix6<f64>],
    info: &Information,
) -> Vec<JointFit> {
    let se = |i: usize| (!info.undetermined[i]).then(|| info.cov[(i, i)].max(0.0).sqrt());
    joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let name = j.name.to_string();
            if param.model == Model::Joint {
                let s = data.screws[i];
                let s2 = x[i][(0, 0)];
                let c = s * s.transpose() * s2;
                let e = se(i);
                JointFit {
                    name,
                    cov: array6(|p, q| c[(p, q)]),
                    cov_se: array6(|p, q| e.map(|e| e * (s[p] * s[q]).abs())),
                    sigma2: Some(s2),
                    sigma2_se: e,
                }
            } else {
                let units = DVector::from_fn(21, |k, _| se(21 * i + k).unwrap_or(f64::NAN));
                let se_m = unit_matrix(&units, 0);
                JointFit {
                    name,
                    cov: array6(|p, q| x[i][(p, q)]),
                    cov_se: array6(|p, q| Some(se_m[(p, q)]).filter(|v| v.is_finite())),
                    sigma2: None,
                    sigma2_se: None,
                }
            }
        })
        .collect()
}

fn array6<T>(f: impl Fn(usize, usize) -> T) -> [[T; 6]; 6] {
    std::array::from_fn(|p| std::array::from_fn(|q| f(p, q)))
}

fn identifiability(info: &Information, determinable: usize, names: &[String]) -> Identifiability {
    Identifiability {
        parameters: names.len(),
        determined: info.rank,
        determinable,
        undetermined: (0..names.len())
            .filter(|&i| info.undetermined[i])
            .map(|i| names[i].clone())
            .collect(),
        null_directions: info
            .null_directions
            .iter()
            .map(|d| d.iter().map(|(i, w)| (names[*i].clone(), *w)).collect())
            .collect(),
    }
}

/// The warnings of a finished fit.
fn warnings(
    fit: &Fit,
    design: &Design,
    x: &[Matrix6<f64>],
    clipped: usize,
    needed: usize,
) -> Vec<String> {
    let mut w = Vec::new();
    if !fit.converged {
        w.push(format!(
            "Fisher scoring did not converge in {} iterations",
            fit.iterations
        ));
    }
    if fit.samples < 10 * needed {
        w.push(format!(
            "{} samples for {} parameters: standard errors are rough; record at least {}",
            fit.samples,
            fit.identifiability.parameters,
            10 * needed
        ));
    }
    w.extend(prediction_warning(fit));
    let large: Vec<&str> = fit
        .joints
        .iter()
        .filter(|j| j.cov[0][0] + j.cov[1][1] + j.cov[2][2] > LARGE_ROTATION_VARIANCE)
        .map(|j| j.name.as_str())
        .collect();
    if !large.is_empty() {
        w.push(format!(
            "joints [{}] have a fitted rotation noise above 0.1 rad: far beyond where the \
             second-order model holds (check the input's units, the joint order and the \
             tracker's frame: data this far from the kinematics are not noise)",
            large.join(", ")
        ));
    }
    if clipped > 0 {
        w.push(format!(
            "{clipped} samples had a joint value outside its limits (clipped, as the PPOE clips)"
        ));
    }
    let g = &fit.goodness_of_fit;
    if !g.fits {
        w.push(format!(
            "the residuals do not follow the fitted model (Kolmogorov-Smirnov p = {:.1e}, mean \
             Mahalanobis² {:.2}): the model does not describe these residuals (systematic errors \
             of the tracker's registration, the marker's place or the kinematics: calibrate \
             with --estimate; or the noise is too large for the second-order model)",
            g.p_value, g.mean_mahalanobis
        ));
    }
    if let Some([fr, ft]) = fit.residual_floor {
        let joints_only = without_floor(x);
        let k = design.eta.len() as f64;
        let (mut vr, mut vt) = (0.0, 0.0);
        for i in 0..design.eta.len() {
            let s = design.sigma(i, &joints_only) - design.r;
            vr += (s[(0, 0)] + s[(1, 1)] + s[(2, 2)]) / (3.0 * k);
            vt += (s[(3, 3)] + s[(4, 4)] + s[(5, 5)]) / (3.0 * k);
        }
        if fr > 0.05 * vr || ft > 0.05 * vt {
            w.push(format!(
                "a residual floor of {fr:.2e} rad² / {ft:.2e} m² remains beside mean predicted \
                 variances of {vr:.2e} rad² / {vt:.2e} m²: joint-value noise alone does not \
                 explain the scatter: if a systematic test fires, calibrate first (--estimate); \
                 otherwise give measurement_cov if the tracker's noise is missing, or try \
                 --model full"
            ));
        }
    }
    w
}

/// A joint's rotation variance (trace of its covariance's rotation block, rad²) above
/// this, σ > 0.1 rad, is beyond the second-order model (the crate docs' Accuracy).
const LARGE_ROTATION_VARIANCE: f64 = 0.01;

/// A median prediction error above this is worth a warning, and how many samples would
/// bring it to `PREDICTION_TARGET`.
const PREDICTION_WARN: f64 = 0.1;
const PREDICTION_TARGET: f64 = 0.05;

/// The warning for a fit whose predictions are uncertain by more than `PREDICTION_WARN`.
fn prediction_warning(fit: &Fit) -> Option<String> {
    let p = &fit.prediction_error;
    (p.median > PREDICTION_WARN).then(|| {
        format!(
            "the fitted model predicts tool covariances to ±{:.1} % (median standard error over \
             {} configurations, worst {:.1} %): about {} samples would bring the median to {} %",
            100.0 * p.median,
            p.configurations,
            100.0 * p.worst,
            samples_for(fit.samples, p.median, PREDICTION_TARGET),
            100.0 * PREDICTION_TARGET
        )
    })
}

/// The samples that bring a sampling error `error` of `samples` samples down to `target`
/// (it shrinks as 1/√samples), rounded up to a hundred; `usize::MAX` if that is not finite.
///
/// ```
/// // 2000 samples left an 8 % error: 5 % needs (8/5)² = 2.56 times as many.
/// assert_eq!(ppoe_fit::samples_for(2000, 0.08, 0.05), 5200);
/// ```
pub fn samples_for(samples: usize, error: f64, target: f64) -> usize {
    let n = samples as f64 * (error / target).powi(2);
    if n.is_finite() {
        ((n / 100.0).ceil() * 100.0) as usize
    } else {
        usize::MAX
    }
}

/// The coefficients with the residual floor's (the last) set to zero: the joints' own Σ.
fn without_floor(x: &[Matrix6<f64>]) -> Vec<Matrix6<f64>> {
    x.iter()
        .take(x.len() - 1)
        .copied()
        .chain([Matrix6::zeros()])
        .collect()
}

/// Position-only samples: each sample's squared Mahalanobis distance of the translation
/// residual under the translation block of Σ (with R and the floor), dimension 3.
fn position_distances(design: &Design, x: &[Matrix6<f64>]) -> Vec<(f64, usize)> {
    (0..design.eta.len())
        .map(|k| {
            let s = design.sigma(k, x).fixed_view::<3, 3>(3, 3).into_owned();
            let e = design.eta[k].fixed_rows::<3>(3).into_owned();
            let d = s.cholesky().map_or(f64::INFINITY, |c| e.dot(&c.solve(&e)));
            (d, 3)
        })
        .collect()
}

/// Each sample's squared Mahalanobis distance and its dimension: all six directions
/// without a floor; with one only the eigen-directions of the joints' Σ (with
/// R) whose variance is at least 10× the floor's there.
fn distances(design: &Design, x: &[Matrix6<f64>], d6: &[f64], floor: bool) -> Vec<(f64, usize)> {
    if !floor {
        return d6.iter().map(|d| (*d, 6)).collect();
    }
    let floor = x[x.len() - 1];
    let joints_only = without_floor(x);
    design
        .eta
        .iter()
        .enumerate()
        .map(|(k, eta)| {
            let e = design.sigma(k, &joints_only).symmetric_eigen();
            let (mut d, mut r) = (0.0, 0);
            for (i, lam) in e.eigenvalues.iter().enumerate() {
                let v = e.eigenvectors.column(i);
                let f = (v.transpose() * floor * v)[(0, 0)];
                if *lam >= 10.0 * f && *lam > 0.0 {
                    d += v.dot(eta).powi(2) / (lam + f);
                    r += 1;
                }
            }
            (d, r.max(1))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use ppoe::chain::screw_noise;

    fn small_fit() -> Fit {
        let joints = [
            Joint::new("a", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -3., 3.).prepared(),
            Joint::new(
                "b",
                JointKind::Revolute,
                [0., 1., 0., -0.3, 0., 0.],
                -2.,
                2.,
            )
            .prepared(),
        ];
        let home =
            Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0.4, 0., 0.3]);
        let truth: Vec<_> = joints.iter().map(|j| screw_noise(&j.screw, 1e-4)).collect();
        let samples = crate::simulate::samples(&joints, &home, &truth, None, 200, 3);
        fit(&joints, &home, &samples, None, Model::Joint, &mut |_, _| {}).unwrap()
    }

    #[test]
    fn a_non_finite_number_anywhere_in_the_result_is_an_error() {
        let f = small_fit();
        assert!(check_finite(&f).is_ok());
        let spoilers: [fn(&mut Fit); 5] = [
            |f| f.joints[1].cov[2][3] = f64::NAN,
            |f| f.joints[0].sigma2_se = Some(f64::INFINITY),
            |f| f.log_likelihood = f64::NEG_INFINITY,
            |f| f.prediction_error.worst = f64::NAN,
            |f| f.residual_floor = Some([0.0, f64::INFINITY]),
        ];
        for spoil in spoilers {
            let mut g = f.clone();
            spoil(&mut g);
            assert!(matches!(check_finite(&g), Err(FitError::Numerical(_))));
        }
    }
}
