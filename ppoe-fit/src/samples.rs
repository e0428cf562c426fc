//! The samples: validation of the recorded joint values and measured poses, and what the
//! likelihood needs from each, computed once: the residual η = Log(T̄(θ)⁻¹·T_meas) and the
//! transports Ad(Gᵢ⁻¹) of every joint's noise to the tip frame.

use crate::error::FitError;
use nalgebra::{Matrix3, Matrix6, Vector6};
use ppoe::chain::Joint;
use ppoe::{se3, Mat3, Transform, Vec3};

/// How far a measured rotation may be from orthonormal (max |RᵀR − I|): trackers write
/// poses with 7–9 significant digits.
pub const RIGID_TOL: f64 = 1e-6;

/// One recorded sample: joint values and the tool pose measured by an external tracker.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// One value per joint (rad or m), base to tip, as the robot's encoders read them.
    pub thetas: Vec<f64>,
    /// The measured pose of the tip in the base frame, 4×4 row-major.
    pub pose: [[f64; 4]; 4],
}

/// What the likelihood needs from the samples.
pub(crate) struct Prepared {
    /// Per sample: η = Log(T̄⁻¹·T_meas) (tip frame, rotation first).
    pub eta: Vec<Vector6<f64>>,
    /// Per sample, per joint: Ad(Gᵢ⁻¹), Gᵢ = Dᵢ₊₁…Dₙ·M (the PPOE's transport).
    pub transports: Vec<Vec<Matrix6<f64>>>,
    /// The screw axes Sᵢ (base frame, rotation first).
    pub screws: Vec<Vector6<f64>>,
    /// How many samples had a joint value outside its limits (clipped like the PPOE).
    pub clipped: usize,
}

pub(crate) fn to_na(m: &ppoe::Mat6<f64>) -> Matrix6<f64> {
    Matrix6::from_fn(|r, c| m.0[r][c])
}

/// The measured pose as a transform with its rotation made exactly orthonormal (nearest
/// rotation), after checking it is rigid within [`RIGID_TOL`].
pub(crate) fn rigid(index: usize, m: &[[f64; 4]; 4]) -> Result<Transform<f64>, FitError> {
    if let Some((r, c)) = (0..16)
        .map(|k| (k / 4, k % 4))
        .find(|&(r, c)| !m[r][c].is_finite())
    {
        return Err(FitError::NonFinite {
            sample: index,
            what: format!("pose[{r}][{c}]"),
        });
    }
    let not = |why: String| FitError::NotRigid { sample: index, why };
    let last = m[3];
    if (last[0].abs() + last[1].abs() + last[2].abs() + (last[3] - 1.0).abs()) > RIGID_TOL {
        return Err(not(format!("last row {last:?} is not [0, 0, 0, 1]")));
    }
    let r = Matrix3::from_fn(|i, j| m[i][j]);
    let dev = (r.transpose() * r - Matrix3::identity()).amax();
    if dev > RIGID_TOL {
        return Err(not(format!(
            "RᵀR differs from I by {dev:.2e} (tolerance 1e-6)"
        )));
    }
    if r.determinant() <= 0.0 {
        return Err(not(
            "the rotation part has determinant ≤ 0 (a reflection)".into()
        ));
    }
    let svd = r.svd(true, true);
    let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
        return Err(not("the rotation part could not be orthonormalised".into()));
    };
    let q = u * vt;
    Ok(Transform {
        rotation: Mat3::from(std::array::from_fn(|i| std::array::from_fn(|j| q[(i, j)]))),
        translation: Vec3::from([m[0][3], m[1][3], m[2][3]]),
    })
}

/// The transports Ad(Gᵢ⁻¹) at joint values `thetas` (clipped to the limits like the
/// PPOE), the mean pose T̄(θ) and whether a value was clipped.
pub(crate) fn transports(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    thetas: &[f64],
) -> (Vec<Matrix6<f64>>, Transform<f64>, bool) {
    let mut g = *home;
    let mut ads = vec![Matrix6::zeros(); joints.len()];
    let mut clipped = false;
    for ((j, t), ad) in joints.iter().zip(thetas).zip(ads.iter_mut()).rev() {
        *ad = to_na(&g.inverse().adjoint());
        let c = j.clip(*t, false);
        clipped |= c != *t;
        g = j.displacement(c) * g;
    }
    (ads, g, clipped)
}

/// Sample `k`'s joint values: one per joint, finite.
pub(crate) fn check_thetas(
    k: usize,
    thetas: &[f64],
    joints: &[Joint<f64>],
) -> Result<(), FitError> {
    if thetas.len() != joints.len() {
        return Err(FitError::WrongLength {
            sample: k,
            got: thetas.len(),
            expected: joints.len(),
        });
    }
    if let Some(i) = thetas.iter().position(|t| !t.is_finite()) {
        let name = joints[i].name;
        return Err(FitError::NonFinite {
            sample: k,
            what: format!("the value of joint {i} ('{name}')"),
        });
    }
    Ok(())
}

/// Validates every sample and computes η and the transports.
pub(crate) fn prepare(
    joints: &[Joint<f64>],
    home: &Transform<f64>,
    samples: &[Sample],
) -> Result<Prepared, FitError> {
    let mut out = Prepared {
        eta: Vec::with_capacity(samples.len()),
        transports: Vec::with_capacity(samples.len()),
        screws: joints
            .iter()
            .map(|j| Vector6::from_fn(|r, _| j.screw.0[r]))
            .collect(),
        clipped: 0,
    };
    for (k, s) in samples.iter().enumerate() {
        check_thetas(k, &s.thetas, joints)?;
        let measured = rigid(k, &s.pose)?;
        let (ads, g, clipped) = transports(joints, home, &s.thetas);
        out.clipped += usize::from(clipped);
        let eta = se3::log(&(g.inverse() * measured));
        if !eta.is_finite() {
            return Err(FitError::NonFinite {
                sample: k,
                what: "the residual Log(T̄⁻¹·T_meas)".into(),
            });
        }
        out.eta.push(Vector6::from_fn(|r, _| eta.0[r]));
        out.transports.push(ads);
    }
    Ok(out)
}
