"""Python entry points of surface maps: ``SurfaceMap.build`` accepting an arm name, and helpers."""
from __future__ import annotations

import numpy as np

from . import arms as _arms
from ._core import CapabilityMap, Robot, Surface, SurfaceMap


def build(robot: Robot, arm, surface: Surface, resolution: float = 0.05, theta_bins: int = 16, z_range=None,
          reference=None, grasps="upper_hemisphere", reference_frame: str = "", directions: int = 200,
          seed: int = 0, check_body: bool = True, check_arm: bool = True, grasp_height: float = 0.05,
          threads: int = 0,
          progress=True) -> SurfaceMap:
    """Surface map of `arm` (name, (base, tip[, approach]) tuple, or a CapabilityMap with solutions).

    Base poses (x, y, z, theta) are of `reference_frame` (default: the robot's root link, e.g.
    base_footprint) in the world frame. z_range=(0, 0) evaluates a robot standing on the floor.
    `reference` fixes the joints off the arm (default: home with the other arm tucked). Grasp points
    lie `grasp_height` above the surface (the tool holds an object standing on it).
    """
    if isinstance(arm, CapabilityMap):
        cap = arm
        if reference is None:
            reference = robot.home()
    else:
        if reference is None:
            reference = _arms.default_reference(robot, arm)
        cap = _arms.capability_map(robot, arm, resolution=resolution, directions=directions, seed=seed,
                                   reference=reference, progress=progress)
    return SurfaceMap._build(robot, cap, surface, reference_frame=reference_frame, grasps=grasps,
                             theta_bins=theta_bins, resolution=resolution, z_range=z_range,
                             reference=np.asarray(reference, float), check_body=check_body, check_arm=check_arm,
                             grasp_height=grasp_height,
                             threads=threads, progress=progress)


SurfaceMap.build = staticmethod(build)
