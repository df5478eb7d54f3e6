"""The explorer robot (urdf/explorer.urdf: mobile base, 5-DOF arm, camera): its camera chain, where
its arm base stands, how far the arm reaches, the base poses around a region, and a coarse
capability map of the arm."""
from __future__ import annotations

import numpy as np

from ._options import given


def explorer_robot():
    """The project's explorer (mobile base + 5-DOF arm + camera, urdf/explorer.urdf) and its camera chain."""
    from .. import robots
    from .._core import Robot

    robot = Robot.from_urdf(str(robots.project_urdf("explorer")))
    return robot, robot.chain("arm_base_link", "camera_optical_frame")


def arm_base_pose(robot, chain, footprint=None) -> np.ndarray:
    """Pose (4x4, world) of `chain`'s base link with the robot at its home configuration and its
    root at `footprint` (4x4, world; default the origin)."""
    root = np.eye(4) if footprint is None else np.asarray(footprint, float)
    return root @ robot.link_poses(robot.home())[chain.base_link]


def arm_reach(chain, seed: int = 0, samples: int = 2000) -> float:
    """How far the tip gets from the chain's base frame origin: the largest distance over `samples`
    random configurations (unbounded joints drawn in [-pi, pi]). A cheap first prune for views."""
    rng = np.random.default_rng(seed)
    lo = np.where(np.isfinite(chain.lower), chain.lower, -np.pi)
    hi = np.where(np.isfinite(chain.upper), chain.upper, np.pi)
    Q = rng.uniform(lo, hi, size=(samples, chain.dof))
    tips = chain.fk_batch(Q)[:, :3, 3]
    return float(np.max(np.linalg.norm(tips, axis=1)))


def base_ring(region, standoff: float = 0.45) -> list:
    """Four base_footprint poses (4x4, world) around a search region ((2, 3) lo, hi), each
    `standoff` metres outside one of its vertical faces and facing the region's centre."""
    lo, hi = np.asarray(region, float)
    c = (lo + hi) / 2
    out = []
    for x, y in ((lo[0] - standoff, c[1]), (c[0], lo[1] - standoff), (c[0], hi[1] + standoff), (hi[0] + standoff, c[1])):
        yaw = np.arctan2(c[1] - y, c[0] - x)
        T = np.eye(4)
        T[:2, :2] = [[np.cos(yaw), -np.sin(yaw)], [np.sin(yaw), np.cos(yaw)]]
        T[:2, 3] = (x, y)
        out.append(T)
    return out


def explorer_capability_map(chain, resolution: float = 0.1, directions: int = 100, seed=None):
    """A coarse capability map of `chain` (camera +z as the approach axis; positions in the chain's
    base link frame) for pruning next-best-view cells and poses: about 5-10 s on two cores.
    `seed` None keeps CapabilityMap.build's default."""
    from .._core import CapabilityMap

    # Coarser than CapabilityMap.build's defaults on purpose (0.1 m, 100 directions, no progress bar):
    # it only prunes; IK stays the final check of each view. The approach axis is the camera's optical
    # axis (+z), stated because the pruning depends on it, not as a copy of the build default.
    return CapabilityMap.build(chain, resolution=resolution, directions=directions, approach_axis=(0.0, 0.0, 1.0),
                               progress=False, **given(seed=seed))
