"""What the viewer can open: map files, .bt occupancy files, map objects, robots by name."""
from __future__ import annotations

import difflib
import os

import numpy as np


# The map kinds the viewer draws (by the kind a map class names, octoreach.map_files) and their layers.
_LAYERS = {"surface": "surface_map", "capability": "capability_map"}


def load(item):
    """(kind, object) of a path or object; kind is "surface_map", "capability_map" or "exploration".
    A file that is not a map: OSError/ValueError naming it."""
    from .._core import ExplorationMap

    where = None
    if isinstance(item, (str, os.PathLike)):
        where = os.fspath(item)
        if not os.path.isfile(where):
            raise OSError(f"{where}: no such file")
        if where.endswith(".bt"):
            return "exploration", ExplorationMap.from_file(where)
        from .. import map_files

        item = map_files.load(where)
    if isinstance(item, ExplorationMap) or isinstance(getattr(item, "map", None), ExplorationMap):
        return "exploration", item
    kind = getattr(type(item), "kind", None)
    if kind in _LAYERS:
        return _LAYERS[kind], item
    if isinstance(kind, str):
        raise ValueError(f"{where or type(item).__name__}: a {kind} map; the viewer shows "
                         f"{' and '.join(_LAYERS)} maps")
    raise ValueError(f"cannot view a {type(item).__name__}: give a map file or a map object")


def exploration_map(source):
    """An ExplorationMap or explore() result as given, or the map of a .bt path."""
    if isinstance(source, (str, os.PathLike)):
        return load(source)[1]
    return source


def robot_by_name(name: str, urdf_hash: str = ""):
    """The robot called `name`: one of the project's own (urdf/), one of example-robot-data by the name it is
    loaded by, or (a map records its URDF's robot name) the one whose URDF declares that name and, when given,
    has that model hash (robots.loadable_name). ValueError (naming the robots there are) if none is."""
    from .. import robots
    from .._core import Robot

    own = name[len("octoreach_"):] if name.startswith("octoreach_") else name
    try:
        return Robot.from_urdf(str(robots.project_urdf(own)))  # the project's own robots (urdf/)
    except ValueError:
        pass
    return robots.load(robots.loadable_name(name, urdf_hash))


def reference_posture(robot, smap) -> np.ndarray:
    """The posture the map was built with: the default reference of its first arm ("base->tip" in smap.arms),
    or home."""
    from .._core import default_reference

    for token in str(smap.arms).split():
        if "->" in token:
            base, tip = token.split("->", 1)
            if robot.has_link(base) and robot.has_link(tip):
                return np.asarray(default_reference(robot, robot.chain(base, tip)), float)
    return np.asarray(robot.home(), float)


def with_joints(robot, q, joints: dict) -> np.ndarray:
    """q with the named joints set; ValueError for an unknown joint (with the nearest names) or a value outside
    the joint's limits (Robot.configuration checks both)."""
    q = np.array(q, dtype=float)
    names = list(robot.joint_names)
    for name in joints:
        if name not in names:  # the moving joints nearest the name, else all of them
            near = difflib.get_close_matches(name, names, n=3, cutoff=0.5) or names
            raise ValueError(f"robot {robot.name!r} has no moving joint named {name!r}; "
                             f"{'did you mean' if near is not names else 'its joints:'} {', '.join(near)}")
    checked = robot.configuration({name: float(value) for name, value in joints.items()})
    for name in joints:
        q[names.index(name)] = checked[names.index(name)]
    return q
