from typing import Any, Literal, Optional, Sequence, Tuple, overload

import numpy as np
import numpy.typing as npt

Convention = Literal["right", "left", "pytransform3d"]

class ProbabilisticRobotKinematics:
    convention: Convention
    dtype: np.dtype[Any]
    joint_names: Optional[list[str]]
    joint_limits: npt.NDArray[np.float64]
    screw_axes_home: npt.NDArray[np.float64]
    ee2base_home: npt.NDArray[np.float64]
    def __init__(
        self,
        robot_urdf: str,
        ee_frame: str,
        base_frame: str,
        joint_names: Optional[Sequence[str]],
        convention: Convention = "right",
        dtype: npt.DTypeLike = np.float64,
    ) -> None: ...
    @property
    def n_joints(self) -> int: ...
    def forward_kinematics(self, thetas: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    def probabilistic_forward_kinematics(
        self,
        thetas: npt.ArrayLike,
        covs: npt.ArrayLike,
        *,
        threads: Optional[int] = None,
        out: Optional[Tuple[npt.NDArray[np.floating], npt.NDArray[np.floating]]] = None,
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
