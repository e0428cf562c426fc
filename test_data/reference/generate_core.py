#!/usr/bin/env python3
"""Oracle for the `ppoe` core: golden JSON test vectors from pytransform3d.

Writes ``test_data/golden/core/*.json`` (layout: ``test_data/golden/README.md``).
Every output value is computed by pytransform3d 3.17.0 itself (a few extra
fields, documented per file, are computed here with numpy from pytransform3d's
own primitives). The script is deterministic: each file has its own RNG seeded
from ``SEED`` and the file name, so editing one generator leaves the other files
unchanged.

Input conventions:
* Random vector / covariance inputs are rounded to 10 significant digits
  *before* they are passed to pytransform3d, so the stored input is exactly the
  input the oracle saw.  Exceptions (stored at full precision because rounding
  would destroy the property being tested): rotation vectors near or at pi,
  and every rotation matrix / transform (produced by pytransform3d from stored
  exponential coordinates, rounding would break orthonormality).
* Exactly rank-deficient covariances are built as L L^T with dyadic-rational L
  (k/64 * 2^e), so that the product is exact in binary floating point.

Usage:  python generate_core.py [OUTPUT_DIR]
(default OUTPUT_DIR: <repo>/test_data/golden/core).
"""

import json
import math
import os
import sys
import time
import zlib

import numpy as np
import scipy
from scipy import linalg as sla

import pytransform3d
import pytransform3d.batch_rotations as pbr
import pytransform3d.rotations as pr
import pytransform3d.trajectories as ptr
import pytransform3d.transformations as pt
import pytransform3d.uncertainty as pu
from pytransform3d.transformations._jacobians import _Q  # private, see README

PT3D_VERSION = "3.17.0"
SEED = 20250601

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_OUT = os.path.join(HERE, os.pardir, "golden", "core")

# --------------------------------------------------------------------------
# encoding helpers


def enc(x):
    """Recursively convert to JSON-able Python objects.

    numpy arrays become nested row-major lists, non-finite floats become the
    strings "inf", "-inf", "nan"; finite floats are kept as Python floats
    (json writes them with repr, which round-trips exactly).
    """
    if isinstance(x, dict):
        return {str(k): enc(v) for k, v in x.items()}
    if isinstance(x, np.ndarray):
        return enc(x.tolist())
    if isinstance(x, (list, tuple)):
        return [enc(v) for v in x]
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        x = float(x)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return x
    if x is None or isinstance(x, str):
        return x
    raise TypeError("cannot encode %r" % type(x))


def write_file(out_dir, name, function, cases):
    doc = {"function": function, "pytransform3d": PT3D_VERSION,
           "cases": enc(cases)}
    path = os.path.join(out_dir, name)
    with open(path, "w") as f:
        json.dump(doc, f, separators=(",", ":"), allow_nan=False)
        f.write("\n")
    return path


def rng_for(name):
    return np.random.default_rng([SEED, zlib.crc32(name.encode())])


def r10(x):
    """Round every element to 10 significant digits (keeps -0.0)."""
    a = np.asarray(x, dtype=float)
    return np.array([float("%.10g" % v) for v in a.ravel()]).reshape(a.shape)


def r10s(x):
    return float("%.10g" % x)


# --------------------------------------------------------------------------
# random inputs

NEAR_PI_DELTAS = [1e-10, 1e-9, 1e-8, 1e-7, 5e-7, 9e-7, 1e-6, 1.1e-6, 2e-6,
                  1e-5, 1e-4, 1e-3]
PI_AXES = [
    [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0],
    [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0],
    [1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, -1.0], [1.0, 1.0, 1.0],
    [-1.0, 2.0, 3.0], [3.0, 4.0, 0.0],
]


def unit3(rng):
    v = rng.standard_normal(3)
    return v / np.linalg.norm(v)


def rotvec(rng, kind, i=0):
    """Rotation vector of the given kind.

    Kinds: zero, tiny (1e-12..1e-6), series (around the sqrt(6 eps) series
    cut-off 3.65e-8), small (1e-6..0.1), medium (0.1..3), axis (single
    non-zero component), near_pi (pi - delta, full precision), pi (angle
    exactly pi, full precision), large (> pi).
    """
    if kind == "zero":
        return np.zeros(3)
    if kind == "near_pi":
        if i % 2 == 0:
            delta = NEAR_PI_DELTAS[(i // 2) % len(NEAR_PI_DELTAS)]
        else:
            delta = 10.0 ** rng.uniform(-10, -3)
        u = r10(unit3(rng))
        u = u / np.linalg.norm(u)
        return u * (np.pi - delta)
    if kind == "pi":
        if i < len(PI_AXES):
            u = np.array(PI_AXES[i])
        else:
            u = r10(unit3(rng))
        return u / np.linalg.norm(u) * np.pi
    if kind == "axis":
        w = np.zeros(3)
        w[rng.integers(3)] = r10s(rng.choice([-1.0, 1.0]) * rng.uniform(1e-3, 3.1))
        return w
    if kind == "tiny":
        angle = 10.0 ** rng.uniform(-12, -6)
    elif kind == "series":
        angle = rng.uniform(2.5e-8, 5.0e-8)
    elif kind == "small":
        angle = 10.0 ** rng.uniform(-6, -1)
    elif kind == "medium":
        angle = rng.uniform(0.1, 3.0)
    elif kind == "large":
        angle = rng.uniform(3.25, 6.0) if rng.random() < 0.7 else rng.uniform(6.6, 12.0)
    else:
        raise ValueError(kind)
    return r10(unit3(rng) * angle)


def transvec(rng, kind):
    """Translation / v part: zero, tiny, unit (~1), large (1e2..1e3), any."""
    if kind == "zero":
        return np.zeros(3)
    if kind == "any":
        kind = rng.choice(["tiny", "unit", "unit", "unit", "large", "mixed"])
    if kind == "tiny":
        s = 10.0 ** rng.uniform(-12, -6)
    elif kind == "unit":
        s = 10.0 ** rng.uniform(-1, 1)
    elif kind == "large":
        s = 10.0 ** rng.uniform(2, 3)
    elif kind == "mixed":
        return r10(rng.standard_normal(3) * 10.0 ** rng.uniform(-12, 3, size=3))
    else:
        raise ValueError(kind)
    return r10(rng.standard_normal(3) * s)


TRANSFORM_KINDS = (["identity"] * 2 + ["translation"] * 2 + ["tiny"] * 2
                   + ["small"] * 2 + ["medium"] * 10 + ["near_pi"] * 2
                   + ["pi"] * 1 + ["large"] * 1)


def random_transform(rng, kind=None, i=0, tkind="unit"):
    """A rigid transform made by pytransform3d from stored exponential coords.

    Returns (label, T).
    """
    if kind is None:
        kind = str(rng.choice(TRANSFORM_KINDS))
    if kind == "identity":
        return kind, np.eye(4)
    if kind == "translation":
        xi = np.r_[np.zeros(3), transvec(rng, tkind)]
    else:
        xi = np.r_[rotvec(rng, kind, i), transvec(rng, tkind)]
    return kind, pt.transform_from_exponential_coordinates(xi)


def sym(C):
    return 0.5 * (C + C.T)


def dyadic_lowrank(rng, n, k, e):
    """Exactly rank-k PSD n x n matrix L L^T, L = ints/64 * 2^e (exact)."""
    L = rng.integers(-64, 65, size=(n, k)).astype(float) / 64.0 * 2.0 ** e
    C = L @ L.T
    assert np.array_equal(C, C.T)
    return C


def random_spd(rng, n, scale=1.0, cond=None):
    """Random SPD matrix, rounded to 10 digits.

    With cond: eigenvalues log-spaced between scale/cond and scale.
    """
    if cond is None:
        A = rng.standard_normal((n, n))
        C = A @ A.T / n + 0.1 * np.eye(n)
        C = scale * C
    else:
        Qm, _ = np.linalg.qr(rng.standard_normal((n, n)))
        ev = scale * np.logspace(-math.log10(cond), 0, n)
        rng.shuffle(ev)
        C = (Qm * ev) @ Qm.T
    return r10(sym(C))


COV_KINDS = ["zero", "rank1", "rank2", "rank3", "rank4", "rank5",
             "diagonal", "diagonal_repeated", "full", "full", "full", "tiny",
             "large", "mixed_scale"]


def random_cov(rng, kind=None, n=6):
    """Covariance of the given kind (n x n). Returns (kind, C)."""
    if kind is None:
        kind = str(rng.choice(COV_KINDS))
    if kind == "zero":
        C = np.zeros((n, n))
    elif kind.startswith("rank"):
        k = int(kind[4:])
        e = int(rng.choice([-20, -6, -3, 0, 1]))
        C = dyadic_lowrank(rng, n, k, e)
    elif kind == "diagonal":
        d = r10(10.0 ** rng.uniform(-6, 1, size=n))
        d[rng.random(n) < 0.15] = 0.0
        C = np.diag(d)
    elif kind == "diagonal_repeated":
        vals = r10(10.0 ** rng.uniform(-4, 1, size=2))
        C = np.diag(rng.choice(vals, size=n))
    elif kind == "full":
        C = random_spd(rng, n, scale=10.0 ** rng.uniform(-4, 0))
    elif kind == "tiny":
        C = random_spd(rng, n, scale=1e-12 * 10.0 ** rng.uniform(0, 2))
    elif kind == "large":
        C = random_spd(rng, n, scale=rng.uniform(2.0, 10.0))
    elif kind == "mixed_scale":
        C = random_spd(rng, n)
        d = np.r_[np.full(n // 2, 10.0 ** rng.uniform(-3, -1)),
                  np.full(n - n // 2, 10.0 ** rng.uniform(-1, 1))]
        C = r10(sym(C * np.outer(d, d)))
    else:
        raise ValueError(kind)
    return kind, C


# --------------------------------------------------------------------------
# so3.json


def gen_so3(rng):
    plan = ([("zero", 3), ("tiny", 40), ("series", 20), ("small", 30),
             ("medium", 70), ("axis", 15), ("near_pi", 48), ("pi", 16),
             ("large", 30)])
    cases = []
    for kind, count in plan:
        for i in range(count):
            omega = rotvec(rng, kind, i)
            R = pr.matrix_from_compact_axis_angle(omega)
            cases.append(dict(label=kind, R_source="exp", omega=omega, R=R))
    # rotation matrices built directly (exactly symmetric at pi: R = 2uu^T - I)
    for u in PI_AXES:
        u = np.array(u) / np.linalg.norm(u)
        R = 2.0 * np.outer(u, u) - np.eye(3)
        cases.append(dict(label="pi", R_source="direct", omega=u * np.pi, R=R))
    for i in range(12):
        delta = NEAR_PI_DELTAS[i % len(NEAR_PI_DELTAS)]
        u = r10(unit3(rng))
        u = u / np.linalg.norm(u)
        t = np.pi - delta
        R = (math.cos(t) * np.eye(3) + math.sin(t) * pr.cross_product_matrix(u)
             + (1.0 - math.cos(t)) * np.outer(u, u))
        cases.append(dict(label="near_pi", R_source="direct", omega=u * t, R=R))
    for c in cases:
        c["log"] = pr.compact_axis_angle_from_matrix(c["R"])
        c["J"] = pr.left_jacobian_SO3(c["omega"])
        c["J_inv"] = pr.left_jacobian_SO3_inv(c["omega"])
    return "rotations.matrix_from_compact_axis_angle", cases


# --------------------------------------------------------------------------
# se3.json


def gen_se3(rng):
    plan = [("zero", "zero", 2), ("zero", "any", 25), ("tiny", "any", 35),
            ("tiny", "large", 10), ("series", "any", 15), ("small", "any", 20),
            ("medium", "any", 32), ("medium", "zero", 4), ("axis", "any", 8),
            ("near_pi", "any", 30), ("pi", "any", 14), ("large", "any", 12)]
    cases = []
    for rkind, tkind, count in plan:
        for i in range(count):
            xi = np.r_[rotvec(rng, rkind, i), transvec(rng, tkind)]
            label = rkind if tkind != "zero" else rkind + "_no_translation"
            if rkind == "zero":
                label = "pure_translation" if tkind != "zero" else "zero"
            T_single = pt.transform_from_exponential_coordinates(xi)
            T_batch = ptr.transforms_from_exponential_coordinates(xi[np.newaxis])[0]
            cases.append(dict(
                label=label, xi=xi, T_single=T_single, T_batch=T_batch,
                log_single=pt.exponential_coordinates_from_transform(T_single),
                log_batch=ptr.exponential_coordinates_from_transforms(
                    T_single[np.newaxis])[0],
                adjoint=pt.adjoint_from_transform(T_single),
                J6=pt.left_jacobian_SE3(xi),
                J_inv6=pt.left_jacobian_SE3_inv(xi),
                Q=_Q(xi),
            ))
    return "transformations.transform_from_exponential_coordinates", cases


# --------------------------------------------------------------------------
# screw.json


def gen_screw(rng):
    cases = []
    for i in range(100):
        q = transvec(rng, "any") if i % 10 else np.zeros(3)
        if i % 7 == 0:
            s = np.zeros(3)
            s[i % 3] = rng.choice([-1.0, 1.0]) * r10s(10.0 ** rng.uniform(-3, 2))
        else:
            s = r10(rng.standard_normal(3) * 10.0 ** rng.uniform(-6, 3))
        m = i % 5
        if m == 0:
            h, label = 0.0, "revolute"
        elif m == 1:
            h, label = math.inf, "prismatic"
        elif m == 4 and i % 20 == 19:
            h, label = -math.inf, "prismatic_neg_inf"
        else:
            h = r10s(rng.standard_normal() * 10.0 ** rng.uniform(-3, 1))
            label = "helical"
        S = pt.screw_axis_from_screw_parameters(q, s, h)
        cases.append(dict(label=label, q=q, s=s, h=h, S=S))
    return "transformations.screw_axis_from_screw_parameters", cases


# --------------------------------------------------------------------------
# concat_globally.json, concat_locally.json, invert.json


def _pair_kinds(i):
    """Mostly random kinds, the first cases walk through every cov kind."""
    if i < len(COV_KINDS) * 2:
        return COV_KINDS[i % len(COV_KINDS)], COV_KINDS[(i // 2) % len(COV_KINDS)]
    return None, None


def gen_concat_globally(rng):
    cases = []
    for i in range(200):
        ka, kb = _pair_kinds(i)
        la, A2B = random_transform(rng, i=i)
        lb, B2C = random_transform(rng, i=i)
        ca, cov_A2B = random_cov(rng, ka)
        cb, cov_B2C = random_cov(rng, kb)
        mean_A2C, cov_A2C = pu.concat_globally_uncertain_transforms(
            A2B, cov_A2B, B2C, cov_B2C)
        ad = pt.adjoint_from_transform(B2C)
        cov_2nd = cov_B2C + np.dot(ad, np.dot(cov_A2B, ad.T))
        cases.append(dict(
            label="%s/%s|%s/%s" % (la, ca, lb, cb),
            mean_A2B=A2B, cov_A2B=cov_A2B, mean_B2C=B2C, cov_B2C=cov_B2C,
            mean_A2C=mean_A2C, cov_A2C=cov_A2C, cov_A2C_2nd=cov_2nd))
    return "uncertainty.concat_globally_uncertain_transforms", cases


def gen_concat_locally(rng):
    cases = []
    for i in range(200):
        ka, kb = _pair_kinds(i)
        la, A2B = random_transform(rng, i=i)
        lb, B2C = random_transform(rng, i=i)
        ca, cov_A = random_cov(rng, ka)
        cb, cov_B = random_cov(rng, kb)
        mean_A2C, cov_A_total = pu.concat_locally_uncertain_transforms(
            A2B, B2C, cov_A, cov_B)
        cases.append(dict(
            label="%s/%s|%s/%s" % (la, ca, lb, cb),
            mean_A2B=A2B, mean_B2C=B2C, cov_A=cov_A, cov_B=cov_B,
            mean_A2C=mean_A2C, cov_A_total=cov_A_total))
    return "uncertainty.concat_locally_uncertain_transforms", cases


def gen_invert(rng):
    cases = []
    for i in range(200):
        kc = COV_KINDS[i % len(COV_KINDS)] if i < 2 * len(COV_KINDS) else None
        tk = "large" if i % 9 == 8 else "unit"
        lt, T = random_transform(rng, i=i, tkind=tk)
        lc, cov = random_cov(rng, kc)
        mean_inv, cov_inv = pu.invert_uncertain_transform(T, cov)
        cases.append(dict(label="%s/%s" % (lt, lc), mean=T, cov=cov,
                          mean_inv=mean_inv, cov_inv=cov_inv))
    return "uncertainty.invert_uncertain_transform", cases


# --------------------------------------------------------------------------
# pose_fusion.json


def pose_fusion_steps(means, covs, n_iter=20):
    """Same loop as pytransform3d.uncertainty.pose_fusion (MATH.md 3.4), with
    the same primitives, additionally returning the norm of every update step
    and the last information matrix (whose inverse pose_fusion returns as cov).
    n_iter > 20 continues pytransform3d's own iteration past its fixed count.
    """
    covs_inv = [np.linalg.inv(cov) for cov in covs]
    mean = np.eye(4)
    LHS = np.empty((6, 6))
    RHS = np.empty(6)
    norms = []
    for _ in range(n_iter):
        LHS[:, :] = 0.0
        RHS[:] = 0.0
        for k in range(len(means)):
            x_ik = pt.exponential_coordinates_from_transform(
                np.dot(mean, pt.invert_transform(means[k])))
            J_inv = pt.left_jacobian_SE3_inv(x_ik)
            J_invT_S = np.dot(J_inv.T, covs_inv[k])
            LHS += np.dot(J_invT_S, J_inv)
            RHS += np.dot(J_invT_S, x_ik)
        x_i = np.linalg.solve(-LHS, RHS)
        norms.append(float(np.linalg.norm(x_i)))
        mean = np.dot(pt.transform_from_exponential_coordinates(x_i), mean)
    return mean, norms, LHS


def fusion_cost(mean, means, covs):
    """V = sum_k 0.5 x_k^T inv(S_k) x_k, x_k = Log(mean T_k^-1), as pose_fusion."""
    V = 0.0
    for T, cov in zip(means, covs):
        x = pt.exponential_coordinates_from_transform(
            np.dot(mean, pt.invert_transform(T)))
        V += 0.5 * np.dot(x, np.dot(np.linalg.inv(cov), x))
    return float(V)


# pytransform3d's loop continued to this many iterations where 20 left it short
# of its fixed point (last step >= 1e-13): the reference for a converging port.
# Converged: its last 100 steps all below 1e-10 (at its rounding floor, which
# reaches 2.4e-12 on the ill-conditioned cases; a cycling loop stays far above).
FIXED_POINT_ITERATIONS = 300


def fusion_fixed_point(means, covs):
    mean, norms, LHS = pose_fusion_steps(means, covs, FIXED_POINT_ITERATIONS)
    return dict(fixed_point_mean=mean, fixed_point_cov=np.linalg.inv(LHS),
                fixed_point_V=fusion_cost(mean, means, covs),
                fixed_point_last_step_norm=norms[-1],
                fixed_point_converged=bool(max(norms[-100:]) < 1e-10))


def gen_pose_fusion(rng):
    cases = []
    n_ok = 200
    for i in range(n_ok):
        K = [2, 3, 2, 4, 3, 5][i % 6]
        spread = ["close", "close", "medium", "wide"][(i // 6) % 4]
        cond_kind = "ill" if i % 3 == 2 else "well"
        _, T0 = random_transform(rng, kind=str(rng.choice(
            ["identity", "small", "medium", "medium", "medium", "large"])), i=i)
        means, covs = [], []
        for _ in range(K):
            if spread == "close":
                ang, tr = 10.0 ** rng.uniform(-6, -1), 10.0 ** rng.uniform(-6, -1)
            elif spread == "medium":
                ang, tr = rng.uniform(0.1, 0.6), rng.uniform(0.1, 1.0)
            else:
                ang, tr = rng.uniform(0.5, np.deg2rad(75.0)), rng.uniform(0.5, 5.0)
            xi = r10(np.r_[unit3(rng) * ang, unit3(rng) * tr])
            means.append(np.dot(pt.transform_from_exponential_coordinates(xi), T0))
            if cond_kind == "well":
                covs.append(random_spd(rng, 6, scale=10.0 ** rng.uniform(-3, 0)))
            else:
                covs.append(random_spd(rng, 6, scale=10.0 ** rng.uniform(-2, 0),
                                       cond=10.0 ** rng.uniform(3, 6)))
        means, covs = np.array(means), np.array(covs)
        mean, cov, V = pu.pose_fusion(means, covs)
        mean2, norms, _ = pose_fusion_steps(means, covs)
        assert np.array_equal(mean, mean2)
        case = dict(
            label="%s/%s/K%d" % (spread, cond_kind, K), means=means, covs=covs,
            mean=mean, cov=cov, V=V, last_step_norm=norms[-1],
            converged=bool(norms[-1] < 1e-10))
        if norms[-1] >= 1e-13:
            case.update(fusion_fixed_point(means, covs))
        cases.append(case)
    # singular covariances: pytransform3d raises numpy.linalg.LinAlgError
    singular_kinds = ["zero", "diag_zero", "zero_rotation_block", "zero_row",
                      "rank5", "rank4", "rank3", "rank1", "zero", "diag_zero",
                      "zero_rotation_block", "zero_row"]
    n_err = 0
    for j, sk in enumerate(singular_kinds):
        K = 2 + j % 3
        means = [random_transform(rng, kind="medium", i=j)[1] for _ in range(K)]
        covs = [random_spd(rng, 6, scale=0.1) for _ in range(K)]
        bad = rng.integers(K)
        if sk == "zero":
            C = np.zeros((6, 6))
        elif sk == "diag_zero":
            d = r10(10.0 ** rng.uniform(-3, 0, size=6))
            d[rng.integers(6)] = 0.0
            C = np.diag(d)
        elif sk == "zero_rotation_block":
            C = covs[bad].copy()
            C[:3, :] = 0.0
            C[:, :3] = 0.0
        elif sk == "zero_row":
            C = covs[bad].copy()
            r = rng.integers(6)
            C[r, :] = 0.0
            C[:, r] = 0.0
        else:
            C = dyadic_lowrank(rng, 6, int(sk[4:]), 0)
        covs[bad] = C
        try:
            pu.pose_fusion(np.array(means), np.array(covs))
        except np.linalg.LinAlgError:
            n_err += 1
            cases.append(dict(label="singular_" + sk, means=np.array(means),
                              covs=np.array(covs), error="LinAlgError"))
    assert n_err >= 8, n_err
    return "uncertainty.pose_fusion", cases


# --------------------------------------------------------------------------
# estimate_transform.json / estimate_rotation.json

N_CHOICES = [2, 2, 3, 3, 4, 4, 5, 5, 6, 7, 8, 10, 12, 15]
N_LARGE = {7: 20, 77: 50, 120: 30, 185: 50}  # case index -> N
NOISE_ROT = [0.0, 1e-8, 1e-4, 1e-2, 0.05, 0.1, 0.3]
NOISE_TRANS = [1e-6, 1e-3, 0.1, 1.0]
CONVERGED_TOL = 1e-12
FIXED_POINT_TOL = 1e-14


def mean_angles(n_below, n_above):
    """Angles of the true mean: pytransform3d's iteration contracts by about
    2 sin(angle / 2) per step (MATH.md 3.5), so within 20 iterations it reaches
    1e-12 only for small angles; 60 % of the cases below 60 deg are below 20 deg.
    """
    n_small = (n_below - 2) * 3 // 5
    below = ([0.0, 0.0]
             + list(np.linspace(0.0, np.deg2rad(20.0), n_small))
             + list(np.linspace(np.deg2rad(20.5), np.deg2rad(59.0),
                                n_below - 2 - n_small)))
    above = list(np.linspace(np.deg2rad(62.0), np.deg2rad(170.0), n_above))
    return [(a, "below_60") for a in below] + [(a, "above_60") for a in above]


def _se3_fixed_point(samples, n_max=200):
    """Consistent right-difference / right-update Frechet mean (numpy, with
    pytransform3d primitives): mean <- mean Exp(avg_i Log(mean^-1 X_i))."""
    mean = samples[0].copy()
    for it in range(n_max):
        diffs = ptr.exponential_coordinates_from_transforms(
            ptr.concat_many_to_one(samples, pt.invert_transform(mean)))
        avg = diffs.mean(axis=0)
        mean = np.dot(mean, pt.transform_from_exponential_coordinates(avg))
        if np.linalg.norm(avg) < FIXED_POINT_TOL:
            break
    diffs = ptr.exponential_coordinates_from_transforms(
        ptr.concat_many_to_one(samples, pt.invert_transform(mean)))
    return mean, np.cov(diffs, rowvar=False, bias=False), \
        float(np.linalg.norm(diffs.mean(axis=0))), it + 1


def _add_fixed_point(case, fp_mean, fp_cov, fp_res, fp_it):
    """Store the consistent-update Frechet mean where pytransform3d's 20
    iterations did not converge (where it did, it equals `mean`, checked)."""
    if case["converged"]:
        scale = max(1.0, np.abs(case["mean"]).max())
        assert np.abs(fp_mean - case["mean"]).max() <= 1e-12 * scale
    else:
        case.update(fixed_point_mean=fp_mean, fixed_point_cov=fp_cov,
                    fixed_point_avg_diff_norm=fp_res,
                    fixed_point_iterations=fp_it)


def gen_estimate_transform(rng):
    cases = []
    for idx, (angle, band) in enumerate(mean_angles(170, 30)):
        N = N_LARGE.get(idx, int(rng.choice(N_CHOICES)))
        side = "left" if rng.random() < 0.5 else "right"
        sr = float(rng.choice(NOISE_ROT))
        st = float(rng.choice(NOISE_TRANS))
        omega = r10(unit3(rng) * angle)
        Tbar = pt.transform_from_exponential_coordinates(
            np.r_[omega, transvec(rng, "unit")])
        mean_angle = float(np.linalg.norm(omega))
        samples = []
        for _ in range(N):
            eps = r10(np.r_[rng.standard_normal(3) * sr,
                            rng.standard_normal(3) * st])
            E = pt.transform_from_exponential_coordinates(eps)
            samples.append(np.dot(E, Tbar) if side == "left" else np.dot(Tbar, E))
        samples = np.array(samples)
        mean, cov = pu.estimate_gaussian_transform_from_samples(samples)
        # same call as inside pytransform3d, to get the last diffs (MATH.md 3.5)
        mean2, diffs = pu.frechet_mean(
            samples=samples, mean0=samples[0],
            exp=ptr.transforms_from_exponential_coordinates,
            log=ptr.exponential_coordinates_from_transforms,
            inv=pt.invert_transform, concat_one_to_one=pt.concat,
            concat_many_to_one=ptr.concat_many_to_one, n_iter=20)
        assert np.array_equal(mean, mean2)
        final = float(np.linalg.norm(np.mean(diffs, axis=0)))
        fp_mean, fp_cov, fp_res, fp_it = _se3_fixed_point(samples)
        cases.append(dict(
            label="%s/%s_noise/N%d" % (band, side, N), samples=samples,
            mean_angle=mean_angle, noise_rot=sr, noise_trans=st,
            mean=mean, cov=cov, converged=bool(final < CONVERGED_TOL),
            final_avg_diff_norm=final))
        _add_fixed_point(cases[-1], fp_mean, fp_cov, fp_res, fp_it)
    return "uncertainty.estimate_gaussian_transform_from_samples", cases


def _compact_axis_angles_from_matrices(Rs):
    A = pbr.axis_angles_from_matrices(Rs)
    return A[:, :3] * A[:, 3, np.newaxis]


def _so3_fixed_point(samples, n_max=200):
    mean = samples[0].copy()
    for it in range(n_max):
        diffs = _compact_axis_angles_from_matrices(
            ptr.concat_many_to_one(samples, mean.T))
        avg = diffs.mean(axis=0)
        mean = np.dot(mean, pbr.matrices_from_compact_axis_angles(avg))
        if np.linalg.norm(avg) < FIXED_POINT_TOL:
            break
    diffs = _compact_axis_angles_from_matrices(
        ptr.concat_many_to_one(samples, mean.T))
    return mean, np.cov(diffs, rowvar=False, bias=False), \
        float(np.linalg.norm(diffs.mean(axis=0))), it + 1


def gen_estimate_rotation(rng):
    cases = []
    for idx, (angle, band) in enumerate(mean_angles(170, 30)):
        N = N_LARGE.get(idx, int(rng.choice(N_CHOICES)))
        side = "left" if rng.random() < 0.5 else "right"
        sr = float(rng.choice(NOISE_ROT[1:]))
        omega = r10(unit3(rng) * angle)
        Rbar = pr.matrix_from_compact_axis_angle(omega)
        samples = []
        for _ in range(N):
            E = pr.matrix_from_compact_axis_angle(
                r10(rng.standard_normal(3) * sr))
            samples.append(np.dot(E, Rbar) if side == "left" else np.dot(Rbar, E))
        samples = np.array(samples)
        mean, cov = pu.estimate_gaussian_rotation_matrix_from_samples(samples)
        mean2, diffs = pu.frechet_mean(
            samples=samples, mean0=samples[0],
            exp=pbr.matrices_from_compact_axis_angles,
            log=_compact_axis_angles_from_matrices, inv=lambda R: R.T,
            concat_one_to_one=lambda R1, R2: np.dot(R2, R1),
            concat_many_to_one=ptr.concat_many_to_one, n_iter=20)
        assert np.array_equal(mean, mean2)
        final = float(np.linalg.norm(np.mean(diffs, axis=0)))
        fp_mean, fp_cov, fp_res, fp_it = _so3_fixed_point(samples)
        cases.append(dict(
            label="%s/%s_noise/N%d" % (band, side, N), samples=samples,
            mean_angle=float(np.linalg.norm(omega)), noise_rot=sr,
            mean=mean, cov=cov, converged=bool(final < CONVERGED_TOL),
            final_avg_diff_norm=final))
        _add_fixed_point(cases[-1], fp_mean, fp_cov, fp_res, fp_it)
    return "uncertainty.estimate_gaussian_rotation_matrix_from_samples", cases


# --------------------------------------------------------------------------
# to_ellipsoid.json


def gen_to_ellipsoid(rng):
    kinds = ["zero", "rank1", "rank2", "diagonal", "diagonal_repeated",
             "isotropic", "full", "full", "full", "tiny", "large",
             "ill_conditioned"]
    cases = []
    for i in range(204):
        kind = kinds[i % len(kinds)]
        mean = transvec(rng, "any") if i % 11 else np.zeros(3)
        if kind == "isotropic":
            C = np.eye(3) * r10s(10.0 ** rng.uniform(-6, 1))
        elif kind == "ill_conditioned":
            C = random_spd(rng, 3, scale=10.0 ** rng.uniform(-2, 1),
                           cond=10.0 ** rng.uniform(4, 10))
        else:
            _, C = random_cov(rng, kind, n=3)
        e2o, radii = pu.to_ellipsoid(mean, C)
        cases.append(dict(label=kind, mean=mean, cov=C,
                          ellipsoid2origin=e2o, radii=radii))
    return "uncertainty.to_ellipsoid", cases


# --------------------------------------------------------------------------
# to_projected_ellipsoid.json


def _projected_from_eig(mean, vals, vecs, factor, n_steps):
    """Body of pytransform3d's to_projected_ellipsoid after its eigh/reorder."""
    from pytransform3d._geometry import unit_sphere_surface_grid
    radii = factor * np.sqrt(vals[:3])
    x, y, z = unit_sphere_surface_grid(n_steps)
    x *= radii[0]
    y *= radii[1]
    z *= radii[2]
    P = np.column_stack((x.reshape(-1), y.reshape(-1), z.reshape(-1)))
    P = np.dot(P, vecs[:, :3].T)
    T_diff = ptr.transforms_from_exponential_coordinates(P)
    P = np.einsum("ikj,ik->ij", T_diff[:, :3, :3], T_diff[:, :3, 3])
    P = (np.dot(P, mean[:3, :3].T) + mean[np.newaxis, :3, 3]).T
    shape = x.shape
    return P[0].reshape(*shape), P[1].reshape(*shape), P[2].reshape(*shape)


def gen_to_projected_ellipsoid(rng):
    kinds = ["full", "full", "full", "full", "diagonal", "diagonal_repeated",
             "rank1", "rank2", "rank3", "rank4", "rank5", "tiny", "large",
             "mixed_scale", "zero", "rank2_float"]
    factors = [1.0, 1.96, 3.0]
    big = {17: 20, 41: 20, 63: 20, 88: 20, 115: 20, 140: 20, 29: 50}
    cases = []
    for i in range(200):
        kind = kinds[i % len(kinds)]
        n_steps = big.get(i, 7 if i % 4 == 0 else 5)
        factor = factors[i % 3]
        lt, T = random_transform(rng, i=i, tkind="any" if i % 5 == 0 else "unit")
        if kind == "rank2_float":
            # rank 2 with rounding in L L^T (stored at full precision): eigh
            # may return a negative third eigenvalue -> pytransform3d's grid
            # is NaN. Every other such case is searched to be one of those.
            want_nan = (i // len(kinds)) % 2 == 0
            while True:
                L = r10(rng.standard_normal((6, 2)))
                C = sym(L @ L.T)
                if not want_nan or np.sort(sla.eigh(C)[0])[-3] < 0.0:
                    break
        else:
            _, C = random_cov(rng, kind)
        with np.errstate(invalid="ignore"):
            x, y, z = pu.to_projected_ellipsoid(T, C, factor=factor,
                                                n_steps=n_steps)
        vals, vecs = sla.eigh(C)
        order = vals.argsort()[::-1]
        vals, vecs = vals[order], vecs[:, order]
        with np.errstate(invalid="ignore"):
            x2, y2, z2 = _projected_from_eig(T, vals, vecs, factor, n_steps)
        for a, b in ((x, x2), (y, y2), (z, z2)):
            assert np.array_equal(a, b, equal_nan=True)
        nan_grid = bool(np.isnan(x).any() or np.isnan(y).any()
                        or np.isnan(z).any())
        case = dict(label="%s/%s" % (kind, lt), mean=T, cov=C, factor=factor,
                    n_steps=n_steps, eigvals_desc=vals, eigvecs_desc=vecs,
                    nan_grid=nan_grid)
        if not nan_grid:
            case.update(x=x, y=y, z=z)
        cases.append(case)
    return "uncertainty.to_projected_ellipsoid", cases


# --------------------------------------------------------------------------

GENERATORS = [
    ("so3.json", gen_so3),
    ("se3.json", gen_se3),
    ("screw.json", gen_screw),
    ("concat_globally.json", gen_concat_globally),
    ("concat_locally.json", gen_concat_locally),
    ("invert.json", gen_invert),
    ("pose_fusion.json", gen_pose_fusion),
    ("estimate_transform.json", gen_estimate_transform),
    ("estimate_rotation.json", gen_estimate_rotation),
    ("to_ellipsoid.json", gen_to_ellipsoid),
    ("to_projected_ellipsoid.json", gen_to_projected_ellipsoid),
]


def main():
    if pytransform3d.__version__ != PT3D_VERSION:
        sys.exit("need pytransform3d==%s, found %s"
                 % (PT3D_VERSION, pytransform3d.__version__))
    out_dir = sys.argv[1] if len(sys.argv) > 1 else DEFAULT_OUT
    os.makedirs(out_dir, exist_ok=True)
    print("pytransform3d %s, numpy %s, scipy %s"
          % (pytransform3d.__version__, np.__version__, scipy.__version__))
    total = 0
    t_start = time.time()
    only = sys.argv[2:]  # optional file names: regenerate only these
    for name, gen in GENERATORS:
        if only and name not in only:
            continue
        t0 = time.time()
        function, cases = gen(rng_for(name))
        path = write_file(out_dir, name, function, cases)
        size = os.path.getsize(path)
        total += size
        print("%-30s %4d cases %9d bytes  %5.1fs"
              % (name, len(cases), size, time.time() - t0))
    print("%-30s %20d bytes  %5.1fs" % ("total", total, time.time() - t_start))


if __name__ == "__main__":
    main()
