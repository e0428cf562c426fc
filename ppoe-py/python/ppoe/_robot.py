"""The Probabilistic Product of Exponentials of a robot loaded from URDF."""

import numpy as np

from . import _ppoe
from ._checks import as_f64

_CONVENTIONS = ("right", "left", "pytransform3d")


def _readonly(a):
    a.flags.writeable = False
    return a


def _check_out(out, shapes, dtype, inputs):
    """Rejects result arrays ``out`` the native call cannot write into: not a pair of
    numpy arrays of ``shapes`` and ``dtype``, not C-contiguous, read-only, or overlapping
    each other or one of ``inputs`` (the arrays handed to the native call)."""
    if not (isinstance(out, tuple) and len(out) == 2):
        raise ValueError(f"out: expected a tuple of two arrays (ee2base, cov), got {type(out).__name__}")
    for k, (a, shape) in enumerate(zip(out, shapes)):
        name = f"out[{k}]"
        if not isinstance(a, np.ndarray):
            raise ValueError(f"{name}: expected a numpy array, got {type(a).__name__}")
        if a.dtype != dtype:
            raise ValueError(f"{name}: expected dtype {dtype}, got {a.dtype}")
        if a.shape != shape:
            raise ValueError(f"{name}: expected shape {shape}, got {a.shape}")
        if not a.flags.c_contiguous:
            raise ValueError(f"{name}: array is not C-contiguous")
        if not a.flags.writeable:
            raise ValueError(f"{name}: array is read-only")
        if any(np.may_share_memory(a, x) for x in inputs):
            raise ValueError(f"{name}: shares memory with an input")
    if np.may_share_memory(out[0], out[1]):
        raise ValueError("out: the two arrays share memory")


class ProbabilisticRobotKinematics:
    """A serial chain of a URDF robot with uncertain joints (Meyer et al. 2022).

    The model is ``T = D_1 Exp(xi_1) ... D_n Exp(xi_n) M``, ``D_i = Exp(S_i theta_i)``,
    ``xi_i ~ N(0, covs[i])`` (exponential coordinates, rotation first, base frame).

    Parameters
    ----------
    robot_urdf : str
        The URDF document (its text, not a file name).
    ee_frame : str
        The tip link.
    base_frame : str
        The base link.
    joint_names : list of str
        The moving joints of the chain, base to tip. Moving joints on the path that are
        not listed are frozen at 0.
    convention : {"right", "left", "pytransform3d"}, optional (default: "right")
        The covariance returned: of the right perturbation ``T = Tbar Exp(eta)`` (tip
        frame), of the left one ``T = Exp(eta) Tbar`` (base frame), or exactly
        pytransform3d's example (``Ad(M) C Ad(M)^T`` in the last step, continuous joints
        clipped to their limits), which is the covariance of neither.
    dtype : {numpy.float64, numpy.float32}, optional (default: float64)
        The scalar of the computation: float32 opt-in runs the core in f32 on the chain
        rounded to f32 (inputs converted to float32, results float32; about 1e-6
        relative). The attributes below stay float64.

    Attributes
    ----------
    joint_limits : array, shape (n, 2)
        Lower and upper limit of each joint (``-inf``/``inf`` if unbounded).
    screw_axes_home : array, shape (n, 6)
        Screw axes in the base frame at the home pose, rotation first.
    ee2base_home : array, shape (4, 4)
        The home pose M of the tip in the base frame.

    Raises
    ------
    ppoe.PpoeError
        If the URDF cannot be read or the chain cannot be built (the message names the
        element and position).
    """

    def __init__(
        self, robot_urdf, ee_frame, base_frame, joint_names, convention="right", dtype=np.float64
    ):
        if convention not in _CONVENTIONS:
            raise ValueError(f"convention must be one of {_CONVENTIONS}, not {convention!r}")
        dtype = np.dtype(dtype)
        if dtype not in (np.dtype(np.float64), np.dtype(np.float32)):
            raise ValueError(f"dtype must be float64 or float32, not {dtype}")
        self.convention = convention
        self.dtype = dtype
        names = None if joint_names is None else [str(n) for n in joint_names]
        self._robot = _ppoe.Robot(str(robot_urdf), str(base_frame), str(ee_frame), names)
        self.joint_names = names
        self.joint_limits = _readonly(self._robot.limits())
        self.screw_axes_home = _readonly(self._robot.screw_axes())
        self.ee2base_home = _readonly(self._robot.home())

    @property
    def _f32(self):
        return self.dtype == np.float32

    @property
    def n_joints(self):
        """int: the number of moving joints."""
        return self._robot.n_joints

    def _thetas(self, thetas):
        n = self.n_joints
        a = as_f64(thetas, "thetas", dtype=self.dtype)
        if a.ndim == 1 and a.shape == (n,):
            return a[np.newaxis], True
        if a.ndim == 2 and a.shape[1] == n:
            return a, False
        raise ValueError(f"thetas: expected shape ({n},) or (N, {n}), got {a.shape}")

    def forward_kinematics(self, thetas):
        """Tip pose(s) for joint values clipped to the limits.

        Parameters
        ----------
        thetas : array-like, shape (n,) or (N, n)
            Joint values.

        Returns
        -------
        ee2base : array, shape (4, 4) or (N, 4, 4)
            The tip pose in the base frame.
        """
        batch, single = self._thetas(thetas)
        fk = self._robot.forward_kinematics_f32 if self._f32 else self._robot.forward_kinematics
        poses = fk(batch)
        return poses[0] if single else poses

    def probabilistic_forward_kinematics(self, thetas, covs, *, threads=None, out=None):
        """Tip pose(s) and covariance(s) of the PPOE.

        Joint values are clipped to the limits (``np.clip`` semantics). The batch form
        runs in the core with the GIL released, and each of its results equals the
        single call of the same configuration exactly.

        Parameters
        ----------
        thetas : array-like, shape (n,) or (N, n)
            Joint values.
        covs : array-like, shape (n, 6, 6) or (N, n, 6, 6)
            Covariance of each joint's displacement (exponential coordinates, rotation
            first), shared by all configurations or one set per configuration; each
            symmetric positive semi-definite (within sqrt(eps) relative).
        threads : int or None, optional
            Threads a batch runs on (keyword only): ``None`` (default) every core the
            operating system offers, an int that many; a batch gets at most one thread
            per 2048 configurations. The results are the same bits whatever the count.
        out : tuple of two arrays, optional
            ``(ee2base, cov)`` to write the results into instead of new arrays (keyword
            only): the shapes below, the robot's dtype, C-contiguous, writeable, sharing
            memory with neither each other nor the joint values and covariances. They are
            returned; repeated batches then allocate no result memory. If the call raises,
            their contents are unspecified.

        Returns
        -------
        ee2base : array, shape (4, 4) or (N, 4, 4)
            The tip pose in the base frame (``out[0]`` if given).
        cov : array, shape (6, 6) or (N, 6, 6)
            Its covariance in the convention chosen at construction (``out[1]`` if
            given).

        Raises
        ------
        ppoe.PpoeError
            For a covariance that is not symmetric PSD, or a non-finite result (naming
            the configuration of a batch).
        ValueError
            For wrong shapes or dtypes, NaN or infinity, or an unusable ``out``.
        """
        n = self.n_joints
        batch, single = self._thetas(thetas)
        c = as_f64(covs, "covs", dtype=self.dtype)
        if c.shape == (n, 6, 6):
            pass
        elif single and c.shape == (1, n, 6, 6):
            c = c[0]
        elif not single and c.shape == (len(batch), n, 6, 6):
            pass
        else:
            want = f"({n}, 6, 6)" if single else f"({n}, 6, 6) or ({len(batch)}, {n}, 6, 6)"
            raise ValueError(f"covs: expected shape {want}, got {c.shape}")
        if threads is None:
            threads = 0
        elif isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
            raise ValueError(f"threads: expected a positive int or None, got {threads!r}")
        # Beyond one thread per 2048 configurations the count changes nothing; capped so
        # that any Python int fits the native call's integer.
        threads = min(threads, 1 << 31)
        if out is None:
            ppoe = self._robot.ppoe_f32 if self._f32 else self._robot.ppoe
            poses, cov = ppoe(batch, c, self.convention, threads)
            return (poses[0], cov[0]) if single else (poses, cov)
        count = len(batch)
        shapes = ((4, 4), (6, 6)) if single else ((count, 4, 4), (count, 6, 6))
        _check_out(out, shapes, self.dtype, (batch, c))
        # A C-contiguous array's reshape is a view: a single call's (4, 4) and (6, 6)
        # arrays are written as batches of one.
        views = tuple(a.reshape((count,) + a.shape[-2:]) for a in out)
        into = self._robot.ppoe_into_f32 if self._f32 else self._robot.ppoe_into
        into(batch, c, self.convention, threads, *views)
        return out
