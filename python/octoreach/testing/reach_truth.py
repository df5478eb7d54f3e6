"""The reachability of tool poses by saturated IK: the truth a capability map is checked against.

A pose (4x4, the chain's base link frame) is reachable when some configuration inside the joint limits, free
of self-collision (joints off the chain at `reference`), puts the tool within 1 mm of the position with its
approach axis within 0.01 rad of the pose's (any roll about it), the criteria of the map's own cells.
``ik_truth`` asks IK in rounds of random restarts, each round only for the poses no earlier round reached, and
reports in which round each pose was first reached: a last round that still finds poses says the truth is not
saturated. ``check_poses`` draws the poses of the agreement checks: half the tool poses of random
self-collision-free configurations (reachable by construction), half uniform in the workspace box with
rotations uniform on SO(3).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._core import Chain, Robot

POSITION_TOLERANCE = 1e-3  # the map's cell criteria (CapabilityMapOptions' defaults)
ORIENTATION_TOLERANCE = 1e-2


@dataclass
class Truth:
    """reachable (N,) bool; solutions (N, dof), NaN rows where unreachable; round (N,) of the round that first
    reached the pose (-1: none); known (N,) True where the pose came from a collision-free configuration."""

    reachable: np.ndarray
    solutions: np.ndarray
    round: np.ndarray
    known: np.ndarray

    @property
    def ik_missed_known(self) -> int:
        """Poses reachable by construction that IK did not reach: the truth's own misses, counted."""
        return int(np.count_nonzero(self.known & (self.round < 0)))


def random_rotations(n: int, rng: np.random.Generator) -> np.ndarray:
    """(n, 3, 3) rotations uniform on SO(3) (unit quaternions from four normal deviates)."""
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=1),
    ], axis=1)


def workspace_box(chain: Chain, samples: int = 20000, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi) corners of the box of the tool positions of `samples` random configurations (base link frame)."""
    P = chain.fk_batch(chain.random_configurations(samples, seed))[:, :3, 3]
    return P.min(axis=0), P.max(axis=0)


def free_configurations(robot: Robot, chain: Chain, reference, n: int, seed: int) -> np.ndarray:
    """(n, dof) random configurations of the chain inside its limits whose robot configuration (the rest at
    `reference`) is free of self-collision."""
    rng_seed, out, drawn = seed, [], 0
    while len(out) < n:
        Q = chain.random_configurations(max(64, 2 * (n - len(out))), rng_seed)
        rng_seed += 1
        for q in Q:
            drawn += 1
            if not robot.in_self_collision(chain.to_robot_configuration(q, reference)):
                out.append(q)
                if len(out) == n:
                    break
        if drawn > 200 * n + 10000:
            raise RuntimeError(f"fewer than 1 in 200 random configurations of {chain.tip_link!r} are free of "
                               "self-collision: check the robot's allowed-collision matrix")
    return np.array(out)


def check_poses(robot: Robot, chain: Chain, reference, n: int, seed: int = 0):
    """(poses (n, 4, 4), known (n,) bool): the first n // 2 are tool poses of self-collision-free random
    configurations (known reachable), the rest uniform in workspace_box with rotations uniform on SO(3)."""
    n_fk = n // 2
    rng = np.random.default_rng(seed)
    fk = chain.fk_batch(free_configurations(robot, chain, reference, n_fk, seed)) if n_fk else np.zeros((0, 4, 4))
    lo, hi = workspace_box(chain, seed=seed + 1)
    box = np.tile(np.eye(4), (n - n_fk, 1, 1))
    box[:, :3, :3] = random_rotations(n - n_fk, rng)
    box[:, :3, 3] = rng.uniform(lo, hi, size=(n - n_fk, 3))
    known = np.zeros(n, bool)
    known[:n_fk] = True
    return np.concatenate([fk, box]), known


def ik_truth(chain: Chain, poses, approach_axis, reference, known=None, rounds: int = 5, attempts: int = 20,
             seed: int = 0) -> Truth:
    """Saturated IK of tool poses (N, 4, 4): `rounds` rounds of `attempts` random restarts (approach mode, any
    roll, self-collision checked with the rest of the robot at `reference`), each round asked only for the
    poses not reached yet. Poses flagged `known` count as reachable whatever IK says."""
    poses = np.asarray(poses, float)
    n = len(poses)
    known = np.zeros(n, bool) if known is None else np.asarray(known, bool)
    solutions = np.full((n, chain.dof), np.nan)
    found = np.full(n, -1)
    for r in range(rounds):
        todo = np.flatnonzero(found < 0)
        if len(todo) == 0:
            break
        Q, ok = chain.ik_batch(poses[todo], mode="approach", approach_axis=approach_axis, self_collision=True,
                               reference=reference, attempts=attempts, rng_seed=seed + 7919 * r,
                               position_tolerance=POSITION_TOLERANCE, orientation_tolerance=ORIENTATION_TOLERANCE)
        solutions[todo[ok]] = Q[ok]
        found[todo[ok]] = r
    return Truth(reachable=(found >= 0) | known, solutions=solutions, round=found, known=known)
