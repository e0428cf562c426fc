//! The noise model of a real measurement campaign: tracker registration, marker offset and
//! kinematic corrections estimated together with the per-joint noise.
//!
//! The measurement model is
//! `T_meas = X·D₁'·Exp(ξ₁)···Dₙ'·Exp(ξₙ)·M'·Y·Exp(ν)`: X the robot base in the tracker's
//! frame, Y the marker in the tip frame, `Dᵢ' = Exp(Sᵢ''·(θᵢ + δᵢ))` and M' the calibrated
//! kinematics (`layout`), ξᵢ, ν the noise model of [`crate::fit`]. Position-only data
//! (`"position"` samples, a laser tracker's retroreflector) measure `X·T̄·m` only; their
//! likelihood is the 3-D one of the tool covariance projected through the marker's lever
//! arm, and Y is the point m (3 parameters).
//!
//! Method: closed-form X and Y (`start`), then alternating maximisation of the likelihood
//! (at most [`ROUNDS`] rounds): the deterministic parameters by weighted least squares
//! under the current noise model (`solve`), then the noise model by [`crate::fit`] on the
//! data mapped through the current calibration, until the log-likelihood gains less than
//! [`ROUND_TOL`]. Standard errors: the noise model's from its Fisher information, the
//! calibration's from `(JᵀΣ⁻¹J)⁺`. Combinations the data cannot separate (the first
//! joint's offset against X's rotation about that axis, the last joint's against Y, an
//! axis correction against X) are the null space of JᵀΣ⁻¹J: the solve does not move them
//! from the start (the gauge: offsets and corrections zero there, X and Y their closed
//! forms), they are reported, and their standard errors are `None`.

mod layout;
mod report;
mod solve;
mod start;
mod systematic;

pub use layout::Estimate;
pub use systematic::{chi2_sf, SystematicTest};

use crate::error::FitError;
use crate::param::Model;
use crate::run::{fit_with, Fit};
use crate::samples::{check_thetas, rigid, transports, Sample};
use nalgebra::{Matrix6, Vector3};
use ppoe::chain::Joint;
use ppoe::{Transform, Vec3};

/// Most rounds of the alternation, and the log-likelihood gain of a round below which it
/// stops (a likelihood-ratio χ² of 0.2: statistically nothing).
pub const ROUNDS: usize = 8;
/// See [`ROUNDS`].
pub const ROUND_TOL: f64 = 0.1;
/// The variance (rad²) given to the rotation residual of position-only samples, which is
/// exactly zero: far above any rotation variance a robot's model predicts, so the
/// 6-D likelihood is the 3-D one of the translations to within ~1e-6 relative.
const POSITION_PAD: f64 = 1e6;

/// What the tracker measured in one sample.
#[derive(Clone, Debug, PartialEq)]
pub enum Measurement {
    /// The marker's pose in the tracker's frame, 4×4 row-major.
    Pose([[f64; 4]; 4]),
    /// The marker's position in the tracker's frame (m).
    Position([f64; 3]),
}

/// One sample of a campaign: joint values as the encoders read them, and the measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct CampaignSample {
    /// One value per joint (rad or m), base to tip.
    pub thetas: Vec<f64>,
    /// What the tracker measured.
    pub measurement: Measurement,
}

/// The tracker's noise: 6×6 for poses (marker frame, rotation first), 3×3 for positions
/// (m², in the tip frame's axes; an isotropic σ²·I is the same in every frame).
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)] // a value passed once per fit
pub enum MeasurementCov {
    /// For pose samples.
    Pose([[f64; 6]; 6]),
    /// For position samples.
    Position([[f64; 3]; 3]),
}

/// The RMS of the residuals (position in mm, rotation in mrad; `None` for position-only
/// data).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResidualRms {
    /// √(mean ‖translation residual‖²), mm.
    pub position_mm: f64,
    /// √(mean ‖rotation residual‖²), mrad.
    pub rotation_mrad: Option<f64>,
}

/// A transform estimate with its covariance (right perturbation, rotation first; `None`
/// where not estimated; entries of undetermined combinations are `None` in the SEs).
#[derive(Clone, Debug, PartialEq)]
pub struct PoseEstimate {
    /// The estimate.
    pub pose: Transform<f64>,
    /// Its covariance (6×6; position-only markers: the translation block only, rotation
    /// rows and columns zero); `None` where not estimated, entries of undetermined
    /// parameters `None`.
    pub cov: Option<[[Option<f64>; 6]; 6]>,
}

/// The calibration estimated with the noise model.
#[derive(Clone, Debug, PartialEq)]
pub struct Calibration {
    /// What was estimated.
    pub estimated: Estimate,
    /// Whether the data were positions only.
    pub position_only: bool,
    /// X: the robot base in the tracker's frame.
    pub base_in_tracker: PoseEstimate,
    /// Y: the marker in the tip frame.
    pub marker_in_tip: PoseEstimate,
    /// δᵢ per joint (zero where not estimated).
    pub offsets: Vec<f64>,
    /// Their standard errors (`None`: not estimated or undetermined).
    pub offset_se: Vec<Option<f64>>,
    /// κᵢ per joint: base-frame twists, rotation first (zero where not estimated).
    pub axis_corrections: Vec<[f64; 6]>,
    /// Their standard errors per component.
    pub axis_correction_se: Vec<[Option<f64>; 6]>,
    /// μ: the home correction (tip frame, right perturbation).
    pub home_correction: [f64; 6],
    /// Its standard errors.
    pub home_correction_se: [Option<f64>; 6],
    /// Residual RMS at the start (nominal kinematics, closed-form X and Y).
    pub rms_before: ResidualRms,
    /// Residual RMS after calibration.
    pub rms_after: ResidualRms,
    /// Parameters the data do not determine (their values are the gauge's).
    pub undetermined: Vec<String>,
    /// Up to 12 undetermined combinations, each as its largest (name, weight) terms.
    pub null_directions: Vec<Vec<(String, f64)>>,
    /// Rounds of the alternation.
    pub rounds: usize,
    /// The calibrated chain (offsets and corrections folded; what `fit.joints[i].cov`
    /// belong to), and its home pose.
    pub joints: Vec<Joint<f64>>,
    /// See `joints`.
    pub home: Transform<f64>,
}

/// The result of [`fit_campaign`].
#[derive(Clone, Debug, PartialEq)]
pub struct CampaignFit {
    /// The noise model, of the calibrated chain (its goodness of fit's `fits` is false
    /// also when a systematic test below fails).
    pub fit: Fit,
    /// The calibration.
    pub calibration: Calibration,
    /// The mean test of the whitened residuals.
    pub mean_test: SystematicTest,
    /// The score test of the calibration groups among base, tip and offsets that were not
    /// estimated (`None` if all were).
    pub calibration_test: Option<SystematicTest>,
}

mod campaign;
pub use campaign::fit_campaign;
