"""The entries of a room description (rooms.py): field checks that name the entry and the key, and the obstacle
entries (boxes, cylinders, spheres, meshes, OctoMaps) as Shapes, the one shape description the collision checks
and the simulated camera share."""
from __future__ import annotations

import math

import numpy as np

from ._core import Shape

BOX_KEYS = {"name", "size", "xyz", "rpy"}
CYLINDER_KEYS = {"name", "radius", "length", "xyz", "rpy"}
SPHERE_KEYS = {"name", "radius", "xyz"}
MESH_KEYS = {"name", "path", "xyz", "rpy", "scale"}
OCTOMAP_KEYS = {"name", "path", "xyz", "rpy"}
# Room list -> (its entries' keys, the default name prefix of an entry).
SHAPE_ENTRIES = {"boxes": (BOX_KEYS, "box"), "cylinders": (CYLINDER_KEYS, "cylinder"),
                 "spheres": (SPHERE_KEYS, "sphere"), "meshes": (MESH_KEYS, "mesh"),
                 "octomaps": (OCTOMAP_KEYS, "octomap")}


def check_keys(entry, known: set, where: str) -> None:
    if not isinstance(entry, dict):
        raise TypeError(f"{where} must be a mapping (JSON object), got {type(entry).__name__}")
    for key in entry:
        if key not in known:
            raise ValueError(f"{where}: unknown key {key!r} (known: {', '.join(sorted(known))})")


def number(entry: dict, key: str, where: str, default=None) -> float:
    value = entry.get(key, default)
    if value is None:
        raise ValueError(f"{where}: {key!r} is required")
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"{where}: {key!r} must be a number, got {type(value).__name__}")
    if not math.isfinite(value):
        raise ValueError(f"{where}: {key!r} must be finite, got {value}")
    return float(value)


def vector(entry: dict, key: str, where: str, n: int, default=None) -> np.ndarray:
    value = entry.get(key, default)
    if value is None:
        raise ValueError(f"{where}: {key!r} is required")
    if not isinstance(value, (list, tuple, np.ndarray)) or len(value) != n or any(
            isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) for v in value):
        raise TypeError(f"{where}: {key!r} must be a list of {n} numbers, got {value!r}")
    out = np.asarray(value, float)
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{where}: {key!r} must be finite, got {value!r}")
    return out


def name(entry: dict, where: str, default: str) -> str:
    value = entry.get("name", default)
    if not isinstance(value, str) or not value:
        raise TypeError(f"{where}: 'name' must be a non-empty string, got {value!r}")
    return value


def pose(entry: dict, where: str) -> np.ndarray:
    """4x4 pose from xyz (m) and rpy (rad, fixed axes x, y, z as in URDF)."""
    x, y, z = vector(entry, "xyz", where, 3, [0, 0, 0])
    r, p, w = vector(entry, "rpy", where, 3, [0, 0, 0])
    cr, sr, cp, sp, cw, sw = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(w), math.sin(w)
    T = np.eye(4)
    T[:3, :3] = np.array([[cw, -sw, 0], [sw, cw, 0], [0, 0, 1]]) @ np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]]) \
        @ np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    T[:3, 3] = [x, y, z]
    return T


def listed(value):
    """Tuples and arrays as lists, anything else as it is (the description's checks name what is wrong)."""
    return list(value.tolist() if isinstance(value, np.ndarray) else value) if isinstance(value, (tuple, list, np.ndarray)) else value


def as_list(value, key: str, where: str) -> list:
    if value is None:
        return []
    if not isinstance(value, list):
        raise TypeError(f"{where}: {key!r} must be a list, got {type(value).__name__}")
    return value


def shape(key: str, entry: dict, where: str, path_of) -> Shape:
    """The Shape of an obstacle entry of room list `key` ("boxes", "cylinders", ...), its keys checked;
    `path_of(entry, where)` resolves a file entry's path."""
    check_keys(entry, SHAPE_ENTRIES[key][0], where)
    T = pose(entry, where)
    if key == "boxes":
        size = vector(entry, "size", where, 3)
        make = lambda: Shape.box(size, T)  # noqa: E731
    elif key in ("cylinders", "spheres"):
        radius = number(entry, "radius", where)
        length = number(entry, "length", where) if key == "cylinders" else None
        make = (lambda: Shape.cylinder(radius, length, T)) if key == "cylinders" else (lambda: Shape.sphere(radius, T))
    elif key == "meshes":
        path, scale = path_of(entry, where), vector(entry, "scale", where, 3, [1, 1, 1])
        make = lambda: Shape.mesh_file(path, T, scale)  # noqa: E731
    else:
        path = path_of(entry, where)
        make = lambda: Shape.octree_file(path, T)  # noqa: E731
    try:
        return make()
    except ValueError as e:  # sizes out of range: the shape's own message, placed
        raise ValueError(f"{where}: {e}") from None
