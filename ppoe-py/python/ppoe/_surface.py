"""Equiprobable surfaces of an uncertain tool pose, for plotting."""

import numpy as np

from . import _ppoe
from ._checks import as_f64, transform


def surface(pose, cov, kind="lift", k=None, probability=None, n_steps=50):
    """Grid of a surface of the tool position of ``T = Tbar Exp(eta)``, eta ~ N(0, cov).

    ``cov`` is the covariance of the **right** perturbation (the robot's default
    convention) for ``"lift"`` and ``"marginal"``; ``"pytransform3d"`` is
    ``to_projected_ellipsoid`` with factor k, for comparison only.

    Parameters
    ----------
    pose : array-like, shape (4, 4)
        The mean pose.
    cov : array-like, shape (6, 6)
        Its right covariance, rotation first.
    kind : {"lift", "marginal", "pytransform3d"}, optional (default: "lift")
        "lift": each point of the marginal ellipsoid mapped back to its most likely full
        perturbation and through the exact exponential (bends like the sampled cloud);
        "marginal": the linear marginal ellipsoid ``tbar + R Sigma_vv^(1/2) k u``.
    k : float, optional
        Radius in standard deviations (default 1, or from ``probability``).
    probability : float, optional
        The probability the 3D Gaussian ball holds, in [0, 1) (e.g. 0.95 gives k = 2.796);
        give ``k`` or ``probability``, not both.
    n_steps : int, optional (default: 50)
        Grid steps per angle (2 to 2000), pytransform3d's unit-sphere grid.

    Returns
    -------
    x, y, z : array, shape (n_steps, n_steps)
        Coordinates of the grid points (a closed quad mesh: rows 0 and n-1 are the poles,
        column n-1 repeats column 0).
    """
    if k is not None and probability is not None:
        raise ValueError("give k or probability, not both")
    if probability is not None:
        k = _ppoe.chi2_3_radius(float(probability))
    k = 1.0 if k is None else float(k)
    n = int(n_steps)
    if not 2 <= n <= 2000:
        raise ValueError(f"n_steps must be 2 to 2000, got {n_steps}")
    points = _ppoe.surface_grid(str(kind), transform(pose, "pose"), as_f64(cov, "cov", (6, 6)), k, n)
    return tuple(np.ascontiguousarray(points[:, c].reshape(n, n)) for c in range(3))


def chi2_3_radius(probability):
    """The radius k (in standard deviations) of the 3D Gaussian ball holding ``probability``."""
    return _ppoe.chi2_3_radius(float(probability))


def chi2_3_probability(k):
    """The probability that a 3D standard normal vector has norm at most ``k``.

    Raises
    ------
    ValueError
        For NaN.
    """
    return _ppoe.chi2_3_probability(float(k))
