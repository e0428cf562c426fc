//! # ppoe-fit — where the per-joint covariances come from
//!
//! [`ppoe`] propagates per-joint covariances to the tool exactly; this host-side crate
//! estimates them from joint values recorded together with tool poses measured by an
//! external tracker. The model is the PPOE's own:
//!
//! `T_meas = D₁·Exp(ξ₁)·D₂·Exp(ξ₂)···Dₙ·Exp(ξₙ)·M·Exp(ν)`, `Dᵢ = Exp(Sᵢθᵢ)`,
//! ξᵢ ~ N(0, Cᵢ) in base-frame screw coordinates (rotation first, what
//! `ChainView::ppoe` takes as `covs[i]`), ν ~ N(0, R) the tracker's noise in the tip frame
//! (given, may be zero). With η = Log(T̄(θ)⁻¹·T_meas) the second-order PPOE gives
//! η ~ N(0, Σ(θ) + R), `Σ(θ) = Σᵢ Ad(Gᵢ⁻¹)·Cᵢ·Ad(Gᵢ⁻¹)ᵀ`, `Gᵢ = Dᵢ₊₁…Dₙ·M`: linear in
//! the Cᵢ, so the log-likelihood's gradient and Fisher information are closed forms.
//!
//! * [`Model::Joint`]: `Cᵢ = σᵢ²·SᵢSᵢᵀ`, σᵢ² = exp(sᵢ). With fewer than six joints (or at
//!   singular configurations) this Σ is singular while the exact residuals are not (their
//!   second-order part leaves the span of the Jacobian), so the joint model also fits a
//!   *residual floor*: isotropic variances τ_rot·I₃ and τ_trans·I₃ in the tip frame,
//!   reported, not baked into the table. A floor comparable to the predicted variances
//!   says the joint model does not explain the scatter.
//! * [`Model::Full`]: `Cᵢ = LᵢLᵢᵀ`, Lᵢ lower triangular. Not every direction is
//!   identifiable (e.g. a variance along joint i+1's screw axis placed on joint i or on
//!   joint i+1 predicts the same); the fit still returns PSD covariances whose
//!   predictions are determined, and reports the rank and the undetermined combinations.
//!
//! Method: method of moments (least squares of Σ(θ) against ηηᵀ) for the start, then
//! maximum likelihood by Fisher scoring with Levenberg–Marquardt damping; standard errors
//! from the inverse Fisher information on the determined subspace; goodness of fit from
//! the residuals' Mahalanobis distances against χ²₆ ([`GoodnessOfFit`]).
//!
//! # Calibration
//! A real campaign measures `T_meas = X·D₁'·Exp(ξ₁)···Dₙ'·Exp(ξₙ)·M'·Y·Exp(ν)` in a
//! tracker's frame: [`fit_campaign`] estimates the base X, the marker Y, joint zero
//! offsets and axis/home corrections ([`Estimate`]) together with the noise, from pose or
//! position-only samples, with standard errors, the combinations the data cannot separate,
//! and tests for the systematic errors not estimated ([`SystematicTest`]); the crate's
//! `calibration_validation` tests check it on simulated campaigns with every systematic
//! error at once.
//!
//! # Accuracy
//! Each fit reports its own sampling error, [`Fit::prediction_error`] (the standard error
//! of the predicted tool covariance; the crate's tests check it against the spread of fits
//! of independent datasets). It does not include the bias of the second-order model,
//! which is exact only to second order in the noise: on the project's test robots the
//! joint model's predictions drift beyond their standard errors above σ ≈ 0.1 rad per
//! joint.
//!
//! ```
//! use ppoe::chain::{screw_noise, Joint, JointKind};
//! use ppoe::Transform;
//! use ppoe_fit::{fit, simulate, Model};
//! let joints = [
//!     Joint::new("a", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -3., 3.).prepared(),
//!     Joint::new("b", JointKind::Revolute, [0., 1., 0., -0.3, 0., 0.], -2., 2.).prepared(),
//!     Joint::new("c", JointKind::Revolute, [1., 0., 0., 0., 0.3, -0.1], -2., 2.).prepared(),
//! ];
//! let home = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0.4, 0., 0.3]);
//! let truth: Vec<_> = joints.iter().map(|j| screw_noise(&j.screw, 1e-4)).collect();
//! let samples = simulate::samples(&joints, &home, &truth, None, 400, 7);
//! let out = fit(&joints, &home, &samples, None, Model::Joint, &mut |_, _| {}).unwrap();
//! for j in &out.joints {
//!     let (s2, se) = (j.sigma2.unwrap(), j.sigma2_se.unwrap());
//!     assert!((s2 - 1e-4).abs() < 5.0 * se);
//! }
//! ```

#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod calibration;
mod design;
mod error;
mod fisher;
#[cfg(feature = "json")]
pub mod json;
mod optimize;
mod parallel;
mod param;
mod prediction;
mod report;
mod samples;
pub mod simulate;

pub use calibration::{
    chi2_sf, fit_campaign, Calibration, CampaignFit, CampaignSample, Estimate, Measurement,
    MeasurementCov, PoseEstimate, ResidualRms, SystematicTest,
};
pub use error::FitError;
pub use param::Model;
pub use prediction::PredictionError;
pub use report::{chi2_cdf, GoodnessOfFit};
pub use samples::{Sample, RIGID_TOL};

mod run;
pub use run::{fit, samples_for, Fit, Identifiability, JointFit};
