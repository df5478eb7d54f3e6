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


class GraspCheck:
    """Brute-force grasp check of one arm at one surface, without any map: from a base pose, the share of
    grasps (R_P by IK) that reach each grasp point. IK in approach mode (random restarts) for every grasp
    direction, keeping only solutions free of self-collision whose arm links do not touch the surface slab or
    any obstacle and whose gripper touches no box or obstacle; a base pose whose body (links the arm does not
    move) touches something reaches nothing. `obstacles` is the rest of the room, as in SurfaceMap.build.

    Used by ``direct_reachability`` (tests of the maps) and by the planner's reachability attachment
    (``octoreach.planning``). ``ik_calls`` counts the IK targets solved so far."""

    def __init__(self, robot: Robot, capability_map: CapabilityMap, surface: Surface, reference=None,
                 reference_frame: str = "", grasps="upper_hemisphere", attempts: int = 20, seed: int = 0,
                 obstacles: Obstacles = None):
        if obstacles is not None and not isinstance(obstacles, Obstacles):
            raise TypeError(f"obstacles must be an octoreach.Obstacles or None, got {type(obstacles).__name__}")
        self.robot, self.attempts, self.seed = robot, int(attempts), int(seed)
        self.chain = robot.chain(capability_map.base_link, capability_map.tip_link)
        self.reference = default_reference(robot, self.chain) if reference is None else np.asarray(reference, float)
        self.axis = np.asarray(capability_map.approach_axis, float)
        frame = reference_frame or robot.root_link
        self.roles = link_roles(robot, self.chain)
        self.slab = surface.obstacles()  # the slab and the surface's boxes: every check but the gripper's
        self.others = Obstacles()  # what the gripper must not touch either: the boxes and the rest of the room
        for size, pose in surface.boxes:
            self.others.add_box(size, pose)
        if obstacles is not None:
            self.slab.add(obstacles)
            self.others.add(obstacles)
        orientations = capability_map.orientations
        dirs_ids = orientations.subset(grasps) if isinstance(grasps, str) else list(grasps)
        ids = grasp_orientations(orientations, dirs_ids)  # orientation indices, as the C++ build
        self.rotations = np.array([orientations.rotation(i, self.axis) for i in ids])
        self.mode = "approach" if orientations.rolls == 1 else "full"
        link_poses = robot.link_poses(self.reference)
        self.root_in_ref = np.linalg.inv(link_poses[frame])
        self.arm_base_in_root = link_poses[capability_map.base_link]
        self.ik_calls = 0

    def frames(self, pose) -> tuple[np.ndarray, np.ndarray]:
        """(root link in the world, world in the arm's base link) for base pose (x, y, z, theta)."""
        root = base_pose(np.asarray(pose, float)) @ self.root_in_ref
        return root, np.linalg.inv(root @ self.arm_base_in_root)

    def body_collides(self, pose) -> bool:
        """True when the robot's body (links the arm does not move) touches the surface or an obstacle."""
        root = self.frames(pose)[0]
        return bool(self.robot.in_collision(self.reference, self.slab, base_pose=root, links=self.roles["body"]))

    def shares(self, pose, targets) -> np.ndarray:
        """Share of grasps (T,) that reach each grasp point of `targets` (T, 3), world frame, from base pose
        (x, y, z, theta)."""
        targets = np.asarray(targets, float).reshape(-1, 3)
        if self.body_collides(pose):
            return np.zeros(len(targets))
        root, world_to_arm = self.frames(pose)
        G = len(self.rotations)
        Ts = np.repeat(np.eye(4)[None], len(targets) * G, axis=0)
        Ts[:, :3, :3] = np.tile(self.rotations, (len(targets), 1, 1))
        Ts[:, :3, 3] = np.repeat(targets, G, axis=0)
        Ts = world_to_arm[None] @ Ts
        self.ik_calls += len(Ts)
        qs, ok = self.chain.ik_batch(Ts, mode=self.mode, approach_axis=self.axis, attempts=self.attempts,
                                     rng_seed=self.seed, position_tolerance=1e-3, orientation_tolerance=1e-2,
                                     self_collision=True, reference=self.reference, obstacles=self.slab,
                                     base_pose=root, obstacle_links=self.roles["arm"])
        if len(self.others) and self.roles["tool"]:
            for i in np.flatnonzero(ok):
                q = self.chain.to_robot_configuration(qs[i], self.reference)
                ok[i] = not self.robot.in_collision(q, self.others, base_pose=root, links=self.roles["tool"],
                                                    self_collision=False)
        return ok.reshape(len(targets), G).mean(axis=1)


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
