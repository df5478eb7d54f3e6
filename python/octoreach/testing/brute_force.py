"""Brute-force references for checking maps: R_S of base poses computed by IK and collision checks alone."""
from __future__ import annotations

import numbers

import numpy as np

from .._checks import check_type, float_array
from .._core import CapabilityMap, Obstacles, Robot, Surface, SurfaceMapOptions
from ..surface_maps import GraspCheck


def direct_reachability(robot: Robot, capability_map: CapabilityMap, surface: Surface, poses, reference=None,
                        reference_frame: str = "", grasps="upper_hemisphere", resolution: float = None,
                        grasp_height: float = SurfaceMapOptions().grasp_height, attempts: int = 20,
                        seed: int = 0, obstacles: Obstacles = None) -> np.ndarray:
    """R_S of base poses (N, 4) computed by brute force, without any map: the mean over the surface's grid
    points (5 cm above it: `grasp_height`) of GraspCheck's share of grasps. `obstacles` is the rest of the
    room, as in SurfaceMap.build. For checking maps; slow. `reference` defaults to the arm's default
    reference posture, as in the map builds."""
    check_type(robot, Robot, "robot", "an octoreach.Robot")
    check_type(capability_map, CapabilityMap, "capability_map", "an octoreach.CapabilityMap")
    check_type(surface, Surface, "surface", "an octoreach.Surface")
    check_type(reference_frame, str, "reference_frame", "a link name (str)")
    check_type(grasps, (str, list, tuple, np.ndarray), "grasps", "a subset name or a list of direction indices")
    check_type(resolution, (numbers.Real, type(None)), "resolution", "a float or None")
    check_type(grasp_height, numbers.Real, "grasp_height", "a float")
    check_type(attempts, numbers.Integral, "attempts", "an int")
    check_type(seed, numbers.Integral, "seed", "an int")
    poses = float_array(poses, "poses", "an (N, 4) array: x, y, z, theta")
    if poses.ndim != 2 or poses.shape[1] != 4:
        raise ValueError("poses must have shape (N, 4): x, y, z, theta")
    if not np.all(np.isfinite(poses)):
        raise ValueError("poses must be finite (x, y, z in m, theta in rad)")
    if obstacles is not None and not isinstance(obstacles, Obstacles):
        raise TypeError(f"obstacles must be an octoreach.Obstacles or None, got {type(obstacles).__name__}")
    if reference is not None:
        reference = float_array(reference, "reference", "a vector of joint values")
    check = GraspCheck(robot, capability_map, surface, reference=reference, reference_frame=reference_frame,
                       grasps=grasps, attempts=attempts, seed=seed, obstacles=obstacles)
    res = capability_map.resolution if resolution is None else resolution
    targets = surface.points(res) + grasp_height * np.asarray(surface.normal)
    return np.array([check.shares(pose, targets).mean() for pose in poses])
