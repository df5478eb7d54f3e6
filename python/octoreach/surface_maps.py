"""Surface-map helpers in Python: link roles and the grasp check by IK and collision checks alone, which the
planner's reachability attachment and the brute-force reference (octoreach.testing.direct_reachability) use.

``SurfaceMap.build(robot, arm, surface, ...)`` itself is compiled: ``arm`` may be a CapabilityMap, an arm
name or a (base, tip[, approach_axis]) tuple.
"""
from __future__ import annotations

import numpy as np

from ._core import CapabilityMap, Obstacles, Robot, Surface, base_pose, default_reference, grasp_orientations
from ._core import link_roles as _link_roles


def link_roles(robot: Robot, chain) -> dict:
    """Collision links split as the surface map uses them: 'body' (not moved by the arm), 'arm' (moved by
    it), 'tool' (rigid with the tip: the gripper, allowed to come close to the surface)."""
    return _link_roles(robot, chain)


class GraspCheck:
    """Brute-force grasp check of one arm at one surface, without any map: from a base pose, the share of
    grasps (R_P by IK) that reach each grasp point. IK in approach mode (random restarts) for every grasp
    direction, keeping only solutions free of self-collision whose arm links do not touch the surface slab or
    any obstacle and whose gripper touches no box or obstacle (nor the slab itself with `tool_checks_slab`: the
    planner's reachability check, where a grasp inside or under the table must not count; the surface map's
    build lets the gripper come close to the slab, and so does this check without it); a base pose whose body
    (links the arm does not move) touches something reaches nothing. `obstacles` is the rest of the room, as in
    SurfaceMap.build.

    Used by ``direct_reachability`` (tests of the maps) and by the planner's reachability attachment
    (``octoreach.planning``). ``ik_calls`` counts the IK targets solved so far."""

    def __init__(self, robot: Robot, capability_map: CapabilityMap, surface: Surface, reference=None,
                 reference_frame: str = "", grasps="upper_hemisphere", attempts: int = 20, seed: int = 0,
                 obstacles: Obstacles = None, tool_checks_slab: bool = False):
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
        if tool_checks_slab:
            self.others.add(surface.obstacles())
        else:
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
