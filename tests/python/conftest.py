"""Shared fixtures of the Python tests: robots, chains, reachable targets and pose errors."""
from __future__ import annotations

import os
import tempfile

import numpy as np
import pytest

# The CLI looks maps up in the map cache: the tests keep theirs out of the user's cache directory.
os.environ.setdefault("OCTOREACH_CACHE_DIR", tempfile.mkdtemp(prefix="octoreach-test-cache-"))

from octoreach import robots


@pytest.fixture
def arm():
    """A fresh test arm (tests may extend its allowed-collision matrix)."""
    return robots.test_arm()


@pytest.fixture
def arm_chain(arm):
    return arm.chain("base_link", "tool0")


def _load_pr2():
    try:
        return robots.pr2()
    except FileNotFoundError as e:  # example-robot-data is an optional extra ("robots")
        pytest.skip(f"PR2 model unavailable: {e}")


@pytest.fixture(scope="session")
def pr2():
    """One PR2 for read-only tests; tests that change the robot load their own with `fresh_pr2`."""
    return _load_pr2()


@pytest.fixture
def fresh_pr2():
    return _load_pr2


def random_configurations(chain, n: int, seed: int) -> np.ndarray:
    """(n, dof) joint rows uniform inside the limits; continuous joints in [-pi, pi)."""
    rng = np.random.default_rng(seed)
    lo = np.where(chain.continuous, -np.pi, chain.lower)
    hi = np.where(chain.continuous, np.pi, chain.upper)
    return rng.uniform(lo, hi, size=(n, chain.dof))


def reachable_targets(chain, n: int, seed: int) -> np.ndarray:
    """(n, 4, 4) tip poses (base link frame) of random configurations: reachable by construction."""
    return chain.fk_batch(random_configurations(chain, n, seed))


def pose_error(A: np.ndarray, B: np.ndarray) -> tuple[float, float]:
    """(position error in m, rotation angle in rad) between two 4x4 poses."""
    dp = float(np.linalg.norm(A[:3, 3] - B[:3, 3]))
    R = A[:3, :3].T @ B[:3, :3]
    angle = float(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)))
    return dp, angle


def rot_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    T = np.eye(4)
    T[:2, :2] = [[c, -s], [s, c]]
    return T


def translation(x: float, y: float, z: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T
