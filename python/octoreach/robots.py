"""Robots shipped by the PyPI package example-robot-data (URDF, SRDF and meshes).

``octoreach.robots.pr2()`` returns the PR2; ``octoreach.robots.load(name)`` any robot
of that package by name (for example "panda", "ur5", "z1"), ``available()`` lists them.
The project's own robots (``urdf/`` in the source tree) are found by ``project_urdf(name)``.
"""
from __future__ import annotations

import glob
import os
import site
import sys
import sysconfig
from pathlib import Path

from ._core import Robot

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
        "example-robot-data is not installed (pip install example-robot-data, or `make demo` does it); "
        "set OCTOREACH_ROBOT_DATA to a folder holding its robots/ to override"
    )


def available() -> list[str]:
    """Names accepted by load(): the known aliases plus every URDF of example-robot-data."""
    names = set(_KNOWN)
    try:
        for path in glob.glob(str(data_dir() / "robots" / "*" / "urdf" / "*.urdf")):
            names.add(Path(path).stem)
    except FileNotFoundError:
        pass
    return sorted(names)


def _package_dirs(root: Path) -> list[str]:
    # package://example-robot-data/robots/... resolves against share/, and package://X_description/...
    # against robots/ for URDFs that name their description package.
    return [str(root.parent), str(root / "robots")]


def load(name: str, srdf: bool = True) -> Robot:
    """Robot `name` from example-robot-data, with its SRDF (groups, disabled collisions) when it has one."""
    root = data_dir()
    if name in _KNOWN:
        folder, urdf, srdf_file = _KNOWN[name]
        urdf_path = root / "robots" / folder / "urdf" / urdf
        srdf_path = root / "robots" / folder / "srdf" / srdf_file if srdf_file else None
    else:
        matches = glob.glob(str(root / "robots" / "*" / "urdf" / f"{name}.urdf"))
        if not matches:
            raise ValueError(f"unknown robot {name!r}; available: {', '.join(available())}")
        urdf_path = Path(matches[0])
        srdf_candidates = glob.glob(str(urdf_path.parent.parent / "srdf" / f"{name}.srdf"))
        srdf_path = Path(srdf_candidates[0]) if srdf_candidates else None
    return Robot.from_urdf(
        str(urdf_path),
        package_dirs=_package_dirs(root),
        srdf=str(srdf_path) if (srdf and srdf_path is not None) else None,
    )


def pr2(srdf: bool = True) -> Robot:
    """The PR2 of example-robot-data (base_footprint root; arms "left_arm" and "right_arm" from its SRDF)."""
    return load("pr2", srdf=srdf)


def project_urdf(name: str) -> Path:
    """Path of a URDF the project owns (``urdf/NAME.urdf``), installed with the package."""
    here = Path(__file__).resolve().parent
    for candidate in (here / "urdf" / f"{name}.urdf", here.parent.parent / "urdf" / f"{name}.urdf"):
        if candidate.is_file():
            return candidate
    raise ValueError(f"no project URDF named {name!r}")


def test_arm() -> Robot:
    """The project's small 6-DOF test arm (base_link -> tool0), made of boxes, cylinders and spheres."""
    return Robot.from_urdf(str(project_urdf("test_arm")))
