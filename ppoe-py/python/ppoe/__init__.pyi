from . import uncertainty as uncertainty
from ._ppoe import PpoeError as PpoeError
from ._robot import ProbabilisticRobotKinematics as ProbabilisticRobotKinematics

__version__: str
__all__ = ["PpoeError", "ProbabilisticRobotKinematics", "uncertainty"]
