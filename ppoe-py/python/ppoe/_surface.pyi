from typing import Literal, Optional, Tuple

import numpy as np
import numpy.typing as npt

_A = npt.NDArray[np.float64]

def surface(
    pose: npt.ArrayLike,
    cov: npt.ArrayLike,
    kind: Literal["lift", "marginal", "pytransform3d"] = "lift",
    k: Optional[float] = None,
    probability: Optional[float] = None,
    n_steps: int = 50,
) -> Tuple[_A, _A, _A]: ...
def chi2_3_radius(probability: float) -> float: ...
def chi2_3_probability(k: float) -> float: ...
