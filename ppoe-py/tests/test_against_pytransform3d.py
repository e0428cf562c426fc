"""Every function of ``ppoe.uncertainty`` against pytransform3d 3.17.0 on random inputs.

Error measure: ``max|ours - ref| / max(1, max|ref|)``, bound 1e-12 (f64). The expected
values are pytransform3d's, computed here by pytransform3d itself.
"""

import numpy as np
import pytest
import pytransform3d.rotations as pr
import pytransform3d.trajectories as ptr
import pytransform3d.transformations as pt
import pytransform3d.uncertainty as ref
from scipy import linalg

import ppoe.uncertainty as pu

TOL = 1e-12
N_CASES = 100


def err(ours, theirs):
    theirs = np.asarray(theirs)
    return np.max(np.abs(np.asarray(ours) - theirs)) / max(1.0, np.max(np.abs(theirs)))


def random_cov(rng, scale=1.0, n=6):
    a = rng.standard_normal((n, n)) * scale
    return a @ a.T


def random_pose(rng):
    return pt.random_transform(rng)


@pytest.mark.parametrize("seed", range(3))
def test_concat_globally_fourth_order(seed):
    rng = np.random.default_rng(seed)
    for _ in range(N_CASES):
        args = (random_pose(rng), random_cov(rng, 0.3), random_pose(rng), random_cov(rng, 0.3))
        (t, c), (rt, rc) = pu.concat_globally_uncertain_transforms(*args), ref.concat_globally_uncertain_transforms(*args)
        assert err(t, rt) <= TOL and err(c, rc) <= TOL


def test_concat_globally_second_order_is_not_the_reference():
    # The keyword changes the result: the fourth-order terms are not negligible here.
    rng = np.random.default_rng(7)
    args = (random_pose(rng), random_cov(rng), random_pose(rng), random_cov(rng))
    _, c2 = pu.concat_globally_uncertain_transforms(*args, order="second")
    _, rc = ref.concat_globally_uncertain_transforms(*args)
    assert err(c2, rc) > 1e-3
    _, cpsd = pu.concat_globally_uncertain_transforms(*args, order="fourth_psd")
    assert np.linalg.eigvalsh(cpsd).min() >= -1e-12 * np.abs(cpsd).max()


@pytest.mark.parametrize("seed", range(3))
def test_concat_locally(seed):
    rng = np.random.default_rng(100 + seed)
    for _ in range(N_CASES):
        args = (random_pose(rng), random_pose(rng), random_cov(rng), random_cov(rng))
        (t, c), (rt, rc) = pu.concat_locally_uncertain_transforms(*args), ref.concat_locally_uncertain_transforms(*args)
        assert err(t, rt) <= TOL and err(c, rc) <= TOL


@pytest.mark.parametrize("seed", range(3))
def test_invert(seed):
    rng = np.random.default_rng(200 + seed)
    for _ in range(N_CASES):
        args = (random_pose(rng), random_cov(rng))
        (t, c), (rt, rc) = pu.invert_uncertain_transform(*args), ref.invert_uncertain_transform(*args)
        assert err(t, rt) <= TOL and err(c, rc) <= TOL


def fusion_problem(rng, k):
    center = pt.transform_from(pr.random_matrix(rng), rng.standard_normal(3))
    means = [pt.concat(center, pt.transform_from_exponential_coordinates(0.1 * rng.standard_normal(6))) for _ in range(k)]
    covs = [random_cov(rng, 0.3) + 0.05 * np.eye(6) for _ in range(k)]
    return means, covs


def test_pose_fusion_where_pytransform3d_converges():
    rng = np.random.default_rng(300)
    compared = 0
    for _ in range(40):
        means, covs = fusion_problem(rng, int(rng.integers(2, 6)))
        rm, rc, rv = ref.pose_fusion(means, covs)
        # pytransform3d runs 20 fixed steps: compare where its last step is at rounding.
        residual = pt.exponential_coordinates_from_transform(
            pt.concat(pt.invert_transform(rm), ref_step(means, covs, rm)))
        if np.max(np.abs(residual)) > 1e-14:
            continue
        compared += 1
        m, c, v = pu.pose_fusion(means, covs)
        assert err(m, rm) <= TOL and err(c, rc) <= TOL and abs(v - rv) <= TOL * max(1.0, rv)
    assert compared >= 30


def ref_step(means, covs, mean):
    """One more Gauss-Newton update of pytransform3d's fusion from ``mean``."""
    lhs, rhs = np.zeros((6, 6)), np.zeros(6)
    for m, c in zip(means, covs):
        x = pt.exponential_coordinates_from_transform(pt.concat(pt.invert_transform(m), mean))
        ji = pt.left_jacobian_SE3_inv(x)
        w = np.linalg.inv(c)
        lhs += ji.T @ w @ ji
        rhs += ji.T @ w @ x
    return pt.concat(mean, pt.transform_from_exponential_coordinates(np.linalg.solve(-lhs, rhs)))


def test_frechet_mean_generic_driver():
    rng = np.random.default_rng(400)
    samples = np.array([pt.random_transform(rng, np.eye(4), 0.01 * np.eye(6)) for _ in range(50)])
    kwargs = dict(
        samples=samples, mean0=samples[0],
        exp=ptr.transforms_from_exponential_coordinates,
        log=ptr.exponential_coordinates_from_transforms,
        inv=pt.invert_transform, concat_one_to_one=pt.concat,
        concat_many_to_one=ptr.concat_many_to_one, n_iter=7)
    (m, d), (rm, rd) = pu.frechet_mean(**kwargs), ref.frechet_mean(**kwargs)
    np.testing.assert_array_equal(m, rm)
    np.testing.assert_array_equal(d, rd)


def mean_pose(rng, angle):
    axis = rng.standard_normal(3)
    axis /= np.linalg.norm(axis)
    return pt.transform_from(pr.matrix_from_compact_axis_angle(angle * axis), rng.standard_normal(3))


@pytest.mark.parametrize("angle", [0.1, 0.5, 0.9, 2.0, 3.0])
def test_estimate_gaussian_transform_compat(angle):
    # Above 60 degrees (1.047 rad) pytransform3d's iteration does not converge; the
    # compat mode reproduces the point it stops at.
    rng = np.random.default_rng(int(500 + 10 * angle))
    for _ in range(8):
        cov = np.diag([0.01, 0.02, 0.01, 0.1, 0.1, 0.2])
        samples = np.array([pt.random_transform(rng, mean_pose(rng, angle), cov) for _ in range(30)])
        ours = pu.estimate_gaussian_transform_from_samples(samples)
        theirs = ref.estimate_gaussian_transform_from_samples(samples)
        bound = TOL if angle < np.pi / 3 else max(TOL, sensitivity(ref.estimate_gaussian_transform_from_samples, samples, rng))
        assert err(ours[0], theirs[0]) <= bound and err(ours[1], theirs[1]) <= bound


def sensitivity(estimator, samples, rng):
    """How far the reference itself moves when its samples move by 1e-14 (relative):
    above 60 degrees its non-converging iteration amplifies every rounding error by about
    (2 sin(theta/2))^20, so no implementation can match it closer than this."""
    moved = samples * (1.0 + 1e-14 * rng.standard_normal(samples.shape))
    a, b = estimator(samples), estimator(moved)
    return max(err(a[0], b[0]), err(a[1], b[1]))


@pytest.mark.parametrize("angle", [0.1, 0.5, 0.9, 2.0, 3.0])
def test_estimate_gaussian_rotation_compat(angle):
    rng = np.random.default_rng(int(600 + 10 * angle))
    for _ in range(8):
        mean = mean_pose(rng, angle)[:3, :3]
        samples = np.array([pr.random_matrix(rng, mean, np.diag([0.01, 0.02, 0.03])) for _ in range(30)])
        ours = pu.estimate_gaussian_rotation_matrix_from_samples(samples)
        theirs = ref.estimate_gaussian_rotation_matrix_from_samples(samples)
        bound = TOL if angle < np.pi / 3 else max(TOL, sensitivity(ref.estimate_gaussian_rotation_matrix_from_samples, samples, rng))
        assert err(ours[0], theirs[0]) <= bound and err(ours[1], theirs[1]) <= bound


def test_estimators_corrected_agree_where_pytransform3d_converged():
    # At a small mean rotation pytransform3d's 20 left updates converge to rounding, and
    # the corrected right-updated iteration has the same fixed point.
    rng = np.random.default_rng(700)
    for _ in range(8):
        samples = np.array([pt.random_transform(rng, mean_pose(rng, 0.01), 1e-4 * np.eye(6)) for _ in range(30)])
        (m, c), (rm, rc) = pu.estimate_gaussian_transform_from_samples(samples, compat=False), ref.estimate_gaussian_transform_from_samples(samples)
        assert err(m, rm) <= TOL and err(c, rc) <= TOL
        rots = samples[:, :3, :3]
        (m, c), (rm, rc) = pu.estimate_gaussian_rotation_matrix_from_samples(rots, compat=False), ref.estimate_gaussian_rotation_matrix_from_samples(rots)
        assert err(m, rm) <= TOL and err(c, rc) <= TOL


def test_estimators_corrected_converge_beyond_60_degrees():
    # Where pytransform3d does not converge, the corrected mean is a fixed point: its
    # average right difference is zero.
    rng = np.random.default_rng(701)
    samples = np.array([pt.random_transform(rng, mean_pose(rng, 2.5), 1e-3 * np.eye(6)) for _ in range(30)])
    m, _ = pu.estimate_gaussian_transform_from_samples(samples, compat=False)
    d = ptr.exponential_coordinates_from_transforms(ptr.concat_many_to_one(samples, pt.invert_transform(m)))
    assert np.max(np.abs(d.mean(axis=0))) < 1e-13
    rm, _ = ref.estimate_gaussian_transform_from_samples(samples)
    d = ptr.exponential_coordinates_from_transforms(ptr.concat_many_to_one(samples, pt.invert_transform(rm)))
    assert np.max(np.abs(d.mean(axis=0))) > 1e-6  # the reference's is not


def test_to_ellipsoid():
    rng = np.random.default_rng(800)
    for _ in range(N_CASES):
        mean, cov = rng.standard_normal(3), random_cov(rng, n=3)
        (frame, radii), (rframe, rradii) = pu.to_ellipsoid(mean, cov), ref.to_ellipsoid(mean, cov)
        assert err(radii, rradii) <= TOL
        assert err(frame[:3, 3], rframe[:3, 3]) == 0.0
        r = frame[:3, :3]
        assert err(r @ np.diag(radii**2) @ r.T, cov) <= TOL
        assert np.linalg.det(r) > 0
        # distinct radii: the same axes up to sign
        assert err(np.abs(r), np.abs(rframe[:3, :3])) <= 1e-10


def reference_eigen(cov):
    vals, vecs = linalg.eigh(cov)
    order = vals.argsort()[::-1]
    return vals[order], vecs[:, order]


def test_to_projected_ellipsoid_given_the_reference_basis():
    rng = np.random.default_rng(900)
    for _ in range(N_CASES):
        mean, cov = random_pose(rng), random_cov(rng, 0.2)
        ours = pu.to_projected_ellipsoid(mean, cov, 1.5, 11, eigen=reference_eigen(cov))
        theirs = ref.to_projected_ellipsoid(mean, cov, 1.5, 11)
        for a, b in zip(ours, theirs):
            assert a.shape == b.shape == (11, 11)
            assert err(a, b) <= TOL


def test_to_projected_ellipsoid_own_basis_aligned():
    # With ppoe's own eigenvectors the points are the reference's once the eigenvector
    # signs are aligned: compare with the reference computed from our basis.
    rng = np.random.default_rng(901)
    for _ in range(50):
        mean, cov = random_pose(rng), random_cov(rng, 0.2)
        vals, vecs = reference_eigen(cov)
        ours = pu.to_projected_ellipsoid(mean, cov, 1.0, 9)
        for sign in np.ndindex(2, 2, 2):
            s = np.array(sign + (0, 0, 0)) * -2 + 1
            cand = pu.to_projected_ellipsoid(mean, cov, 1.0, 9, eigen=(vals, vecs * s))
            if max(err(a, b) for a, b in zip(ours, cand)) <= 1e-10:
                break
        else:
            pytest.fail("no sign choice of the reference basis gives our grid")
