"""``ProbabilisticRobotKinematics`` against pytransform3d's example class, and its batch
form against the loop of single calls."""

import numpy as np
import pytest

import ppoe
from conftest import SEED_JOINTS

TOL = 1e-12


def err(ours, theirs):
    return np.max(np.abs(ours - theirs)) / max(1.0, np.max(np.abs(theirs)))


@pytest.fixture(scope="module")
def robots(seed_urdf, oracle_module):
    ours = {
        c: ppoe.ProbabilisticRobotKinematics(seed_urdf, "tcp", "linkmount", SEED_JOINTS, convention=c)
        for c in ("pytransform3d", "right", "left")
    }
    oracle = oracle_module.ProbabilisticChain(seed_urdf, "tcp", "linkmount", SEED_JOINTS)
    return ours, oracle


def random_case(rng, n=6):
    thetas = rng.uniform(-2.5, 2.5, n)  # beyond the seed's limits of +-1 sometimes
    a = rng.standard_normal((n, 6, 6)) * 0.1
    return thetas, a @ np.transpose(a, (0, 2, 1))


def test_home_data_equal_the_example(robots):
    ours, oracle = robots
    r = ours["pytransform3d"]
    assert err(r.screw_axes_home, oracle.screw_axes) == 0.0
    assert err(r.ee2base_home, oracle.home) == 0.0
    np.testing.assert_array_equal(r.joint_limits, oracle.limits)


def test_seed_example_in_the_compat_convention(robots, seed_covs):
    ours, oracle = robots
    thetas = -0.5 * np.array([1, 1, 1, 0, 1, 0])
    t, c = ours["pytransform3d"].probabilistic_forward_kinematics(thetas, seed_covs)
    _, rt, rc, _, _ = oracle.evaluate(thetas, seed_covs)
    assert t.shape == (4, 4) and c.shape == (6, 6)
    assert err(t, rt) <= TOL and err(c, rc) <= TOL


def test_every_convention_against_the_oracle(robots):
    ours, oracle = robots
    rng = np.random.default_rng(1)
    for _ in range(300):
        thetas, covs = random_case(rng)
        _, rt, compat, right, left = oracle.evaluate(thetas, covs)
        for conv, want in (("pytransform3d", compat), ("right", right), ("left", left)):
            t, c = ours[conv].probabilistic_forward_kinematics(thetas, covs)
            assert err(t, rt) <= TOL and err(c, want) <= TOL, conv


def test_integer_thetas_are_promoted(robots, seed_covs):
    r = robots[0]["right"]
    a = r.probabilistic_forward_kinematics(np.array([1, 1, 1, 0, 1, 0]), seed_covs)
    b = r.probabilistic_forward_kinematics(np.array([1.0, 1, 1, 0, 1, 0]), seed_covs)
    np.testing.assert_array_equal(a[0], b[0])
    np.testing.assert_array_equal(a[1], b[1])


@pytest.mark.parametrize("conv", ["pytransform3d", "right", "left"])
def test_batch_equals_loop_exactly(robots, conv):
    r = robots[0][conv]
    rng = np.random.default_rng(2)
    thetas = rng.uniform(-2, 2, (64, 6))
    shared = random_case(rng)[1]
    per = np.array([random_case(rng)[1] for _ in range(64)])
    t, c = r.probabilistic_forward_kinematics(thetas, shared)
    assert t.shape == (64, 4, 4) and c.shape == (64, 6, 6)
    tp, cp = r.probabilistic_forward_kinematics(thetas, per)
    fk = r.forward_kinematics(thetas)
    assert fk.shape == (64, 4, 4)
    for i in range(64):
        ts, cs = r.probabilistic_forward_kinematics(thetas[i], shared)
        np.testing.assert_array_equal(t[i], ts)
        np.testing.assert_array_equal(c[i], cs)
        ts, cs = r.probabilistic_forward_kinematics(thetas[i], per[i])
        np.testing.assert_array_equal(tp[i], ts)
        np.testing.assert_array_equal(cp[i], cs)
        np.testing.assert_array_equal(fk[i], r.forward_kinematics(thetas[i]))


@pytest.mark.parametrize("conv", ["pytransform3d", "right"])
def test_threads_give_the_same_bits(robots, conv):
    # 5000 configurations: two threads of 2500 (one per 2048 at most), three with threads=3
    # (or any larger int) capped to two; per-configuration covariances exercise the other core call.
    r = robots[0][conv]
    rng = np.random.default_rng(5)
    thetas = rng.uniform(-2, 2, (5000, 6))
    shared = random_case(rng)[1]
    per = np.repeat(shared[np.newaxis], 5000, axis=0)
    one = r.probabilistic_forward_kinematics(thetas, shared, threads=1)
    for covs in (shared, per):
        for threads in (None, 2, 3, 2**70):
            got = r.probabilistic_forward_kinematics(thetas, covs, threads=threads)
            np.testing.assert_array_equal(got[0], one[0])
            np.testing.assert_array_equal(got[1], one[1])


def test_threaded_batch_names_the_failing_configuration(robots):
    r = robots[0]["right"]
    rng = np.random.default_rng(6)
    thetas = rng.uniform(-2, 2, (5000, 6))
    per = np.repeat(random_case(rng)[1][np.newaxis], 5000, axis=0)
    per[4321, 2] = -np.eye(6)  # in the second thread's range
    with pytest.raises(ppoe.PpoeError, match="configuration 4321: "):
        r.probabilistic_forward_kinematics(thetas, per, threads=2)


@pytest.mark.parametrize("bad", [0, -1, 1.5, True, "2"])
def test_threads_must_be_a_positive_int(robots, seed_covs, bad):
    with pytest.raises(ValueError, match="threads"):
        robots[0]["right"].probabilistic_forward_kinematics(np.zeros(6), seed_covs, threads=bad)


def test_forward_kinematics_is_the_mean(robots):
    ours, oracle = robots
    rng = np.random.default_rng(3)
    for _ in range(50):
        thetas, covs = random_case(rng)
        _, rt, _, _, _ = oracle.evaluate(thetas, covs)
        assert err(ours["right"].forward_kinematics(thetas), rt) <= TOL


def test_empty_batch(robots, seed_covs):
    t, c = robots[0]["right"].probabilistic_forward_kinematics(np.zeros((0, 6)), seed_covs)
    assert t.shape == (0, 4, 4) and c.shape == (0, 6, 6)


def test_attributes_are_read_only(robots):
    r = robots[0]["right"]
    with pytest.raises(ValueError):
        r.joint_limits[0, 0] = 5.0


F32_TOL = 1e-5  # the bound of the repository's f32 golden PPOE tests against the oracle


@pytest.fixture(scope="module")
def robots32(seed_urdf):
    return {
        c: ppoe.ProbabilisticRobotKinematics(
            seed_urdf, "tcp", "linkmount", SEED_JOINTS, convention=c, dtype=np.float32
        )
        for c in ("pytransform3d", "right", "left")
    }


def test_float32_against_the_oracle(robots, robots32):
    _, oracle = robots
    rng = np.random.default_rng(4)
    for _ in range(200):
        thetas, covs = random_case(rng)
        _, rt, compat, right, left = oracle.evaluate(thetas, covs)
        for conv, want in (("pytransform3d", compat), ("right", right), ("left", left)):
            t, c = robots32[conv].probabilistic_forward_kinematics(thetas, covs)
            assert t.dtype == c.dtype == np.float32
            assert err(t, rt) <= F32_TOL and err(c, want) <= F32_TOL, conv


def test_float32_batch_equals_loop_exactly(robots32):
    r = robots32["right"]
    rng = np.random.default_rng(5)
    thetas = rng.uniform(-2, 2, (32, 6))
    covs = random_case(rng)[1]
    t, c = r.probabilistic_forward_kinematics(thetas, covs)
    fk = r.forward_kinematics(thetas)
    assert fk.dtype == np.float32
    for i in range(32):
        ts, cs = r.probabilistic_forward_kinematics(thetas[i], covs)
        np.testing.assert_array_equal(t[i], ts)
        np.testing.assert_array_equal(c[i], cs)
        np.testing.assert_array_equal(fk[i], r.forward_kinematics(thetas[i]))


def test_float32_rejects_values_beyond_its_range(robots32, seed_covs):
    with pytest.raises(ValueError, match="NaN or infinity"):
        robots32["right"].probabilistic_forward_kinematics(np.full(6, 1e300), seed_covs)
    with pytest.raises(ValueError, match="dtype"):
        ppoe.ProbabilisticRobotKinematics("", "tcp", "linkmount", SEED_JOINTS, dtype=np.int32)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("count", [None, 0, 1, 5000])
def test_out_arrays_get_the_same_bits(robots, robots32, dtype, count):
    # None: a single call into (4, 4) and (6, 6); 5000: two threads write one pair of arrays.
    r = (robots[0] if dtype == np.float64 else robots32)["pytransform3d"]
    rng = np.random.default_rng(7)
    shape = (6,) if count is None else (count, 6)
    thetas = rng.uniform(-2, 2, shape)
    per = np.repeat(random_case(rng)[1][np.newaxis], 1 if count is None else count, axis=0)
    for covs in (random_case(rng)[1], per):
        if count is None:
            covs = covs[0] if covs.ndim == 4 else covs
        want = r.probabilistic_forward_kinematics(thetas, covs)
        # Filled with NaN first: every element must be written.
        out = (np.full(want[0].shape, np.nan, dtype), np.full(want[1].shape, np.nan, dtype))
        got = r.probabilistic_forward_kinematics(thetas, covs, out=out)
        assert got[0] is out[0] and got[1] is out[1]
        np.testing.assert_array_equal(out[0], want[0])
        np.testing.assert_array_equal(out[1], want[1])


def test_out_arrays_are_checked(robots, seed_covs):
    r = robots[0]["right"]
    thetas = np.zeros((3, 6))
    ok = (np.empty((3, 4, 4)), np.empty((3, 6, 6)))
    bad = {
        "a tuple of two arrays": [ok[0], ok[1]],
        "expected a numpy array": (ok[0], [[0.0] * 6] * 6),
        "expected dtype float64": (ok[0].astype(np.float32), ok[1]),
        r"expected shape \(3, 6, 6\)": (ok[0], np.empty((2, 6, 6))),
        "not C-contiguous": (np.empty((4, 4, 3)).transpose(2, 0, 1), ok[1]),
        "read-only": (_readonly(np.empty((3, 4, 4))), ok[1]),
        "share memory": _overlapping(3),
    }
    for match, out in bad.items():
        before = [np.array(a, copy=True) for a in out if isinstance(a, np.ndarray)]
        with pytest.raises(ValueError, match=match):
            r.probabilistic_forward_kinematics(thetas, seed_covs, out=out)
        # Refused before anything was written.
        for a, b in zip([a for a in out if isinstance(a, np.ndarray)], before):
            np.testing.assert_array_equal(a, b)
    with pytest.raises(ValueError, match="shares memory with an input"):
        covs = np.array(seed_covs)
        r.probabilistic_forward_kinematics(np.zeros(6), covs, out=(np.empty((4, 4)), covs[0]))


def test_the_native_call_refuses_overlapping_arrays(robots, seed_covs):
    # Past the wrapper's checks, rust-numpy's borrow check refuses a result array that
    # overlaps the other or an input.
    r = robots[0]["right"]._robot
    covs = np.array(seed_covs)
    with pytest.raises(TypeError, match="already borrowed"):
        r.ppoe_into(np.zeros((2, 6)), covs, "right", 1, *_overlapping(2))
    base = np.zeros(2 * 6 + 2 * 16)
    thetas, poses = base[:12].reshape(2, 6), base[:32].reshape(2, 4, 4)
    with pytest.raises(TypeError, match="already borrowed"):
        r.ppoe_into(thetas, covs, "right", 1, poses, np.empty((2, 6, 6)))


def _overlapping(count):
    """(count, 4, 4) and (count, 6, 6) views of one buffer."""
    base = np.empty(36 * count)
    return base[: 16 * count].reshape(count, 4, 4), base.reshape(count, 6, 6)


def _readonly(a):
    a.flags.writeable = False
    return a


def test_robot_stub_matches_the_signatures():
    # _robot.pyi is what type checkers see: every public method's parameters, kinds and
    # defaults as the class has them.
    import ast
    import inspect
    import os

    path = os.path.join(os.path.dirname(ppoe.__file__), "_robot.pyi")
    with open(path) as f:
        tree = ast.parse(f.read())
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "ProbabilisticRobotKinematics")
    methods = {n.name: n for n in cls.body if isinstance(n, ast.FunctionDef)}
    for name in ("probabilistic_forward_kinematics", "forward_kinematics"):
        a = methods[name].args
        params = list(inspect.signature(getattr(ppoe.ProbabilisticRobotKinematics, name)).parameters.values())
        assert [x.arg for x in a.args] == [p.name for p in params if p.kind is p.POSITIONAL_OR_KEYWORD], name
        stub_kw = {x.arg: d for x, d in zip(a.kwonlyargs, a.kw_defaults)}
        runtime_kw = {p.name: p.default for p in params if p.kind is p.KEYWORD_ONLY}
        assert list(stub_kw) == list(runtime_kw), name
        for k, default in runtime_kw.items():
            assert ast.literal_eval(stub_kw[k]) == default, (name, k)
