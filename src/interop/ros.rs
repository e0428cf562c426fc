//! ROS's `geometry_msgs/PoseWithCovariance`: its covariance order and its frame.
//!
//! **Order.** ROS orders the 6×6 covariance (row-major, 36 numbers) **translation first**:
//! `(x, y, z, rotX, rotY, rotZ)`. ppoe is rotation first: `(ω, v)`. [`to_ros_order`] and
//! [`from_ros_order`] swap the two 3×3 block rows and columns: a pure permutation, exact.
//!
//! **Frame.** A permutation alone is right only if the perturbation means the same thing.
//! The message documents the rotation part as rotations about the *fixed* axes X, Y, Z;
//! here it is read as the first-order perturbation of the pose in the message's
//! `header.frame_id` (the parent frame, ppoe's base frame):
//! `p = p̄ + δp`, `R = Exp(δθ)·R̄`, with `(δp, δθ)` in the parent frame. In those terms,
//! to first order:
//! * ppoe's **right** perturbation `T = T̄·Exp(η)` (η = (ω, v) in the tip frame,
//!   [`Convention::Right`](crate::chain::Convention::Right), the PPOE's default) gives
//!   `δθ = R̄·ω`, `δp = R̄·v`: the ROS covariance is the right covariance rotated into the
//!   parent frame and permuted ([`ros_from_right`]).
//! * ppoe's **left** perturbation `T = Exp(η)·T̄` (η in the base frame,
//!   [`Convention::Left`](crate::chain::Convention::Left)) gives `δθ = ω`,
//!   `δp = v + ω × p̄`: not a permutation either, because the left twist's translation
//!   part is not the displacement of the origin ([`ros_from_left`]).
//! * A covariance meant in the child (tip) frame, `δθ, δp` in the tip frame, is the right
//!   covariance permuted ([`to_ros_order`] of it).
//!
//! Tools that treat the rotation block as variances of roll, pitch and yaw angles agree
//! with this reading only to first order and only near zero roll and pitch.
//!
//! None of these functions check their input (use
//! [`check_covariance`](crate::uncertainty::check_covariance)): they are linear maps,
//! exact up to rounding, and a symmetric input gives an exactly symmetric output.

use crate::linalg::{Mat3, Mat6};
use crate::scalar::Real;
use crate::se3::Transform;
use crate::so3;

/// A ppoe covariance (rotation first) in ROS's order (translation first): the 3×3 blocks
/// swapped, `out[i][j] = cov[(i + 3) % 6][(j + 3) % 6]`. Its own inverse.
///
/// ```
/// use ppoe::interop::ros::to_ros_order;
/// use ppoe::{Mat6, Vector};
/// // Rotation variance 1, translation variance 2 (ppoe order) ...
/// let cov = Mat6::from_diagonal(&Vector([1.0, 1.0, 1.0, 2.0, 2.0, 2.0]));
/// // ... is translation variance 2 first in ROS's order.
/// assert_eq!(to_ros_order(&cov).diagonal().0, [2.0, 2.0, 2.0, 1.0, 1.0, 1.0]);
/// ```
pub fn to_ros_order<T: Real>(cov: &Mat6<T>) -> Mat6<T> {
    let mut out = Mat6::zeros();
    for (i, row) in out.0.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = cov.0[(i + 3) % 6][(j + 3) % 6];
        }
    }
    out
}

/// A ROS covariance (translation first) in ppoe's order (rotation first): the inverse of
/// [`to_ros_order`], which is the same permutation.
///
/// ```
/// use ppoe::interop::ros::{from_ros_order, to_ros_order};
/// use ppoe::Mat6;
/// let mut cov = Mat6::<f64>::identity();
/// cov.0[0][4] = 0.5;
/// cov.0[4][0] = 0.5;
/// assert_eq!(from_ros_order(&to_ros_order(&cov)), cov);
/// ```
pub fn from_ros_order<T: Real>(cov: &Mat6<T>) -> Mat6<T> {
    to_ros_order(cov)
}

/// The ROS covariance (translation first, parent frame; see the module docs) of a pose
/// `mean` whose **right** perturbation has covariance `cov` (ppoe order, tip frame):
/// `A·Σ·Aᵀ` with `A = [[0, R̄], [R̄, 0]]`.
///
/// # Accuracy
/// Exact up to rounding as a linear map; it is the first-order relation between the two
/// perturbations (tested against finite differences of `T̄·Exp(η)`).
///
/// ```
/// use ppoe::interop::ros::ros_from_right;
/// use ppoe::{Mat6, Transform, Vector};
/// // Tip turned 90° about z: a tip-frame x variance of 4 is a parent-frame y variance.
/// let pose = Transform::from_rpy(&[0.0, 0.0, core::f64::consts::FRAC_PI_2], [1.0, 0.0, 0.0])?;
/// let right = Mat6::from_diagonal(&Vector([0.0, 0.0, 0.0, 4.0, 0.0, 0.0]));
/// let ros = ros_from_right(&pose, &right);
/// assert!((ros.0[1][1] - 4.0).abs() < 1e-12 && ros.0[0][0].abs() < 1e-12);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn ros_from_right<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Mat6<T> {
    let (r, z) = (mean.rotation, Mat3::zeros());
    cov.congruence(&Mat6::from_blocks(&z, &r, &r, &z))
}

/// The **right** covariance (ppoe order, tip frame) of a pose `mean` from its ROS
/// covariance `cov_ros` (translation first, parent frame): the inverse of
/// [`ros_from_right`], `A⁻¹ = [[0, R̄ᵀ], [R̄ᵀ, 0]]`.
///
/// # Accuracy
/// Exact up to rounding as a linear map (first order in the perturbation).
///
/// ```
/// use ppoe::interop::ros::{right_from_ros, ros_from_right};
/// use ppoe::{Mat6, Transform};
/// let pose = Transform::from_rpy(&[0.1, 0.2, 0.3], [1.0, 2.0, 3.0])?;
/// let cov = Mat6::<f64>::identity().scale(1e-4);
/// let back = right_from_ros(&pose, &ros_from_right(&pose, &cov));
/// assert!((back - cov).amax() < 1e-18);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn right_from_ros<T: Real>(mean: &Transform<T>, cov_ros: &Mat6<T>) -> Mat6<T> {
    let (rt, z) = (mean.rotation.transpose(), Mat3::zeros());
    cov_ros.congruence(&Mat6::from_blocks(&z, &rt, &rt, &z))
}

/// The ROS covariance (translation first, parent frame) of a pose `mean` whose **left**
/// perturbation has covariance `cov` (ppoe order, base frame): `A·Σ·Aᵀ` with
/// `A = [[−[p̄]×, I], [I, 0]]` (`δp = v + ω × p̄`, `δθ = ω`).
///
/// # Accuracy
/// Exact up to rounding as a linear map; first order in the perturbation (tested against
/// finite differences of `Exp(η)·T̄`).
///
/// ```
/// use ppoe::interop::ros::ros_from_left;
/// use ppoe::{Mat6, Transform, Vector};
/// // A yaw variance of a pose 2 m along x moves its origin along y: variance 4·σ².
/// let pose = Transform::<f64>::from_rpy(&[0.0; 3], [2.0, 0.0, 0.0])?;
/// let left = Mat6::from_diagonal(&Vector([0.0, 0.0, 1e-4, 0.0, 0.0, 0.0]));
/// let ros = ros_from_left(&pose, &left);
/// assert!((ros.0[1][1] - 4e-4).abs() < 1e-18 && (ros.0[5][5] - 1e-4).abs() < 1e-18);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn ros_from_left<T: Real>(mean: &Transform<T>, cov: &Mat6<T>) -> Mat6<T> {
    let (i, z) = (Mat3::identity(), Mat3::zeros());
    let minus_px = so3::hat(&mean.translation).scale(-T::ONE);
    cov.congruence(&Mat6::from_blocks(&minus_px, &i, &i, &z))
}

/// The **left** covariance (ppoe order, base frame) of a pose `mean` from its ROS
/// covariance `cov_ros`: the inverse of [`ros_from_left`],
/// `A⁻¹ = [[0, I], [I, [p̄]×]]` (`ω = δθ`, `v = δp − δθ × p̄`).
///
/// # Accuracy
/// Exact up to rounding as a linear map (first order in the perturbation).
///
/// ```
/// use ppoe::interop::ros::{left_from_ros, ros_from_left};
/// use ppoe::{Mat6, Transform};
/// let pose = Transform::from_rpy(&[0.1, 0.2, 0.3], [1.0, 2.0, 3.0])?;
/// let cov = Mat6::<f64>::identity().scale(1e-4);
/// let back = left_from_ros(&pose, &ros_from_left(&pose, &cov));
/// assert!((back - cov).amax() < 1e-17);
/// # Ok::<(), ppoe::Error>(())
/// ```
pub fn left_from_ros<T: Real>(mean: &Transform<T>, cov_ros: &Mat6<T>) -> Mat6<T> {
    let (i, z) = (Mat3::identity(), Mat3::zeros());
    let px = so3::hat(&mean.translation);
    cov_ros.congruence(&Mat6::from_blocks(&z, &i, &i, &px))
}
