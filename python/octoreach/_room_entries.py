"""The entries of a room description (rooms.py): field checks that name the entry and the key, and the obstacle
entries (boxes, cylinders, spheres, meshes, OctoMaps) as Shapes, the one shape description the collision checks
and the simulated camera share."""
from __future__ import annotations

import math
import os
import stat
from pathlib import Path

import numpy as np

from . import limits
from ._core import Shape
from ._checks import shown
from .data_files import file_kind

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
            raise ValueError(f"{where}: unknown key {shown(key)} (known: {', '.join(sorted(known))})")


def number(entry: dict, key: str, where: str, default=None) -> float:
    value = entry.get(key, default)
    if value is None:
        raise ValueError(f"{where}: {key!r} is required")
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"{where}: {key!r} must be a number, got {type(value).__name__}")
    return finite(value, f"{where}: {key!r}")


def finite(value, what: str) -> float:
    """float(value), ValueError unless finite (an integer too large for a float included)."""
    try:
        out = float(value)
    except OverflowError:
        out = math.inf
    if not math.isfinite(out):
        raise ValueError(f"{what} must be finite, got {shown(value)}")
    return out


def vector(entry: dict, key: str, where: str, n: int, default=None) -> np.ndarray:
    value = entry.get(key, default)
    if value is None:
        raise ValueError(f"{where}: {key!r} is required")
    if not isinstance(value, (list, tuple, np.ndarray)) or len(value) != n or any(
            isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) for v in value):
        raise TypeError(f"{where}: {key!r} must be a list of {n} numbers, got {shown(value)}")
    try:
        out = np.asarray(value, float)
    except OverflowError:  # an integer too large for a float
        out = np.full(n, np.inf)
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{where}: {key!r} must be finite, got {shown(value)}")
    return out


def name(entry: dict, where: str, default: str) -> str:
    """The entry's name: a non-empty string of at most limits.MAX_NAME_LENGTH characters without '/' (shelf
    boards are "<shelf>/<i>"), '\\' or control characters (names become file names)."""
    if "name" not in entry:
        return default
    value = entry["name"]
    if not isinstance(value, str) or not value:
        raise TypeError(f"{where}: 'name' must be a non-empty string, got {shown(value)}")
    if len(value) > limits.MAX_NAME_LENGTH:
        raise ValueError(f"{where}: 'name' has {len(value):,} characters, more than the limit of "
                         f"{limits.MAX_NAME_LENGTH} (octoreach.limits.MAX_NAME_LENGTH)")
    bad = next((c for c in value if c in "/\\" or ord(c) < 32 or ord(c) == 127), None)
    if bad is not None:
        why = "is kept for shelf boards (<shelf>/<i>)" if bad == "/" else "cannot be part of a file name"
        raise ValueError(f"{where}: 'name' {shown(value)} holds {bad!r}, which {why}")
    return value


def regular_path(entry: dict, where: str, base: Path) -> str:
    """The entry's 'path' (relative to `base`): a regular, non-empty file where it exists (a missing file is
    the loader's to report; a FIFO would block the reader, /dev/zero never end)."""
    path = entry.get("path")
    if not isinstance(path, str) or not path:
        raise TypeError(f"{where}: 'path' must be a file name, got {shown(path)}")
    p = Path(path)
    p = p if p.is_absolute() else base / p
    try:
        st = os.stat(p)
    except (OSError, ValueError):
        return str(p)
    if not stat.S_ISREG(st.st_mode):
        raise OSError(f"{where}: 'path' {str(p)!r} is {file_kind(st.st_mode)}, not a regular file")
    if st.st_size == 0:  # no mesh or OctoMap is empty; /proc's files say 0 and read as anything
        raise OSError(f"{where}: 'path' {str(p)!r} is empty")
    return str(p)


def check_counts(description: dict) -> None:
    """The room's surfaces (boards included) and obstacles counted from its lists against the limits, before any
    entry is built (the entries' own checks name what is wrong inside them)."""
    def entries(key):
        value = description.get(key)
        return value if isinstance(value, list) else []

    def length(entry, key):
        value = entry.get(key) if isinstance(entry, dict) else None
        return len(value) if isinstance(value, list) else 0

    surfaces, shelves = entries("surfaces"), entries("shelves")
    count = len(surfaces) + sum(length(s, "boards") for s in shelves)
    if count > limits.MAX_SURFACES:
        raise ValueError(f"room: {count:,} surfaces (shelf boards included), more than the limit of "
                         f"{limits.MAX_SURFACES:,} (octoreach.limits.MAX_SURFACES)")
    panels = sum(3 * (not isinstance(s, dict) or s.get("panels", True) is not False) for s in shelves)
    count = sum(len(entries(k)) for k in SHAPE_ENTRIES) + panels + sum(
        length(s, "boxes") + length(s, "meshes") + 4 * (isinstance(s, dict) and "legs" in s) for s in surfaces)
    if count > limits.MAX_OBSTACLES:
        raise ValueError(f"room: {count:,} obstacles (boxes, cylinders, spheres, meshes, OctoMaps, legs, panels), "
                         f"more than the limit of {limits.MAX_OBSTACLES:,} (octoreach.limits.MAX_OBSTACLES)")


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
