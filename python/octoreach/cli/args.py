"""Arguments shared by the commands: which robot, which arm, the build options, the cache; angles."""
from __future__ import annotations

import argparse

import numpy as np


def load_robot(args):
    from .. import robots

    how = getattr(args, "allowed_collisions", "auto")
    if args.urdf:
        return robots.from_urdf(args.urdf, args.package_dir or [], args.srdf, allowed_collisions=how)
    return robots.load(getattr(args, "robot_name", None) or args.robot, allowed_collisions=how)


def arm_arg(args, robot):
    """The Arm of --arm NAME or --base/--tip, with --approach-axis overriding the inferred axis."""
    from .._core import Arm

    axis = None if args.approach_axis is None else tuple(args.approach_axis)
    if args.arm is None:
        if args.base or args.tip:
            if not (args.base and args.tip):
                raise ValueError("give both --base LINK and --tip LINK (or --arm NAME)")
            return Arm.resolve(robot, (args.base, args.tip), approach_axis=axis)
        from ..arms import default_arm

        return Arm.resolve(robot, default_arm(robot), approach_axis=axis)
    return Arm.resolve(robot, args.arm, approach_axis=axis)


def named_arm(args, robot, name):
    from .._core import Arm

    return Arm.resolve(robot, name, approach_axis=None if args.approach_axis is None else tuple(args.approach_axis))


def angle(text: str) -> float:
    """An angle on the command line: radians, or degrees with an explicit suffix ("90deg")."""
    t = str(text).strip().lower()
    try:
        return float(np.radians(float(t[:-3]))) if t.endswith("deg") else float(t)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an angle: {text!r} (radians, or degrees as e.g. 90deg)") from None


def metres(text: str) -> float:
    """A length on the command line: a finite number of metres above 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of metres: {text!r}") from None
    if not (np.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be a finite number of metres above 0, got {text!r}")
    return value


def robot_spec(args) -> dict:
    """How a cluster's workers load the robot of --robot/--urdf (they check its model hash)."""
    import os

    if args.urdf:
        return {"urdf": os.path.abspath(args.urdf), "srdf": os.path.abspath(args.srdf) if args.srdf else None,
                "package_dirs": [os.path.abspath(p) for p in args.package_dir or []],
                "allowed_collisions": args.allowed_collisions}
    return {"name": getattr(args, "robot_name", None) or args.robot, "allowed_collisions": args.allowed_collisions}


def robot_args(sp):
    """--robot/--urdf/--srdf/--package-dir/--allowed-collisions: which robot, and its collision set-up."""
    sp.add_argument("--robot", default="pr2", help="robot of example-robot-data by name (default: pr2)")
    sp.add_argument("--urdf", help="URDF file of your own robot (overrides --robot)")
    sp.add_argument("--srdf", help="SRDF file for --urdf (groups and disabled collision pairs)")
    sp.add_argument("--package-dir", action="append", help="folder to resolve package:// URIs (repeatable)")
    sp.add_argument("--allowed-collisions", choices=["auto", "sample", "srdf"], default="auto",
                    help="auto (default): sample the allowed-collision matrix (cached) when the SRDF is missing or "
                         "incomplete; sample: always; srdf: only what the URDF/SRDF say")


def arm_args(sp, many=False):
    """Which arm(s) and the build options; defaults from CapabilityMapOptions and SurfaceMapOptions (C++).

    many=True is the surface command: --resolution then defaults to SurfaceMapOptions().resolution (None: the
    capability map's, as SurfaceMap.build), and a capability map built from an arm name uses the capability
    default."""
    from .._core import CapabilityMapOptions

    defaults = CapabilityMapOptions()  # the build defaults, defined once in C++
    if many:
        sp.add_argument("--arms", nargs="+",
                        help="arm names (SRDF groups, e.g. right_arm left_arm) or saved capability maps (.orcm "
                             "with solutions); several are combined (default: right_arm, or the robot's only arm)")
    else:
        sp.add_argument("--arm", help="arm name (see `octoreach robot NAME`, e.g. right_arm; default: right_arm, or "
                                      "the robot's only arm)")
        sp.add_argument("--base", help="chain base link (instead of --arm)")
        sp.add_argument("--tip", help="chain tip (tool) link (instead of --arm)")
    sp.add_argument("--approach-axis", type=float, nargs=3, metavar=("X", "Y", "Z"),
                    help="tool axis that approaches the object, tip frame (default: inferred from the gripper)")
    if many:
        sp.add_argument("--resolution", type=metres, default=None,
                        help="grid of base positions and surface points in m (default: the capability map's; a map "
                             f"built from an arm name uses {defaults.resolution})")
    else:
        sp.add_argument("--resolution", type=metres, default=defaults.resolution,
                        help=f"voxel edge in m (default {defaults.resolution})")
    sp.add_argument("--directions", type=int, default=defaults.directions,
                    help=f"approach directions (default {defaults.directions}; a map file has its own)")
    sp.add_argument("--poles", action="store_true",
                    help="also the directions straight up and down: for a tool held vertical (a SCARA)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.add_argument("--quiet", action="store_true", help="no progress bar")
    sp.add_argument("--octovis", help="also write a colour octree (.ot) for octovis")


def cache_args(sp):
    sp.add_argument("--cache-dir", help="map cache folder (default $OCTOREACH_CACHE_DIR or ~/.cache/octoreach/maps)")
    sp.add_argument("--no-cache", action="store_true", help="neither look maps up in the cache nor store them")
