"""A pose and its covariance as ROS's ``geometry_msgs/PoseWithCovariance`` wants them."""

from . import _ppoe
from ._checks import as_f64, transform


def to_ros_pose_with_covariance(pose, cov, convention="right"):
    """The fields of a ``geometry_msgs/PoseWithCovariance``.

    ROS orders the covariance **translation first**, ``(x, y, z, rotX, rotY, rotZ)``, and
    means it in the parent frame (``header.frame_id``, the robot's base): to first order
    ``p = pbar + dp``, ``R = Exp(dtheta) Rbar`` with ``(dp, dtheta)`` in that frame. ppoe's
    covariances are rotation first, so this is a permutation *and* a change of frame.

    Parameters
    ----------
    pose : array-like, shape (4, 4)
        The mean pose (tip in base).
    cov : array-like, shape (6, 6)
        Its covariance, rotation first.
    convention : {"right", "left"}, optional (default: "right")
        Which perturbation ``cov`` belongs to: ``T = Tbar Exp(eta)`` (the PPOE's default)
        or ``T = Exp(eta) Tbar``. pytransform3d's example covariance is neither and is
        rejected.

    Returns
    -------
    msg : dict
        ``position`` (x, y, z), ``orientation`` (x, y, z, w) -- ROS's quaternion order --
        and ``covariance``, 36 floats row-major, translation first.

    Raises
    ------
    ValueError
        For an invalid pose, covariance or convention.
    """
    t = transform(pose, "pose")
    c = as_f64(cov, "cov", (6, 6))
    (w, x, y, z), ros_cov = _ppoe.ros_pose_with_covariance(t, c, str(convention))
    return {
        "position": t[:3, 3].copy(),
        "orientation": (x, y, z, w),
        "covariance": ros_cov.reshape(36),
    }
