//! Calibrated kinematics folded into a chain: joint zero offsets, corrections of each
//! joint's axis and of the home pose, applied to the screw axes and the home pose
//! exactly, so a calibrated robot is an ordinary chain (no new field, no run-time cost).
//!
//! The calibrated product is `Exp(S₁''·(θ₁+δ₁))···Exp(Sₙ''·(θₙ+δₙ))·M·Exp(μ)` with
//! `Sᵢ'' = Ad(Exp(κᵢ))·Sᵢ` (κᵢ: joint i's axis correction, a base-frame twist, left
//! perturbation of the axis; rotation first) and μ the home correction (tip frame, right
//! perturbation). Moving `Eᵢ = Exp(Sᵢ''·δᵢ)` to the right through the later joints
//! changes their screws by an adjoint: with `Pᵢ = E₁···Eᵢ₋₁`,
//! `Exp(Sᵢ''θᵢ)·Eᵢ = …` gives the folded chain `Exp(S₁'θ₁)···Exp(Sₙ'θₙ)·M'` with
//! `Sᵢ' = Ad(Pᵢ)·Sᵢ''` and `M' = E₁···Eₙ·M·Exp(μ)`, for every θ.
//!
//! # Accuracy
//! Exact algebra; rounding of a few ε per adjoint product, growing with the number of
//! joints and with the size of the offsets (an offset of δ moves the later screws' moment
//! parts by up to ‖Sᵢ''‖·|δ|·(arm length)). The crate's tests compare the folded chain's
//! forward kinematics with the unfolded product at random configurations.
//!
//! ```
//! use ppoe::chain::{fold_calibration, Chain, Joint, JointKind};
//! use ppoe::{Transform, Vec6};
//! const INF: f64 = f64::INFINITY;
//! let mut joints = [
//!     Joint::new("a", JointKind::Revolute, [0., 0., 1., 0., 0., 0.], -INF, INF),
//!     Joint::new("b", JointKind::Revolute, [0., 1., 0., 0., 0., 0.5], -INF, INF),
//! ];
//! let nominal = joints;
//! let mut home = Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0.5, 0., 0.]);
//! let offsets = [1e-3, -2e-3];
//! fold_calibration(&mut joints, &mut home, &offsets, &[], &Vec6::zeros()).unwrap();
//! // The folded chain at θ is the nominal chain at θ + δ.
//! let folded = Chain::new("base", "tip", joints, home);
//! let nominal_home =
//!     Transform::from_parts([[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]], [0.5, 0., 0.]);
//! let unfolded = Chain::new("base", "tip", nominal, nominal_home);
//! let (t, d) = ([0.3, -0.7], [0.3 + 1e-3, -0.7 - 2e-3]);
//! let (a, b) = (folded.forward_kinematics(&t), unfolded.forward_kinematics(&d));
//! assert!((a.translation - b.translation).norm() < 1e-15);
//! ```

use crate::error::Error;
use crate::joint::Joint;
use crate::linalg::Vec6;
use crate::scalar::Real;
use crate::se3::{self, Transform};

/// Folds joint zero offsets `offsets` (δᵢ, rad or m, one per joint), axis corrections
/// `axis_corrections` (κᵢ, base-frame twists, rotation first, one per joint, or empty for
/// none) and the home correction `home_correction` (μ, tip frame, right perturbation)
/// into `joints`' screw axes and `home`, as the module docs derive; each joint is
/// [`Joint::prepared`] again. On error nothing is changed.
///
/// # Errors
/// [`Error::LengthMismatch`] if `offsets` (or a non-empty `axis_corrections`) does not
/// have one entry per joint; [`Error::NonFinite`] if an input or a folded value is not
/// finite.
pub fn fold_calibration<T: Real>(
    joints: &mut [Joint<T>],
    home: &mut Transform<T>,
    offsets: &[T],
    axis_corrections: &[Vec6<T>],
    home_correction: &Vec6<T>,
) -> Result<(), Error> {
    let n = joints.len();
    let corrected = !axis_corrections.is_empty();
    if offsets.len() != n || (corrected && axis_corrections.len() != n) {
        return Err(Error::LengthMismatch);
    }
    let finite = offsets.iter().all(|d| d.is_finite())
        && axis_corrections.iter().all(Vec6::is_finite)
        && home_correction.is_finite();
    if !finite {
        return Err(Error::NonFinite);
    }
    // Joint i's corrected screw Sᵢ'' and folded screw Sᵢ' = Ad(Pᵢ)·Sᵢ''.
    let screws = |i: usize, joints: &[Joint<T>], p: &Transform<T>| -> (Vec6<T>, Vec6<T>) {
        let s = match axis_corrections.get(i) {
            Some(k) => se3::exp(k).adjoint().mul_vec(&joints[i].screw),
            None => joints[i].screw,
        };
        (s, p.adjoint().mul_vec(&s))
    };
    // First pass: every folded value checked before any is written (nothing changes on
    // error). Pᵢ₊₁ = Pᵢ·Exp(Sᵢ''·δᵢ).
    let mut p = Transform::identity();
    for (i, d) in offsets.iter().enumerate() {
        let (s, folded) = screws(i, joints, &p);
        if !folded.is_finite() {
            return Err(Error::NonFinite);
        }
        p = p * se3::exp(&(s * *d));
    }
    let new_home = p * *home * se3::exp(home_correction);
    if !new_home.translation.is_finite() || !new_home.rotation.is_finite() {
        return Err(Error::NonFinite);
    }
    let mut p = Transform::identity();
    for (i, d) in offsets.iter().enumerate() {
        let (s, folded) = screws(i, joints, &p);
        p = p * se3::exp(&(s * *d));
        joints[i].screw = folded;
        joints[i] = joints[i].prepared();
    }
    *home = new_home;
    Ok(())
}
