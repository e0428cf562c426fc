"""The seed example (ppoe-py/examples/seed.py) gives pytransform3d's example's T and cov."""

import importlib.util
import os

import numpy as np

from conftest import ROOT, SEED_JOINTS


def test_seed_example_matches_the_oracle(seed_urdf, seed_covs, oracle_module, capsys):
    path = os.path.join(ROOT, "ppoe-py", "examples", "seed.py")
    spec = importlib.util.spec_from_file_location("seed_example", path)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    T, cov = example.main()
    assert "frame 0 equals the initial state: True" in capsys.readouterr().out
    oracle = oracle_module.ProbabilisticChain(seed_urdf, "tcp", "linkmount", SEED_JOINTS)
    _, rt, rc, _, _ = oracle.evaluate(-0.5 * np.array([1, 1, 1, 0, 1, 0]), seed_covs)
    assert np.max(np.abs(T - rt)) <= 1e-12 and np.max(np.abs(cov - rc)) <= 1e-12
