"""Arms of a robot as capability-map chains: base link, tool link, approach axis, reference posture.

An arm is named (the compiled core's small table of known arms, e.g. the PR2's gripper tool frames
with +x approach axis, then the SRDF chain groups), given as a tuple (base_link, tip_link[,
approach_axis]), or passed as a ready CapabilityMap. The rules live in C++ (``octoreach.Arm``,
``octoreach.default_reference``); these functions are the Python spelling of them.
"""
from __future__ import annotations

import numpy as np

from ._core import Arm, CapabilityMap, Robot
from ._core import default_reference as _default_reference


def resolve(robot: Robot, arm) -> tuple[str, str, np.ndarray]:
    """(base_link, tip_link, approach_axis) of an arm name or tuple."""
    a = Arm.resolve(robot, arm)
    return a.base_link, a.tip_link, np.array(a.approach_axis, float)


def default_reference(robot: Robot, arm) -> np.ndarray:
    """Home posture with every SRDF 'tuck*' state applied that does not move this arm (the other arm tucked)."""
    a = Arm.resolve(robot, arm)
    return _default_reference(robot, robot.chain(a.base_link, a.tip_link))


def capability_map(robot: Robot, arm, progress=True, **kwargs) -> CapabilityMap:
    """Builds the capability map of an arm (name or tuple) with its approach axis, keeping joint solutions
    for surface maps; keywords set CapabilityMapOptions fields (resolution, directions, seed, reference...)."""
    return CapabilityMap.build_for_arm(robot, arm, progress=progress, **kwargs)
