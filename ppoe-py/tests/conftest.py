"""Shared fixtures: the repository's seed robot, pytransform3d's example class."""

import importlib.util
import os

import numpy as np
import pytest

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
SEED_URDF = os.path.join(ROOT, "test_data", "urdf", "seed.urdf")
SEED_JOINTS = [f"joint{i}" for i in range(1, 7)]


@pytest.fixture(scope="session")
def seed_urdf():
    with open(SEED_URDF) as f:
        return f.read()


@pytest.fixture(scope="session")
def seed_covs():
    """The seed example's joint covariances (pytransform3d's example)."""
    covs = np.zeros((6, 6, 6))
    covs[0] = np.diag([0, 0, 1, 0, 0, 0])
    covs[1] = covs[2] = covs[4] = np.diag([0, 1, 0, 0, 0, 0])
    return covs * 0.05


@pytest.fixture(scope="session")
def oracle_module():
    """test_data/reference/generate_ppoe.py: its ``ProbabilisticChain`` follows the code
    path of pytransform3d's ``ProbabilisticRobotKinematics`` example (which is not
    shipped in pytransform3d's wheel)."""
    path = os.path.join(ROOT, "test_data", "reference", "generate_ppoe.py")
    spec = importlib.util.spec_from_file_location("generate_ppoe", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
