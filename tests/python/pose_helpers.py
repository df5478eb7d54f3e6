"""Pose helpers of the Python tests: reachable targets, pose errors, simple transforms.

A plain module, not conftest.py: `pytest tests/python tests/fuzz` in one run would import the other folder's
conftest under the same name.
"""
from __future__ import annotations

import numpy as np


def reachable_targets(chain, n: int, seed: int) -> np.ndarray:
    """(n, 4, 4) tip poses (base link frame) of random configurations: reachable by construction."""
    return chain.fk_batch(chain.random_configurations(n, seed))


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
