"""``ppoe.surface`` against its definitions written out in numpy (on pytransform3d's
unit-sphere grid), and the chi-squared helpers against scipy."""

import numpy as np
import pytest
import pytransform3d.transformations as pt
from pytransform3d._geometry import unit_sphere_surface_grid
from scipy import stats

import ppoe


def sym_power(m, power):
    vals, vecs = np.linalg.eigh(m)
    return vecs @ np.diag(vals**power) @ vecs.T


def case(rng):
    pose = pt.random_transform(rng)
    a = rng.standard_normal((6, 6)) * 0.1
    return pose, a @ a.T


def grid_points(n):
    x, y, z = unit_sphere_surface_grid(n)
    return np.column_stack((x.reshape(-1), y.reshape(-1), z.reshape(-1)))


def rel(ours, want):
    return np.max(np.abs(ours - want)) / max(1.0, np.max(np.abs(want)))


def test_marginal_and_lift_against_their_definitions():
    rng = np.random.default_rng(21)
    n, k = 9, 2.0
    u = grid_points(n)
    for _ in range(30):
        pose, cov = case(rng)
        r, t = pose[:3, :3], pose[:3, 3]
        a = r @ sym_power(cov[3:, 3:], 0.5)
        want = t + (k * u) @ a.T
        got = np.column_stack([c.reshape(-1) for c in ppoe.surface(pose, cov, "marginal", k=k, n_steps=n)])
        assert rel(got, want) <= 1e-12
        b = cov[:, 3:] @ sym_power(cov[3:, 3:], -0.5)
        want = np.array([pt.concat(pt.transform_from_exponential_coordinates(b @ (k * s)), pose)[:3, 3] for s in u])
        got = np.column_stack([c.reshape(-1) for c in ppoe.surface(pose, cov, "lift", k=k, n_steps=n)])
        assert rel(got, want) <= 1e-12


def test_probability_gives_the_chi2_radius():
    for p in (0.2, 0.5, 0.95, 0.999):
        assert abs(ppoe.chi2_3_radius(p) - np.sqrt(stats.chi2.ppf(p, 3))) <= 1e-12
    for k in (0.5, 1.0, 2.796, 4.0):
        assert abs(ppoe.chi2_3_probability(k) - stats.chi2.cdf(k * k, 3)) <= 1e-14
    pose, cov = case(np.random.default_rng(22))
    a = ppoe.surface(pose, cov, probability=0.95, n_steps=5)
    b = ppoe.surface(pose, cov, k=ppoe.chi2_3_radius(0.95), n_steps=5)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)


def test_surface_arguments():
    with pytest.raises(ValueError, match="kind"):
        ppoe.surface(np.eye(4), np.eye(6), "sphere")
    with pytest.raises(ValueError, match="probability"):
        ppoe.surface(np.eye(4), np.eye(6), probability=1.0)
    with pytest.raises(ValueError, match="not both"):
        ppoe.surface(np.eye(4), np.eye(6), k=1.0, probability=0.5)
    x, y, z = ppoe.surface(np.eye(4), np.eye(6), "pytransform3d", n_steps=4)
    assert x.shape == y.shape == z.shape == (4, 4)
