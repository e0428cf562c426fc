//! [`fit_campaign`]: the checks, the alternation of calibration and noise model, and the
//! report.

use super::layout::{Estimate, Layout, Point};
use super::solve::{linearise, solve, tip, Campaign, Data, Whitening};
use super::systematic::SystematicTest;
use super::*;
use crate::report::information;

/// Checks the samples (one kind of measurement, lengths, finite values, rigid poses).
fn check<'a>(
    joints: &'a [Joint<f64>],
    home: &'a Transform<f64>,
    samples: &[CampaignSample],
) -> Result<Campaign<'a>, FitError> {
    let position = matches!(
        samples.first().map(|s| &s.measurement),
        Some(Measurement::Position(_))
    );
    let (mut poses, mut points) = (Vec::new(), Vec::new());
    for (k, s) in samples.iter().enumerate() {
        check_thetas(k, &s.thetas, joints)?;
        match (&s.measurement, position) {
            (Measurement::Pose(m), false) => poses.push(rigid(k, m)?),
            (Measurement::Position(p), true) => {
                if let Some(i) = p.iter().position(|x| !x.is_finite()) {
                    return Err(FitError::NonFinite {
                        sample: k,
                        what: format!("position[{i}]"),
                    });
                }
                points.push(Vec3::from(*p));
            }
            _ => return Err(FitError::MixedMeasurements { sample: k }),
        }
    }
    let thetas = samples.iter().map(|s| s.thetas.clone()).collect();
    let data = if position {
        Data::Positions(points)
    } else {
        Data::Poses(poses)
    };
    Ok(Campaign {
        joints,
        home,
        thetas,
        data,
    })
}

/// The tracker's noise as the 6×6 R of the residual (position-only: the padded rotation
/// block and the translation block).
fn measurement_r(cov: Option<&MeasurementCov>, position: bool) -> Result<Matrix6<f64>, FitError> {
    let bad = |why: &str| FitError::BadMeasurementCov(why.to_string());
    let mut r = Matrix6::zeros();
    match (cov, position) {
        (None, _) => {}
        (Some(MeasurementCov::Pose(m)), false) => {
            ppoe::uncertainty::check_covariance(&ppoe::Mat6::from(*m))
                .map_err(|e| bad(&e.to_string()))?;
            r = Matrix6::from_fn(|i, j| m[i][j]);
        }
        (Some(MeasurementCov::Position(m)), true) => {
            let mut full = [[0.0; 6]; 6];
            for i in 0..3 {
                full[i][i] = 1.0;
                for j in 0..3 {
                    full[3 + i][3 + j] = m[i][j];
                }
            }
            ppoe::uncertainty::check_covariance(&ppoe::Mat6::from(full))
                .map_err(|e| bad(&e.to_string()))?;
            r = Matrix6::from_fn(|i, j| {
                if i >= 3 && j >= 3 {
                    m[i - 3][j - 3]
                } else {
                    0.0
                }
            });
        }
        (Some(MeasurementCov::Pose(_)), true) => {
            return Err(bad(
                "the samples are positions: measurement_cov must be 3×3",
            ))
        }
        (Some(MeasurementCov::Position(_)), false) => {
            return Err(bad("the samples are poses: measurement_cov must be 6×6"))
        }
    }
    if position {
        for i in 0..3 {
            r[(i, i)] = POSITION_PAD;
        }
    }
    Ok(r)
}

/// Closed-form X and Y for the estimated groups.
fn start_point(c: &Campaign, e: &Estimate) -> Point {
    let f: Vec<Transform<f64>> = c.thetas.iter().map(|t| tip(c.joints, c.home, t)).collect();
    let (x, y) = match &c.data {
        Data::Poses(t) => super::start::poses(&f, t, e.base, e.tip),
        Data::Positions(p) => {
            let p: Vec<Vector3<f64>> = p.iter().map(|v| Vector3::from(v.0)).collect();
            super::start::positions(&f, &p, e.base, e.tip)
        }
    };
    Point::nominal(c.joints.len(), x, y)
}

/// Residual RMS (mm, mrad) of residuals with `dim` components per sample.
fn rms(r: &[f64], dim: usize) -> ResidualRms {
    let k = (r.len() / dim).max(1) as f64;
    let sq = |range: std::ops::Range<usize>| {
        let s: f64 = r
            .chunks(dim)
            .map(|c| c[range.clone()].iter().map(|x| x * x).sum::<f64>())
            .sum();
        (s / k).sqrt()
    };
    if dim == 6 {
        ResidualRms {
            position_mm: 1e3 * sq(3..6),
            rotation_mrad: Some(1e3 * sq(0..3)),
        }
    } else {
        ResidualRms {
            position_mm: 1e3 * sq(0..3),
            rotation_mrad: None,
        }
    }
}

/// A calibrated chain, its home pose with the marker, and the samples in its base frame.
type Mapped = (Vec<Joint<f64>>, Transform<f64>, Vec<Sample>);

/// The data mapped through the calibration at `at`: the calibrated chain with Y in its
/// home pose, and samples in the base frame (position-only: padded to poses whose
/// rotation is the model's, so their rotation residual is zero).
fn mapped(c: &Campaign, at: &Point) -> Option<Mapped> {
    let (joints, home) = at.chain(c.joints, c.home)?;
    let xi = at.x.inverse();
    let samples = c
        .thetas
        .iter()
        .enumerate()
        .map(|(k, th)| {
            let pose = match &c.data {
                Data::Poses(t) => (xi * t[k]).to_matrix4(),
                Data::Positions(p) => Transform {
                    rotation: tip(&joints, &home, th).rotation,
                    translation: xi.transform_point(&p[k]),
                }
                .to_matrix4(),
            };
            Sample {
                thetas: th.clone(),
                pose,
            }
        })
        .collect();
    Some((joints, home * at.y, samples))
}

/// Each sample's residual covariance under `fit` (marker frame; position-only: the
/// translation block, moved to the top-left corner).
fn sigmas(c: &Campaign, at: &Point, fit: &Fit, r: &Matrix6<f64>) -> Option<Vec<Matrix6<f64>>> {
    let (joints, home) = at.chain(c.joints, c.home)?;
    let home = home * at.y;
    let covs: Vec<Matrix6<f64>> = fit
        .joints
        .iter()
        .map(|j| Matrix6::from_fn(|p, q| j.cov[p][q]))
        .collect();
    let floor = fit.residual_floor.map_or(Matrix6::zeros(), |[a, b]| {
        Matrix6::from_diagonal(&nalgebra::Vector6::new(a, a, a, b, b, b))
    });
    let position = matches!(c.data, Data::Positions(_));
    let out = c.thetas.iter().map(|th| {
        let (ads, _, _) = transports(&joints, &home, th);
        let s = ads
            .iter()
            .zip(&covs)
            .fold(r + floor, |s, (a, cv)| s + a * cv * a.transpose());
        if position {
            Matrix6::from_fn(|i, j| {
                if i < 3 && j < 3 {
                    s[(i + 3, j + 3)]
                } else {
                    0.0
                }
            })
        } else {
            s
        }
    });
    Some(out.collect())
}

/// Isotropic starting weights from the residuals' mean squared components.
fn first_weights(r: &[f64], dim: usize, k: usize) -> Whitening {
    let mean = |range: std::ops::Range<usize>| {
        let s: f64 = r
            .chunks(dim)
            .map(|c| c[range.clone()].iter().map(|x| x * x).sum::<f64>())
            .sum();
        (s / (k * range.len()).max(1) as f64).max(1e-30)
    };
    if dim == 6 {
        Whitening::isotropic(k, 6, mean(0..3), mean(3..6))
    } else {
        Whitening::isotropic(k, 3, 1.0, mean(0..3))
    }
}

/// The noise model fitted to the data mapped through `at`, and the weights it gives.
fn noise_at(
    c: &Campaign,
    at: &Point,
    r: &Matrix6<f64>,
    model: Model,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<(Fit, Whitening), FitError> {
    let position = matches!(c.data, Data::Positions(_));
    let singular = || FitError::Numerical("the calibrated chain is not finite".into());
    let (joints, home, samples) = mapped(c, at).ok_or_else(singular)?;
    let pad = position.then_some(POSITION_PAD);
    let fit = fit_with(&joints, &home, &samples, *r, model, pad, progress)?;
    let s = sigmas(c, at, &fit, r).ok_or_else(singular)?;
    let w = Whitening::of(&s, c.data.dim())
        .ok_or_else(|| FitError::Numerical("a residual covariance is singular".into()))?;
    Ok((fit, w))
}

/// Fits the noise model (`model`) of a measurement campaign together with the
/// calibration groups in `estimate` (see the module docs of `calibration`):
/// `samples` all poses or all positions, `measurement_cov` the tracker's noise of that
/// kind. With `Estimate::NONE` the noise model is [`crate::fit`]'s, plus the systematic
/// tests. `progress(iteration, log_likelihood)` as in [`crate::fit`].
///
/// # Errors
/// As [`crate::fit`], plus [`FitError::MixedMeasurements`] for poses and positions in
/// one campaign, and a measurement covariance of the other kind.
///
/// ```
/// use ppoe::chain::{screw_noise, Joint, JointKind};
/// use ppoe::{se3, Transform, Vec6};
/// use ppoe_fit::{fit_campaign, simulate, CampaignSample, Estimate, Measurement, Model};
/// let joints = [
///     Joint::new("a", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -3., 3.).prepared(),
///     Joint::new("b", JointKind::Revolute, [0., 1., 0., -0.3, 0., 0.], -2., 2.).prepared(),
///     Joint::new("c", JointKind::Revolute, [1., 0., 0., 0., 0.3, -0.1], -2., 2.).prepared(),
/// ];
/// let home = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0.4, 0., 0.3]);
/// let truth: Vec<_> = joints.iter().map(|j| screw_noise(&j.screw, 1e-6)).collect();
/// // The tracker 2 m away, turned; the samples in its frame.
/// let x = se3::exp(&Vec6::from([0.3, -1.2, 0.5, 2.0, -0.4, 0.8]));
/// let samples: Vec<CampaignSample> = simulate::samples(&joints, &home, &truth, None, 600, 3)
///     .into_iter()
///     .map(|s| CampaignSample {
///         measurement: Measurement::Pose((x * Transform::from_matrix4(&s.pose)).to_matrix4()),
///         thetas: s.thetas,
///     })
///     .collect();
/// let base = Estimate { base: true, ..Estimate::NONE };
/// let out = fit_campaign(&joints, &home, &samples, None, Model::Joint, base, &mut |_, _| {})
///     .unwrap();
/// let t = out.calibration.base_in_tracker.pose.translation;
/// assert!((t - x.translation).norm() < 1e-4);
/// for j in &out.fit.joints {
///     assert!((j.sigma2.unwrap() - 1e-6).abs() < 5.0 * j.sigma2_se.unwrap());
/// }
/// ```
pub fn fit_campaign(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    samples: &[CampaignSample],
    measurement_cov: Option<&MeasurementCov>,
    model: Model,
    estimate: Estimate,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<CampaignFit, FitError> {
    // Before any closed form: they need samples to work on.
    crate::run::check_count(samples.len(), joints.len(), model)?;
    let c = check(joints, home, samples)?;
    let position = matches!(c.data, Data::Positions(_));
    let r = measurement_r(measurement_cov, position)?;
    let dim = c.data.dim();
    let not_finite = || FitError::Numerical("a residual is not finite".into());
    let start = start_point(&c, &estimate);
    let r0 = c.residuals(&start).ok_or_else(not_finite)?;
    let layout = Layout::new(estimate, position, joints);
    let mut w = first_weights(&r0, dim, samples.len());
    let mut point = start.clone();
    let mut last = f64::NEG_INFINITY;
    let mut rounds = 0;
    let fit = loop {
        if layout.len() > 0 {
            point = solve(&c, &layout, &point, &w).ok_or_else(not_finite)?;
        }
        let (fit, next) = noise_at(&c, &point, &r, model, progress)?;
        w = next;
        rounds += 1;
        if layout.len() == 0 || fit.log_likelihood - last < ROUND_TOL || rounds == ROUNDS {
            break fit;
        }
        last = fit.log_likelihood;
    };
    let (z, j) = linearise(&c, &layout, &point, &w).ok_or_else(not_finite)?;
    let info = information(&(j.transpose() * &j));
    let g = j.transpose() * &z;
    let estimated_score = g.dot(&(&info.cov * &g));
    let mean_test = mean_test(&z, dim);
    let calibration_test = calibration_test(&c, &layout, &point, &w, (info.rank, estimated_score))?;
    let r1 = c.residuals(&point).ok_or_else(not_finite)?;
    let calibration = super::report::calibration(
        &layout,
        &point,
        &info,
        (rms(&r0, dim), rms(&r1, dim)),
        rounds,
        (joints, home),
    )
    .ok_or_else(not_finite)?;
    let mut out = CampaignFit {
        fit,
        calibration,
        mean_test,
        calibration_test,
    };
    super::report::warn(&mut out);
    Ok(out)
}

/// The mean test of the whitened residuals `z` (`dim` per sample).
fn mean_test(z: &nalgebra::DVector<f64>, dim: usize) -> SystematicTest {
    let k = (z.len() / dim).max(1) as f64;
    let mut mean = vec![0.0; dim];
    for c in z.as_slice().chunks(dim) {
        mean.iter_mut().zip(c).for_each(|(m, x)| *m += x / k);
    }
    let s = k * mean.iter().map(|m| m * m).sum::<f64>();
    SystematicTest::new(vec!["mean".into()], s, dim)
}

/// The score test of the groups among base, tip and offsets not estimated, at the fit
/// (`estimated`: the estimated parameters' rank and score statistic under the same
/// weights, which the efficient score of the tested ones excludes).
fn calibration_test(
    c: &Campaign,
    layout: &Layout,
    at: &Point,
    w: &Whitening,
    estimated: (usize, f64),
) -> Result<Option<SystematicTest>, FitError> {
    let e = layout.estimate;
    let tested: Vec<String> = [(e.base, "base"), (e.tip, "tip"), (e.offsets, "offsets")]
        .into_iter()
        .filter(|(done, _)| !done)
        .map(|(_, g)| g.to_string())
        .collect();
    if tested.is_empty() {
        return Ok(None);
    }
    let all = Estimate {
        base: true,
        tip: true,
        offsets: true,
        kinematics: e.kinematics,
    };
    let full = Layout::new(all, layout.position, c.joints);
    let not_finite = || FitError::Numerical("a residual is not finite".into());
    let (z, j) = linearise(c, &full, at, w).ok_or_else(not_finite)?;
    let g = j.transpose() * &z;
    let info = information(&(j.transpose() * &j));
    // gᵀN⁺g of all minus that of the estimated ones: the efficient score statistic of the
    // tested ones (the estimated ones' score is near zero at their optimum anyway).
    let s = (g.dot(&(&info.cov * &g)) - estimated.1).max(0.0);
    let dof = info.rank.saturating_sub(estimated.0);
    Ok(Some(SystematicTest::new(tested, s, dof)))
}
