"""Input conversion and validation shared by the wrappers.

Every array goes to the native module as a C-contiguous float64 copy (or view) of the
right shape; anything else is rejected here with a ``ValueError`` naming the argument.
Integer and float inputs of any width are converted; complex, object, string and
boolean arrays, wrong shapes, NaN and infinity are rejected.
"""

import numpy as np


def as_f64(x, name, shape=None, finite=True, dtype=np.float64):
    """``x`` as a C-contiguous float64 (or ``dtype``) array, checked.

    Parameters
    ----------
    x : array-like
        The input.
    name : str
        The argument's name, for error messages.
    shape : tuple of (int or None), optional
        The required shape; ``None`` entries match any length.
    finite : bool, optional (default: True)
        Reject NaN and infinity (after the conversion: a float64 value beyond float32's
        range is rejected, not turned into infinity silently).
    dtype : numpy dtype, optional (default: float64)
        The dtype of the result.

    Returns
    -------
    a : array
        The checked float64 array.

    Raises
    ------
    ValueError
        For a non-numeric dtype, a wrong shape or a non-finite element.
    """
    a = np.asarray(x)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{name}: expected a real numeric array, got dtype {a.dtype}")
    if shape is not None:
        ok = a.ndim == len(shape) and all(
            s is None or g == s for g, s in zip(a.shape, shape)
        )
        if not ok:
            want = "(" + ", ".join("N" if s is None else str(s) for s in shape) + ")"
            raise ValueError(f"{name}: expected shape {want}, got {a.shape}")
    with np.errstate(over="ignore"):
        a = np.ascontiguousarray(a, dtype=dtype)
    if finite and not np.isfinite(a).all():
        raise ValueError(f"{name}: input contains NaN or infinity")
    return a


def check_transform(a, name):
    """Rejects a 4x4 array that is not a rigid transform, with pytransform3d's rule.

    The rotation block must satisfy ``R R^T ~ I`` (``np.allclose``, ``atol=1e-6``) and
    ``det R >= 0``, the last row must be ``(0, 0, 0, 1)`` (``np.allclose``).

    Raises
    ------
    ValueError
        If ``a`` is not a rigid transform.
    """
    r = a[:3, :3]
    if not np.allclose(r @ r.T, np.eye(3), atol=1e-6) or np.linalg.det(r) < 0.0:
        raise ValueError(f"{name}: rotation part is not orthonormal with determinant +1")
    if not np.allclose(a[3], [0.0, 0.0, 0.0, 1.0]):
        raise ValueError(f"{name}: last row must be (0, 0, 0, 1), got {a[3]}")


def transform(x, name):
    """``x`` as a checked rigid transform, shape (4, 4)."""
    a = as_f64(x, name, (4, 4))
    check_transform(a, name)
    return a
