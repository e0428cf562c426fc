"""``to_ros_pose_with_covariance`` against the first-order perturbation written out in
numpy (and scipy's quaternion)."""

import numpy as np
import pytest
import pytransform3d.transformations as pt
from scipy.spatial.transform import Rotation

import ppoe


def skew(p):
    return np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])


def translation_first(c):
    return np.block([[c[3:, 3:], c[3:, :3]], [c[:3, 3:], c[:3, :3]]])


def test_right_and_left_against_the_perturbation_maps():
    rng = np.random.default_rng(11)
    for _ in range(50):
        pose = pt.random_transform(rng)
        a = rng.standard_normal((6, 6))
        cov = a @ a.T
        r, p = pose[:3, :3], pose[:3, 3]
        z = np.zeros((3, 3))
        # right: dtheta = R w, dp = R v; left: dtheta = w, dp = v + w x p = v - [p]x w
        right = np.block([[r, z], [z, r]])
        left = np.block([[np.eye(3), z], [-skew(p), np.eye(3)]])
        for conv, g in (("right", right), ("left", left)):
            msg = ppoe.to_ros_pose_with_covariance(pose, cov, conv)
            want = translation_first(g @ cov @ g.T).reshape(36)
            assert np.max(np.abs(msg["covariance"] - want)) <= 1e-12 * max(1.0, np.abs(want).max())
            np.testing.assert_array_equal(msg["position"], p)
            q = np.array(msg["orientation"])
            ref = Rotation.from_matrix(r).as_quat()  # x, y, z, w
            assert min(np.abs(q - ref).max(), np.abs(q + ref).max()) <= 1e-12


def test_pytransform3d_convention_is_rejected():
    with pytest.raises(ValueError, match="neither"):
        ppoe.to_ros_pose_with_covariance(np.eye(4), np.eye(6), "pytransform3d")
