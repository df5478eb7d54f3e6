"""Surface-map helpers in Python: a brute-force reference of R_S for checking maps.

``SurfaceMap.build(robot, arm, surface, ...)`` itself is compiled: ``arm`` may be a CapabilityMap, an arm
name or a (base, tip[, approach_axis]) tuple.
"""
from __future__ import annotations

import numbers

import numpy as np

from ._core import (CapabilityMap, Obstacles, Robot, Surface, SurfaceMapOptions, base_pose, default_reference,
                    grasp_orientations)
from ._checks import check_type, float_array
from ._core import link_roles as _link_roles


def link_roles(robot: Robot, chain) -> dict:
    """Collision links split as the surface map uses them: 'body' (not moved by the arm), 'arm' (moved by
    it), 'tool' (rigid with the tip: the gripper, allowed to come close to the surface)."""
    return _link_roles(robot, chain)


def direct_reachability(robot: Robot, capability_map: CapabilityMap, surface: Surface, poses, reference=None,
                        reference_frame: str = "", grasps="upper_hemisphere", resolution: float = None,
                        grasp_height: float = SurfaceMapOptions().grasp_height, attempts: int = 20,
                        seed: int = 0, obstacles: Obstacles = None) -> np.ndarray:
    """R_S of base poses (N, 4) computed by brute force, without any map: for every surface point and every
    grasp direction, IK (approach mode, random restarts) of the arm from that base pose, keeping only
    solutions free of self-collision whose arm links do not touch the surface slab or any obstacle and whose
    gripper touches no box or obstacle, and poses whose body (links the arm does not move) touches nothing.
    `obstacles` is the rest of the room, as in SurfaceMap.build. For checking maps; slow.
    `reference` defaults to the arm's default reference posture, as in the map builds."""
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
    chain = robot.chain(capability_map.base_link, capability_map.tip_link)
    reference = default_reference(robot, chain) if reference is None else float_array(reference, "reference",
                                                                                       "a vector of joint values")
    axis = np.asarray(capability_map.approach_axis, float)
    res = capability_map.resolution if resolution is None else resolution
    frame = reference_frame or robot.root_link
    roles = link_roles(robot, chain)
    slab = surface.obstacles()  # the slab and the surface's boxes: every check but the gripper's
    others = Obstacles()  # what the gripper must not touch either: the boxes and the rest of the room
    for size, pose in surface.boxes:
        others.add_box(size, pose)
    if obstacles is not None:
        slab.add(obstacles)
        others.add(obstacles)
    targets = surface.points(res) + grasp_height * np.asarray(surface.normal)
    orientations = capability_map.orientations
    dirs_ids = orientations.subset(grasps) if isinstance(grasps, str) else list(grasps)
    ids = grasp_orientations(orientations, dirs_ids)  # orientation indices, as the C++ build
    rots = np.array([orientations.rotation(i, axis) for i in ids])
    link_poses = robot.link_poses(reference)
    root_in_ref = np.linalg.inv(link_poses[frame])
    arm_base_in_root = link_poses[capability_map.base_link]
    out = np.zeros(len(poses))
    for k, pose in enumerate(poses):
        root = base_pose(pose) @ root_in_ref
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
        rolls = orientations.rolls
        qs, ok = chain.ik_batch(Ts, mode="approach" if rolls == 1 else "full", approach_axis=axis, attempts=attempts, rng_seed=seed,
                               position_tolerance=1e-3, orientation_tolerance=1e-2, self_collision=True,
                               reference=reference, obstacles=slab, base_pose=root, obstacle_links=roles["arm"])
        if len(others) and roles["tool"]:
            for i in np.flatnonzero(ok):
                q = chain.to_robot_configuration(qs[i], reference)
                ok[i] = not robot.in_collision(q, others, base_pose=root, links=roles["tool"], self_collision=False)
        out[k] = ok.reshape(len(targets), len(ids)).mean(axis=1).mean()
    return out
