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
    _print_diagnostics(robot, arms, args)
    if args.write_srdf:
        robot.write_srdf(args.write_srdf)
        print(f"wrote {args.write_srdf}")
    return 0


def _print_diagnostics(robot, arms, args) -> None:
    """Where the allowed-collision pairs came from, how often random configurations collide, and per arm the
    joints map builds hold still; all computed in C++ (octoreach.self_collision_report, octoreach.arm_report)."""
    from .._core import arm_report, camera_link, self_collision_report

    _print_allowed(robot)
    whole = self_collision_report(robot, samples=args.samples, seed=args.seed)
    print(f"self-collision, every joint drawn: {_share(whole)} free (an arm reaching into the body counts here; the "
          "hint below looks at each arm's own links)")
    _print_pairs(whole, "  ")
    for a in arms:
        r = arm_report(robot, a, samples=args.samples, seed=args.seed)
        print(f"arm {a.name}: moves {', '.join(r.moving)}")
        if r.held:
            held = ", ".join(f"{h.name} at {h.value:.4g}" for h in r.held)
            print(f"  holds still (they carry the arm; map builds never move them): {held}; to include them: "
                  f"--base {r.base_to_include_held} --tip {a.tip_link}")
        sc = r.self_collision
        print(f"  self-collision, its joints drawn: {_share(sc)} free among its own links, "
              f"{100 * r.with_body.free_share:.0f} % with the body too")
        _print_pairs(sc, "    ")
        if sc.suspicious and sc.pairs:
            _print_hint(sc, "    ")
    try:
        cam = camera_link(robot)
        print(f"camera link: {cam.link} ({cam.reason})")
    except ValueError as e:
        print(f"camera link: none found ({e})")


def _share(report) -> str:
    return f"{100 * report.free_share:.0f} % of {report.samples} random configurations"


def _print_pairs(report, indent: str) -> None:
    top = report.pairs[:5]
    if top:
        print(f"{indent}most often in collision: " + ", ".join(
            f"{p.link_a}/{p.link_b} {100 * p.hits / report.samples:.0f} %" for p in top))


def _print_hint(report, indent: str) -> None:
    p = report.pairs[0]
    print(f"{indent}hint: under {100 * report.FREE_SHARE_HINT:.0f} % free (arms whose collision models match their hardware "
          f"are free in more): check the collision shapes of {p.link_a} and {p.link_b} (a cylinder longer or fatter "
          "than its link, a shape reaching over the joint); if they cannot touch on the real robot, allow the pair: "
          f"<disable_collisions link1=\"{p.link_a}\" link2=\"{p.link_b}\" reason=\"Never\"/> in an SRDF (--srdf)")


def _print_allowed(robot) -> None:
    """The allowed pairs by where they came from; the sampled 'always' and 'at home' pairs by name."""
    by: dict = {}
    for a, b, why in robot.allowed_collision_sources:
        by.setdefault(why, []).append(f"{a}/{b}")
    counts = ", ".join(f"{len(v)} {k if k != 'SRDF' else 'from the SRDF'}" for k, v in by.items())
    print(f"allowed-collision pairs: {len(robot.allowed_collisions)} ({counts or 'none'})")
    for why in ("always in collision", "in collision at home", "given"):
        pairs = by.get(why, [])
        if pairs:
            shown = ", ".join(pairs[:12]) + (", ..." if len(pairs) > 12 else "")
            print(f"  sampled, {why} (never checked again): {shown}" if why != "given" else f"  given: {shown}")
    if by.get("in collision at home"):
        print("  hint: pairs in collision at the home posture are allowed for good (MoveIt's 'Default'); if they can "
              "touch in use (a hand inside a thigh), give an SRDF whose <disable_collisions> you choose (--srdf) "
              "and --allowed-collisions srdf")


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
    sp = sub.add_parser("robot", help="print a robot's links, joints with limits, SRDF groups, end effectors, arms, "
                                      "where its allowed-collision pairs came from, how often it collides with itself, "
                                      "the joints map builds hold still and its camera link")
    sp.add_argument("robot_name", metavar="name", nargs="?", help="robot of example-robot-data by name (same as --robot)")
    robot_args(sp)
    sp.add_argument("--write-srdf", metavar="PATH", help="write the robot's SRDF (groups, allowed-collision pairs) to PATH")
    from .._core import SelfCollisionOptions

    sp.add_argument("--samples", type=int, default=SelfCollisionOptions().samples,
                    help="random configurations of the self-collision report (default %(default)s)")
    sp.add_argument("--seed", type=int, default=0, help="random seed of the self-collision report (default 0)")
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
