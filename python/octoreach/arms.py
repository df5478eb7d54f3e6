"""Arms of a robot as capability-map chains: base link, tool link, approach axis, reference posture.

An arm is named (``find_arms(robot)``: SRDF groups with their tips moved to the tool frame, else the
branches of the kinematic tree that end in a gripper), given as a tuple (base_link, tip_link[,
approach_axis]), or passed as a ready CapabilityMap. The approach axis is inferred from the gripper
(``arm.reason`` says how) unless given; ``approach_axis=`` overrides it. The rules live in C++
(``octoreach.Arm``, ``octoreach.find_arms``, ``octoreach.default_reference``); these functions are
the Python spelling of them.
"""
from __future__ import annotations

import numpy as np

from ._core import Arm, CapabilityMap, Robot, find_arms  # noqa: F401  (find_arms: the package's spelling)
from ._core import default_reference as _default_reference


def resolve(robot: Robot, arm, approach_axis=None) -> tuple[str, str, np.ndarray]:
    """(base_link, tip_link, approach_axis) of an arm name or tuple (approach_axis overrides the inferred one)."""
    a = Arm.resolve(robot, arm, approach_axis=approach_axis)
    return a.base_link, a.tip_link, np.array(a.approach_axis, float)


def default_arm(robot: Robot) -> str:
    """The arm a command uses when none is named: "right_arm" where the robot has one (the PR2's convention), else
    the robot's only arm; ValueError naming the arms when there are several (or none)."""
    names = [a.name for a in find_arms(robot)]
    if "right_arm" in names:
        return "right_arm"
    if len(names) == 1:
        return names[0]
    if not names:
        raise ValueError(f"robot {robot.name!r} has no arm that could be found ({Arm.NOT_FOUND}): give one by its "
                         "links (--base LINK --tip LINK)")
    raise ValueError(f"robot {robot.name!r} has {len(names)} arms ({', '.join(sorted(names))}): choose with --arm "
                     "(or --arms, several are combined)")


def default_reference(robot: Robot, arm) -> np.ndarray:
    """Home posture with every SRDF 'tuck*' state applied that does not move this arm (the other arm tucked)."""
    a = Arm.resolve(robot, arm)
    return _default_reference(robot, robot.chain(a.base_link, a.tip_link))


def capability_map(robot: Robot, arm, progress=True, approach_axis=None, cache=None, **kwargs) -> CapabilityMap:
    """Builds the capability map of an arm (name, Arm or tuple) with its approach axis (inferred from the gripper
    unless approach_axis=(x, y, z) is given), keeping joint solutions for surface maps; keywords set
    CapabilityMapOptions fields (resolution, directions, seed, reference...). cache: True (the default cache
    directory), a directory or an octoreach.cache.MapCache looks the map up first and stores it after a build."""
    from . import cache as _cache

    store = _cache.resolve(cache)
    if store is not None:
        return store.capability_map(robot, arm, progress=progress, approach_axis=approach_axis, **kwargs)
    if approach_axis is not None:
        kwargs["approach_axis"] = approach_axis
    return CapabilityMap.build_for_arm(robot, arm, progress=progress, **kwargs)
