"""ppoe: the Probabilistic Product of Exponentials from Python.

* :mod:`ppoe.uncertainty`: a drop-in for ``pytransform3d.uncertainty`` (3.17.0): the same
  functions, arguments and results, computed by the Rust core.
* :class:`ProbabilisticRobotKinematics`: a robot from URDF, its tool pose and the 6x6
  covariance of that pose for one joint configuration or a batch.
* :func:`surface`: the lift / marginal surfaces of the tool position, for plotting.
* :func:`to_ros_pose_with_covariance`: a pose and its covariance in ROS's order and frame.
* :func:`fit`: per-joint noise (and a calibration) fitted to measured tool poses, as
  ``ppoe fit`` does.

Every error of the core is a :class:`PpoeError`, a subclass of ``ValueError``; invalid
arrays (shape, dtype, NaN) are ``ValueError`` too.
"""

from ._ppoe import PpoeError
from . import uncertainty
from ._robot import ProbabilisticRobotKinematics
from ._surface import chi2_3_probability, chi2_3_radius, surface
from ._ros import to_ros_pose_with_covariance
from ._fit import fit

__all__ = ["PpoeError", "ProbabilisticRobotKinematics", "to_ros_pose_with_covariance", "uncertainty", "surface", "chi2_3_radius", "chi2_3_probability", "fit"]
__version__ = "0.1.0"
