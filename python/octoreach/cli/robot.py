"""`octoreach robot` and `octoreach ik`: a robot's model, arms and inverse kinematics."""
from __future__ import annotations

import numpy as np

from .args import load_robot, robot_args


def _cmd_robot(args) -> int:
    from .._core import find_arms

    robot = load_robot(args)
    print(f"{robot.name}: {len(robot.link_names)} links ({len(robot.collision_links)} with collision geometry), "
          f"{robot.dof} dof, root {robot.root_link}, {len(robot.allowed_collisions)} allowed-collision pairs")
    print("links:")
    for name in robot.link_names:
        print(f"  {name}")
    print("joints (configuration order, limits in rad or m):")
    for name, lo, hi in zip(robot.joint_names, robot.lower, robot.upper):
        print(f"  {name}: [{lo:.4g}, {hi:.4g}]")
    for name in robot.mimic_joints:
        print(f"  {name}: mimic")
    if robot.srdf_groups:
        print("SRDF groups:")
    for name, g in robot.srdf_groups.items():
        parts = [f"chain {b} -> {t}" for b, t in g["chains"]]
        parts += [f"joints {', '.join(g['joints'])}"] if g["joints"] else []
        parts += [f"links {', '.join(g['links'])}"] if g["links"] else []
        parts += [f"subgroups {', '.join(g['subgroups'])}"] if g["subgroups"] else []
        print(f"  {name}: {'; '.join(parts) or 'empty'}")
    for e in robot.end_effectors:
        print(f"end effector {e['name']}: parent link {e['parent_link']}, group {e['group'] or '-'}"
              f"{', parent group ' + e['parent_group'] if e['parent_group'] else ''}")
    arms = find_arms(robot)
    print("arms (what --arm NAME uses; tool frame, approach axis and why):" if arms else
          "arms: none found (give one by its links: --base LINK --tip LINK --approach-axis X Y Z)")
    for a in arms:
        print(f"  {a.name}: {a.base_link} -> {a.tip_link}, approach axis {tuple(round(float(v), 3) for v in a.approach_axis)}"
              f" ({a.reason}); from {a.source}")
    poses = robot.link_poses(robot.home()) if arms else {}
    for a in arms:  # where the tool frame's axes point at home, in the arm's base frame
        R = (np.linalg.inv(poses[a.base_link]) @ poses[a.tip_link])[:3, :3]
        axes = ", ".join(f"{n} -> {tuple(round(float(v), 2) for v in R[:, k])}" for k, n in enumerate("xyz"))
        print(f"tool frame {a.tip_link} (arm {a.name}) at home, axes in {a.base_link}: {axes}")
    if args.write_srdf:
        robot.write_srdf(args.write_srdf)
        print(f"wrote {args.write_srdf}")
    return 0


def _cmd_ik(args) -> int:
    robot = load_robot(args)
    chain = robot.chain(args.base, args.tip)
    T = np.eye(4)
    T[:3, 3] = args.xyz
    q = chain.ik(T, mode=args.mode, rng_seed=args.seed, approach_axis=np.array(args.approach_axis, float))
    if q is None:
        print("no solution")
        return 1
    print(" ".join(f"{v:.6f}" for v in q))
    return 0


def add_commands(sub):
    """robot, ik."""
    sp = sub.add_parser("robot", help="print a robot's links, joints with limits, SRDF groups, end effectors and arms")
    sp.add_argument("name", nargs="?", help="robot of example-robot-data by name (same as --robot)")
    robot_args(sp)
    sp.add_argument("--write-srdf", metavar="PATH", help="write the robot's SRDF (groups, allowed-collision pairs) to PATH")
    sp.set_defaults(func=_cmd_robot)

    sp = sub.add_parser("ik", help="solve inverse kinematics for a position")
    robot_args(sp)
    sp.add_argument("--base", required=True, help="base link of the chain")
    sp.add_argument("--tip", required=True, help="tip link of the chain")
    sp.add_argument("--xyz", type=float, nargs=3, required=True, help="target position in the base frame (m)")
    sp.add_argument("--mode", choices=["full", "position", "approach"], default="position", help="IK mode")
    sp.add_argument("--approach-axis", type=float, nargs=3, default=[0, 0, 1],
                    help="tool axis that approaches the target, tip frame (unit vector; default 0 0 1)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.set_defaults(func=_cmd_ik)
