from typing import Any, Dict, Literal

import numpy.typing as npt

def to_ros_pose_with_covariance(
    pose: npt.ArrayLike, cov: npt.ArrayLike, convention: Literal["right", "left"] = "right"
) -> Dict[str, Any]: ...
