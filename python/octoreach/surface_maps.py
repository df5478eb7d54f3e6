"""Python entry points of surface maps: ``SurfaceMap.build`` accepting an arm name, and helpers."""
from __future__ import annotations

import numpy as np

from . import arms as _arms
from ._core import CapabilityMap, Robot, Surface, SurfaceMap


def build(robot: Robot, arm, surface: Surface, resolution: float = None, theta_bins: int = 16, z_range=None,
          reference=None, grasps="upper_hemisphere", reference_frame: str = "", directions: int = 200,
          seed: int = 0, check_body: bool = True, check_arm: bool = True, grasp_height: float = 0.05,
          threads: int = 0,
          progress=True) -> SurfaceMap:
    """Surface map of `arm` (name, (base, tip[, approach]) tuple, or a CapabilityMap with solutions).

    Base poses (x, y, z, theta) are of `reference_frame` (default: the robot's root link, e.g.
    base_footprint) in the world frame. z_range=(0, 0) evaluates a robot standing on the floor.
    `reference` fixes the joints off the arm (default: home with the other arm tucked, whether the arm is
    given by name or as a CapabilityMap). resolution defaults to the capability map's (0.05 m when the map
    is built here). Grasp points
    lie `grasp_height` above the surface (the tool holds an object standing on it).
    """
    if isinstance(arm, CapabilityMap):
        cap = arm
        if reference is None:
            reference = _arms.default_reference(robot, (cap.base_link, cap.tip_link))
        if resolution is None:
            resolution = cap.resolution
    else:
        if reference is None:
            reference = _arms.default_reference(robot, arm)
        if resolution is None:
            resolution = 0.05
        cap = _arms.capability_map(robot, arm, resolution=resolution, directions=directions, seed=seed,
                                   reference=reference, progress=progress)
    return SurfaceMap._build(robot, cap, surface, reference_frame=reference_frame, grasps=grasps,
                             theta_bins=theta_bins, resolution=resolution, z_range=z_range,
                             reference=np.asarray(reference, float), check_body=check_body, check_arm=check_arm,
                             grasp_height=grasp_height,
                             threads=threads, progress=progress)


SurfaceMap.build = staticmethod(build)


def link_roles(robot: Robot, chain) -> dict:
    """Collision links split as the surface map uses them: 'body' (not moved by the arm), 'arm' (moved by
    it), 'tool' (rigid with the tip: the gripper, allowed to come close to the surface)."""
    full = (1 << chain.dof) - 1
    roles = {"body": [], "arm": [], "tool": []}
    for link in robot.collision_links:
        mask = chain.link_mask(link)
        roles["body" if mask == 0 else "tool" if mask == full else "arm"].append(link)
    return roles


def direct_reachability(robot: Robot, capability_map: CapabilityMap, surface: Surface, poses, reference=None,
                        reference_frame: str = "", grasps="upper_hemisphere", resolution: float = None,
                        grasp_height: float = 0.05, attempts: int = 20, seed: int = 0) -> np.ndarray:
    """R_S of base poses (N, 4) computed by brute force, without any map: for every surface point and every
    grasp direction, IK (approach mode, random restarts) of the arm from that base pose, keeping only
    solutions free of self-collision whose arm links do not touch the surface slab, and poses whose body
    (links the arm does not move) does not touch the surface or its boxes. For checking maps; slow."""
    poses = np.asarray(poses, float)
    if poses.ndim != 2 or poses.shape[1] != 4:
        raise ValueError("poses must have shape (N, 4): x, y, z, theta")
    reference = robot.home() if reference is None else np.asarray(reference, float)
    chain = robot.chain(capability_map.base_link, capability_map.tip_link)
    axis = np.asarray(capability_map.approach_axis, float)
    res = capability_map.resolution if resolution is None else resolution
    frame = reference_frame or robot.root_link
    roles = link_roles(robot, chain)
    slab = surface.obstacles()
    targets = surface.points(res) + grasp_height * np.asarray(surface.normal)
    dirs_ids = capability_map.orientations.subset(grasps) if isinstance(grasps, str) else list(grasps)
    rolls = capability_map.orientations.rolls
    ids = [d * rolls + r for d in dirs_ids for r in range(rolls)]  # orientation indices, as the C++ build
    rots = np.array([capability_map.orientations.rotation(i, axis) for i in ids])
    link_poses = robot.link_poses(reference)
    root_in_ref = np.linalg.inv(link_poses[frame])
    arm_base_in_root = link_poses[capability_map.base_link]
    out = np.zeros(len(poses))
    for k, (x, y, z, th) in enumerate(poses):
        B = np.eye(4)
        c, s = np.cos(th), np.sin(th)
        B[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
        B[:3, 3] = [x, y, z]
        root = B @ root_in_ref
        if robot.in_collision(reference, slab, base_pose=root, links=roles["body"]):
            continue
        world_to_arm = np.linalg.inv(root @ arm_base_in_root)
        Ts = np.empty((len(targets) * len(ids), 4, 4))
        n = 0
        for t in targets:
            for R in rots:
                T = np.eye(4)
                T[:3, :3] = R
                T[:3, 3] = t
                Ts[n] = world_to_arm @ T
                n += 1
        _, ok = chain.ik_batch(Ts, mode="approach" if rolls == 1 else "full", approach_axis=axis, attempts=attempts, rng_seed=seed,
                               position_tolerance=1e-3, orientation_tolerance=1e-2, self_collision=True,
                               reference=reference, obstacles=slab, base_pose=root, obstacle_links=roles["arm"])
        out[k] = ok.reshape(len(targets), len(ids)).mean(axis=1).mean()
    return out
