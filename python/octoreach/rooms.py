"""Rooms: one scene of working surfaces (tables, shelf boards) and obstacles (walls, meshes, OctoMaps),
from which every surface gets its surface map with all the room's obstacles checked against body and arm.

A room is described by a plain dictionary, which is also its file format (JSON, or YAML where PyYAML is
installed). Lengths in metres, angles in radians, poses as ``xyz`` (3,) and ``rpy`` (3,)::

    {"surfaces": [{"name": "table", "rectangle": {"size": [1.2, 0.8], "height": 0.75, "x": 0.6, "yaw": 0.0},
                   "legs": 0.05}],
     "shelves":  [{"name": "shelf", "size": [0.8, 0.35], "boards": [0.4, 0.8, 1.2], "x": -0.8, "y": 1.0,
                   "yaw": 0.0}],
     "boxes":    [{"name": "wall", "size": [0.05, 2.0, 2.0], "xyz": [1.5, 0.0, 1.0]}],
     "cylinders": [{"name": "bin", "radius": 0.15, "length": 0.4, "xyz": [0.5, -1, 0.2]}],
     "spheres":  [{"name": "ball", "radius": 0.1, "xyz": [1, 1, 0.1]}],
     "meshes":   [{"name": "lamp", "path": "lamp.stl", "xyz": [0, -1, 0], "scale": [1, 1, 1]}],
     "octomaps": [{"name": "rest", "path": "scan.bt"}]}

A surface is a ``rectangle`` or a polygon given by ``vertices`` (a list of [x, y, z]), with an optional
``thickness``, ``legs`` (leg width) and its own ``boxes`` and ``meshes``. A shelf is several boards
(surfaces named ``<shelf>/<i>``, bottom first) between two side panels and a back panel. Relative
mesh and OctoMap paths are relative to the file. An unknown key is a ValueError that names it; a value
of the wrong type is a TypeError that names the field. Names become file names: at most 200 characters,
without '/', '\\' or control characters. Files are read within ``octoreach.limits`` (``data_files``), and
a room holds at most limits.MAX_SURFACES surfaces, MAX_BOARDS boards per shelf and MAX_OBSTACLES obstacles.

Every obstacle is a Shape (the description collision checks and the simulated camera share): ``Room.obstacles()``
checks them against body and arm, ``Room.scene()`` shows the same room to a simulated depth camera.
"""
from __future__ import annotations

import copy
import json
import math
import os
from pathlib import Path

import numpy as np

from . import limits
from ._core import CapabilityMap, Obstacles, Robot, Scene, Shape, Surface, SurfaceMap
from ._checks import PATH, check_type, shown
from .atomic_write import write_atomically
from .data_files import read_data as _read_data
from ._room_entries import BOX_KEYS as _BOX_KEYS, SHAPE_ENTRIES as _SHAPE_ENTRIES
from ._room_entries import as_list as _list, check_keys as _check_keys, listed as _listed, name as _name, \
    number as _number, pose as _pose, shape as _shape, vector as _vector, check_counts as _check_counts, \
    regular_path as _regular_path

_SURFACE_KEYS = {"name", "rectangle", "vertices", "thickness", "legs", "boxes", "meshes"}
_RECTANGLE_KEYS = {"size", "height", "x", "y", "yaw"}
_SHELF_KEYS = {"name", "size", "boards", "x", "y", "yaw", "thickness", "panels"}
_ROOM_KEYS = {"surfaces", "shelves", *_SHAPE_ENTRIES}
_KINDS = {"surfaces": "surface", "shelves": "shelf", **{k: kind for k, (_, kind) in _SHAPE_ENTRIES.items()}}


class Room:
    """Working surfaces and obstacles of one room (world frame). ``Room(description, base_dir)`` checks and
    builds a description (see the module docstring); ``Room.load(path)`` reads a JSON or YAML file."""

    def __init__(self, description: dict | None = None, base_dir: str | os.PathLike = "."):
        check_type(base_dir, PATH, "base_dir", "a folder path (str or os.PathLike)")
        self._base = Path(base_dir)
        self._description: dict = {}
        self._surfaces: dict[str, Surface] = {}
        self._part_names: dict[str, list[str]] = {}  # surface -> names of its boxes (legs first), as in the file
        self._objects = Obstacles()  # boxes, meshes, OctoMaps and shelf panels: everything but the surfaces
        self._owner: dict[str, str] = {}  # name -> kind, to refuse duplicates
        self._obstacle_count = 0  # every obstacle entry, a surface's legs and boxes, shelf panels
        description = {} if description is None else description
        _check_keys(description, _ROOM_KEYS, "room")
        _check_counts(description)
        for key in ("surfaces", "shelves", *_SHAPE_ENTRIES):
            for entry in _list(description.get(key), key, "room"):
                self._add(key, entry)

    # ------------------------------------------------------------------ description and files
    @property
    def description(self) -> dict:
        """The room as a plain dictionary (a copy): what save() writes and Room() reads."""
        return copy.deepcopy(self._description)

    @classmethod
    def load(cls, path: str | os.PathLike) -> "Room":
        """Reads a room file: JSON, or YAML where PyYAML is installed."""
        check_type(path, PATH, "path", "a path (str or os.PathLike)")
        path = Path(path)
        data = _read_data(path, "room file")
        try:
            return cls(data, base_dir=path.parent)
        except (ValueError, TypeError) as e:
            raise type(e)(f"room file {str(path)!r}: {e}") from None

    def save(self, path: str | os.PathLike) -> None:
        """Writes the description as JSON (YAML for a .yaml/.yml name), atomically."""
        check_type(path, PATH, "path", "a path (str or os.PathLike)")
        path = Path(path)
        if path.suffix in (".yaml", ".yml"):
            import yaml

            text = yaml.safe_dump(self._description, sort_keys=False)
        else:
            text = json.dumps(self._description, indent=2)
        write_atomically(path, text + "\n", "room file")

    # ------------------------------------------------------------------ building a room in code
    def add_table(self, name: str, size_x: float, size_y: float, height: float, x: float = 0.0, y: float = 0.0,
                  yaw: float = 0.0, legs: float | None = 0.05) -> Surface:
        """A rectangular table top (yaw in rad) with four legs of width `legs` (None: no legs)."""
        entry = {"name": name, "rectangle": {"size": [size_x, size_y], "height": height, "x": x, "y": y, "yaw": yaw}}
        if legs is not None:
            entry["legs"] = legs
        return self._add_surface(entry)

    def add_surface(self, name: str, vertices, thickness: float = 0.03) -> Surface:
        """A polygon surface (vertices (N, 3), world frame)."""
        vertices = vertices.tolist() if isinstance(vertices, np.ndarray) else vertices
        return self._add_surface({"name": name, "vertices": vertices, "thickness": thickness})

    def add_shelf(self, name: str, width: float, depth: float, boards, x: float = 0.0, y: float = 0.0,
                  yaw: float = 0.0, thickness: float = 0.02, panels: bool = True) -> list[Surface]:
        """A shelf of `width` (local x) by `depth` (local y, open towards +y) with boards at the given heights (m),
        turned by `yaw` (rad) about its centre (x, y); `panels` adds two side panels and a back panel."""
        return self._add_shelf({"name": name, "size": [width, depth], "boards": list(boards) if isinstance(boards, (tuple, np.ndarray)) else boards, "x": x, "y": y, "yaw": yaw,
                                "thickness": thickness, "panels": panels})

    def add_box(self, name: str, size, xyz, rpy=(0.0, 0.0, 0.0)) -> None:
        """An obstacle box (a wall, a cupboard): extents `size`, centre at xyz, orientation rpy (rad)."""
        self._add_shape("boxes", {"name": name, "size": _listed(size), "xyz": _listed(xyz), "rpy": _listed(rpy)})

    def add_cylinder(self, name: str, radius: float, length: float, xyz, rpy=(0.0, 0.0, 0.0)) -> None:
        """An obstacle cylinder (a bin, a post) along its local z axis, centre at xyz, orientation rpy (rad)."""
        self._add_shape("cylinders", {"name": name, "radius": radius, "length": length, "xyz": _listed(xyz),
                                      "rpy": _listed(rpy)})

    def add_sphere(self, name: str, radius: float, xyz) -> None:
        """An obstacle sphere centred at xyz."""
        self._add_shape("spheres", {"name": name, "radius": radius, "xyz": _listed(xyz)})

    def add_mesh(self, name: str, path: str, xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0), scale=(1.0, 1.0, 1.0)) -> None:
        """An obstacle mesh file (STL, DAE, OBJ...)."""
        check_type(path, PATH, "path", "a mesh file path (str or os.PathLike)")
        self._add_shape("meshes", {"name": name, "path": str(path), "xyz": _listed(xyz), "rpy": _listed(rpy),
                                   "scale": _listed(scale)})

    def add_octomap(self, name: str, path: str, xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)) -> None:
        """The occupied cells of an OctoMap file (.bt or .ot) as obstacles."""
        check_type(path, PATH, "path", "an OctoMap file path (str or os.PathLike)")
        self._add_shape("octomaps", {"name": name, "path": str(path), "xyz": _listed(xyz), "rpy": _listed(rpy)})

    # ------------------------------------------------------------------ reading
    @property
    def surfaces(self) -> dict[str, Surface]:
        """The working surfaces by name, in the order they were added (each with its own legs and boxes)."""
        return dict(self._surfaces)

    def obstacles(self, without: str | None = None) -> Obstacles:
        """Every obstacle of the room (surfaces with their boxes, boxes, meshes, OctoMaps) except the surface
        named `without` (the one a map is built for: its slab and boxes come with it)."""
        if without is not None and without not in self._surfaces:
            raise KeyError(f"no surface {without!r} in the room (surfaces: {', '.join(self._surfaces) or 'none'})")
        out = Obstacles()
        for name, surface in self._surfaces.items():
            if name != without:  # each piece named after its surface: "counter", "counter/leg_1", "counter/drawers"
                own = surface.obstacles()  # the slab, then its boxes (legs first) in the order they were added
                parts = iter(self._part_names.get(name, []))
                for shape, part in zip(own.shapes, own.names):
                    piece = part.removeprefix("surface_") if part != "surface_box" else next(parts, "box")
                    out.add_shape(shape, name if part == "surface" else f"{name}/{piece}")
        out.add(self._objects)
        return out

    def scene(self) -> Scene:
        """The room for the simulated depth camera: a Scene holding every obstacle (surfaces with their legs and
        boxes, shelves, boxes, cylinders, spheres, meshes, OctoMaps), the same shapes obstacles() checks."""
        scene = Scene()
        scene.add_obstacles(self.obstacles())
        return scene

    def surface_maps(self, robot: Robot, arm, progress=True, directions: int | None = None, seed: int | None = None,
                     poles: bool | None = None, **kwargs) -> dict[str, SurfaceMap]:
        """One surface map per surface, each built with every other obstacle of the room. `arm` is a CapabilityMap
        with solutions, an arm name or a (base, tip[, approach_axis]) tuple (its capability map is built once,
        at `resolution`); other keywords set SurfaceMapOptions fields."""
        if not isinstance(robot, Robot):
            raise TypeError(f"robot must be an octoreach.Robot, got {type(robot).__name__}")
        if "obstacles" in kwargs:
            raise TypeError("surface_maps takes the obstacles from the room; add them to it instead")
        if not self._surfaces:
            raise ValueError("the room has no surface")
        if not isinstance(arm, CapabilityMap):
            from . import arms

            cap_kwargs = {} if seed is None else {"seed": seed}
            if kwargs.get("resolution"):
                cap_kwargs["resolution"] = kwargs["resolution"]
            if directions is not None:
                cap_kwargs["directions"] = directions
            if poles is not None:
                cap_kwargs["poles"] = poles
            arm = arms.capability_map(robot, arm, progress=progress, **cap_kwargs)
        else:  # a map fixes its directions and seed: SurfaceMap.build refuses keywords that ask for others
            kwargs.update({k: v for k, v in (("directions", directions), ("poles", poles), ("seed", seed)) if v is not None})
        return {name: SurfaceMap.build(robot, arm, surface, obstacles=self.obstacles(without=name), progress=progress,
                                       **kwargs)
                for name, surface in self._surfaces.items()}

    def __repr__(self) -> str:
        return (f"<octoreach.Room {len(self._surfaces)} surfaces ({', '.join(self._surfaces)}), "
                f"{len(self._objects)} other obstacles>")

    # ------------------------------------------------------------------ entries
    def _claim(self, name: str, where: str, kind: str | None = None) -> None:
        if name in self._owner:
            owner = self._owner[name]
            article = "an" if owner[0] in "aeiou" else "a"
            raise ValueError(f"{where}: the name {name!r} is already used by {article} {owner} of this room "
                             "(every surface, shelf and obstacle needs a name of its own)")
        key = where.split("[")[0]
        self._owner[name] = kind or _KINDS.get(key, key)

    def _grow(self, where: str, surfaces: int = 0, obstacles: int = 0) -> None:
        """Counts new surfaces and obstacles against limits.MAX_SURFACES and MAX_OBSTACLES (before adding them)."""
        if len(self._surfaces) + surfaces > limits.MAX_SURFACES:
            raise ValueError(f"{where}: the room would hold more than {limits.MAX_SURFACES:,} surfaces (shelf boards "
                             "included; octoreach.limits.MAX_SURFACES)")
        if self._obstacle_count + obstacles > limits.MAX_OBSTACLES:
            raise ValueError(f"{where}: the room would hold more than {limits.MAX_OBSTACLES:,} obstacles (boxes, "
                             "meshes, OctoMaps, legs, panels; octoreach.limits.MAX_OBSTACLES)")
        self._obstacle_count += obstacles

    def _record(self, key: str, entry: dict) -> None:
        self._description.setdefault(key, []).append(copy.deepcopy(entry))

    def _path(self, entry: dict, where: str) -> str:
        return _regular_path(entry, where, self._base)

    def _surface_from(self, entry: dict, where: str, parts: list | None = None) -> Surface:
        """The Surface of a room entry; `parts` (if given) receives the names of its boxes, legs first."""
        if ("rectangle" in entry) == ("vertices" in entry):
            raise ValueError(f"{where}: give exactly one of 'rectangle' and 'vertices'")
        thickness = _number(entry, "thickness", where, 0.03)
        if "rectangle" in entry:
            rect = entry["rectangle"]
            rw = where + ".rectangle"
            _check_keys(rect, _RECTANGLE_KEYS, rw)
            sx, sy = _vector(rect, "size", rw, 2)
            surface = Surface.rectangle(sx, sy, _number(rect, "height", rw), _number(rect, "x", rw, 0.0),
                                        _number(rect, "y", rw, 0.0), _number(rect, "yaw", rw, 0.0), thickness)
        else:
            vertices = entry["vertices"]
            if not isinstance(vertices, list) or not all(isinstance(v, list) for v in vertices):
                raise TypeError(f"{where}: 'vertices' must be a list of [x, y, z], got {shown(vertices)}")
            surface = Surface(np.array([_vector({"v": v}, "v", f"{where}.vertices[{i}]", 3) for i, v in
                                        enumerate(vertices)]).reshape(-1, 3), thickness)
        boxes = _list(entry.get("boxes"), "boxes", where)
        meshes = _list(entry.get("meshes"), "meshes", where)
        self._grow(where, surfaces=1, obstacles=len(boxes) + len(meshes) + 4 * ("legs" in entry))
        names = [] if parts is None else parts
        if "legs" in entry:
            surface.add_legs(_number(entry, "legs", where))
            names += [f"leg_{k}" for k in range(1, 5)]
        for i, box in enumerate(boxes):
            bw = f"{where}.boxes[{i}]"
            _check_keys(box, _BOX_KEYS, bw)
            names.append(_name(box, bw, "box"))  # not a file name, but checked as every name of the room is
            surface.add_box(_vector(box, "size", bw, 3), _pose(box, bw))
        return surface

    def _add_surface(self, entry: dict) -> Surface:
        where, name = self._entry("surfaces", entry, _SURFACE_KEYS, "surface")
        where += f" ({name!r})"
        parts: list[str] = []
        surface = self._surface_from(entry, where, parts)
        meshes = Obstacles()  # a surface's meshes (a sink, a lamp) are room obstacles
        for i, mesh in enumerate(_list(entry.get("meshes"), "meshes", where)):
            mw = f"{where}.meshes[{i}]"
            meshes.add_shape(_shape("meshes", mesh, mw, self._path), _name(mesh, mw, f"{name}/mesh_{i}"))
        self._claim(name, where)
        self._surfaces[name] = surface
        self._part_names[name] = parts
        self._objects.add(meshes)
        self._record("surfaces", entry)
        return surface

    def _add_shelf(self, entry: dict) -> list[Surface]:
        where, name = self._entry("shelves", entry, _SHELF_KEYS, "shelf")
        where += f" ({name!r})"
        width, depth = _vector(entry, "size", where, 2)
        boards = _list(entry.get("boards"), "boards", where)
        if not boards:
            raise ValueError(f"{where}: 'boards' must list at least one board height")
        if len(boards) > limits.MAX_BOARDS:
            raise ValueError(f"{where}: {len(boards):,} boards, more than the limit of {limits.MAX_BOARDS} "
                             "(octoreach.limits.MAX_BOARDS)")
        heights = [_number({"h": h}, "h", f"{where}.boards[{i}]") for i, h in enumerate(boards)]
        x, y, yaw = (_number(entry, k, where, 0.0) for k in ("x", "y", "yaw"))
        t = _number(entry, "thickness", where, 0.02)
        panels = entry.get("panels", True)
        if not isinstance(panels, bool):
            raise TypeError(f"{where}: 'panels' must be true or false, got {shown(panels)}")
        if min(width, depth, t) <= 0:
            raise ValueError(f"{where}: 'size' and 'thickness' must be positive")
        self._grow(where, surfaces=len(heights), obstacles=3 * panels)
        self._claim(name, where)
        c, s = math.cos(yaw), math.sin(yaw)
        out = []
        for i, h in enumerate(sorted(heights)):
            board = Surface.rectangle(width, depth, h, x, y, yaw, t)
            self._claim(f"{name}/{i}", where, "shelf board")
            self._surfaces[f"{name}/{i}"] = board
            out.append(board)
        if panels:  # two sides and a back (local -y), up to the top board and a little above
            top = max(heights) + 0.05

            def panel(size, local):
                T = np.eye(4)
                T[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
                T[:3, 3] = [x + c * local[0] - s * local[1], y + s * local[0] + c * local[1], top / 2]
                self._objects.add_shape(Shape.box(np.asarray(size, float), T), f"{name}/panel")

            panel([t, depth, top], [-(width + t) / 2, 0])
            panel([t, depth, top], [(width + t) / 2, 0])
            panel([width + 2 * t, t, top], [0, -(depth + t) / 2])
        self._record("shelves", entry)
        return out

    def _entry(self, key: str, entry: dict, known: set, prefix: str) -> tuple[str, str]:
        """(where, name) of a new entry of list `key`, its keys checked."""
        count = len(self._description.get(key, []))
        where = f"{key}[{count}]"
        _check_keys(entry, known, where)
        return where, _name(entry, where, f"{prefix}_{count}")

    def _add(self, key: str, entry: dict) -> None:
        if key == "surfaces":
            self._add_surface(entry)
        elif key == "shelves":
            self._add_shelf(entry)
        else:
            self._add_shape(key, entry)

    def _add_shape(self, key: str, entry: dict) -> None:
        """An obstacle entry of room list `key` (boxes, cylinders, spheres, meshes, octomaps)."""
        where, name = self._entry(key, entry, _SHAPE_ENTRIES[key][0], _SHAPE_ENTRIES[key][1])
        shape = _shape(key, entry, where, self._path)
        self._grow(where, obstacles=1)
        self._claim(name, where)
        self._objects.add_shape(shape, name)
        self._record(key, entry)


def surface_from_file(path: str | os.PathLike) -> tuple[Surface, Obstacles]:
    """A polygon file: a list of [x, y, z] vertices, or one surface entry of a room file ({"vertices": ...,
    "thickness", "legs", "boxes", "meshes"}). Returns the surface and the obstacles of its meshes."""
    check_type(path, PATH, "path", "a path (str or os.PathLike)")
    path = Path(path)
    data = _read_data(path, "polygon file")
    if isinstance(data, list):
        data = {"vertices": data}
    if isinstance(data, dict):
        data = {"name": "surface", **data}
    try:
        room = Room({"surfaces": [data]}, base_dir=path.parent)
    except (ValueError, TypeError) as e:
        where = "surfaces[0] ('surface')"
        message = str(e).replace(where + ": ", "").replace(where, "surface")
        raise type(e)(f"polygon file {str(path)!r}: {message}") from None
    (surface,) = room.surfaces.values()
    return surface, room.obstacles(without=next(iter(room.surfaces)))
