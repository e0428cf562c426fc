from typing import Any, Callable, Dict, Literal, Optional, Sequence, Union

import numpy.typing as npt

from ._robot import ProbabilisticRobotKinematics

def fit(
    robot: ProbabilisticRobotKinematics,
    thetas: npt.ArrayLike,
    measurements: npt.ArrayLike,
    *,
    model: Literal["joint", "full"],
    estimate: Optional[Union[str, Sequence[str]]] = None,
    measurement_cov: Optional[npt.ArrayLike] = None,
    progress: Optional[Callable[[int, float], Any]] = None,
) -> Dict[str, Any]: ...
