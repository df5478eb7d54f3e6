"""Arms of a robot as capability-map chains: base link, tool link, approach axis, reference posture.

An arm is named by an SRDF chain group ("right_arm"), given as a tuple (base_link, tip_link[,
approach_axis]), or passed as a ready CapabilityMap. For the PR2 the arms end at the gripper tool
frames, whose x axis is the approach axis.
"""
from __future__ import annotations

import numpy as np

from ._core import CapabilityMap, Robot

# robot name -> arm name -> (base link, tip link, approach axis)
KNOWN_ARMS = {
    "pr2": {
        "right_arm": ("torso_lift_link", "r_gripper_tool_frame", (1.0, 0.0, 0.0)),
        "left_arm": ("torso_lift_link", "l_gripper_tool_frame", (1.0, 0.0, 0.0)),
    },
}


def resolve(robot: Robot, arm) -> tuple[str, str, np.ndarray]:
    """(base_link, tip_link, approach_axis) of an arm name or tuple."""
    if isinstance(arm, str):
        known = KNOWN_ARMS.get(robot.name, {})
        if arm in known:
            base, tip, axis = known[arm]
            return base, tip, np.array(axis, float)
        if arm in robot.groups:
            base, tip = robot.groups[arm]
            return base, tip, np.array([0.0, 0.0, 1.0])
        names = sorted(set(known) | set(robot.groups))
        raise ValueError(f"robot {robot.name!r} has no arm {arm!r}; known: {', '.join(names) or 'none (pass (base, tip))'}")
    if isinstance(arm, (tuple, list)) and len(arm) in (2, 3):
        axis = np.array(arm[2], float) if len(arm) == 3 else np.array([0.0, 0.0, 1.0])
        for link in arm[:2]:
            if not robot.has_link(link):
                raise ValueError(f"robot {robot.name!r} has no link named {link!r}")
        return arm[0], arm[1], axis
    raise ValueError(f"arm must be a name, a (base_link, tip_link[, approach_axis]) tuple or a CapabilityMap, got {arm!r}")


def default_reference(robot: Robot, arm) -> np.ndarray:
    """Home posture with every SRDF 'tuck*' state applied that does not move this arm (the other arm tucked)."""
    base, tip, _ = resolve(robot, arm)
    chain_joints = set(robot.chain(base, tip).joint_names)
    values = {}
    for name, joints in sorted(robot.named_states.items()):
        if name.startswith("tuck") and not (set(joints) & chain_joints):
            values.update(joints)
    return robot.configuration(values)


def capability_map(robot: Robot, arm, resolution: float = 0.05, directions: int = 200, seed: int = 0,
                   reference=None, progress=True, **kwargs) -> CapabilityMap:
    """Builds the capability map of an arm (name or tuple), keeping joint solutions for surface maps."""
    base, tip, axis = resolve(robot, arm)
    if reference is None:
        reference = default_reference(robot, arm)
    chain = robot.chain(base, tip)
    return CapabilityMap.build(chain, resolution=resolution, directions=directions, approach_axis=axis,
                               reference=reference, seed=seed, progress=progress, keep_solutions=True, **kwargs)
