"""Rooms for the tidy-up task: the paper's and harder ones where the choice of base poses matters.

Every scene is an ``octoreach.rooms.Room`` (walls, tables, shelves, chairs) with the robot's start pose, the
surfaces objects may lie on (and where on them), and the **predefined poses** a person would record for
each surface: the middle of every side of the surface's outline, STANDOFF metres out from the edge, facing
the surface; longest sides first (a person starts with the long side of a table), equally long sides in the
order of their distance from the robot's start. Sides shorter than MIN_SIDE that follow each other (a round
table's rim, a rounded corner) count as one stretch, cut into one piece per right angle it turns (a whole
round outline: four), each with a pose at its middle facing along its chord's normal. A pose that would put
the base (a FOOTPRINT square) into a wall, shelf panel or another surface's legs, or that has an obstacle at
base height between it and the edge (a wall behind a counter), is left out: nobody records a pose inside or
behind a wall. Chairs are movable clutter: they are put in after the poses were recorded, so a chair
may stand on a predefined pose (the surface map then gives it R_S = 0 and the condition attachment drops it).

Rooms have no surrounding walls (the robot's poses are bounded by the surface maps; walls stand where they
matter: behind the shelf, along the passage). Scenes (``SCENES``): ``paper`` (the paper's room: two 1.4 x 0.65 m tables at 0.72 m, objects on either),
``chairs`` (chairs pushed to three sides of the table), ``corners`` (objects only near the corners and along
the far side), ``shelf`` (a shelf with two boards against a wall, and a table), ``l_table`` (an L-shaped
table), ``narrow`` (a table in a passage: a wall 0.8 m from one long side leaves the robot room only when it
stands square to it).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._core import Obstacles, Surface
from ..rooms import Room

__all__ = ["Scene", "SCENES", "scene", "place_objects", "predefined_poses"]

TABLE = (1.4, 0.65, 0.72)  # the paper's table: 1.4 x 0.65 m, 0.72 m high
STANDOFF = 0.45  # m from the surface's edge to the base centre (the PR2's base is 0.67 m square)
FOOTPRINT = (0.67, 0.67, 0.3)  # the PR2 base, for checking predefined poses against walls
MIN_SIDE = 0.3  # m: shorter sides get no predefined pose of their own (runs of them do, see _stretches)
EDGE_GAP = 0.05  # m: the outline point just outside an edge, where a concave corner or a wall is looked for
EDGE_MARGIN = 0.07  # objects stand at least this far inside the surface's outline
OBJECT_SPACING = 0.12  # and this far from each other


@dataclass
class Scene:
    """A room, where the robot starts (x, y, z, theta), the surfaces objects go on (with an optional filter of
    allowed object positions per surface) and the predefined poses {surface: (k, 4)} in the order a person
    would use them. The task searches `search` (None: the object surfaces); the room's other surfaces are only
    obstacles. The built-in scenes search every surface of their room, including those no object is put on."""

    name: str
    room: Room
    start: np.ndarray
    object_surfaces: list
    predefined: dict
    allowed: dict = field(default_factory=dict)  # surface -> callable(point (3,)) -> bool
    description: str = ""
    search: list | None = None  # the surfaces the task searches; None: object_surfaces

    def searched_surfaces(self) -> list:
        """The surfaces a task in this scene searches (``search``, else ``object_surfaces``); ValueError naming one
        the room lacks."""
        names = list(self.object_surfaces if self.search is None else self.search)
        for name in names:
            if name not in self.room.surfaces:
                raise ValueError(f"scene {self.name!r}: no surface {name!r} in its room (surfaces: "
                                 f"{', '.join(self.room.surfaces)})")
        return names


def _pose_free(obstacles: Obstacles, pose) -> bool:
    T = np.eye(4)
    c, s = math.cos(pose[3]), math.sin(pose[3])
    T[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    T[:3, 3] = (pose[0], pose[1], FOOTPRINT[2] / 2 + 0.01)
    return not obstacles.collides_box(FOOTPRINT, T)


def _nothing_between(obstacles: Obstacles, xy, edge, n) -> bool:
    """True when nothing stands at base height on the straight line from base position `xy` to the outline point
    `edge` (outward normal `n`): the robot stands on the surface's side of every wall. The line stops 5 mm short of
    the edge: clear of a cabinet flush with it, not of a wall behind it."""
    gap = 0.005
    length = float(np.linalg.norm(np.asarray(xy) - edge)) - gap
    if length <= 0:
        return True
    T = np.eye(4)
    T[:3, :3] = [[-n[0], n[1], 0], [-n[1], -n[0], 0], [0, 0, 1]]  # local x along -n (towards the surface)
    T[:3, 3] = (*(edge + (gap + length / 2) * n), FOOTPRINT[2] / 2 + 0.01)
    return not obstacles.collides_box((length, 0.02, FOOTPRINT[2]), T)


def _stretches(v: np.ndarray, sign: float) -> list:
    """(length, middle point, outward unit normal) of each stretch of outline `v` (N, 2) a person would stand at:
    every side of at least MIN_SIDE, and every run of shorter sides (a round table's rim, a rounded corner) cut
    by arc length into as many pieces as it turns right angles (at least one; a whole round outline: four),
    each piece facing along its chord's normal. Sides in outline order; `sign` +1 for a counter-clockwise outline."""
    sides = [(v[i], v[(i + 1) % len(v)]) for i in range(len(v))]
    lengths = [float(np.linalg.norm(b - a)) for a, b in sides]
    normal = lambda d: sign * np.array([d[1], -d[0]]) / np.linalg.norm(d)  # noqa: E731
    short = [ln < MIN_SIDE for ln in lengths]
    out = [(lengths[i], (a + b) / 2, normal(b - a)) for i, (a, b) in enumerate(sides) if not short[i]]
    if not any(short):
        return out
    start = 0 if all(short) else next(i for i in range(len(v)) if short[i] and not short[i - 1])
    order = [(start + k) % len(v) for k in range(len(v))]
    runs, run = [], []
    for i in order + ([] if all(short) else [None]):
        if i is not None and short[i]:
            run.append(i)
        elif run:
            runs.append(run)
            run = []
    if run:
        runs.append(run)
    for run in runs:
        out += _run_pieces(sides, lengths, run, closed=all(short), normal=normal, sign=sign)
    return out


def _run_pieces(sides, lengths, run, closed, normal, sign) -> list:
    """The pieces of one run of short sides (see _stretches)."""
    heading = [math.atan2(*(sides[i][1] - sides[i][0])[::-1]) for i in run]
    turns = [(b - a + math.pi) % (2 * math.pi) - math.pi for a, b in zip(heading, heading[1:] + heading[:1])]
    turn = sign * sum(turns if closed else turns[:-1])
    pieces = max(1, math.ceil(turn / (math.pi / 2) - 1e-6))
    cumulative = np.concatenate([[0.0], np.cumsum([lengths[i] for i in run])])

    def at(s):  # the outline point at arc length s along the run
        k = min(int(np.searchsorted(cumulative, s, side="right")) - 1, len(run) - 1)
        a, b = sides[run[k]]
        return a + (b - a) * (s - cumulative[k]) / lengths[run[k]]
    out = []
    for j in range(pieces):
        s0, s1 = cumulative[-1] * j / pieces, cumulative[-1] * (j + 1) / pieces
        chord = at(s1) - at(s0)
        middle = at((s0 + s1) / 2)
        k = min(int(np.searchsorted(cumulative, (s0 + s1) / 2, side="right")) - 1, len(run) - 1)
        n = normal(chord) if np.linalg.norm(chord) > 1e-9 else normal(sides[run[k]][1] - sides[run[k]][0])
        if s1 - s0 >= MIN_SIDE:
            out.append((float(s1 - s0), middle, n))
    return out


def predefined_poses(room: Room, surface: str, start, count: int = 4) -> np.ndarray:
    """The poses a person would record for `surface` of `room` (see the module docstring): (k <= count, 4)."""
    poly = room.surfaces[surface]
    v = np.asarray(poly.vertices, float)[:, :2]
    area2 = float(np.sum(v[:, 0] * np.roll(v[:, 1], -1) - np.roll(v[:, 0], -1) * v[:, 1]))
    sign = 1.0 if area2 > 0 else -1.0  # counter-clockwise: the outward normal of edge d is (d_y, -d_x)
    obstacles = room.obstacles()
    sides = []
    for length, mid, n in _stretches(v, sign):
        xy = mid + STANDOFF * n
        if poly.contains(np.array([[*(mid + EDGE_GAP * n), poly.vertices[0][2]]]))[0]:
            continue  # a concave corner: outward is the surface itself
        pose = np.array([xy[0], xy[1], 0.0, math.atan2(-n[1], -n[0])])
        if not _pose_free(obstacles, pose) or not _nothing_between(obstacles, xy, mid, n):
            continue
        sides.append((-round(length, 3), float(np.hypot(*(xy - np.asarray(start[:2], float)))), pose))
    sides.sort(key=lambda s: (s[0], s[1]))
    return np.array([s[2] for s in sides[:count]]).reshape(-1, 4)


def _chair(room: Room, name: str, x: float, y: float, yaw: float) -> None:
    """A chair: a 0.45 m seat at 0.45 m on legs (one box to the floor) and a backrest, facing yaw."""
    c, s = math.cos(yaw), math.sin(yaw)
    room.add_box(f"{name}_seat", (0.45, 0.45, 0.47), (x, y, 0.235), (0.0, 0.0, yaw))
    room.add_box(f"{name}_back", (0.05, 0.45, 0.45), (x - 0.2 * c, y - 0.2 * s, 0.47 + 0.225), (0.0, 0.0, yaw))


def _paper(room: Room) -> None:
    room.add_table("table_1", *TABLE, x=-0.9, y=-1.0, yaw=0.0)
    room.add_table("table_2", *TABLE, x=1.6, y=0.8, yaw=math.pi / 2)


def _make(name, build, start, surfaces, clutter=None, allowed=None, description="") -> Scene:
    room = Room()
    build(room)
    start = np.asarray(start, float)
    predefined = {s: predefined_poses(room, s, start) for s in room.surfaces}
    if clutter is not None:
        clutter(room)
    return Scene(name, room, start, list(surfaces), predefined, allowed or {}, description, list(room.surfaces))


def _scene_paper():
    return _make("paper", _paper, (-2.3, 1.6, 0.0, 0.0), ["table_1", "table_2"],
                 description="the paper's room: two 1.4 x 0.65 m tables, objects at random on either")


def _scene_chairs():
    def chairs(room):
        sx, sy, _ = TABLE
        x, y = -0.9, -1.0
        _chair(room, "chair_south", x, y - sy / 2 - 0.15, math.pi / 2)
        _chair(room, "chair_north", x, y + sy / 2 + 0.15, -math.pi / 2)
        _chair(room, "chair_east", x + sx / 2 + 0.15, y, math.pi)
    return _make("chairs", _paper, (-2.3, 1.6, 0.0, 0.0), ["table_1"], clutter=chairs,
                 description="chairs pushed to both long sides and the east end of table 1")


def _scene_corners():
    sx, sy, h = TABLE
    x0, y0 = -0.9, -1.0

    def corner_or_far(p):
        lx, ly = abs(p[0] - x0), p[1] - y0
        return (lx > sx / 2 - 0.3 and abs(ly) > sy / 2 - 0.25) or ly > sy / 2 - 0.15
    return _make("corners", _paper, (-2.3, 1.6, 0.0, 0.0), ["table_1"], allowed={"table_1": corner_or_far},
                 description="objects only within 0.3 x 0.25 m of a corner of table 1 or along its far (north) side")


def _scene_shelf():
    def build(room):
        room.add_box("wall_north", (2.0, 0.1, 1.5), (0.0, 2.55, 0.75))  # the wall behind the shelf
        room.add_shelf("shelf", 0.8, 0.35, [0.55, 0.9], x=0.0, y=2.5 - 0.175 - 0.02, yaw=math.pi)
        room.add_table("table_1", *TABLE, x=-0.9, y=-1.0, yaw=0.0)
    return _make("shelf", build, (-2.3, 1.6, 0.0, 0.0), ["shelf/0", "shelf/1", "table_1"],
                 description="a 0.8 x 0.35 m shelf with boards at 0.55 and 0.9 m against the north wall, and table 1")


def _scene_l_table():
    def build(room):
        h = TABLE[2]
        room.add_surface("l_table", [[-1.5, -1.6, h], [0.3, -1.6, h], [0.3, -0.95, h], [-0.85, -0.95, h],
                                     [-0.85, 0.4, h], [-1.5, 0.4, h]])
    return _make("l_table", build, (1.5, 1.5, 0.0, math.pi), ["l_table"],
                 description="an L-shaped table, 1.8 x 2.0 m outside, 0.65 m deep arms")


def _scene_narrow():
    def build(room):
        room.add_table("table_1", *TABLE, x=0.0, y=0.0, yaw=0.0)
        room.add_box("passage_wall", (3.0, 0.1, 1.0), (0.0, TABLE[1] / 2 + 0.8 + 0.05, 0.5))
    return _make("narrow", build, (-2.3, -1.6, 0.0, 0.0), ["table_1"],
                 description="table 1 in a passage: a wall 0.8 m from its north side")


SCENES = {"paper": _scene_paper, "chairs": _scene_chairs, "corners": _scene_corners, "shelf": _scene_shelf,
          "l_table": _scene_l_table, "narrow": _scene_narrow}


def scene(name: str) -> Scene:
    """A scene by name (ValueError listing the names for an unknown one)."""
    if name not in SCENES:
        raise ValueError(f"unknown scene {name!r} (scenes: {', '.join(SCENES)})")
    return SCENES[name]()


def place_objects(scene: Scene, count: int, rng: np.random.Generator) -> dict:
    """`count` objects at random: {name: (surface, point (3,) on its top)}, each on a surface drawn uniformly
    from the scene's object surfaces, uniformly inside its outline (EDGE_MARGIN in), allowed by the scene's
    filter and OBJECT_SPACING from the others."""
    if count < 0:
        raise ValueError(f"count must be at least 0, got {count!r}")
    out = {}
    for i in range(count):
        for _ in range(10000):
            name = scene.object_surfaces[int(rng.integers(len(scene.object_surfaces)))]
            surface: Surface = scene.room.surfaces[name]
            v = np.asarray(surface.vertices, float)
            lo, hi = v.min(axis=0), v.max(axis=0)
            p = np.array([rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1]), v[0, 2]])
            ring = p + EDGE_MARGIN * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 0]])
            if not np.all(surface.contains(ring)):
                continue
            if name in scene.allowed and not scene.allowed[name](p):
                continue
            if any(np.linalg.norm(p - q) < OBJECT_SPACING for _, q in out.values()):
                continue
            out[f"object_{i + 1}"] = (name, p)
            break
        else:
            raise ValueError(f"scene {scene.name!r}: no room for object {i + 1}")
    return out
