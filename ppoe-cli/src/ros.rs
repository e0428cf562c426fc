//! `ppoe eval --format ros`: each result as a ROS `geometry_msgs/PoseWithCovariance`,
//! `{"pose": {"position": {x, y, z}, "orientation": {x, y, z, w}}, "covariance": [36]}`.
//!
//! The covariance is ROS's: translation first, `(x, y, z, rotX, rotY, rotZ)`, row-major,
//! in the **parent frame** (`header.frame_id`, the chain's base link), converted by the
//! core ([`ppoe::interop::ros`], whose module docs give the first-order perturbation
//! convention) from the right (`--convention ppoe`) or left (`--convention left`)
//! covariance. The quaternion is the rotation's (Hamilton, written x, y, z, w as ROS
//! orders it).

use crate::args::ConventionArg;
use crate::eval::{ChainOut, Output};
use anyhow::{anyhow, bail};
use ppoe::interop::ros::{ros_from_left, ros_from_right};
use ppoe::{Mat6, Transform};
use serde::Serialize;

/// The output of `ppoe eval --format ros`: the chain as in the JSON format (its `base` is
/// the messages' `header.frame_id`) and one message per case.
#[derive(Serialize, Debug)]
pub struct RosOutput {
    /// The chain the cases were evaluated on.
    pub chain: ChainOut,
    /// One `PoseWithCovariance` per case.
    pub results: Vec<PoseWithCovariance>,
}

/// `geometry_msgs/PoseWithCovariance`.
#[derive(Serialize, Debug)]
pub struct PoseWithCovariance {
    /// The mean pose.
    pub pose: Pose,
    /// 6×6 row-major, translation first, parent frame.
    pub covariance: Vec<f64>,
}

/// `geometry_msgs/Pose`.
#[derive(Serialize, Debug)]
pub struct Pose {
    /// `geometry_msgs/Point`.
    pub position: Point,
    /// `geometry_msgs/Quaternion`.
    pub orientation: Quaternion,
}

/// `geometry_msgs/Point`.
#[derive(Serialize, Debug)]
pub struct Point {
    /// x (m).
    pub x: f64,
    /// y (m).
    pub y: f64,
    /// z (m).
    pub z: f64,
}

/// `geometry_msgs/Quaternion` (x, y, z vector part, w scalar part).
#[derive(Serialize, Debug)]
pub struct Quaternion {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
    /// w.
    pub w: f64,
}

/// The results of `eval` as ROS messages; `convention` is the one they were computed in.
///
/// # Errors
/// `--convention pytransform3d` (its covariance is not a perturbation of the returned
/// pose, so ROS's has no meaning for it); a pose whose rotation is not one.
pub fn ros_output(out: Output, convention: ConventionArg) -> anyhow::Result<RosOutput> {
    if convention == ConventionArg::Pytransform3d {
        bail!(
            "--format ros needs --convention ppoe or left: pytransform3d's covariance is not \
             a perturbation of the returned pose"
        );
    }
    let mut results = Vec::with_capacity(out.results.len());
    for (i, r) in out.results.iter().enumerate() {
        let pose = Transform::from_matrix4(&r.pose);
        let cov = Mat6::from(r.cov);
        let ros = match convention {
            ConventionArg::Left => ros_from_left(&pose, &cov),
            _ => ros_from_right(&pose, &cov),
        };
        let [w, x, y, z] = pose
            .quaternion()
            .map_err(|e| anyhow!("case {i}: the pose's rotation: {e}"))?;
        let [px, py, pz] = pose.translation.0;
        results.push(PoseWithCovariance {
            pose: Pose {
                position: Point {
                    x: px,
                    y: py,
                    z: pz,
                },
                orientation: Quaternion { x, y, z, w },
            },
            covariance: ros.0.iter().flatten().copied().collect(),
        });
    }
    Ok(RosOutput {
        chain: out.chain,
        results,
    })
}
