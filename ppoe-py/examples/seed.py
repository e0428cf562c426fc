"""The seed example (pytransform3d's "Probabilistic Product of Exponentials") with ppoe.

The robot of the repository's test_data/urdf/seed.urdf, base ``linkmount``, tip ``tcp``,
six revolute joints; a variance of 0.05 rad^2 on joint 1's rotation about z and on the
rotations about y of joints 2, 3 and 5; joint values -0.5 * (1, 1, 1, 0, 1, 0).

Prints the tip pose T and its covariance in pytransform3d's convention (the example's
numbers) and in ppoe's default, the right perturbation ``T = Tbar Exp(eta)``; then the
example's surface, ``to_projected_ellipsoid(T, cov, factor=1, n_steps=50)``, and the
200-frame animation's poses as one batch call.

Run: python ppoe-py/examples/seed.py [path/to/seed.urdf]
"""

import os
import sys

import numpy as np

import ppoe
import ppoe.uncertainty as pu

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_URDF = os.path.join(HERE, "..", "..", "test_data", "urdf", "seed.urdf")


def seed_covs():
    covs = np.zeros((6, 6, 6))
    covs[0] = np.diag([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    covs[1] = covs[2] = covs[4] = np.diag([0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    return covs * 0.05


def main(urdf_path=DEFAULT_URDF):
    """Returns (T, cov) of the example in pytransform3d's convention."""
    with open(urdf_path) as f:
        urdf = f.read()
    joints = [f"joint{i}" for i in range(1, 7)]
    thetas = np.array([1, 1, 1, 0, 1, 0])
    covs = seed_covs()
    compat = ppoe.ProbabilisticRobotKinematics(urdf, "tcp", "linkmount", joints, convention="pytransform3d")
    T, cov = compat.probabilistic_forward_kinematics(-0.5 * thetas, covs)
    np.set_printoptions(precision=6, suppress=False, linewidth=110)
    print("T (tip in base):\n", T)
    print("cov, pytransform3d's convention:\n", cov)
    right = ppoe.ProbabilisticRobotKinematics(urdf, "tcp", "linkmount", joints)
    print("cov, right perturbation (ppoe's default):\n", right.probabilistic_forward_kinematics(-0.5 * thetas, covs)[1])
    x, y, z = pu.to_projected_ellipsoid(T, cov, factor=1.0, n_steps=50)
    print("projected ellipsoid: grid", x.shape, "x from %.4f to %.4f" % (x.min(), x.max()))
    # The example's animation: 200 frames, all in one call (GIL released).
    angles = 0.5 * np.cos(2.0 * np.pi * (0.5 + np.arange(200) / 200.0))
    poses, cov_frames = compat.probabilistic_forward_kinematics(angles[:, np.newaxis] * thetas, covs)
    print("animation:", poses.shape, cov_frames.shape, "frame 0 equals the initial state:",
          bool(np.array_equal(poses[0], T) and np.array_equal(cov_frames[0], cov)))
    return T, cov


if __name__ == "__main__":
    main(*sys.argv[1:])
