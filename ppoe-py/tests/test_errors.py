"""Bad input: a clear ValueError (``ppoe.PpoeError`` for the core's errors), never a
crash or a silent wrong answer; copies for dtypes and layouts that are merely
inconvenient."""

import numpy as np
import pytest

import ppoe
import ppoe.uncertainty as pu
from conftest import SEED_JOINTS


@pytest.fixture(scope="module")
def robot(seed_urdf):
    return ppoe.ProbabilisticRobotKinematics(seed_urdf, "tcp", "linkmount", SEED_JOINTS)


def test_ppoe_error_is_a_value_error():
    assert issubclass(ppoe.PpoeError, ValueError)


def test_core_message_for_a_non_psd_covariance(robot, seed_covs):
    bad = seed_covs.copy()
    bad[0] = -np.eye(6)
    with pytest.raises(ppoe.PpoeError, match="covariance is not positive semi-definite"):
        robot.probabilistic_forward_kinematics(np.zeros(6), bad)


def test_batch_error_names_the_configuration(robot, seed_covs):
    covs = np.repeat(seed_covs[np.newaxis], 3, axis=0)
    covs[2, 1] = np.diag([0, 1, 0, 0, 0, -1.0])
    with pytest.raises(ppoe.PpoeError, match="configuration 2: covariance is not positive"):
        robot.probabilistic_forward_kinematics(np.zeros((3, 6)), covs)


@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_non_finite_thetas(robot, seed_covs, value):
    thetas = np.zeros(6)
    thetas[3] = value
    with pytest.raises(ValueError, match="NaN or infinity"):
        robot.probabilistic_forward_kinematics(thetas, seed_covs)


@pytest.mark.parametrize(
    "thetas, covs_shape",
    [((5,), (6, 6, 6)), ((6,), (5, 6, 6)), ((6,), (6, 6)), ((2, 6), (3, 6, 6, 6)), ((2, 3, 6), (6, 6, 6))],
)
def test_wrong_shapes(robot, thetas, covs_shape):
    with pytest.raises(ValueError, match="expected shape"):
        robot.probabilistic_forward_kinematics(np.zeros(thetas), np.zeros(covs_shape))


@pytest.mark.parametrize("dtype", [np.complex128, object, bool, "U3"])
def test_wrong_dtypes_are_rejected(robot, seed_covs, dtype):
    with pytest.raises(ValueError, match="real numeric array"):
        robot.probabilistic_forward_kinematics(np.zeros(6, dtype=dtype), seed_covs)


def test_non_contiguous_and_float32_inputs_are_copied(robot, seed_covs):
    rng = np.random.default_rng(5)
    thetas = rng.uniform(-1, 1, (4, 12))
    strided = thetas[:, ::2]  # not contiguous
    covs = np.asfortranarray(seed_covs)
    t, c = robot.probabilistic_forward_kinematics(strided, covs)
    t2, c2 = robot.probabilistic_forward_kinematics(np.ascontiguousarray(strided), seed_covs)
    np.testing.assert_array_equal(t, t2)
    np.testing.assert_array_equal(c, c2)
    t3, _ = robot.probabilistic_forward_kinematics(strided.astype(np.float32), seed_covs)
    np.testing.assert_array_equal(t3, robot.probabilistic_forward_kinematics(strided.astype(np.float32).astype(np.float64), seed_covs)[0])


def test_bad_urdf_names_the_problem(seed_urdf):
    with pytest.raises(ppoe.PpoeError, match="nolink"):
        ppoe.ProbabilisticRobotKinematics(seed_urdf, "nolink", "linkmount", SEED_JOINTS)
    with pytest.raises(ppoe.PpoeError):
        ppoe.ProbabilisticRobotKinematics("<robot", "tcp", "linkmount", SEED_JOINTS)
    with pytest.raises(ValueError, match="convention"):
        ppoe.ProbabilisticRobotKinematics(seed_urdf, "tcp", "linkmount", SEED_JOINTS, convention="up")


def test_uncertainty_inputs():
    with pytest.raises(ValueError, match="rotation part"):
        pu.invert_uncertain_transform(2 * np.eye(4), np.eye(6))
    with pytest.raises(ValueError, match="NaN"):
        pu.invert_uncertain_transform(np.eye(4), np.full((6, 6), np.nan))
    with pytest.raises(ValueError, match="expected shape"):
        pu.concat_locally_uncertain_transforms(np.eye(4), np.eye(4), np.eye(6), np.eye(5))
    with pytest.raises(ValueError, match="order"):
        pu.concat_globally_uncertain_transforms(np.eye(4), np.eye(6), np.eye(4), np.eye(6), order="third")
    with pytest.raises(ppoe.PpoeError, match="too few samples"):
        pu.estimate_gaussian_transform_from_samples(np.eye(4)[np.newaxis])
    with pytest.raises(ppoe.PpoeError, match="singular"):
        pu.pose_fusion([np.eye(4)], [np.zeros((6, 6))])
    with pytest.raises(ValueError, match="n_steps"):
        pu.to_projected_ellipsoid(np.eye(4), np.eye(6), n_steps=-3)


def test_native_module_checks_shapes_itself():
    # Called directly (bypassing the wrappers) a wrong array is still an error.
    from ppoe import _ppoe

    with pytest.raises(ValueError, match="expected shape"):
        _ppoe.invert(np.eye(3), np.eye(6))
    with pytest.raises(ValueError, match="C-contiguous"):
        _ppoe.invert(np.eye(4), np.asfortranarray(np.arange(36.0).reshape(6, 6)))


def test_mimic_joints_are_refused_not_ignored():
    # gripper.urdf's path base -> left_tip has two mimic joints; the Python package does not
    # expand them, so it must refuse the chain rather than treat them as independent.
    from conftest import ROOT
    import os

    with open(os.path.join(ROOT, "test_data", "urdf", "gripper.urdf")) as f:
        urdf = f.read()
    with pytest.raises(ppoe.PpoeError, match="mimic joints"):
        ppoe.ProbabilisticRobotKinematics(urdf, "left_tip", "base", None)



def _memory():
    """RAM plus swap in bytes, and whether Linux refuses one allocation beyond them
    outright (heuristic overcommit, mode 0); (0, False) where that cannot be read."""
    try:
        with open("/proc/sys/vm/overcommit_memory") as f:
            mode = f.read().strip()
        with open("/proc/meminfo") as f:
            info = {line.split(":")[0]: int(line.split()[1]) * 1024 for line in f}
    except (OSError, ValueError, IndexError):
        return 0, False
    return info.get("MemTotal", 0) + info.get("SwapTotal", 0), mode == "0"


def test_results_that_do_not_fit_are_a_memory_error(robot, seed_covs):
    # Joint values the machine holds, results it cannot (52 float64 per configuration
    # against 6, twice the memory there is): a MemoryError, not an aborted interpreter.
    # np.zeros maps zero pages, so the input costs little memory.
    memory, refuses = _memory()
    if not refuses:
        pytest.skip("this system's overcommit setting may grant the allocation")
    count = 2 * memory // (52 * 8) + 1
    thetas = np.zeros((count, 6))
    with pytest.raises(MemoryError, match="configurations' results"):
        robot.probabilistic_forward_kinematics(thetas, seed_covs, threads=1)


def _far():
    """A rigid transform 1e308 m from the origin: finite, but products with it overflow."""
    t = np.eye(4)
    t[:3, 3] = [1e308, 1e308, 0.0]
    return t


@pytest.mark.parametrize(
    "call",
    [
        lambda: pu.invert_uncertain_transform(_far(), np.eye(6)),
        lambda: pu.concat_globally_uncertain_transforms(_far(), np.eye(6), _far(), np.eye(6)),
        lambda: pu.concat_locally_uncertain_transforms(_far(), _far(), np.eye(6), np.eye(6)),
        lambda: pu.to_projected_ellipsoid(np.eye(4), np.eye(6) * 1e300, 1e300, 5),
    ],
)
def test_results_that_overflow_are_errors(call):
    # Finite inputs whose results are not (pytransform3d hands back inf and NaN here).
    with pytest.raises(ppoe.PpoeError, match="not finite"):
        call()


def test_chi2_probability_of_nan_is_an_error():
    with pytest.raises(ValueError, match="NaN"):
        ppoe.chi2_3_probability(float("nan"))
    assert ppoe.chi2_3_probability(float("inf")) == 1.0
