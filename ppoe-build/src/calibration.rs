//! The calibration a noise file may carry (issue #27): joint zero offsets δᵢ, axis
//! corrections κᵢ and a home correction μ, read strictly from the file and folded into a
//! [`RobotChain`] with the core's [`ppoe::chain::fold_calibration`], so that every consumer
//! (the tables, `ppoe eval|render|mesh|demo --noise`) uses the chain the fit's covariances
//! belong to.
//!
//! In the file: `joints[i].offset` (rad or m, absent = 0), `joints[i].axis_correction` (6
//! numbers, a base-frame twist, rotation first; absent = zeros) and
//! `calibration.home_correction` (6 numbers, tip frame, right perturbation; absent =
//! zeros); `calibration.estimated` lists what the fit estimated. Every other field of
//! `calibration` (`base_in_tracker`, `marker_in_tip`, `residual_rms`, …) and
//! `joints[i].offset_se` are the fit's report and are not read here.
//!
//! The calibrated product is `Exp(S₁''(θ₁+δ₁))···Exp(Sₙ''(θₙ+δₙ))·M·Exp(μ)` with
//! `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ`; folded, it is the ordinary chain `Exp(S₁'θ₁)···M'` (see the
//! core's `calibration` module). A calibration whose values are all zero (or absent)
//! changes nothing: [`Calibration::apply`] then returns the chain as it is, bit for bit.

use crate::chain::RobotChain;
use crate::error::{Error, ErrorKind, Result};
use ppoe::se3::{self, Transform};
use ppoe::Vec6;
use serde_json::Value;

/// A row-major 4×4 homogeneous transform.
type Mat4 = [[f64; 4]; 4];

/// The calibration of a noise model (all zeros for a file without one).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Calibration {
    /// `calibration.estimated`: what the fit estimated (`"base"`, `"tip"`, `"offsets"`,
    /// `"kinematics"`); empty when the file has no `calibration` object.
    pub estimated: Vec<String>,
    /// δᵢ per joint (rad or m), base to tip; empty means none.
    pub offsets: Vec<f64>,
    /// κᵢ per joint (base-frame twists, rotation first), base to tip; empty means none.
    pub axis_corrections: Vec<[f64; 6]>,
    /// μ, the home correction (tip frame, right perturbation, rotation first).
    pub home_correction: [f64; 6],
}

fn config(msg: String) -> Error {
    Error::new(ErrorKind::Config, msg)
}

/// A finite number, or `None` when the field is absent (an explicit `null` is a wrong
/// type, not an absent field).
fn number(v: Option<&Value>, what: &dyn Fn() -> String) -> Result<Option<f64>> {
    let Some(v) = v else {
        return Ok(None);
    };
    match v.as_f64().filter(|x| x.is_finite()) {
        Some(x) => Ok(Some(x)),
        None => Err(config(format!("{}: expected a finite number", what()))),
    }
}

/// Six finite numbers, or `None` when the field is absent.
fn vector6(v: Option<&Value>, what: &dyn Fn() -> String) -> Result<Option<[f64; 6]>> {
    let Some(v) = v else {
        return Ok(None);
    };
    let bad = || config(format!("{}: expected an array of 6 finite numbers", what()));
    let items = v.as_array().filter(|a| a.len() == 6).ok_or_else(bad)?;
    let mut out = [0.0; 6];
    for (o, x) in out.iter_mut().zip(items) {
        *o = x.as_f64().filter(|x| x.is_finite()).ok_or_else(bad)?;
    }
    Ok(Some(out))
}

impl Calibration {
    /// Reads the calibration fields of a noise file's JSON `file` whose `joints` array is
    /// `joints` (already checked to be an array of objects with names `names`).
    ///
    /// # Errors
    /// [`ErrorKind::Config`] naming the joint and the field for an `offset` that is not a
    /// finite number, an `axis_correction` or a `home_correction` that is not 6 finite
    /// numbers, a `calibration` that is not an object or an `estimated` that is not an
    /// array of strings.
    pub(crate) fn parse(file: &Value, joints: &[Value], names: &[&str]) -> Result<Self> {
        let mut c = Calibration::default();
        let (mut any_offset, mut any_axis) = (false, false);
        for (i, (j, name)) in joints.iter().zip(names).enumerate() {
            let what = |field: &str| format!("noise model: joint {i} ('{name}') {field}");
            let offset = number(j.get("offset"), &|| what("offset"))?;
            any_offset |= offset.is_some();
            c.offsets.push(offset.unwrap_or(0.0));
            let axis = vector6(j.get("axis_correction"), &|| what("axis_correction"))?;
            any_axis |= axis.is_some();
            c.axis_corrections.push(axis.unwrap_or([0.0; 6]));
        }
        if !any_offset {
            c.offsets.clear();
        }
        if !any_axis {
            c.axis_corrections.clear();
        }
        let Some(cal) = file.get("calibration") else {
            return Ok(c);
        };
        let cal = cal
            .as_object()
            .ok_or_else(|| config("noise model: \"calibration\" is not an object".into()))?;
        if let Some(est) = cal.get("estimated") {
            let bad = || {
                config("noise model: calibration.estimated: expected an array of strings".into())
            };
            for e in est.as_array().ok_or_else(bad)? {
                c.estimated.push(e.as_str().ok_or_else(bad)?.to_string());
            }
        }
        let what = || "noise model: calibration.home_correction".to_string();
        if let Some(mu) = vector6(cal.get("home_correction"), &what)? {
            c.home_correction = mu;
        }
        Ok(c)
    }

    /// `true` if every offset and correction is zero (or absent): applying it changes
    /// nothing.
    pub fn is_identity(&self) -> bool {
        let zero = |x: &f64| *x == 0.0;
        self.offsets.iter().all(zero)
            && self.axis_corrections.iter().flatten().all(zero)
            && self.home_correction.iter().all(zero)
    }

    /// Checks the per-joint lists have one entry per joint of a chain of `n` joints (or
    /// none), for a calibration built by hand.
    fn check_len(&self, n: usize) -> Result<()> {
        for (len, what) in [
            (self.offsets.len(), "offsets"),
            (self.axis_corrections.len(), "axis corrections"),
        ] {
            if len != 0 && len != n {
                return Err(config(format!(
                    "the calibration has {len} {what}, the chain has {n} joints"
                )));
            }
        }
        Ok(())
    }

    /// `Fᵢ = E₁···Eᵢ` for i = 1..n with `Eᵢ = Exp(Sᵢ''·δᵢ)`: what the fold moves to the
    /// right of joint i. A link below joint i of the calibrated robot is at
    /// `Exp(S₁'θ₁)···Exp(Sᵢ'θᵢ)·Fᵢ·L` for its nominal home pose L, so pictures place the
    /// links (and [`RobotChain::home_frames`]) with these. Computed with the same
    /// operations as the core's fold, on [`RobotChain::to_core_joints`].
    ///
    /// # Errors
    /// [`ErrorKind::Config`] for lists of another length than the chain's joints,
    /// [`ErrorKind::NonFinite`] if a product is not finite.
    pub fn link_folds(&self, chain: &RobotChain) -> Result<Vec<Mat4>> {
        self.check_len(chain.joints.len())?;
        let joints = chain.to_core_joints();
        let mut p = Transform::<f64>::identity();
        let mut out = Vec::with_capacity(joints.len());
        for (i, j) in joints.iter().enumerate() {
            let s = match self.axis_corrections.get(i) {
                Some(k) => se3::exp(&Vec6::from(*k)).adjoint().mul_vec(&j.screw),
                None => j.screw,
            };
            let d = self.offsets.get(i).copied().unwrap_or(0.0);
            p = p * se3::exp(&(s * d));
            let m = p.to_matrix4();
            if m.iter().flatten().any(|x| !x.is_finite()) {
                return Err(non_finite(j.name));
            }
            out.push(m);
        }
        Ok(out)
    }

    /// The calibrated chain: `chain` with the calibration folded into its screws and home
    /// pose ([`ppoe::chain::fold_calibration`]) and its joints' home frames moved by
    /// [`Calibration::link_folds`]. An identity calibration ([`Calibration::is_identity`])
    /// returns `chain` unchanged, bit for bit.
    ///
    /// # Errors
    /// As [`Calibration::link_folds`], and the fold's errors ([`ErrorKind::NonFinite`]).
    pub fn apply(&self, chain: &RobotChain) -> Result<RobotChain> {
        if self.is_identity() {
            return Ok(chain.clone());
        }
        let folds = self.link_folds(chain)?;
        let mut joints = chain.to_core_joints();
        let mut home = chain.home_transform();
        let offsets = if self.offsets.is_empty() {
            vec![0.0; joints.len()]
        } else {
            self.offsets.clone()
        };
        let kappa: Vec<Vec6<f64>> = self
            .axis_corrections
            .iter()
            .map(|k| Vec6::from(*k))
            .collect();
        ppoe::chain::fold_calibration(
            &mut joints,
            &mut home,
            &offsets,
            &kappa,
            &Vec6::from(self.home_correction),
        )
        .map_err(|e| {
            Error::new(
                ErrorKind::NonFinite,
                format!("the calibration cannot be folded into the chain: {e}"),
            )
        })?;
        let mut out = chain.clone();
        for ((o, j), f) in out.joints.iter_mut().zip(&joints).zip(&folds) {
            o.screw = j.screw.0;
            o.home_frame =
                (Transform::from_matrix4(f) * Transform::from_matrix4(&o.home_frame)).to_matrix4();
        }
        out.home = home.to_matrix4();
        Ok(out)
    }
}

fn non_finite(joint: &str) -> Error {
    Error::new(
        ErrorKind::NonFinite,
        format!("the calibration of joint '{joint}' moves the chain beyond finite numbers"),
    )
}
