"""The room a surface map records (``SurfaceMap.room``: the obstacles it was built with and the robot body checked
against them), used where the map is used: the sampler checks the body against it by default, a room file given
instead replaces it and is compared with it first.

    smap = octoreach.SurfaceMap.load("counter.orsm")
    sampler = room_checks.sampler(smap)                    # the body checked against the map's own room
    sampler = room_checks.sampler(smap, scene="room.json")  # ... against a room file (a differing one is said)
    sampler = room_checks.sampler(smap, room_check=False)   # no check
"""
from __future__ import annotations

import os
import sys

from ._core import Obstacles, PoseSampler, SurfaceMap

#: Differences listed in a warning before "and N more".
SHOWN_DIFFERENCES = 3


def scene_obstacles(scene) -> Obstacles:
    """Every obstacle of a room: a room file path (JSON or YAML), a ``rooms.Room`` or an ``Obstacles`` as given."""
    if isinstance(scene, Obstacles):
        return scene
    from .rooms import Room

    if isinstance(scene, (str, os.PathLike)):
        scene = Room.load(scene)
    if not isinstance(scene, Room):
        raise TypeError(f"a room must be a room file path, a Room or an Obstacles, got {type(scene).__name__}")
    return scene.obstacles()


def differences(smap: SurfaceMap, obstacles: Obstacles) -> list[str]:
    """How `obstacles` differ from the room `smap` was built with (lines; [] when the same or the map records
    none)."""
    return [] if smap.room.empty else list(smap.room.differences(obstacles))


def warn_differences(smap: SurfaceMap, obstacles: Obstacles, where: str, file=None) -> list[str]:
    """Says on stderr (one warning line, then the first differences) when `obstacles` (from `where`, e.g. a room
    file's name) differ from the room the map was built with; returns the differences."""
    found = differences(smap, obstacles)
    if found:
        out = sys.stderr if file is None else file
        more = len(found) - SHOWN_DIFFERENCES
        print(f"octoreach: warning: {where} differs from the room the map was built with ({len(found)} "
              f"difference{'s' if len(found) > 1 else ''}); checking against {where}:", file=out)
        for line in found[:SHOWN_DIFFERENCES]:
            print(f"  {line}", file=out)
        if more > 0:
            print(f"  ... and {more} more", file=out)
    return found


def sampler(smap: SurfaceMap, scene=None, room_check: bool = True, where: str | None = None, **kwargs) -> PoseSampler:
    """A PoseSampler over `smap` whose poses keep the body out of the room: the map's own room, or `scene` (a room
    file, Room or Obstacles, compared with the map's room first: see warn_differences) instead; room_check=False
    checks nothing. Other keywords go to PoseSampler (candidates, seed, ...). A map that records no room (a file
    written before maps recorded theirs) and no `scene`: the poses are not checked, and a note says so."""
    if scene is not None and room_check:
        obstacles = scene_obstacles(scene)
        label = where or (os.fspath(scene) if isinstance(scene, (str, os.PathLike)) else "the given room")
        warn_differences(smap, obstacles, label)
        if not smap.room.body:
            raise ValueError(f"the surface map records no robot body to check against {label} (a file written before "
                             "maps recorded their room, or built without the body check): rebuild it, or check poses "
                             "with PoseSampler(in_collision=(robot, obstacles))")
        return PoseSampler(smap, in_collision=obstacles, **kwargs)
    if room_check and smap.room.empty:
        print("octoreach: note: the surface map records no room (a file written before maps recorded theirs): "
              "sampled poses are not checked for collisions; give a room file (--scene) or rebuild the map",
              file=sys.stderr)
    return PoseSampler(smap, room_check=room_check, **kwargs)
