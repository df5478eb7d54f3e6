"""The simulator's physical check: whether an arm configuration is clear of the scene's true geometry and of
the robot itself (a chosen view whose arm would touch the scene is not taken)."""
from __future__ import annotations

import numpy as np


def robot_root(robot, chain, chain_base, reference=None) -> np.ndarray:
    """Pose (4x4, world) of the robot's root when its `chain` base link sits at `chain_base`, the robot at
    `reference` (None: home)."""
    q = robot.home() if reference is None else reference
    return np.asarray(chain_base, float) @ np.linalg.inv(robot.link_poses(q)[chain.base_link])


class PhysicalCheck:
    """Whether an arm configuration is clear of the scene's true geometry (every shape of the scene:
    Scene.obstacles(); the links the chain moves: Chain.moved_links) and of the robot itself (robot known), else
    always True. The joints off the chain stand at `reference` (None: home), as in the search's checks."""

    def __init__(self, robot, chain, scene, enabled, reference=None):
        self.on = bool(enabled and robot is not None and chain is not None)
        if self.on:
            self.robot, self.chain, self.obstacles = robot, chain, scene.obstacles()
            self.links, self.reference = chain.moved_links, reference

    def valid(self, q, chain_base) -> bool:
        if not self.on or q is None:
            return True
        root = robot_root(self.robot, self.chain, chain_base, self.reference)
        q_robot = self.chain.to_robot_configuration(np.asarray(q, float), self.reference)
        return not self.robot.in_collision(q_robot, self.obstacles, root, self_collision=True, links=self.links)
