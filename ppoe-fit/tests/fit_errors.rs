//! Honest errors and warnings: malformed samples name the sample, too few samples and
//! configurations that do not vary are errors, and a model that does not describe the
//! data is flagged by the goodness of fit.

mod common;
use common::*;
use ppoe_fit::{fit, simulate, FitError, Model};

fn seed() -> (Vec<ppoe::chain::Joint<f64>>, ppoe::Transform<f64>) {
    robot(ROBOTS[0].0, ROBOTS[0].1, ROBOTS[0].2)
}

#[test]
fn malformed_samples_name_the_sample() {
    let (joints, home) = seed();
    let truth = joint_covs(&joints, &joint_truth(&joints, 1.0));
    let good = simulate::samples(&joints, &home, &truth, None, 100, 9);
    let run = |s: &[ppoe_fit::Sample]| fit(&joints, &home, s, None, Model::Joint, &mut |_, _| {});
    let mut s = good.clone();
    s[7].thetas.pop();
    assert!(matches!(
        run(&s),
        Err(FitError::WrongLength {
            sample: 7,
            got: 5,
            expected: 6
        })
    ));
    let mut s = good.clone();
    s[3].thetas[2] = f64::NAN;
    assert!(matches!(
        run(&s),
        Err(FitError::NonFinite { sample: 3, .. })
    ));
    let mut s = good.clone();
    s[5].pose[0][0] *= 1.01;
    let e = run(&s).unwrap_err();
    assert!(matches!(e, FitError::NotRigid { sample: 5, .. }), "{e}");
    assert!(e.to_string().contains("sample 5"));
    let mut s = good.clone();
    s[9].pose[1][3] = f64::INFINITY;
    assert!(matches!(
        run(&s),
        Err(FitError::NonFinite { sample: 9, .. })
    ));
    let mut s = good.clone();
    s[2].pose[3][0] = 0.5;
    assert!(matches!(run(&s), Err(FitError::NotRigid { sample: 2, .. })));
    let bad_r = [[1.0; 6]; 6].map(|mut r| {
        r[0] = -1.0;
        r
    });
    let e = fit(
        &joints,
        &home,
        &good,
        Some(&bad_r),
        Model::Joint,
        &mut |_, _| {},
    );
    assert!(matches!(e, Err(FitError::BadMeasurementCov(_))));
    // Issue #26 item 4: antisymmetric by its own scale of 1e-8 (an absolute tolerance of
    // 1.5e-8 let it through); the same matrix made symmetric is accepted.
    let mut small = [[0.0; 6]; 6];
    for (i, row) in small.iter_mut().enumerate() {
        row[i] = 1e-8;
    }
    small[0][1] = 5e-9;
    small[1][0] = -5e-9;
    let e = fit(
        &joints,
        &home,
        &good,
        Some(&small),
        Model::Joint,
        &mut |_, _| {},
    );
    assert!(
        matches!(&e, Err(FitError::BadMeasurementCov(why)) if why.contains("symmetric")),
        "{:?}",
        e.err()
    );
    small[1][0] = 5e-9;
    let e = fit(
        &joints,
        &home,
        &good,
        Some(&small),
        Model::Joint,
        &mut |_, _| {},
    );
    assert!(!matches!(e, Err(FitError::BadMeasurementCov(_))));
}

#[test]
fn too_few_samples() {
    let (joints, home) = seed();
    let truth = full_truth(&joints, 1.0);
    let s = simulate::samples(&joints, &home, &truth, None, 60, 3);
    let e = fit(&joints, &home, &s, None, Model::Full, &mut |_, _| {}).unwrap_err();
    assert_eq!(
        e,
        FitError::TooFewSamples {
            got: 60,
            needed: 126
        }
    );
    let e = fit(&joints, &home, &s[..5], None, Model::Joint, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, FitError::TooFewSamples { got: 5, .. }));
}

/// Every sample at one configuration (or joints that never move): the model is not
/// determined, and the fit says so instead of returning a confident answer.
#[test]
fn configurations_that_do_not_vary() {
    // One configuration: the full model sees a single 6×6 covariance, 21 numbers for 126
    // parameters. (The joint model's σᵢ²·uᵢuᵢᵀ are linearly independent even at one
    // regular configuration, so it is determined there, and the fit says so.)
    let (joints, home) = seed();
    let one = vec![vec![0.3, -0.2, 0.4, 0.1, 0.5, -0.3]; 400];
    let s = simulate::samples_at(&joints, &home, &full_truth(&joints, 1.0), None, &one, 5);
    let e = fit(&joints, &home, &s, None, Model::Full, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, FitError::NotIdentifiable(_)), "{e}");
    assert!(e.to_string().contains("determine 21 of"), "{e}");
    // Joint 2 never moves, the others do: the full model cannot tell joint 1's noise from
    // joint 2's in the directions joint 2's motion would reveal. (Joint 1's value never
    // matters: the tip-frame covariance does not depend on it.)
    let mut configs = simulate::configurations(&joints, 1500, 8);
    for c in configs.iter_mut() {
        c[1] = 0.0;
    }
    let s = simulate::samples_at(&joints, &home, &full_truth(&joints, 1.0), None, &configs, 6);
    let e = fit(&joints, &home, &s, None, Model::Full, &mut |_, _| {}).unwrap_err();
    assert!(e.to_string().contains("of joint 'joint1'"), "{e}");
}

/// Link bending fitted with the joint model: the fit warns (the residuals do not follow
/// the fitted model, or joint noise leaves a large residual floor).
#[test]
fn wrong_model_is_flagged() {
    let (joints, home) = seed();
    let s = simulate::samples(&joints, &home, &full_truth(&joints, 1.0), None, 1500, 12);
    let f = fit(&joints, &home, &s, None, Model::Joint, &mut |_, _| {}).unwrap();
    assert!(
        f.warnings
            .iter()
            .any(|w| w.contains("do not follow") || w.contains("residual floor")),
        "{:?}",
        f.warnings
    );
}

/// A campaign's bad inputs are errors before any closed form runs: no samples, too few,
/// poses mixed with positions (naming the first sample of the other kind), a measurement
/// covariance of the other kind.
#[test]
fn campaign_errors() {
    use ppoe::chain::screw_noise;
    use ppoe_fit::{fit_campaign, CampaignSample, Estimate, Measurement, MeasurementCov};
    let (joints, home) = seed();
    let truth: Vec<_> = joints.iter().map(|j| screw_noise(&j.screw, 1e-6)).collect();
    let samples: Vec<CampaignSample> = simulate::samples(&joints, &home, &truth, None, 40, 5)
        .into_iter()
        .map(|s| CampaignSample {
            thetas: s.thetas,
            measurement: Measurement::Pose(s.pose),
        })
        .collect();
    let fit = |s: &[CampaignSample], cov: Option<&MeasurementCov>| {
        fit_campaign(
            &joints,
            &home,
            s,
            cov,
            Model::Joint,
            Estimate::ALL,
            &mut |_, _| {},
        )
    };
    for k in [0, 1, 3] {
        assert!(
            matches!(
                fit(&samples[..k], None),
                Err(FitError::TooFewSamples { .. })
            ),
            "{k}"
        );
    }
    let mut mixed = samples.clone();
    mixed[17].measurement = Measurement::Position([0.1, 0.2, 0.3]);
    assert_eq!(
        fit(&mixed, None).unwrap_err(),
        FitError::MixedMeasurements { sample: 17 }
    );
    let wrong = MeasurementCov::Position([[1e-8, 0.0, 0.0], [0.0, 1e-8, 0.0], [0.0, 0.0, 1e-8]]);
    assert!(matches!(
        fit(&samples, Some(&wrong)),
        Err(FitError::BadMeasurementCov(_))
    ));
    let mut nan = samples.clone();
    nan[3].measurement = Measurement::Pose([[f64::NAN; 4]; 4]);
    assert!(matches!(
        fit(&nan, None),
        Err(FitError::NonFinite { sample: 3, .. })
    ));
}
