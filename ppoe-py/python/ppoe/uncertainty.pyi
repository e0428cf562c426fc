from typing import Any, Callable, Literal, Optional, Tuple

import numpy as np
import numpy.typing as npt

_A = npt.NDArray[np.float64]

def concat_globally_uncertain_transforms(
    mean_A2B: npt.ArrayLike,
    cov_A2B: npt.ArrayLike,
    mean_B2C: npt.ArrayLike,
    cov_B2C: npt.ArrayLike,
    *,
    order: Literal["fourth", "second", "fourth_psd"] = "fourth",
) -> Tuple[_A, _A]: ...
def concat_locally_uncertain_transforms(
    mean_A2B: npt.ArrayLike,
    mean_B2C: npt.ArrayLike,
    cov_A: npt.ArrayLike,
    cov_B: npt.ArrayLike,
) -> Tuple[_A, _A]: ...
def invert_uncertain_transform(mean: npt.ArrayLike, cov: npt.ArrayLike) -> Tuple[_A, _A]: ...
def pose_fusion(means: npt.ArrayLike, covs: npt.ArrayLike) -> Tuple[_A, _A, float]: ...
def frechet_mean(
    samples: npt.ArrayLike,
    mean0: npt.ArrayLike,
    exp: Callable[[Any], Any],
    log: Callable[[Any], Any],
    inv: Callable[[Any], Any],
    concat_one_to_one: Callable[[Any, Any], Any],
    concat_many_to_one: Callable[[Any, Any], Any],
    n_iter: int = 20,
) -> Tuple[Any, Any]: ...
def estimate_gaussian_rotation_matrix_from_samples(
    samples: npt.ArrayLike, *, compat: bool = True
) -> Tuple[_A, _A]: ...
def estimate_gaussian_transform_from_samples(
    samples: npt.ArrayLike, *, compat: bool = True
) -> Tuple[_A, _A]: ...
def to_ellipsoid(mean: npt.ArrayLike, cov: npt.ArrayLike) -> Tuple[_A, _A]: ...
def to_projected_ellipsoid(
    mean: npt.ArrayLike,
    cov: npt.ArrayLike,
    factor: float = 1.96,
    n_steps: int = 20,
    *,
    eigen: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = None,
) -> Tuple[_A, _A, _A]: ...
