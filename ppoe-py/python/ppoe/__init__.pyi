from . import uncertainty as uncertainty
from ._ppoe import PpoeError as PpoeError
from ._robot import ProbabilisticRobotKinematics as ProbabilisticRobotKinematics
from ._ros import to_ros_pose_with_covariance as to_ros_pose_with_covariance

__version__: str
__all__ = ["PpoeError", "ProbabilisticRobotKinematics", "to_ros_pose_with_covariance", "uncertainty"]
