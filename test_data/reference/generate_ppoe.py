#!/usr/bin/env python3
"""Golden vectors for the Probabilistic Product of Exponentials (PPOE).

Oracle: pytransform3d 3.17.0.  The class below follows the code path of the
library's example "Probabilistic Product of Exponentials"
(``ProbabilisticRobotKinematics``, specified in our own words in
shared/reference/MATH.md section 5; the example is not shipped in the wheel):

* the robot is loaded by ``pytransform3d.urdf.UrdfTransformManager``
  (constructed with ``check=False``, as the example does);
* home pose ``M = get_transform(tip, base)``; for every joint the child link's
  home pose ``L = get_transform(child, base)`` gives the axis ``R(L) a`` and the
  point ``p(L)``, turned into a screw axis by
  ``pytransform3d.transformations.screw_axis_from_screw_parameters`` with pitch
  0 (revolute/continuous) or inf (prismatic);
* ``probabilistic_forward_kinematics``: ``np.clip`` the joint values to the
  URDF limits, joint displacements by the batch exponential
  ``pytransform3d.trajectories.transforms_from_exponential_coordinates``, then
  ``pytransform3d.uncertainty.concat_locally_uncertain_transforms`` joint by
  joint from the base, finally ``T . M`` and ``Ad(M) C Ad(M)^T`` with
  ``pytransform3d.transformations.adjoint_from_transform``.

Besides the example's covariance (``cov_pytransform3d``) every case stores, from
the same accumulated ``C`` (the covariance before the last step):

* ``cov_right = Ad(M^-1) C Ad(M^-1)^T``, the covariance of the right (local)
  perturbation of the returned pose (``M^-1`` by ``invert_transform``);
* ``cov_left = Ad(T) cov_right Ad(T)^T``, the left (global) perturbation.

Output: ``test_data/golden/ppoe/<robot>_<base>_<tip>.json`` (layout in
``test_data/golden/ppoe/README.md``).  Deterministic: fixed seeds, inputs
rounded to 8 significant digits before use.

Run from the repository root (or anywhere; paths are relative to this file):

    python3 -m venv /tmp/venv-ppoe
    /tmp/venv-ppoe/bin/pip install -r test_data/reference/requirements-ppoe.txt
    /tmp/venv-ppoe/bin/python test_data/reference/generate_ppoe.py
"""

import json
import math
import os
import sys
import zlib

import numpy as np
import pytransform3d
import pytransform3d.trajectories as ptr
import pytransform3d.transformations as pt
import pytransform3d.uncertainty as pu
from pytransform3d.urdf import UrdfTransformManager

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
URDF_DIR = os.path.join("test_data", "urdf")
OUT_DIR = os.path.join(ROOT, "test_data", "golden", "ppoe")

N_RANDOM = 500

# (robot = URDF file stem, base link, tip link); joints = moving joints on the
# path base -> tip, in order from the base.
CHAINS = [
    ("seed", "linkmount", "tcp"),
    ("prismatic", "base_link", "tool0"),
    ("fixed_between", "world", "tool_tip"),
    ("continuous", "base", "ee"),
    ("rpy_everywhere", "base", "tool"),
    ("rpy_everywhere", "link2", "tool"),
    ("tree", "base_footprint", "left_tip"),
    ("tree", "base_footprint", "right_tip"),
]

EXPECTED_VERSIONS = {"pytransform3d": "3.17.0"}


# --------------------------------------------------------------------------
# The oracle
# --------------------------------------------------------------------------
class ProbabilisticChain(UrdfTransformManager):
    """PPOE of one base -> tip chain, as in pytransform3d's example."""

    def __init__(self, urdf_xml, tip, base, joint_names):
        super().__init__(check=False)
        self.load_urdf(urdf_xml)
        self.home = self.get_transform(tip, base)
        axes = []
        for name in joint_names:
            child, _parent, _c2p, axis, _limits, kind = self._joints[name]
            child2base = self.get_transform(child, base)
            direction = np.dot(child2base[:3, :3], axis)
            point = child2base[:3, 3]
            if kind == "revolute":
                pitch = 0.0
            elif kind == "prismatic":
                pitch = np.inf
            else:
                raise NotImplementedError("joint %s has type %s" % (name, kind))
            axes.append(pt.screw_axis_from_screw_parameters(point, direction, pitch))
        self.screw_axes = np.vstack(axes)
        self.limits = np.array([self.get_joint_limits(n) for n in joint_names])

    def evaluate(self, thetas, covs):
        """Returns (clipped thetas, pose, cov_pytransform3d, cov_right, cov_left)."""
        thetas = np.clip(thetas, self.limits[:, 0], self.limits[:, 1])
        exp_coords = self.screw_axes * thetas[:, np.newaxis]
        displacements = ptr.transforms_from_exponential_coordinates(exp_coords)
        pose = np.eye(4)
        cov = np.zeros((6, 6))
        for i in range(len(thetas)):
            pose, cov = pu.concat_locally_uncertain_transforms(
                displacements[i], pose, covs[i], cov
            )
        pose = pose.dot(self.home)
        ad_home = pt.adjoint_from_transform(self.home)
        cov_compat = ad_home.dot(cov).dot(ad_home.T)

        ad_home_inv = pt.adjoint_from_transform(pt.invert_transform(self.home))
        cov_right = ad_home_inv.dot(cov).dot(ad_home_inv.T)
        ad_pose = pt.adjoint_from_transform(pose)
        cov_left = ad_pose.dot(cov_right).dot(ad_pose.T)
        return thetas, pose, cov_compat, cov_right, cov_left


def independent_check(chain, thetas, covs, result):
    """Closed-form re-computation (MATH.md 5.2), guards the generator itself."""
    th, pose, cov_compat, cov_right, cov_left = result

    def adj(T):
        R, p = T[:3, :3], T[:3, 3]
        px = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
        A = np.zeros((6, 6))
        A[:3, :3] = R
        A[3:, 3:] = R
        A[3:, :3] = px.dot(R)
        return A

    def exp(S, t):
        w, v = S[:3] * t, S[3:] * t
        a = np.linalg.norm(w)
        T = np.eye(4)
        if a == 0.0:
            T[:3, 3] = v
            return T
        W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]) / a
        T[:3, :3] = np.eye(3) + math.sin(a) * W + (1 - math.cos(a)) * W.dot(W)
        V = np.eye(3) * a + (1 - math.cos(a)) * W + (a - math.sin(a)) * W.dot(W)
        T[:3, 3] = V.dot(v / a)
        return T

    n = len(th)
    D = [exp(chain.screw_axes[i], th[i]) for i in range(n)]
    P = np.eye(4)
    for d in D:
        P = P.dot(d)
    C = np.zeros((6, 6))
    G = np.eye(4)
    for i in range(n - 1, -1, -1):
        A = adj(G)
        C += A.dot(covs[i]).dot(A.T)
        G = G.dot(np.linalg.inv(D[i]))
    M = chain.home
    Tm = P.dot(M)
    scale = 1.0 + np.abs(covs).max()
    assert np.allclose(Tm, pose, rtol=0, atol=1e-9), "pose mismatch"
    A = adj(M)
    assert np.allclose(A.dot(C).dot(A.T), cov_compat, rtol=1e-9, atol=1e-11 * scale)
    A = adj(np.linalg.inv(M))
    assert np.allclose(A.dot(C).dot(A.T), cov_right, rtol=1e-9, atol=1e-11 * scale)
    A = adj(P)
    assert np.allclose(A.dot(C).dot(A.T), cov_left, rtol=1e-9, atol=1e-11 * scale)


# --------------------------------------------------------------------------
# URDF helpers
# --------------------------------------------------------------------------
def read_urdf(robot):
    rel = os.path.join(URDF_DIR, robot + ".urdf")
    with open(os.path.join(ROOT, rel), "r", encoding="utf-8") as f:
        return rel.replace(os.sep, "/"), f.read()


def moving_joints_on_path(tm, base, tip):
    """Moving joints from base to tip (tm._joints: name -> (child, parent, ...))."""
    by_child = {}
    for name, (child, parent, _c2p, _axis, _lim, kind) in tm._joints.items():
        by_child[child] = (name, parent, kind)
    path = []
    link = tip
    while link != base:
        if link not in by_child:
            raise ValueError("%s is not below %s" % (tip, base))
        name, parent, kind = by_child[link]
        path.append((name, kind))
        link = parent
    path.reverse()
    return [name for name, kind in path if kind != "fixed"]


def urdf_joint_types(urdf_xml):
    from lxml import etree

    root = etree.XML(urdf_xml.strip().encode("utf-8"))
    return {j.get("name"): j.get("type") for j in root.findall("joint")}


# --------------------------------------------------------------------------
# Inputs
# --------------------------------------------------------------------------
def r8(x):
    """Round to 8 significant digits (keeps -0.0 and exact zeros)."""
    return float("%.8g" % x)


def r8a(a):
    return np.vectorize(r8, otypes=[np.float64])(np.asarray(a, dtype=np.float64))


def seed_covs():
    covs = np.zeros((6, 6, 6))
    covs[0] = np.diag([0, 0, 1, 0, 0, 0])
    covs[1] = np.diag([0, 1, 0, 0, 0, 0])
    covs[2] = np.diag([0, 1, 0, 0, 0, 0])
    covs[4] = np.diag([0, 1, 0, 0, 0, 0])
    covs *= 0.05
    return covs


THETA_KINDS = ["inside", "outside", "at_limit", "tiny", "large", "mixed"]
COV_KINDS = ["zero", "seed", "diag", "rankdef", "full", "full_float", "mixed"]


def theta_value(rng, kind, lo, hi, prismatic):
    """One joint value of the given kind, already rounded to 8 digits.

    Limits are used as they are (not rounded), so "at_limit" hits them exactly
    and "outside" values are checked to stay outside after rounding.
    """
    span = 0.5 if prismatic else math.pi
    if kind == "mixed":
        kind = rng.choice(["inside", "outside", "at_limit", "tiny", "large"])
    if kind == "inside":
        a = lo if math.isfinite(lo) else (hi - 2 * span if math.isfinite(hi) else -span)
        b = hi if math.isfinite(hi) else (lo + 2 * span if math.isfinite(lo) else span)
        return r8(rng.uniform(a, b))
    if kind == "outside":
        sides = [s for s, v in (("lo", lo), ("hi", hi)) if math.isfinite(v)]
        if not sides:
            return theta_value(rng, "large", lo, hi, prismatic)
        side = sides[rng.integers(len(sides))]
        while True:
            gap = 10.0 ** rng.uniform(-6, 0) * (0.5 if prismatic else 2.0)
            x = r8(lo - gap if side == "lo" else hi + gap)
            if (x < lo) if side == "lo" else (x > hi):
                return x
    if kind == "at_limit":
        finite = [v for v in (lo, hi) if math.isfinite(v)]
        if not finite:
            return theta_value(rng, "inside", lo, hi, prismatic)
        return float(finite[rng.integers(len(finite))])
    if kind == "tiny":
        u = rng.integers(6)
        if u == 0:
            return 0.0
        if u == 1:
            return -0.0
        return r8(float(rng.choice([-1.0, 1.0])) * 10.0 ** rng.uniform(-12, -7))
    if kind == "large":
        if prismatic:
            return r8(float(rng.choice([-1.0, 1.0])) * rng.uniform(1.0, 20.0))
        return r8(float(rng.choice([-1.0, 1.0])) * 10.0 ** rng.uniform(0.5, 3.0))
    raise ValueError(kind)


def cov_value(rng, kind):
    """One joint covariance (6x6, symmetric, already with short decimals)."""
    if kind == "mixed":
        kind = rng.choice(["zero", "seed", "diag", "rankdef", "full", "full_float"])
    if kind == "zero":
        return np.zeros((6, 6))
    if kind == "seed":
        c = np.zeros((6, 6))
        i = rng.integers(6)
        c[i, i] = 0.05 if rng.random() < 0.5 else r8(10.0 ** rng.uniform(-6, -1))
        return c
    if kind == "diag":
        d = 10.0 ** rng.uniform(-6, -1, size=6)
        d[rng.random(6) < 0.3] = 0.0
        return np.diag(r8a(d))
    if kind in ("rankdef", "full"):
        # integer factor: L L^T * 10^-e is exact in decimal (short numbers) and
        # exactly of rank k up to the rounding of the decimal to binary
        # (eigenvalues that should be 0 are ~1e-17 of the largest).
        k = int(rng.integers(1, 6)) if kind == "rankdef" else 6
        L = rng.integers(-9, 10, size=(6, k))
        e = int(rng.integers(3, 7))
        C = L.dot(L.T)
        return np.array([[float("%de-%d" % (C[i, j], e)) for j in range(6)]
                         for i in range(6)])
    if kind == "full_float":
        # generic full-rank matrix with 8-digit entries; resampled until the
        # rounding cannot make it indefinite
        while True:
            L = rng.normal(size=(6, 6)) * 10.0 ** rng.uniform(-3, -0.5)
            C = L.dot(L.T)
            C = r8a(0.5 * (C + C.T))
            ev = np.linalg.eigvalsh(C)
            if ev[0] > 1e-6 * ev[-1]:
                return C
    raise ValueError(kind)


def random_cases(rng, chain, kinds, n_cases):
    n = chain.screw_axes.shape[0]
    cases = []
    for k in range(n_cases):
        tkind = THETA_KINDS[k % len(THETA_KINDS)]
        ckind = COV_KINDS[(k // len(THETA_KINDS)) % len(COV_KINDS)]
        thetas = np.array([
            theta_value(rng, tkind, chain.limits[j, 0], chain.limits[j, 1],
                        kinds[j] == "prismatic")
            for j in range(n)
        ])
        if ckind == "mixed":
            covs = np.array([cov_value(rng, "mixed") for _ in range(n)])
        else:
            covs = np.array([cov_value(rng, ckind) for _ in range(n)])
        cases.append(("random_%03d_%s_%s" % (k, tkind, ckind), thetas, covs))
    return cases


# --------------------------------------------------------------------------
# JSON
# --------------------------------------------------------------------------
def enc(x):
    """Nested lists of Python floats; non-finite numbers as strings."""
    if isinstance(x, np.ndarray):
        return enc(x.tolist())
    if isinstance(x, (list, tuple)):
        return [enc(v) for v in x]
    if isinstance(x, (float, np.floating)):
        x = float(x)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return x
    if isinstance(x, (int, np.integer)):
        return float(x)
    return x


def build_case(chain, label, thetas, covs):
    result = chain.evaluate(thetas, covs)
    independent_check(chain, thetas, covs, result)
    th, pose, cov_compat, cov_right, cov_left = result
    return {
        "label": label,
        "thetas": enc(thetas),
        "covs": enc(covs),
        "thetas_clipped": enc(th),
        "pose": enc(pose),
        "cov_pytransform3d": enc(cov_compat),
        "cov_right": enc(cov_right),
        "cov_left": enc(cov_left),
    }


def generate(robot, base, tip, n_random):
    rel, xml = read_urdf(robot)
    probe = UrdfTransformManager(check=False)
    probe.load_urdf(xml)
    joints = moving_joints_on_path(probe, base, tip)
    types = urdf_joint_types(xml)
    chain = ProbabilisticChain(xml, tip, base, joints)
    kinds = [chain._joints[j][5] for j in joints]

    cases = []
    if robot == "seed":
        assert joints == ["joint%d" % i for i in range(1, 7)]
        thetas = np.array([1, 1, 1, 0, 1, 0])
        covs = seed_covs()
        cases.append(build_case(chain, "seed_initial", -0.5 * thetas, covs))
        n_frames = 200
        for step in range(n_frames):
            angle = 0.5 * np.cos(2.0 * np.pi * (0.5 + step / n_frames))
            cases.append(build_case(chain, "frame_%d" % step, angle * thetas, covs))

    rng = np.random.default_rng(zlib.crc32(("%s/%s/%s" % (robot, base, tip)).encode()))
    for label, thetas, covs in random_cases(rng, chain, kinds, n_random):
        cases.append(build_case(chain, label, thetas, covs))

    doc = {
        "urdf": rel,
        "base": base,
        "tip": tip,
        "joints": joints,
        "joint_types": [types[j] for j in joints],
        "screw_axes": enc(chain.screw_axes),
        "home": enc(chain.home),
        "limits": enc(chain.limits),
        "cases": cases,
    }
    name = "%s_%s_%s.json" % (robot, base, tip)
    text = json.dumps(doc, separators=(",", ":"), allow_nan=False)
    with open(os.path.join(OUT_DIR, name), "w", encoding="utf-8") as f:
        f.write(text)
        f.write("\n")
    return name, len(joints), len(cases), len(text)


def main():
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--random", type=int, default=N_RANDOM,
        help="random cases per chain (default %(default)s); the cases of a "
        "smaller count are a prefix of those of a larger one",
    )
    args = parser.parse_args()
    want = EXPECTED_VERSIONS["pytransform3d"]
    if pytransform3d.__version__ != want:
        sys.exit("pytransform3d %s installed, the oracle is %s"
                 % (pytransform3d.__version__, want))
    os.makedirs(OUT_DIR, exist_ok=True)
    total = 0
    for robot, base, tip in CHAINS:
        name, n, ncases, size = generate(robot, base, tip, args.random)
        total += size
        print("%-45s N=%d cases=%d %7.0f kB" % (name, n, ncases, size / 1e3))
    print("total %.2f MB" % (total / 1e6))


if __name__ == "__main__":
    main()
