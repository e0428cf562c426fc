from . import uncertainty as uncertainty
from ._ppoe import PpoeError as PpoeError
from ._robot import ProbabilisticRobotKinematics as ProbabilisticRobotKinematics
from ._surface import chi2_3_probability as chi2_3_probability
from ._surface import chi2_3_radius as chi2_3_radius
from ._surface import surface as surface
from ._ros import to_ros_pose_with_covariance as to_ros_pose_with_covariance
from ._fit import fit as fit

__version__: str
__all__ = ["PpoeError", "ProbabilisticRobotKinematics", "to_ros_pose_with_covariance", "uncertainty", "surface", "chi2_3_radius", "chi2_3_probability", "fit"]
