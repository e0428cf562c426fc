"""The noise fit of ``ppoe fit`` from numpy arrays."""

import warnings

from . import _ppoe
from ._checks import as_f64
from ._robot import ProbabilisticRobotKinematics

_MODELS = ("joint", "full")

# A rejected model is written by `ppoe fit` all the same, with goodness_of_fit.fits false.
_REJECTED = (
    "the goodness-of-fit test rejects the noise model (goodness_of_fit['fits'] is False, "
    "see the result's 'warnings'); `ppoe table --noise` refuses such a model unless "
    "--allow-rejected-noise"
)


def _estimate(estimate):
    if estimate is None:
        return []
    if isinstance(estimate, str):
        return [s.strip() for s in estimate.split(",")]
    items = list(estimate)
    if not all(isinstance(s, str) for s in items):
        raise ValueError(f"estimate: expected a str or a sequence of str, got {estimate!r}")
    return items


def _measurements(measurements, count):
    m = as_f64(measurements, "measurements")
    if m.shape not in ((count, 4, 4), (count, 3)):
        raise ValueError(
            f"measurements: expected shape ({count}, 4, 4) (poses) or ({count}, 3) "
            f"(positions), one per row of thetas, got {m.shape}"
        )
    return m


def fit(robot, thetas, measurements, *, model, estimate=None, measurement_cov=None, progress=None):
    """Per-joint noise fitted by maximum likelihood, as ``ppoe fit`` does.

    The model is ``T_meas = X D_1 Exp(xi_1) ... D_n Exp(xi_n) M Y Exp(nu)``: ``xi_i`` the
    joints' noise (base-frame screw coordinates, rotation first), ``nu`` the tracker's,
    ``X`` the base in the tracker's frame and ``Y`` the marker in the tip frame (identity
    unless estimated). The fit runs in Rust with the GIL released.

    Parameters
    ----------
    robot : ProbabilisticRobotKinematics
        The chain (its ``convention`` and ``dtype`` play no part: the fit is float64).
    thetas : array-like, shape (N, n)
        The joint values recorded with each measurement, as the encoders read them.
    measurements : array-like, shape (N, 4, 4) or (N, 3)
        The measured tool poses (rigid transforms; rotations orthonormal within 1e-6) or,
        position-only, the measured positions (m).
    model : {"joint", "full"}
        Keyword only, required (as ``--model``): one variance per joint along its screw
        axis, or any 6x6 PSD covariance per joint.
    estimate : str or sequence of str, optional
        The calibration groups estimated with the noise (``--estimate``): ``"base"``,
        ``"tip"``, ``"offsets"``, ``"kinematics"`` or ``"all"``, as a list or a
        comma-separated string. ``None`` (default): nothing; the measurements are then
        in the base frame with the marker at the tip frame.
    measurement_cov : array-like, shape (6, 6) or (3, 3), optional
        The tracker's noise (the input's ``measurement_cov``): 6x6 for poses (marker
        frame, rotation first), 3x3 for positions (m^2). ``None`` (default): zero.
    progress : callable, optional
        ``progress(step, log_likelihood)`` after each step of the optimiser. An exception
        it raises stops further calls and is raised once the fit has finished.

    Returns
    -------
    result : dict
        The content of ``ppoe fit``'s JSON output, key for key: ``model``, ``chain``
        (``base``, ``tip``, ``joints``), ``joints`` (a list of dicts: ``name``, ``cov``
        (6, 6), ``cov_se`` (6, 6), ``sigma2``, ``sigma2_se``, ``sigma``, ``offset``,
        ``offset_se``, ``axis_correction`` (6,), ``axis_correction_se`` (6,)),
        ``log_likelihood``, ``samples``, ``converged``, ``iterations``, ``measurement``,
        ``measurement_cov``, ``residual_floor``, ``identifiability``,
        ``goodness_of_fit`` (with ``mean_test`` and ``calibration_test``),
        ``prediction_error``, ``calibration`` and ``warnings``. Numeric vectors and
        matrices are float64 arrays of their shape, an entry the data do not determine
        (``null`` in the JSON) NaN; scalars are float, int or bool, a ``null`` scalar
        None; ``null_directions`` lists hold ``[name, weight]`` lists.

    Warns
    -----
    RuntimeWarning
        One per entry of ``result["warnings"]`` (``ppoe fit`` prints them on standard
        error: not converged, clipped joint values, a large residual floor, ...), and
        one if ``result["goodness_of_fit"]["fits"]`` is False (the goodness-of-fit test
        rejects the model): the result is returned, as ``ppoe fit`` writes it, and is not
        to be used as a noise model.

    Raises
    ------
    ppoe.PpoeError
        If the fit cannot be made (the message names the sample where it can): too few
        samples, a pose that is not rigid, a measurement covariance that is not
        symmetric PSD, configurations that do not determine the model.
    ValueError
        For wrong shapes or dtypes, NaN or infinity, an unknown ``model`` or
        ``estimate`` group.
    TypeError
        If ``robot`` is not a :class:`ProbabilisticRobotKinematics` or ``progress`` is
        not callable.
    """
    if not isinstance(robot, ProbabilisticRobotKinematics):
        raise TypeError(
            f"robot: expected a ppoe.ProbabilisticRobotKinematics, got {type(robot).__name__}"
        )
    if model not in _MODELS:
        raise ValueError(f"model must be one of {_MODELS}, not {model!r}")
    if progress is not None and not callable(progress):
        raise TypeError(f"progress: expected a callable or None, got {progress!r}")
    t = as_f64(thetas, "thetas", (None, robot.n_joints))
    m = _measurements(measurements, len(t))
    r = None
    if measurement_cov is not None:
        d = 6 if m.ndim == 3 else 3
        r = as_f64(measurement_cov, "measurement_cov", (d, d))
    result = _ppoe.fit(robot._robot, t, m, r, model, _estimate(estimate), progress)
    for w in result["warnings"]:
        warnings.warn(w, RuntimeWarning, stacklevel=2)
    if not result["goodness_of_fit"]["fits"]:
        warnings.warn(_REJECTED, RuntimeWarning, stacklevel=2)
    return result
