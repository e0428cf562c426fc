"""Benchmark (not a test): the PPOE of 10,000 seed-robot configurations from Python.

Per configuration, median of repeats:

* ``ppoe batch``: one ``probabilistic_forward_kinematics`` call on (10000, 6) joint values
  with the joint covariances shared (the GIL released inside), on every core (the
  default ``threads=None``), and the same with ``threads=1``;
* ``ppoe batch, out=``: the default call writing into the same two result arrays every
  time (``out=``), which allocates nothing;
* ``ppoe batch, per-config covs``: the same with (10000, 6, 6, 6) covariances;
* ``ppoe loop``: a Python loop of single calls over the same configurations;
* ``pytransform3d example``: the example's ``probabilistic_forward_kinematics`` as
  scripts/bench_pytransform3d.py times it for BENCHMARKS.md (``np.clip``, batch
  exponential, ``concat_locally_uncertain_transforms`` per joint, ``Ad(M) C Ad(M)^T``, on
  test_data/reference/generate_ppoe.py's ``ProbabilisticChain``), timed on the first 200
  configurations (10,000 would take several seconds per repeat).

``interleaved_speedup`` (and ``_one_thread``): the ratio example / ppoe batch measured in
15 rounds, each timing the ppoe batch (median of 3 calls) right before the example on its
200 configurations, so that load from other work on a shared machine falls on both alike;
the median, min and max of the rounds' ratios.

The configurations are uniform in [-1, 1]^6, the covariances the seed example's. All in
the ``pytransform3d`` convention so that the work is the example's; ``right`` costs the
same in ppoe. Prints one JSON object. Run with the wheel and pytransform3d 3.17.0
installed (the venv of scripts/python-check.sh has both):

    target/python-check/venv/bin/python ppoe-py/benches/batch.py
"""

import importlib.util
import json
import os

# OpenBLAS's idle worker threads spin on the other cores for a while after any BLAS call and
# would compete with ppoe's threads; pytransform3d's example (3x3 to 6x6 products) runs on
# one thread either way. An explicit setting in the environment is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import platform
import statistics
import time

import numpy as np

import ppoe

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
JOINTS = [f"joint{i}" for i in range(1, 7)]
N = 10_000
N_REFERENCE = 200
ROUNDS = 15


def per_config(fn, count, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) / count)
    return statistics.median(times)


def interleaved(rounds, ours, reference, count, reference_count):
    """Per-round ratios reference / ours (per configuration), the two timed back to back in
    every round so that load from other work falls on both alike: median, min, max."""
    ratios = []
    for _ in range(rounds):
        a = per_config(ours, count, 3)
        b = per_config(reference, reference_count, 1)
        ratios.append(b / a)
    return {"median": statistics.median(ratios), "min": min(ratios), "max": max(ratios)}


def seed_covs():
    covs = np.zeros((6, 6, 6))
    covs[0] = np.diag([0, 0, 1, 0, 0, 0])
    covs[1] = covs[2] = covs[4] = np.diag([0, 1, 0, 0, 0, 0])
    return covs * 0.05


def load(path, name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(ROOT, path))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    with open(os.path.join(ROOT, "test_data", "urdf", "seed.urdf")) as f:
        urdf = f.read()
    robot = ppoe.ProbabilisticRobotKinematics(urdf, "tcp", "linkmount", JOINTS, convention="pytransform3d")
    rng = np.random.default_rng(0)
    thetas = rng.uniform(-1.0, 1.0, (N, 6))
    covs = seed_covs()
    per = np.repeat(covs[np.newaxis], N, axis=0)
    pfk = robot.probabilistic_forward_kinematics
    out = (np.empty((N, 4, 4)), np.empty((N, 6, 6)))
    baseline = load(os.path.join("scripts", "bench_pytransform3d.py"), "bench_pytransform3d")
    chain = baseline.seed_chain()
    example = baseline.probabilistic_forward_kinematics

    def reference():
        return [example(chain, t, covs) for t in thetas[:N_REFERENCE]]

    result = {
        "machine": platform.machine(),
        "load_average": os.getloadavg(),
        "configurations": N,
        "cpu_count": os.cpu_count(),
        "openblas_num_threads": os.environ.get("OPENBLAS_NUM_THREADS"),
        "ppoe_batch_us": 1e6 * per_config(lambda: pfk(thetas, covs), N, 21),
        "ppoe_batch_one_thread_us": 1e6 * per_config(lambda: pfk(thetas, covs, threads=1), N, 21),
        "ppoe_batch_out_us": 1e6 * per_config(lambda: pfk(thetas, covs, out=out), N, 21),
        "ppoe_batch_per_config_covs_us": 1e6 * per_config(lambda: pfk(thetas, per), N, 11),
        "ppoe_loop_us": 1e6 * per_config(lambda: [pfk(t, covs) for t in thetas], N, 3),
        "pytransform3d_example_us": 1e6 * per_config(reference, N_REFERENCE, 3),
    }
    result["interleaved_rounds"] = ROUNDS
    result["interleaved_speedup"] = interleaved(ROUNDS, lambda: pfk(thetas, covs), reference, N, N_REFERENCE)
    result["interleaved_speedup_one_thread"] = interleaved(
        ROUNDS, lambda: pfk(thetas, covs, threads=1), reference, N, N_REFERENCE
    )
    result["speedup_batch_vs_example"] = result["pytransform3d_example_us"] / result["ppoe_batch_us"]
    result["speedup_batch_vs_loop"] = result["ppoe_loop_us"] / result["ppoe_batch_us"]
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
