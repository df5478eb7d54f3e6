"""The `octoreach` command line."""
from __future__ import annotations

import argparse
import sys

import numpy as np


def _load_robot(args):
    from . import robots
    from ._core import Robot

    if args.urdf:
        return Robot.from_urdf(args.urdf, package_dirs=args.package_dir or [], srdf=args.srdf)
    return robots.load(args.robot)


def _cmd_robot(args) -> int:
    robot = _load_robot(args)
    print(f"{robot.name}: {len(robot.link_names)} links, {robot.dof} dof, root {robot.root_link}")
    for name, (base, tip) in robot.groups.items():
        print(f"  group {name}: {base} -> {tip}")
    for name, lo, hi in zip(robot.joint_names, robot.lower, robot.upper):
        print(f"  joint {name}: [{lo:.3f}, {hi:.3f}]")
    return 0


def _cmd_ik(args) -> int:
    robot = _load_robot(args)
    chain = robot.chain(args.base, args.tip)
    T = np.eye(4)
    T[:3, 3] = args.xyz
    q = chain.ik(T, mode=args.mode, rng_seed=args.seed, approach_axis=np.array(args.approach_axis, float))
    if q is None:
        print("no solution")
        return 1
    print(" ".join(f"{v:.6f}" for v in q))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="octoreach", description="Where a robot should stand and where it should look.")
    sub = p.add_subparsers(dest="command", required=True)

    def robot_args(sp):
        sp.add_argument("--robot", default="pr2", help="robot of example-robot-data by name (default: pr2)")
        sp.add_argument("--urdf", help="URDF file of your own robot (overrides --robot)")
        sp.add_argument("--srdf", help="SRDF file for --urdf (groups and disabled collision pairs)")
        sp.add_argument("--package-dir", action="append", help="folder to resolve package:// URIs (repeatable)")

    sp = sub.add_parser("robot", help="print a robot's links, groups and joint limits")
    robot_args(sp)
    sp.set_defaults(func=_cmd_robot)

    sp = sub.add_parser("ik", help="solve inverse kinematics for a position")
    robot_args(sp)
    sp.add_argument("--base", required=True, help="base link of the chain")
    sp.add_argument("--tip", required=True, help="tip link of the chain")
    sp.add_argument("--xyz", type=float, nargs=3, required=True, help="target position in the base frame (m)")
    sp.add_argument("--mode", choices=["full", "position", "approach"], default="position")
    sp.add_argument("--approach-axis", type=float, nargs=3, default=[0, 0, 1])
    sp.add_argument("--seed", type=int, default=0)
    sp.set_defaults(func=_cmd_ik)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, OSError) as e:
        print(f"octoreach: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    raise SystemExit(main())
