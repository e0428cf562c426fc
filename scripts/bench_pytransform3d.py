#!/usr/bin/env python3
"""Times the pytransform3d baselines of BENCHMARKS.md; prints µs per call as JSON.

Inputs are those of benches/ops.rs: the seed robot (test_data/urdf/seed.urdf, base
``linkmount``, tip ``tcp``) in its initial state, thetas = (-0.5, -0.5, -0.5, 0, -0.5, 0),
joint covariances diag 0.05 on entry 2 (joint 1) and on entry 1 (joints 2, 3, 5), zero
otherwise.

Timed:

* ``example_ppoe``: the ``probabilistic_forward_kinematics`` of pytransform3d 3.17.0's
  example "Probabilistic Product of Exponentials", re-implemented exactly as
  test_data/reference/generate_ppoe.py does (``ProbabilisticChain.evaluate`` without the
  extra right/left covariances the generator adds): ``np.clip``, batch exponential
  ``ptr.transforms_from_exponential_coordinates``, ``pu.concat_locally_uncertain_transforms``
  per joint, ``T.M`` and ``Ad(M) C Ad(M)^T``;
* ``to_projected_ellipsoid_n50`` / ``_n20``: ``pu.to_projected_ellipsoid(pose, cov,
  factor=1, n_steps)`` on that PPOE's result (right-perturbation covariance, as the Rust
  bench);
* ``lean_numpy_ppoe``: the same PPOE written directly in numpy (4x4 and 6x6 arrays, no
  input validation, no pytransform3d calls), checked to agree with the example.

Each figure is the median over 7 repeats of the mean time per call of a loop sized to last
>= 0.2 s (timeit's autorange). Environment: test_data/reference/requirements.txt.

Usage: python scripts/bench_pytransform3d.py [--quick]
"""

import json
import math
import os
import platform
import statistics
import sys
import timeit

import numpy as np
import pytransform3d
import pytransform3d.trajectories as ptr
import pytransform3d.transformations as pt
import pytransform3d.uncertainty as pu
from pytransform3d.urdf import UrdfTransformManager

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "test_data", "reference"))

# The example's class and the path helper, exactly as the golden generator has them.
from generate_ppoe import ProbabilisticChain, moving_joints_on_path  # noqa: E402


def seed_chain():
    with open(os.path.join(ROOT, "test_data", "urdf", "seed.urdf"), encoding="utf-8") as f:
        xml = f.read()
    probe = UrdfTransformManager(check=False)
    probe.load_urdf(xml)
    joints = moving_joints_on_path(probe, "linkmount", "tcp")
    return ProbabilisticChain(xml, "tcp", "linkmount", joints)


def seed_inputs():
    thetas = np.array([-0.5, -0.5, -0.5, 0.0, -0.5, 0.0])
    covs = np.zeros((6, 6, 6))
    covs[0, 2, 2] = 0.05
    for i in (1, 2, 4):
        covs[i, 1, 1] = 0.05
    return thetas, covs


def probabilistic_forward_kinematics(chain, thetas, covs):
    """The example's method (generate_ppoe.py's ``evaluate`` up to ``cov_compat``)."""
    thetas = np.clip(thetas, chain.limits[:, 0], chain.limits[:, 1])
    exp_coords = chain.screw_axes * thetas[:, np.newaxis]
    displacements = ptr.transforms_from_exponential_coordinates(exp_coords)
    pose = np.eye(4)
    cov = np.zeros((6, 6))
    for i in range(len(thetas)):
        pose, cov = pu.concat_locally_uncertain_transforms(
            displacements[i], pose, covs[i], cov
        )
    pose = pose.dot(chain.home)
    ad_home = pt.adjoint_from_transform(chain.home)
    return pose, ad_home.dot(cov).dot(ad_home.T)


def _adj(t):
    r, p = t[:3, :3], t[:3, 3]
    px = np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])
    a = np.zeros((6, 6))
    a[:3, :3] = r
    a[3:, 3:] = r
    a[3:, :3] = px @ r
    return a


def _inv(t):
    out = np.eye(4)
    rt = t[:3, :3].T
    out[:3, :3] = rt
    out[:3, 3] = -rt @ t[:3, 3]
    return out


def lean_ppoe(screws, limits, home, ad_home, thetas, covs):
    """The same PPOE in plain numpy: no validation, dense 4x4 / 6x6 arrays."""
    th = np.clip(thetas, limits[:, 0], limits[:, 1])
    pose = np.eye(4)
    cov = np.zeros((6, 6))
    for i in range(len(th)):
        w = screws[i, :3] * th[i]
        v = screws[i, 3:] * th[i]
        a = math.sqrt(w @ w)
        d = np.eye(4)
        if a == 0.0:
            d[:3, 3] = v
        else:
            k = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]]) / a
            k2 = k @ k
            s, c = math.sin(a), math.cos(a)
            d[:3, :3] = np.eye(3) + s * k + (1.0 - c) * k2
            d[:3, 3] = (np.eye(3) + (1.0 - c) / a * k + (a - s) / a * k2) @ v
        pose = pose @ d
        g = _adj(_inv(d))
        cov = g @ cov @ g.T + covs[i]
    return pose @ home, ad_home @ cov @ ad_home.T


def time_us(fn, quick):
    t = timeit.Timer(fn)
    n, _ = t.autorange()  # loop count for >= 0.2 s
    if quick:
        n = max(1, n // 4)
    runs = t.repeat(repeat=3 if quick else 7, number=n)
    return statistics.median(runs) / n * 1e6


def main():
    quick = "--quick" in sys.argv
    chain = seed_chain()
    thetas, covs = seed_inputs()

    pose, cov_compat = probabilistic_forward_kinematics(chain, thetas, covs)
    # Right-perturbation covariance of the tip (what the Rust bench's surfaces use).
    ad_home_inv = pt.adjoint_from_transform(pt.invert_transform(chain.home))
    ad_home = pt.adjoint_from_transform(chain.home)
    c_acc = np.linalg.solve(ad_home, np.linalg.solve(ad_home, cov_compat).T).T
    cov_right = ad_home_inv @ c_acc @ ad_home_inv.T

    lp, lc = lean_ppoe(chain.screw_axes, chain.limits, chain.home, ad_home, thetas, covs)
    assert np.allclose(lp, pose, rtol=0, atol=1e-12), "lean numpy pose differs"
    assert np.allclose(lc, cov_compat, rtol=1e-9, atol=1e-12), "lean numpy cov differs"

    res = {
        "pytransform3d_version": pytransform3d.__version__,
        "numpy_version": np.__version__,
        "python": platform.python_version(),
        "us_per_call": {
            "example_ppoe": time_us(
                lambda: probabilistic_forward_kinematics(chain, thetas, covs), quick
            ),
            "lean_numpy_ppoe": time_us(
                lambda: lean_ppoe(
                    chain.screw_axes, chain.limits, chain.home, ad_home, thetas, covs
                ),
                quick,
            ),
        },
    }
    for n in (20, 50):
        res["us_per_call"]["to_projected_ellipsoid_n%d" % n] = time_us(
            lambda n=n: pu.to_projected_ellipsoid(pose, cov_right, factor=1.0, n_steps=n),
            quick,
        )
    json.dump(res, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
