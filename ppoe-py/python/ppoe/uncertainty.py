"""A drop-in for ``pytransform3d.uncertainty`` (pytransform3d 3.17.0), computed by ppoe.

The functions have pytransform3d's names, argument order, keyword names, defaults,
shapes and return values, and reproduce its results (its quirks included) unless a
keyword asks for the corrected behaviour. Covariances are 6x6 over exponential
coordinates, rotation first; transforms are 4x4 ``A2B`` matrices.

Deliberate differences (each one listed in ``ppoe-py/README.md`` too):

* Invalid input raises ``ValueError`` (a subclass, :class:`ppoe.PpoeError`, for the
  core's errors): NaN or infinity anywhere, non-numeric dtypes, wrong shapes. Transforms
  are checked with pytransform3d's own rule (``R R^T ~ I`` within 1e-6, ``det R >= 0``,
  last row ``(0, 0, 0, 1)``), also where pytransform3d does not check.
* ``concat_globally_uncertain_transforms`` returns an exactly symmetric covariance;
  ``order="fourth_psd"`` projects it onto the nearest positive semi-definite matrix
  (pytransform3d's fourth-order sum can have large negative eigenvalues).
* ``pose_fusion`` iterates to convergence (damped Newton, several starts) instead of 20
  fixed Gauss-Newton steps from the identity: the same stationary point wherever
  pytransform3d converges, and one of lower cost where it does not. At most 16 poses.
* The estimators from samples need at least two samples (pytransform3d returns a NaN
  covariance for one), and reject samples that are not rotations / rigid transforms.
  ``compat=False`` uses the consistent right update, which converges for mean rotations
  of any angle (pytransform3d's left update converges only below 60 degrees).
* ``to_ellipsoid`` and ``to_projected_ellipsoid`` use ppoe's eigen-solver, so eigenvector
  signs (and bases of repeated eigenvalues) may differ from LAPACK's: the ellipsoid is the
  same, the rotation columns / grid points may be permuted or flipped. Exactly equal
  eigenvalues of ``to_projected_ellipsoid`` are ordered as LAPACK orders those of a
  diagonal matrix (so ``np.eye(6)`` gives the translation axes, as in pytransform3d). Negative
  rounding-noise eigenvalues are clamped to 0 (pytransform3d: ``sqrt(|l|)`` resp. NaN).
  ``to_projected_ellipsoid(..., eigen=(values, vectors))`` takes a given basis and then
  reproduces the reference's points. ``n_steps`` must be 2..2000.
"""

import numpy as np

from . import _ppoe
from ._checks import as_f64, check_transform, transform

__all__ = [
    "concat_globally_uncertain_transforms",
    "concat_locally_uncertain_transforms",
    "invert_uncertain_transform",
    "pose_fusion",
    "frechet_mean",
    "estimate_gaussian_rotation_matrix_from_samples",
    "estimate_gaussian_transform_from_samples",
    "to_ellipsoid",
    "to_projected_ellipsoid",
]


def _cov6(x, name):
    return as_f64(x, name, (6, 6))


def concat_globally_uncertain_transforms(
    mean_A2B, cov_A2B, mean_B2C, cov_B2C, *, order="fourth"
):
    """Concatenate two independent globally uncertain transformations.

    Left (global) perturbations, ``Exp(xi) T``: the result's covariance is in frame C.

    Parameters
    ----------
    mean_A2B : array-like, shape (4, 4)
        Mean of transform from A to B.
    cov_A2B : array-like, shape (6, 6)
        Covariance of transform from A to B (in frame B).
    mean_B2C : array-like, shape (4, 4)
        Mean of transform from B to C.
    cov_B2C : array-like, shape (6, 6)
        Covariance of transform from B to C (in frame C).
    order : {"fourth", "second", "fourth_psd"}, optional (default: "fourth")
        "fourth": pytransform3d's fourth-order compounding (Barfoot & Furgale 2014),
        not positive semi-definite in general; "second": second order only;
        "fourth_psd": fourth order projected onto the nearest PSD matrix.

    Returns
    -------
    mean_A2C : array, shape (4, 4)
        Mean of the new pose.
    cov_A2C : array, shape (6, 6)
        Covariance of the new pose (in frame C).
    """
    return _ppoe.concat_globally(
        transform(mean_A2B, "mean_A2B"),
        _cov6(cov_A2B, "cov_A2B"),
        transform(mean_B2C, "mean_B2C"),
        _cov6(cov_B2C, "cov_B2C"),
        order,
    )


def concat_locally_uncertain_transforms(mean_A2B, mean_B2C, cov_A, cov_B):
    """Concatenate two independent locally uncertain transformations.

    Right (local) perturbations, ``T Exp(xi)``; note the argument order (both means
    first), as in pytransform3d. Second order.

    Parameters
    ----------
    mean_A2B : array-like, shape (4, 4)
        Mean of transform from A to B.
    mean_B2C : array-like, shape (4, 4)
        Mean of transform from B to C.
    cov_A : array-like, shape (6, 6)
        Covariance of the perturbation in frame A.
    cov_B : array-like, shape (6, 6)
        Covariance of the perturbation in frame B.

    Returns
    -------
    mean_A2C : array, shape (4, 4)
        Mean of the new pose.
    cov_A_total : array, shape (6, 6)
        Covariance of the accumulated perturbation in frame A.
    """
    return _ppoe.concat_locally(
        transform(mean_A2B, "mean_A2B"),
        transform(mean_B2C, "mean_B2C"),
        _cov6(cov_A, "cov_A"),
        _cov6(cov_B, "cov_B"),
    )


def invert_uncertain_transform(mean, cov):
    """Invert uncertain transform (left / global perturbation).

    Parameters
    ----------
    mean : array-like, shape (4, 4)
        Mean of the transform.
    cov : array-like, shape (6, 6)
        Covariance of the transform.

    Returns
    -------
    mean_inv : array, shape (4, 4)
        Mean of the inverted transform.
    cov_inv : array, shape (6, 6)
        Covariance of the inverted transform.
    """
    return _ppoe.invert(transform(mean, "mean"), _cov6(cov, "cov"))


def pose_fusion(means, covs):
    """Fuse poses of the same frame (left / global perturbations).

    Minimises ``V(T) = 1/2 sum_k Log(T T_k^-1)^T covs_k^-1 Log(T T_k^-1)``
    (Barfoot & Furgale 2014).

    Parameters
    ----------
    means : array-like, shape (K, 4, 4)
        The K estimated poses (1 <= K <= 16).
    covs : array-like, shape (K, 6, 6)
        Their covariances (invertible).

    Returns
    -------
    mean : array, shape (4, 4)
        The fused pose.
    cov : array, shape (6, 6)
        Its covariance.
    V : float
        The error of the fused estimate, ``V(mean)``.

    Raises
    ------
    ppoe.PpoeError
        For a singular covariance, more than 16 poses, or a run that did not converge.
    """
    means = as_f64(means, "means", (None, 4, 4))
    for k, m in enumerate(means):
        check_transform(m, f"means[{k}]")
    covs = as_f64(covs, "covs", (len(means), 6, 6))
    mean, cov, cost, _iterations, converged = _ppoe.pose_fusion(means, covs)
    if not converged:
        raise _ppoe.PpoeError("pose_fusion: the iteration did not reach a stationary point")
    return mean, cov, cost


def frechet_mean(
    samples,
    mean0,
    exp,
    log,
    inv,
    concat_one_to_one,
    concat_many_to_one,
    n_iter=20,
):
    """Compute the Fréchet mean of samples on a smooth Riemannian manifold.

    The generic driver with the caller's group operations (all the math is in the
    callables; the estimators below run the core's iteration instead):
    ``n_iter`` times ``diffs = log(concat_many_to_one(samples, inv(mean)))``,
    ``mean = concat_one_to_one(mean, exp(mean of diffs))``.

    Parameters
    ----------
    samples : array-like, shape (n_samples, ...)
        Samples on the manifold.
    mean0 : array-like, shape (...)
        Initial guess for the mean.
    exp : callable
        Exponential map (tangent vector to manifold element).
    log : callable
        Logarithmic map of many elements, shape (n_samples, ...) to (n_samples, d).
    inv : callable
        Inverse of one element.
    concat_one_to_one : callable
        Concatenation of two elements.
    concat_many_to_one : callable
        Concatenation of many elements with one.
    n_iter : int, optional (default: 20)
        Number of iterations.

    Returns
    -------
    mean : array, shape (...)
        The Fréchet mean.
    mean_diffs : array, shape (n_samples, d)
        Differences of the samples to the mean before the last update.
    """
    if len(samples) == 0:
        raise ValueError("samples: no input elements")
    samples = np.asarray(samples)
    mean = np.copy(mean0)
    mean_diffs = None
    for _ in range(n_iter):
        mean_diffs = log(concat_many_to_one(samples, inv(mean)))
        mean = concat_one_to_one(mean, exp(np.mean(mean_diffs, axis=0)))
    return mean, mean_diffs


def estimate_gaussian_rotation_matrix_from_samples(samples, *, compat=True):
    """Estimate Gaussian distribution over rotations from samples.

    Fréchet mean and the covariance (divisor N - 1) of the right differences
    ``Log(mean^T R_i)``.

    Parameters
    ----------
    samples : array-like, shape (n_samples, 3, 3)
        Rotation matrices (at least 2).
    compat : bool, optional (default: True)
        True: pytransform3d's 20 left-updated iterations (converges only for mean
        rotations below 60 degrees). False: the core's right-updated iteration to
        convergence (any angle; the same result where pytransform3d converges).

    Returns
    -------
    mean : array, shape (3, 3)
        Mean rotation matrix.
    cov : array, shape (3, 3)
        Covariance of the right differences (compact axis-angle).
    """
    samples = as_f64(samples, "samples", (None, 3, 3))
    return _ppoe.estimate_gaussian_rotation(samples, bool(compat))


def estimate_gaussian_transform_from_samples(samples, *, compat=True):
    """Estimate Gaussian distribution over transformations from samples.

    Fréchet mean and the covariance (divisor N - 1) of the right differences
    ``Log(mean^-1 T_i)`` (exponential coordinates, rotation first).

    Parameters
    ----------
    samples : array-like, shape (n_samples, 4, 4)
        Rigid transforms (at least 2).
    compat : bool, optional (default: True)
        As in :func:`estimate_gaussian_rotation_matrix_from_samples`.

    Returns
    -------
    mean : array, shape (4, 4)
        Mean transform.
    cov : array, shape (6, 6)
        Covariance of the right differences.
    """
    samples = as_f64(samples, "samples", (None, 4, 4))
    return _ppoe.estimate_gaussian_transform(samples, bool(compat))


def to_ellipsoid(mean, cov):
    """Compute error ellipsoid of a 3D Gaussian.

    Parameters
    ----------
    mean : array-like, shape (3,)
        Mean of the distribution.
    cov : array-like, shape (3, 3)
        Covariance of the distribution.

    Returns
    -------
    ellipsoid2origin : array, shape (4, 4)
        Ellipsoid frame in the world frame: rotation columns are the axes (ascending
        radii, ``det = +1``), translation the mean.
    radii : array, shape (3,)
        Standard deviations along the axes, ascending.
    """
    return _ppoe.to_ellipsoid(as_f64(mean, "mean", (3,)), as_f64(cov, "cov", (3, 3)))


def _reference_order(values, vectors):
    """The core's eigenpairs in pytransform3d's order: descending, and exactly equal
    eigenvalues ordered by the index of their vector's largest component, descending.

    pytransform3d reverses the ascending order of LAPACK, which returns the eigenvectors of
    a diagonal matrix's equal entries in index order: so ``np.eye(6)`` gives the
    translation axes first, whose grid is the unit sphere (its own test checks this).
    """
    dominant = np.argmax(np.abs(vectors), axis=0)
    order = np.lexsort((-dominant, -values))
    return np.ascontiguousarray(values[order]), np.ascontiguousarray(vectors[:, order])


def to_projected_ellipsoid(mean, cov, factor=1.96, n_steps=20, *, eigen=None):
    """Compute projected error ellipsoid (pytransform3d's surface of a pose).

    Points ``Rbar (R(E)^T p(E)) + tbar``, ``E = Exp(V_3 diag(factor sqrt(l_3)) u)``
    over a unit-sphere grid u, with the three largest eigenvalues ``l_3`` of ``cov``.

    Parameters
    ----------
    mean : array-like, shape (4, 4)
        Mean pose.
    cov : array-like, shape (6, 6)
        Covariance of the pose.
    factor : float, optional (default: 1.96)
        Multiple of the standard deviations.
    n_steps : int, optional (default: 20)
        Grid steps per angle (2 to 2000).
    eigen : tuple (values (6,), vectors (6, 6)), optional
        An eigen basis of ``cov``, values descending, vectors as columns (e.g. from
        ``scipy.linalg.eigh`` reordered) instead of ppoe's.

    Returns
    -------
    x, y, z : array, shape (n_steps, n_steps)
        Coordinates of the grid points.
    """
    mean = transform(mean, "mean")
    cov = _cov6(cov, "cov")
    if eigen is None:
        eigen = _reference_order(*_ppoe.symmetric_eigen6(cov))
    else:
        values, vectors = eigen
        eigen = (as_f64(values, "eigen values", (6,)), as_f64(vectors, "eigen vectors", (6, 6)))
    n = int(n_steps)
    if not 2 <= n <= 2000:
        raise ValueError(f"n_steps must be 2 to 2000, got {n_steps}")
    points = _ppoe.to_projected_ellipsoid(mean, cov, float(factor), n, eigen)
    return tuple(np.ascontiguousarray(points[:, k].reshape(n, n)) for k in range(3))
