#!/usr/bin/env python3
"""A new robot in minutes: from a robot's name to a saved capability map and a table surface map, and how
well its capability map agrees with direct IK.

For each robot (PR2, TIAGo, Panda, UR5 of example-robot-data), the path of the README's "Your own robot in
five minutes", with no file of ours and an empty allowed-collision cache (a temporary OCTOREACH_CACHE_DIR):
- onboarding: wall-clock seconds from the name to a loaded robot (`robots.load(name)`: the allowed-collision
  matrix is sampled where the SRDF is missing or incomplete, as MoveIt's setup assistant does, 10,000
  random configurations), to its arm by name (`Arm.named`: base, tool frame, inferred approach axis), to a
  saved capability map at 0.1 m (with joint solutions), and to a saved surface map of a table in front of
  it; and the same load again from the cache;
- fidelity at 0.1 m and (unless --no-fine) 0.05 m: N random tool poses, positions uniform in the map's box
  (`map.bounds`, arm base frame), rotations uniform on SO(3). Truth: IK of the exact pose with any roll
  about the approach axis (mode 'approach'), self-collision-free at the arm's reference posture,
  20 random restarts, tolerances 1e-3 m / 1e-2 rad (the capability map's own). The map answers
  `map.reachable(pose)`. agreement = share of poses where both agree; false positives (map yes, IK no)
  and false negatives (map no, IK yes) as shares of all poses; also the false negatives as a share of the
  poses IK reaches.
- anchor: MoveIt's setup assistant's self-collision step at its default density (10,000 random
  configurations) takes tens of seconds to minutes (the issue's figure; MoveIt needs ROS, which this
  machine does not have, so it is quoted, not measured). Measured here in the same run: the same step
  (`Robot.with_sampled_collisions(samples=10000)`, the URDF alone: every link pair, no cache) on each robot.

Targets of the issue: agreement >= 97 %, false positives and false negatives each <= 2 % at 0.05 m.
Prints one JSON document. The 0.05 m maps take about a minute each.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import octoreach
from octoreach import robots

sys.path.insert(0, str(Path(__file__).resolve().parent))
from capability_map import random_poses, shares  # noqa: E402  (the same pose sampling and shares)

# name -> (arm name as find_arms reports it, table (size x, size y, height, x, y) in front of the robot)
ROBOTS = {
    "pr2": ("right_arm", (1.4, 0.65, 0.72, 0.0, 0.0)),
    "tiago": ("arm", (1.2, 0.8, 0.75, 0.0, 0.0)),
    "panda": ("arm", (0.6, 0.8, 0.3, 0.0, 0.0)),
    "ur5": ("arm", (0.6, 0.8, 0.3, 0.0, 0.0)),
}


def fidelity(robot, arm: octoreach.Arm, cap, poses_n: int, seed: int) -> dict:
    chain = robot.chain(arm.base_link, arm.tip_link)
    reference = octoreach.default_reference(robot, chain)
    lo, hi = cap.bounds
    poses = random_poses(lo, hi, poses_n, np.random.default_rng(seed))
    t0 = time.perf_counter()
    _, truth = chain.ik_batch(poses, mode="approach", approach_axis=np.asarray(arm.approach_axis), self_collision=True,
                              reference=reference, attempts=20, position_tolerance=1e-3, orientation_tolerance=1e-2,
                              rng_seed=seed + 1)
    ik_seconds = time.perf_counter() - t0
    yes = cap.reachable(poses)
    out = shares(yes, truth)
    reached = truth.sum()
    out["false_negatives_of_ik_reachable"] = f"{int((~yes & truth).sum())} of {int(reached)}"
    out["ik_seconds"] = round(ik_seconds, 2)
    return out


def run_robot(name: str, args, workdir: str) -> dict:
    arm_name, table = ROBOTS[name]
    t0 = time.perf_counter()
    robot = robots.load(name)  # cold: the allowed-collision cache is empty (main() points it at a temp dir)
    t_robot = time.perf_counter() - t0
    arm = octoreach.Arm.named(robot, arm_name)
    t_arm = time.perf_counter() - t0
    cap = octoreach.arms.capability_map(robot, arm, resolution=0.1, seed=args.seed, progress=args.progress)
    cap_path = os.path.join(workdir, f"{name}.orcm")
    cap.save(cap_path, with_solutions=True)
    t_cap = time.perf_counter() - t0
    sx, sy, h, x, y = table
    surface = octoreach.Surface.rectangle(sx, sy, h, x, y)
    if h > 0.05:
        surface.add_legs()
    sm = octoreach.SurfaceMap.build(robot, cap, surface, progress=args.progress)
    sm.save(os.path.join(workdir, f"{name}.orsm"))
    t_sm = time.perf_counter() - t0
    t1 = time.perf_counter()
    robots.load(name)
    t_cached = time.perf_counter() - t1
    # MoveIt's step from scratch: no SRDF (every link pair checked), 10,000 configurations, no cache.
    bare = robots.load(name, srdf=False, allowed_collisions="srdf")
    t1 = time.perf_counter()
    sampled = bare.with_sampled_collisions(samples=10000, seed=0, cache_dir="none")
    t_acm = time.perf_counter() - t1
    out = {
        "arm": {"name": arm.name, "base": arm.base_link, "tip": arm.tip_link,
                "approach_axis": [round(v, 6) for v in arm.approach_axis], "why": arm.reason, "source": arm.source},
        "seconds_to_robot": round(t_robot, 2),
        "seconds_to_robot_cached": round(t_cached, 3),
        "seconds_to_arm": round(t_arm, 2),
        "allowed_collision_sampling_10000_seconds": round(t_acm, 2),
        "allowed_collision_sampling_pairs": {"links": len(bare.collision_links),
                                             "allowed_pairs": len(sampled.allowed_collisions)},
        "seconds_to_capability_map_0.1": round(t_cap, 2),
        "seconds_to_table_surface_map": round(t_sm, 2),
        "capability_map_0.1": {"build_seconds": round(cap.stats["seconds"], 2),
                               "reachable_cells": cap.stats["reachable_cells"]},
        "surface_map": {"build_seconds": round(sm.stats["seconds"], 2), "best_r_s": round(sm.max_reachability, 4),
                        "table": dict(zip(("size_x", "size_y", "height", "x", "y"), table))},
        "fidelity": {"0.1": fidelity(robot, arm, cap, args.poses, args.seed)},
    }
    if not args.no_fine:
        t1 = time.perf_counter()
        fine = octoreach.arms.capability_map(robot, arm, resolution=0.05, seed=args.seed, progress=args.progress)
        out["capability_map_0.05"] = {"build_seconds": round(time.perf_counter() - t1, 2),
                                      "reachable_cells": fine.stats["reachable_cells"]}
        out["fidelity"]["0.05"] = fidelity(robot, arm, fine, args.poses, args.seed)
    return out


def obstacle_cost(pr2, seed: int) -> dict:
    """What checking the arm against obstacles costs: the PR2 paper table (1.4 x 0.65 m at 0.72 m, 0.1 m,
    right arm) without obstacles (the reference: no arm-obstacle check runs), with its four legs, and in a
    room with a wall beside it and a shelf of three boards; best of three builds each."""
    from octoreach import rooms

    cap = octoreach.arms.capability_map(pr2, "right_arm", resolution=0.1, seed=seed, progress=False)
    room = rooms.Room()
    room.add_table("table", 1.4, 0.65, 0.72)
    room.add_box("wall", [3.0, 0.05, 2.0], [0.0, 0.8, 1.0])
    room.add_shelf("shelf", 0.8, 0.35, [0.4, 0.8, 1.2], x=-1.5, y=-0.5)
    bare = octoreach.Surface.rectangle(1.4, 0.65, 0.72)
    cases = {"table_without_obstacles": (bare, None),
             "table_with_legs": (room.surfaces["table"], None),
             "table_with_legs_wall_and_shelf": (room.surfaces["table"], room.obstacles(without="table"))}
    out = {}
    for name, (surface, obstacles) in cases.items():
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            sm = octoreach.SurfaceMap.build(pr2, cap, surface, obstacles=obstacles, progress=False)
            times.append(time.perf_counter() - t0)
        out[name] = {"seconds": round(min(times), 3), "best_r_s": round(sm.max_reachability, 4),
                     "arm_rejections": sm.stats["arm_rejections"]}
    ref = out["table_without_obstacles"]["seconds"]
    for name in out:
        out[name]["times_reference"] = round(out[name]["seconds"] / ref, 2)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--robots", nargs="+", default=list(ROBOTS), choices=list(ROBOTS), help="robots to run")
    ap.add_argument("--poses", type=int, default=3000, help="random poses per fidelity figure (default 3000)")
    ap.add_argument("--no-fine", action="store_true", help="skip the 0.05 m maps (about a minute each)")
    ap.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    ap.add_argument("--progress", action="store_true", help="progress bars on stderr")
    args = ap.parse_args(argv)
    out = {"benchmark": "onboarding", "octoreach": octoreach.__version__,
           "targets": {"agreement_percent_min": 97.0, "false_positive_percent_max": 2.0,
                       "false_negative_percent_max": 2.0, "at_resolution_m": 0.05}}
    out["anchor"] = {"what": "MoveIt setup assistant's self-collision step at its default density (10,000 random "
                               "configurations)", "seconds": "tens of seconds to minutes (quoted from the issue; MoveIt "
                               "needs ROS, not installable here)",
                     "ours": "robots/*/allowed_collision_sampling_10000_seconds: the same step here, same density"}
    pr2 = robots.pr2()
    out["arm_obstacle_check_cost"] = obstacle_cost(pr2, args.seed)
    out["robots"] = {}
    with tempfile.TemporaryDirectory() as workdir:
        os.environ["OCTOREACH_CACHE_DIR"] = os.path.join(workdir, "cache")  # cold allowed-collision cache
        for name in args.robots:
            out["robots"][name] = run_robot(name, args, workdir)
    met = {}
    for name, r in out["robots"].items():
        f = r["fidelity"].get("0.05")
        if f:
            met[name] = bool(f["agreement_percent"] >= 97 and f["false_positive_percent"] <= 2
                             and f["false_negative_percent"] <= 2)
    out["targets_met_at_0.05"] = met
    out["machine"] = {"cpu_count": os.cpu_count(), "platform": platform.platform(), "python": platform.python_version(),
                      "load_average": [round(x, 2) for x in os.getloadavg()],
                      "note": "2 cores shared with other jobs unless said otherwise"}
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
