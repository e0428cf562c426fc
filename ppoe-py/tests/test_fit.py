"""ppoe.fit: the noise fit of `ppoe fit` from numpy arrays.

* Recovery: on poses simulated here in numpy (a product of exponentials written below,
  not the core's), the fitted per-joint variances recover the simulated ones within a few
  of their reported standard errors.
* Against the command: on the datasets of test_data/fit/, the result equals, bit for bit
  and key for key, the JSON `ppoe fit` wrote for them (test_data/fit/README.md: how they
  were made). The files are the oracle; the test cannot tell a change of the command's
  output since they were written, only a difference between the binding and them. It
  fails if a key is missing or extra, a type differs (int, float, bool, str, None), an
  array has another shape, or one number differs in any bit (exact: the same arithmetic
  on the same doubles; on a platform whose libm rounds exp/log differently in the last
  bit the files would have to be rewritten there).
* Errors: wrong shapes, NaN, too few samples, a non-rigid pose, bad options.
"""

import json
import os
import warnings

import numpy as np
import pytest

import ppoe
from ppoe import _ppoe
from conftest import ROOT

DATA = os.path.join(ROOT, "test_data", "fit")


@pytest.fixture(scope="module")
def robot(seed_urdf):
    return ppoe.ProbabilisticRobotKinematics(seed_urdf, "tcp", "linkmount", None)


def _hat(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _exp(screw, theta):
    """Exp(S theta) for a unit screw S = (w, v), rotation first (|w| = 1 or w = 0)."""
    w, v = screw[:3], screw[3:]
    t = np.eye(4)
    if np.linalg.norm(w) == 0.0:
        t[:3, 3] = v * theta
        return t
    k = _hat(w)
    s, c = np.sin(theta), np.cos(theta)
    t[:3, :3] = np.eye(3) + s * k + (1.0 - c) * k @ k
    t[:3, 3] = (np.eye(3) * theta + (1.0 - c) * k + (theta - s) * k @ k) @ v
    return t


def _poe(robot, theta):
    t = np.eye(4)
    for s, x in zip(robot.screw_axes_home, theta):
        t = t @ _exp(s, x)
    return t @ robot.ee2base_home


def test_numpy_product_of_exponentials_is_the_robots(robot):
    # The simulator below is only as good as this: it must be the robot's kinematics.
    rng = np.random.default_rng(3)
    th = rng.uniform(-0.8, 0.8, (5, robot.n_joints))
    fk = robot.forward_kinematics(th)
    for t, f in zip(th, fk):
        np.testing.assert_allclose(_poe(robot, t), f, atol=1e-12)


def test_recovers_simulated_joint_variances(robot):
    n, count = robot.n_joints, 1000
    truth = np.array([4.0, 1.0, 2.0, 3.0, 0.5, 5.0]) * 1e-5
    rng = np.random.default_rng(29)
    lim = np.clip(robot.joint_limits, -3.0, 3.0)
    thetas = rng.uniform(0.8 * lim[:, 0], 0.8 * lim[:, 1], (count, n))
    # Joint noise: Exp(S(theta + e)) = Exp(S theta) Exp(S e), the joint model exactly.
    noisy = thetas + rng.normal(0.0, np.sqrt(truth), (count, n))
    poses = np.array([_poe(robot, t) for t in noisy])
    out = ppoe.fit(robot, thetas, poses, model="joint")
    assert out["converged"] and out["goodness_of_fit"]["fits"], out["warnings"]
    assert [j["name"] for j in out["joints"]] == [f"joint{i}" for i in range(1, 7)]
    for j, s2, screw in zip(out["joints"], truth, robot.screw_axes_home):
        est, se = j["sigma2"], j["sigma2_se"]
        # Standard errors small enough for the check to mean something (1000 samples:
        # about 5 % of the variance), and the truth within 4 of them.
        assert 0.0 < se < 0.1 * s2, j
        assert abs(est - s2) < 4.0 * se, (j["name"], est, s2, se)
        assert j["sigma"] == np.sqrt(est)
        # The joint model's covariance is sigma^2 S S^T.
        np.testing.assert_allclose(j["cov"], est * np.outer(screw, screw), rtol=1e-12, atol=1e-20)


def _load(name):
    with open(os.path.join(DATA, name + ".json")) as f:
        d = json.load(f)
    thetas = np.array([s["thetas"] for s in d["samples"]])
    key = "pose" if "pose" in d["samples"][0] else "position"
    return thetas, np.array([s[key] for s in d["samples"]]), d.get("measurement_cov")


def _numeric(v):
    """Whether the JSON value is a rectangular array of numbers and nulls."""
    if not isinstance(v, list) or not v:
        return False
    if all(x is None or (isinstance(x, (int, float)) and not isinstance(x, bool)) for x in v):
        return True
    return all(_numeric(x) for x in v) and len({np.shape(x) for x in v}) == 1


def _same(got, want, path="result"):
    """`got` (the binding's) against `want` (the command's JSON), exactly."""
    if isinstance(want, dict):
        assert isinstance(got, dict) and set(got) == set(want), (path, set(got) ^ set(want))
        for k in want:
            _same(got[k], want[k], f"{path}[{k!r}]")
    elif _numeric(want):
        expected = np.array(want, dtype=object)
        expected = np.where(expected == None, np.nan, expected).astype(np.float64)  # noqa: E711
        assert isinstance(got, np.ndarray) and got.dtype == np.float64, path
        assert got.shape == expected.shape, (path, got.shape, expected.shape)
        assert np.array_equal(got, expected, equal_nan=True), (path, got, expected)
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), (path, got)
        for i, (g, w) in enumerate(zip(got, want)):
            _same(g, w, f"{path}[{i}]")
    else:
        assert type(got) is type(want) and got == want, (path, got, want)


@pytest.mark.parametrize(
    "name, oracle, options",
    [
        ("seed_joint", "seed_joint.fit", {"model": "joint"}),
        # Not converged in 241 steps (the command says so in its warnings): the same steps.
        ("seed_joint", "seed_joint.full.fit", {"model": "full"}),
        ("seed_position", "seed_position.fit", {"model": "joint", "estimate": "base,tip"}),
    ],
)
def test_equals_the_commands_output(robot, name, oracle, options):
    thetas, measured, r = _load(name)
    with open(os.path.join(DATA, oracle + ".json")) as f:
        want = json.load(f)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = ppoe.fit(robot, thetas, measured, measurement_cov=r, **options)
    _same(got, want)
    # Each of the command's stderr warnings is a RuntimeWarning here.
    assert [str(w.message) for w in caught] == want["warnings"]
    assert all(w.category is RuntimeWarning for w in caught)


def test_estimate_as_a_list_is_the_string(robot):
    thetas, measured, r = _load("seed_position")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        a = ppoe.fit(robot, thetas, measured, model="joint", estimate="base, tip", measurement_cov=r)
        b = ppoe.fit(robot, thetas, measured, model="joint", estimate=["tip", "base"], measurement_cov=r)
    assert a["calibration"]["estimated"] == b["calibration"]["estimated"] == ["base", "tip"]
    assert a["log_likelihood"] == b["log_likelihood"]


def test_a_rejected_fit_is_returned_with_a_warning(robot):
    # Positions in a tracker's frame 2 m away, fitted as if in the base frame: the
    # goodness-of-fit test rejects the model, which is returned all the same.
    thetas, measured, r = _load("seed_position")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = ppoe.fit(robot, thetas, measured, model="joint", measurement_cov=r)
    assert out["goodness_of_fit"]["fits"] is False
    messages = [str(w.message) for w in caught]
    assert messages[:-1] == out["warnings"]
    assert messages[-1].startswith("the goodness-of-fit test rejects the noise model")


def test_progress_is_called_and_its_exception_raised(robot):
    thetas, measured, _ = _load("seed_joint")
    steps = []
    ppoe.fit(robot, thetas, measured, model="joint", progress=lambda i, l: steps.append((i, l)))
    assert steps and all(isinstance(i, int) and np.isfinite(l) for i, l in steps)

    calls = []

    def fail(i, l):
        calls.append(i)
        raise KeyError("stop")

    with pytest.raises(KeyError, match="stop"):
        ppoe.fit(robot, thetas, measured, model="joint", progress=fail)
    assert len(calls) == 1


@pytest.fixture(scope="module")
def data():
    thetas, measured, _ = _load("seed_joint")
    return thetas[:50], measured[:50]


@pytest.mark.parametrize(
    "thetas_shape, measured_shape, match",
    [
        ((50, 5), (50, 4, 4), r"thetas: expected shape \(N, 6\)"),
        ((50,), (50, 4, 4), r"thetas: expected shape \(N, 6\)"),
        ((50, 6), (50, 4, 3), r"measurements: expected shape \(50, 4, 4\)"),
        ((50, 6), (49, 4, 4), r"measurements: expected shape \(50, 4, 4\)"),
        ((50, 6), (50, 2), r"or \(50, 3\)"),
    ],
)
def test_wrong_shapes(robot, thetas_shape, measured_shape, match):
    with pytest.raises(ValueError, match=match) as e:
        ppoe.fit(robot, np.zeros(thetas_shape), np.zeros(measured_shape), model="joint")
    assert not isinstance(e.value, ppoe.PpoeError)


@pytest.mark.parametrize("what", ["thetas", "measurements"])
@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_non_finite(robot, data, what, value):
    thetas, measured = data[0].copy(), data[1].copy()
    (thetas if what == "thetas" else measured)[7].flat[2] = value
    with pytest.raises(ValueError, match=f"{what}: input contains NaN or infinity"):
        ppoe.fit(robot, thetas, measured, model="joint")


def test_wrong_dtype(robot, data):
    with pytest.raises(ValueError, match="thetas: expected a real numeric array"):
        ppoe.fit(robot, data[0].astype(complex), data[1], model="joint")


def test_too_few_samples(robot, data):
    with pytest.raises(ppoe.PpoeError, match="5 samples given, the model needs at least 10"):
        ppoe.fit(robot, data[0][:5], data[1][:5], model="joint")
    with pytest.raises(ppoe.PpoeError, match="0 samples given"):
        ppoe.fit(robot, np.zeros((0, 6)), np.zeros((0, 4, 4)), model="joint")


def test_pose_not_rigid_names_the_sample(robot, data):
    measured = data[1].copy()
    measured[4, 0, 0] = 2.0
    with pytest.raises(ppoe.PpoeError, match="sample 4: the pose is not a rigid transform"):
        ppoe.fit(robot, data[0], measured, model="joint")


def test_measurement_cov(robot, data):
    with pytest.raises(ValueError, match=r"measurement_cov: expected shape \(6, 6\)"):
        ppoe.fit(robot, *data, model="joint", measurement_cov=np.eye(3))
    with pytest.raises(ValueError, match=r"measurement_cov: expected shape \(3, 3\)"):
        ppoe.fit(robot, data[0], data[1][:, :3, 3], model="joint", measurement_cov=np.eye(6))
    with pytest.raises(ppoe.PpoeError, match="measurement_cov"):
        ppoe.fit(robot, *data, model="joint", measurement_cov=-np.eye(6))


def test_bad_options(robot, data):
    with pytest.raises(ValueError, match="model must be one of"):
        ppoe.fit(robot, *data, model="diagonal")
    with pytest.raises(TypeError):
        ppoe.fit(robot, *data)  # model is required, as --model is
    with pytest.raises(ValueError, match="estimate: unknown group \"knee\""):
        ppoe.fit(robot, *data, model="joint", estimate="base,knee")
    with pytest.raises(ValueError, match="estimate: expected a str or a sequence of str"):
        ppoe.fit(robot, *data, model="joint", estimate=[1])
    with pytest.raises(TypeError, match="progress: expected a callable"):
        ppoe.fit(robot, *data, model="joint", progress=3)
    with pytest.raises(TypeError, match="robot: expected a ppoe.ProbabilisticRobotKinematics"):
        ppoe.fit("seed.urdf", *data, model="joint")


def test_native_module_checks_shapes_itself(robot, data):
    with pytest.raises(ValueError, match=r"thetas: expected shape \(N, 6\)"):
        _ppoe.fit(robot._robot, np.zeros((50, 5)), data[1], None, "joint", [])
    with pytest.raises(ValueError, match=r"measurements: expected shape \(50, 3\)"):
        _ppoe.fit(robot._robot, data[0], np.zeros((50, 4)), None, "joint", [])
    with pytest.raises(ValueError, match="model must be 'joint' or 'full'"):
        _ppoe.fit(robot._robot, *data, None, "other", [])


def test_stub_matches_the_signature():
    # _fit.pyi is what type checkers see: the same parameters, kinds and defaults.
    import ast
    import inspect

    path = os.path.join(os.path.dirname(ppoe.__file__), "_fit.pyi")
    with open(path) as f:
        stub = next(n for n in ast.parse(f.read()).body if isinstance(n, ast.FunctionDef))
    a = stub.args
    positional = [x.arg for x in a.args]
    keyword = {x.arg: d for x, d in zip(a.kwonlyargs, a.kw_defaults)}
    params = inspect.signature(ppoe.fit).parameters.values()
    assert positional == [p.name for p in params if p.kind is p.POSITIONAL_OR_KEYWORD]
    runtime = {p.name: p.default for p in params if p.kind is p.KEYWORD_ONLY}
    assert list(keyword) == list(runtime)
    for name, default in runtime.items():
        # A required keyword has no default in the stub either.
        assert (keyword[name] is None) == (default is inspect.Parameter.empty), name
        if keyword[name] is not None:
            assert ast.literal_eval(keyword[name]) == default, name
