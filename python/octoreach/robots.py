"""Robots shipped by the PyPI package example-robot-data (URDF, SRDF and meshes).

``octoreach.robots.pr2()`` returns the PR2; ``octoreach.robots.load(name)`` any robot
of that package by name (for example "panda", "tiago", "talos", "kinova"), ``available()`` lists them,
``files(name)`` gives the URDF, SRDF and package folders load(name) reads (the viewer draws the URDF's meshes).
Robots without a complete SRDF get their allowed-collision matrix sampled (cached on disk).
The project's own robots (``urdf/`` in the source tree) are found by ``project_urdf(name)``.
"""
from __future__ import annotations

import difflib
import os
import re
import warnings
import site
import sys
import sysconfig
from pathlib import Path

from ._core import Robot
from ._checks import PATH, check_paths, check_type

# name -> (description folder, URDF file, SRDF file or None)
_KNOWN = {
    "pr2": ("pr2_description", "pr2.urdf", "pr2.srdf"),
    "panda": ("panda_description", "panda.urdf", "panda.srdf"),
    "ur3": ("ur_description", "ur3_robot.urdf", None),
    "ur5": ("ur_description", "ur5_robot.urdf", "ur5.srdf"),
    "ur10": ("ur_description", "ur10_robot.urdf", None),
    "z1": ("z1_description", "z1.urdf", "z1.srdf"),
    "xarm7": ("xarm_description", "xarm7.urdf", "xarm7.srdf"),
    "baxter": ("baxter_description", "baxter.urdf", "baxter_manipulation.srdf"),
    "so100": ("so_arm_description", "so100.urdf", None),
    "so101": ("so_arm_description", "so101.urdf", None),
}


def data_dir() -> Path:
    """Folder that holds example-robot-data's `robots/` (its package root for package:// URIs)."""
    env = os.environ.get("OCTOREACH_ROBOT_DATA")
    candidates = [Path(env)] if env else []
    roots = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"], sys.prefix}
    try:
        roots.update(site.getsitepackages())
    except AttributeError:  # virtualenvs of old Pythons
        pass
    for root in sorted(roots):
        candidates.append(Path(root) / "cmeel.prefix" / "share" / "example-robot-data")
    for c in candidates:
        if (c / "robots").is_dir():
            return c
    raise FileNotFoundError(
        "robots by name come from example-robot-data, which is not installed: install octoreach's robots extra "
        "(pip install 'octoreach[robots]' beside an installed octoreach, or pip install example-robot-data); "
        "set OCTOREACH_ROBOT_DATA to a folder holding its robots/ to override"
    )


def _index() -> dict[str, tuple[Path, Path | None]]:
    """name -> (URDF, SRDF or None) for every URDF of example-robot-data and the known aliases.

    URDFs sit in robots/<description>/urdf/ or robots/<description>/robots/. A URDF's name is its file
    stem; a stem two descriptions share (anymal) is named "<description without _description>/<stem>"
    for each. Its SRDF is robots/<description>/srdf/<stem>.srdf, else the longest SRDF stem that starts
    the URDF stem (talos_reduced -> talos.srdf).
    """
    root = data_dir()
    found: dict[str, list[Path]] = {}
    for path in sorted((root / "robots").glob("*/*/*.urdf")):
        if path.parent.name in ("urdf", "robots"):
            found.setdefault(path.stem, []).append(path)
    index: dict[str, tuple[Path, Path | None]] = {}
    for stem, paths in found.items():
        for path in paths:
            srdfs = sorted((path.parent.parent / "srdf").glob("*.srdf"))
            exact = [p for p in srdfs if p.stem == stem]
            prefix = sorted((p for p in srdfs if stem.startswith(p.stem)), key=lambda p: -len(p.stem))
            srdf = (exact or prefix or [None])[0]
            name = stem if len(paths) == 1 else f"{path.parent.parent.name.removesuffix('_description')}/{stem}"
            index[name] = (path, srdf)
    for alias, (folder, urdf, srdf_file) in _KNOWN.items():
        urdf_path = root / "robots" / folder / "urdf" / urdf
        if urdf_path.is_file():
            if alias in index and index[alias][0] != urdf_path:  # ur3.urdf next to the alias ur3 -> ur3_robot.urdf
                shadowed = index[alias]
                index[f"{shadowed[0].parent.parent.name.removesuffix('_description')}/{alias}"] = shadowed
            index[alias] = (urdf_path, root / "robots" / folder / "srdf" / srdf_file if srdf_file else None)
    return index


def available() -> list[str]:
    """Names accepted by load(): every URDF of example-robot-data (and the aliases pr2, ur5, ...)."""
    try:
        return sorted(_index())
    except FileNotFoundError:
        return []


def package_dirs(root: Path | None = None) -> list[str]:
    """Folders that example-robot-data's package:// mesh URIs resolve against (root: data_dir()):
    package://example-robot-data/robots/... against share/, package://X_description/... against robots/."""
    root = data_dir() if root is None else Path(root)
    return [str(root.parent), str(root / "robots")]


def files(name: str) -> tuple[Path, Path | None, list[str]]:
    """(URDF, SRDF or None, package_dirs) of robot `name` of example-robot-data, the files load(name) reads.
    An unknown name: ValueError with the nearest names."""
    if len(name) > 200:  # a name read from a file; difflib below is quadratic in its length
        raise ValueError(f"unknown robot {name[:60]!r}... ({len(name):,} characters; robot names are short)")
    index = _index()
    if name not in index:
        qualified = [n for n in index if n.endswith("/" + name)]
        if qualified:
            raise ValueError(f"robot name {name!r} is ambiguous: {', '.join(qualified)}")
        close = difflib.get_close_matches(name, list(index), n=3, cutoff=0.5)
        hint = f"; did you mean {', '.join(map(repr, close))}?" if close else ""
        raise ValueError(f"unknown robot {name!r}{hint} Available: {', '.join(sorted(index))}")
    urdf_path, srdf_path = index[name]
    return urdf_path, srdf_path, package_dirs()


_PROJECT_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,199}")
_ROBOT_NAME = re.compile(r"<robot\b[^>]*?\bname\s*=\s*[\"']([^\"']+)[\"']")


def catalogue_name(robot_name: str, urdf_hash: str = "") -> str | None:
    """The name load() takes for the robot of example-robot-data whose URDF declares `robot_name`
    (<robot name=...>; a Robot and a map carry that name, which need not be the one it is loaded by: xarm7's URDF
    says "UF_ROBOT") and, when `urdf_hash` is given, whose model has that hash; None if there is none."""
    check_type(robot_name, str, "robot_name", "a str")
    try:
        index = _index()
    except FileNotFoundError:
        return None
    for name, (urdf_path, _) in sorted(index.items()):
        with open(urdf_path, encoding="utf-8", errors="replace") as f:
            m = _ROBOT_NAME.search(f.read())
        if m is None or m.group(1) != robot_name:
            continue
        if not urdf_hash or Robot.from_urdf(str(urdf_path), package_dirs=package_dirs()).urdf_hash == urdf_hash:
            return name
    return None


def loadable_name(name: str, urdf_hash: str = "") -> str:
    """`name` if load() takes it, else catalogue_name(name, urdf_hash) (the robot whose URDF declares the
    robot name `name`: what a Robot and a map carry); the ValueError of files(name) if neither."""
    try:
        files(name)
        return name
    except ValueError:
        known = catalogue_name(name, urdf_hash)
        if known is None:
            raise
        return known


def complete_allowed_collisions(robot: Robot, srdf_given: bool = True, options=None, progress=False, **kwargs) -> Robot:
    """The robot with the sampled allowed-collision matrix (MoveIt setup assistant's method, cached on disk by
    model hash) added when no SRDF was given or its list is incomplete (the home posture is in self-collision);
    else the robot itself. Keywords set AllowedCollisionOptions fields (samples, seed, cache_dir, ...)."""
    check_type(robot, Robot, "robot", "an octoreach.Robot")
    check_type(srdf_given, bool, "srdf_given", "a bool")
    if srdf_given and not robot.self_collisions(robot.home()):
        return robot
    return robot.with_sampled_collisions(options, progress=progress, **kwargs)


def from_urdf(urdf, package_dirs=(), srdf=None, allowed_collisions: str = "auto", srdf_mismatch=None) -> Robot:
    """Robot from a URDF (path or XML) with its SRDF; allowed_collisions: "auto" samples the allowed-collision
    matrix when the SRDF is missing or incomplete (complete_allowed_collisions), "sample" always adds the
    sampled pairs, "srdf" keeps what the URDF and SRDF say. srdf_mismatch as in Robot.from_urdf ("error", the
    default, or "leave_out")."""
    check_type(urdf, PATH, "urdf", "a path or URDF text (str or os.PathLike)")
    check_type(srdf, PATH + (type(None),), "srdf", "a path or SRDF text (str or os.PathLike) or None")
    check_type(allowed_collisions, str, "allowed_collisions", "'auto', 'sample' or 'srdf'")
    dirs = check_paths(package_dirs, "package_dirs")
    for what, value in (("URDF", urdf), ("SRDF", srdf)):
        _check_regular(value, what)
    robot = Robot.from_urdf(str(urdf), package_dirs=dirs, srdf=None if srdf is None else str(srdf),
                            srdf_mismatch=srdf_mismatch)
    if allowed_collisions == "auto":
        return complete_allowed_collisions(robot, srdf_given=srdf is not None)
    if allowed_collisions == "sample":
        return robot.with_sampled_collisions()
    if allowed_collisions != "srdf":
        raise ValueError(f"allowed_collisions must be 'auto', 'sample' or 'srdf', got {allowed_collisions!r}")
    return robot


def _check_regular(value, what: str) -> None:
    """OSError when a path names a FIFO, a device or a folder (a reader would block or never end); URDF text
    and missing files pass (Robot.from_urdf reports those)."""
    import stat

    if value is None or isinstance(value, str) and ("<" in value or len(value) > 4096):
        return
    try:
        mode = os.stat(value).st_mode
    except (OSError, ValueError):
        return
    if not stat.S_ISREG(mode):
        from .data_files import file_kind

        raise OSError(f"cannot read {what} {os.fspath(value)!r}: it is {file_kind(mode)}, not a regular file")


def load(name: str, srdf: bool = True, allowed_collisions: str = "auto") -> Robot:
    """Robot `name` of example-robot-data (see available()) with its SRDF when it has one (groups, end
    effectors, disabled collisions); allowed_collisions as in from_urdf ("auto" samples the allowed-collision
    matrix, cached, when the SRDF is missing or incomplete)."""
    check_type(name, str, "name", "a robot name (str; see available())")
    check_type(srdf, bool, "srdf", "a bool")
    check_type(allowed_collisions, str, "allowed_collisions", "'auto', 'sample' or 'srdf'")
    urdf_path, srdf_path, dirs = files(name)
    if not srdf:
        srdf_path = None
    # example-robot-data ships SRDFs of other variants (talos.srdf for talos_left_arm, a group naming a link
    # the URDF lacks): the entries that do not fit are left out, as MoveIt does, and the rest is used.
    robot = from_urdf(urdf_path, dirs, srdf_path, allowed_collisions, srdf_mismatch="leave_out")
    left_out = robot.srdf_left_out
    if left_out:
        shown = "; ".join(left_out[:3]) + ("; ..." if len(left_out) > 3 else "")
        warnings.warn(f"{name}: {len(left_out)} group(s)/end effector(s) of {srdf_path.name} name links, joints or "
                      f"groups its URDF does not have and were left out (the rest of the SRDF is used): {shown}",
                      stacklevel=2)
    return robot


def pr2(srdf: bool = True) -> Robot:
    """The PR2 of example-robot-data (base_footprint root; arms "left_arm" and "right_arm" from its SRDF)."""
    return load("pr2", srdf=srdf)


def project_urdf(name: str) -> Path:
    """Path of a URDF the project owns (``urdf/NAME.urdf``), installed with the package. A name is a file
    stem of that folder (letters, digits, '_', '-', '.'; no path: a name read from a map header or a job file
    never reaches a file elsewhere)."""
    check_type(name, str, "name", "a URDF name (str)")
    if not _PROJECT_NAME.fullmatch(name):
        raise ValueError(f"no project URDF named {name[:200]!r} (a name, not a path)")
    here = Path(__file__).resolve().parent
    for candidate in (here / "urdf" / f"{name}.urdf", here.parent.parent / "urdf" / f"{name}.urdf"):
        if candidate.is_file():
            return candidate
    raise ValueError(f"no project URDF named {name!r}")


def test_arm() -> Robot:
    """The project's small 6-DOF test arm (base_link -> tool0), made of boxes, cylinders and spheres."""
    return Robot.from_urdf(str(project_urdf("test_arm")))
