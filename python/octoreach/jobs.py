"""Job files of ``octoreach build-many``: many maps (robots x arms x surfaces x resolutions x base heights).

A job file is YAML (or JSON)::

    robots: [pr2, {name: tiago, arms: [arm_right]}, {urdf: my_robot.urdf, srdf: my_robot.srdf}]
    arms: [right_arm]             # the arms of every robot that names none (default: right_arm, else its only arm)
    resolutions: [0.1]            # m
    capability: {directions: 100, seed: 0}    # CapabilityMapOptions fields (not resolution)
    surfaces:
      - {name: table, rectangle: {size: [1.4, 0.65], height: 0.72}, legs: 0.05}   # a room file's surface entry
      - {room: kitchen.yaml}      # every surface of a room file, each with the room's other obstacles
    surface: {theta_bins: 16}     # SurfaceMapOptions fields (not obstacles, z range, resolution, threads)
    base_heights: [0.0]           # z of the robot's reference frame (m): one surface map per height
    out: maps                     # output folder (relative to the job file; --out overrides it, both are checked)

Each (robot, arm, resolution) is one capability map, each (capability map, surface, base height) one
surface map. ``read_job`` checks the whole file before any work starts: it loads every robot, resolves
every arm and surface, and names the entry and key of the first problem. Output files are named after the
robot, arm, resolution (exactly: 0.2 and 0.2000001 differ), surface and height; two maps whose files would
meet (names that differ only in characters a file name replaces, or in letter case) are an error, and a job
holds at most ``limits.MAX_JOB_MAPS`` maps. The task functions (``capability_task``, ``surface_task``,
``block_task``...: ``octoreach.job_tasks``) are plain functions of plain data, run in this process or by a
cluster's workers (``octoreach.cluster``).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

from . import cache as _cache
from . import limits
from ._checks import shown
from .arms import default_arm
from .data_files import read_data, sha256_of
from .job_tasks import (block_task, blocks_plan, capability_task, load_robot, map_bytes,  # noqa: F401  (what a
                        map_from_bytes, sample_task, surface_task)                     # cluster runs, by name)
from ._core import Arm, Robot, SurfaceMapOptions

_JOB_KEYS = {"robots", "arms", "resolutions", "capability", "surfaces", "surface", "base_heights", "out"}
_ROBOT_KEYS = {"name", "urdf", "srdf", "package_dirs", "allowed_collisions", "arms"}
_SURFACE_OPTION_EXCLUDED = {"obstacles", "z_range", "z_min", "z_max", "resolution", "threads"}


class JobError(ValueError):
    """A job file that cannot be run; the message names the entry and the key."""


# ---------------------------------------------------------------------------------------------- job files
@dataclass
class CapabilityJob:
    """One capability map of a job."""
    name: str                # "<robot>/<arm>/<resolution>"
    robot: Robot
    spec: dict
    arm: Arm
    options: dict            # CapabilityMapOptions fields (without threads)
    fields: dict             # cache key fields
    out: Path

    @property
    def arm_tuple(self) -> tuple:
        return (self.arm.base_link, self.arm.tip_link, tuple(float(v) for v in self.arm.approach_axis))


@dataclass
class SurfaceJob:
    """One surface map of a job."""
    name: str
    capability: int          # index into Job.capability
    room: dict
    base_dir: str
    surface: str
    height: float
    options: dict
    fields: dict
    out: Path
    polygon: object = None   # (N, 3) vertices of the surface: what its map's header must name


@dataclass
class Job:
    capability: list[CapabilityJob] = field(default_factory=list)
    surfaces: list[SurfaceJob] = field(default_factory=list)
    out: Path = Path("build_many_out")

    def __len__(self) -> int:
        return len(self.capability) + len(self.surfaces)


def _err(where: str, message: str) -> JobError:
    return JobError(f"{where}: {message}")


def _out_folder(value, where: str, base: Path) -> Path:
    """The output folder a job file's `out` or the `out` argument names (relative to `base`): a non-empty path
    without NUL; JobError naming `where` otherwise."""
    text = os.fspath(value) if isinstance(value, os.PathLike) else value
    if not isinstance(text, str) or not text or "\x00" in text:
        raise _err(where, f"must be a folder path (a non-empty string), got {shown(value)}")
    return base / text


def _numbers(value, where: str, positive: bool) -> list[float]:
    values = value if isinstance(value, list) else [value]
    out = []
    for i, v in enumerate(values):
        try:
            f = float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else math.nan
        except OverflowError:  # an integer too large for a float
            f = math.inf
        if not math.isfinite(f) or (positive and f <= 0):
            raise _err(f"{where}[{i}]", f"must be a finite {'positive ' if positive else ''}number (m), got {shown(v)}")
        if f in out:
            raise _err(f"{where}[{i}]", f"{f!r} is listed twice")
        out.append(f)
    if not out:
        raise _err(where, "must list at least one value")
    return out


def _safe(name: str) -> str:
    """A file-name form of a name: letters, digits, '-', '_' and '.' kept, anything else '_' (outputs whose
    names meet in this form are refused by _check_outputs)."""
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in str(name))


def _check_outputs(result: "Job", where: str) -> None:
    """JobError when two maps of the job would be written to one file (names that differ only in characters a
    file name replaces, or in letter case, which some file systems ignore)."""
    seen: dict[str, str] = {}
    for j in [*result.capability, *result.surfaces]:
        key = str(j.out).casefold()
        if key in seen:
            raise _err(where, f"the maps {seen[key]!r} and {j.name!r} would both be written to {str(j.out)!r}: "
                              "rename one (names become file names: characters other than letters, digits, "
                              "'-', '_' and '.' are written as '_')")
        seen[key] = j.name


def _file_digests(description: dict, base_dir: Path) -> dict:
    """sha256 of every file a room description names (meshes, OctoMaps): part of a surface map's key."""
    out = {}

    def walk(node):
        if isinstance(node, dict):
            if isinstance(node.get("path"), str):
                p = Path(node["path"])
                p = p if p.is_absolute() else base_dir / p
                try:
                    out[str(p)] = sha256_of(p, "file")
                except OSError:
                    out[str(p)] = "unreadable"
            for v in node.values():
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    walk(description)
    return out


def _robot_specs(data: dict, where: str, base: Path) -> list[tuple[dict, list, str]]:
    robots_ = data.get("robots")
    if not isinstance(robots_, list) or not robots_:
        raise _err(f"{where}: robots", "must list at least one robot (a name or {name: ..., arms: [...]})")
    default_arms = data.get("arms")
    out = []
    for i, entry in enumerate(robots_):
        w = f"{where}: robots[{i}]"
        if isinstance(entry, str):
            entry = {"name": entry}
        if not isinstance(entry, dict):
            raise _err(w, f"must be a robot name or a mapping, got {shown(entry)}")
        unknown = set(entry) - _ROBOT_KEYS
        if unknown:
            first = shown(sorted(map(str, unknown))[0])
            raise _err(w, f"unknown key {first} (known: {', '.join(sorted(_ROBOT_KEYS))})")
        if ("name" in entry) == ("urdf" in entry):
            raise _err(w, "give exactly one of 'name' and 'urdf'")
        _check_robot_types(entry, w)
        spec = {k: v for k, v in entry.items() if k != "arms"}
        for k in ("urdf", "srdf"):
            if k in spec:
                p = Path(spec[k])
                spec[k] = str(p if p.is_absolute() else (base / p).resolve())
        if "package_dirs" in spec:
            spec["package_dirs"] = [str(p if Path(p).is_absolute() else (base / p).resolve()) for p in spec["package_dirs"]]
        arms_ = entry.get("arms", default_arms)
        if arms_ is None:
            arms_ = []  # the robot's default arm (arms.default_arm), once it is loaded
        elif not isinstance(arms_, list) or not arms_ or not all(isinstance(a, (str, list)) for a in arms_):
            raise _err(w, "'arms' must list arm names (or [base, tip] pairs); give 'arms' here or at the top")
        out.append((spec, arms_, w))
    return out


def _check_robot_types(entry: dict, w: str) -> None:
    """JobError naming the key of a robot entry whose value has the wrong type."""
    for k in ("name", "urdf", "srdf"):
        if k in entry and (not isinstance(entry[k], str) or not entry[k] or "\x00" in entry[k]):
            raise _err(f"{w}: {k}", f"must be a {'robot name' if k == 'name' else 'file path'} (a non-empty string), "
                                    f"got {shown(entry[k])}")
    dirs = entry.get("package_dirs", [])
    if not isinstance(dirs, list) or not all(isinstance(d, str) and d and "\x00" not in d for d in dirs):
        raise _err(f"{w}: package_dirs", f"must be a list of folder paths, got {shown(dirs)}")
    how = entry.get("allowed_collisions", "auto")
    if how not in ("auto", "sample", "srdf"):
        raise _err(f"{w}: allowed_collisions", f"must be 'auto', 'sample' or 'srdf', got {shown(how)}")


def _surfaces(data: dict, where: str, base: Path) -> list[tuple[dict, str, str, object]]:
    """(room description, base dir, surface name, polygon vertices) of every surface of the job."""
    from .rooms import Room

    entries = data.get("surfaces", [])
    if not isinstance(entries, list):
        raise _err(f"{where}: surfaces", "must be a list")
    out = []
    for i, entry in enumerate(entries):
        w = f"{where}: surfaces[{i}]"
        try:
            if isinstance(entry, dict) and set(entry) == {"room"}:
                if not isinstance(entry["room"], str) or not entry["room"] or "\x00" in entry["room"]:
                    raise TypeError(f"'room' must be a room file path, got {shown(entry['room'])}")
                path = Path(entry["room"])
                path = path if path.is_absolute() else base / path
                description, room_base = read_data(path, "room file"), path.parent.resolve()
            else:
                description, room_base = {"surfaces": [entry]}, base.resolve()
            room = Room(description, base_dir=room_base)
        except (ValueError, TypeError, OSError) as e:
            raise _err(w, str(e)) from None
        if not room.surfaces:
            raise _err(w, "holds no surface")
        for name, surface in room.surfaces.items():
            out.append((room.description, str(room_base), name, surface.vertices))
    names: set = set()
    for s in out:
        if s[2] in names:
            raise _err(f"{where}: surfaces", f"the surface name {s[2]!r} is used twice (output files are named after it)")
        names.add(s[2])
    return out


def _options(data: dict, key: str, where: str, make, excluded: set) -> dict:
    entry = data.get(key, {})
    if not isinstance(entry, dict):
        raise _err(f"{where}: {key}", "must be a mapping of option names to values")
    probe = make()
    for name, value in entry.items():
        if not isinstance(name, str) or name in excluded or name.startswith("_") or not hasattr(probe, name) or \
                callable(getattr(probe, name)):
            label = name[:60] if isinstance(name, str) else shown(name)
            raise _err(f"{where}: {key}.{label}", "unknown or not settable here" +
                       (f" (excluded: {', '.join(sorted(excluded))})" if excluded else ""))
        plain = isinstance(value, (int, float, str, type(None))) or isinstance(value, list) and len(value) <= 1000 \
            and all(isinstance(v, (int, float)) for v in value)
        if not plain:  # an option is a number, a string or a short list of numbers (a reference posture)
            raise _err(f"{where}: {key}.{name}", f"must be a number, a string or a list of numbers, got {shown(value)}")
        try:
            setattr(probe, name, value)
        except (TypeError, ValueError, OverflowError) as e:
            why = " ".join(str(e).split())[:200]
            raise _err(f"{where}: {key}.{name}", f"bad value {shown(value)} ({why})") from None
    return dict(entry)


def read_job(job, out: str | os.PathLike | None = None) -> Job:
    """A checked job from a job file (YAML or JSON) or a dict; raises JobError naming the entry and key."""
    if isinstance(job, dict):
        data, where, base = job, "job", Path(".")
    else:
        path = Path(job)
        try:
            data = read_data(path, "job file")
        except (OSError, ValueError) as e:
            raise JobError(str(e)) from None
        where, base = f"job file {str(path)!r}", path.parent
    if not isinstance(data, dict):
        raise JobError(f"{where}: must be a mapping with 'robots', 'arms', 'resolutions', 'surfaces'...")
    unknown = set(data) - _JOB_KEYS
    if unknown:
        raise _err(where, f"unknown key {shown(sorted(map(str, unknown))[0])} (known: {', '.join(sorted(_JOB_KEYS))})")
    resolutions = _numbers(data.get("resolutions", [0.05]), f"{where}: resolutions", True)
    heights = _numbers(data.get("base_heights", [0.0]), f"{where}: base_heights", False)
    cap_options = _options(data, "capability", where, _cache.capability_options, {"resolution", "threads", "approach_axis"})
    surf_options = _options(data, "surface", where, SurfaceMapOptions, _SURFACE_OPTION_EXCLUDED)
    surfaces = _surfaces(data, where, base)
    # The file's out is checked even when the argument replaces it: a bad value in a file is a bad input.
    out_value = _out_folder(data.get("out", "build_many_out"), f"{where}: out", base)
    out_dir = _out_folder(out, "out (--out)", Path(".")) if out is not None else out_value
    if out_dir.exists() and not out_dir.is_dir():
        raise _err("out (--out)" if out is not None else f"{where}: out",
                   f"{str(out_dir)!r} exists and is not a folder")
    result = Job(out=out_dir)
    specs = _robot_specs(data, where, base)
    arm_count = sum(max(1, len(a)) for _, a, _ in specs)
    maps = arm_count * len(resolutions) * (1 + len(surfaces) * len(heights))
    if maps > limits.MAX_JOB_MAPS:
        raise _err(where, f"{maps:,} maps, more than the limit of {limits.MAX_JOB_MAPS:,} (octoreach.limits.MAX_JOB_MAPS)")
    for spec, arm_names, w in specs:
        try:
            robot = load_robot(spec)
        except (ValueError, TypeError, OSError, RuntimeError) as e:
            raise _err(f"{w}", f"cannot load the robot: {e}") from None
        rname = _safe(spec.get("name") or Path(spec["urdf"]).stem)
        if not arm_names:
            try:
                arm_names = [default_arm(robot)]
            except ValueError as e:
                raise _err(f"{w}: arms", str(e)) from None
        for j, arm_name in enumerate(arm_names):
            try:
                arm = Arm.resolve(robot, arm_name if isinstance(arm_name, str) else tuple(arm_name))
            except (ValueError, TypeError) as e:
                raise _err(f"{w}: arms[{j}]", str(e)) from None
            for res in resolutions:
                options = {**cap_options, "resolution": res, "keep_solutions": True}
                fields = _cache.capability_key_fields(robot, arm, _cache.capability_options(None, **options))
                # repr: the shortest text that reads back as the same float (0.2 and 0.2000001 differ)
                folder = out_dir / rname / _safe(arm_name if isinstance(arm_name, str) else arm.tip_link) / f"res{res!r}"
                cap = CapabilityJob(f"{rname}/{arm.tip_link}/{res!r}", robot, spec, arm, options, fields,
                                    folder / "capability.orcm")
                result.capability.append(cap)
                for room, room_base, sname, polygon in surfaces:
                    for h in heights:
                        suffix = "" if len(heights) == 1 and h == 0 else f"@z{h!r}"
                        sfields = {"kind": "surface", "capability": fields, "room": room, "surface": sname,
                                   "files": _file_digests(room, Path(room_base)), "height": h, "options": surf_options}
                        result.surfaces.append(SurfaceJob(f"{cap.name}/{sname}{suffix}", len(result.capability) - 1,
                                                          room, room_base, sname, h, surf_options, sfields,
                                                          folder / f"{_safe(sname)}{suffix}.orsm", polygon))
    _check_outputs(result, where)
    return result
