"""Writes the ppoe fit datasets of this directory (run from the repository root with the
ppoe Python package installed; the numbers are rounded to 9 significant digits, as a
tracker writes them, so that every JSON reader parses them to the same doubles):

* seed_joint.json: 300 tool poses of the seed robot (linkmount -> tcp), each joint's
  value perturbed by N(0, sigma_i^2), sigma_i^2 = (1, 2, 3, 1, 2, 3) * 1e-4 rad^2.
* seed_position.json: 300 marker positions in a tracker's frame (the base 2 m away and
  turned, the marker 5 cm off the tool), joints perturbed by 1e-6 rad^2, tracker noise
  0.2 mm per axis, with its "measurement_cov".

The *.fit.json files beside them are what `ppoe fit` wrote for them (see README.md).
"""

import json

import numpy as np

import ppoe


def rounded(a):
    return [float(f"{x:.9g}") for x in np.ravel(a)]


def main():
    urdf = open("test_data/urdf/seed.urdf").read()
    robot = ppoe.ProbabilisticRobotKinematics(urdf, "tcp", "linkmount", None)
    rng = np.random.default_rng(20261204)
    lim = np.clip(robot.joint_limits, -3.0, 3.0)
    n, count = robot.n_joints, 300
    # 0.8 of the range: the perturbed values stay inside the limits (no clipping).
    thetas = rng.uniform(0.8 * lim[:, 0], 0.8 * lim[:, 1], (count, n))
    s2 = np.array([1.0, 2.0, 3.0, 1.0, 2.0, 3.0]) * 1e-4
    poses = robot.forward_kinematics(thetas + rng.normal(0.0, np.sqrt(s2), (count, n)))
    samples = [
        {"thetas": rounded(t), "pose": np.reshape(rounded(p), (4, 4)).tolist()}
        for t, p in zip(thetas, poses)
    ]
    with open("test_data/fit/seed_joint.json", "w") as f:
        json.dump({"samples": samples}, f)
    c, s = np.cos(0.4), np.sin(0.4)
    x = np.array([[c, -s, 0, 2.0], [s, c, 0, -0.5], [0, 0, 1, 0.3], [0, 0, 0, 1]])
    marker = np.array([0.05, 0.0, 0.02, 1.0])
    thetas = rng.uniform(0.8 * lim[:, 0], 0.8 * lim[:, 1], (count, n))
    poses = robot.forward_kinematics(thetas + rng.normal(0.0, 1e-3, (count, n)))
    points = (x @ poses @ marker)[:, :3] + rng.normal(0.0, 2e-4, (count, 3))
    samples = [{"thetas": rounded(t), "position": rounded(p)} for t, p in zip(thetas, points)]
    r = (4e-8 * np.eye(3)).tolist()
    with open("test_data/fit/seed_position.json", "w") as f:
        json.dump({"samples": samples, "measurement_cov": r}, f)


if __name__ == "__main__":
    main()
