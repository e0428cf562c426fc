"""ppoe: the Probabilistic Product of Exponentials from Python.

* :mod:`ppoe.uncertainty`: a drop-in for ``pytransform3d.uncertainty`` (3.17.0): the same
  functions, arguments and results, computed by the Rust core.
* :class:`ProbabilisticRobotKinematics`: a robot from URDF, its tool pose and the 6x6
  covariance of that pose for one joint configuration or a batch.

Every error of the core is a :class:`PpoeError`, a subclass of ``ValueError``; invalid
arrays (shape, dtype, NaN) are ``ValueError`` too.
"""

from ._ppoe import PpoeError
from . import uncertainty
from ._robot import ProbabilisticRobotKinematics

__all__ = ["PpoeError", "ProbabilisticRobotKinematics", "uncertainty"]
__version__ = "0.1.0"
