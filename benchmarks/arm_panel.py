#!/usr/bin/env python3
"""Capability maps of a panel of arms against saturated IK: agreement, false positives, false negatives.

Arms: twelve arms of example-robot-data (PANEL; ``--hold-out`` adds arms the lookups were never tuned on,
``--arms robot:arm,...`` picks any: a robot robots.load knows, or the path of your own URDF, ending in .urdf, loaded
with robots.from_urdf; the arm a name or base_link/tip_link, e.g. ``--arms my_arm.urdf:base_link/tool0``). Each map is the one users build: ``arms.capability_map(robot, arm,
resolution=...)`` (the arm's approach axis and default reference posture, 200 directions, any roll, joint
solutions kept); its build CPU seconds (user + system of this process) are reported.

Poses (``--poses`` per arm, seed ``--seed``): half the tool poses of random configurations inside the joint
limits and free of self-collision (reachable by construction), half uniform in the workspace box (the box of
the tool positions of 20,000 random configurations) with rotations uniform on SO(3). Truth: the pose is
reachable when it came from a collision-free configuration or saturated IK reaches it: 5 rounds of 20 random
restarts, approach mode (any roll about the arm's approach axis), self-collision checked at the arm's
reference posture, the map's tolerances (1 mm, 0.01 rad) (octoreach.testing.reach_truth). The rounds in which
poses were first reached show the saturation; ``truth.ik_missed_known`` counts the poses IK missed although a
configuration reaches them. Truths are cached in ``benchmarks/out/panel_truth`` (beside this script, wherever it
runs from; ``--truth-cache``): they do not depend on the map.

Lookups: every CapabilityLookup of ``map.reachable`` and the certified lookup (``CertifiedLookup``: the map
where it is sure, IK where it is not), with the share of poses the certified lookup sent to IK and its mean
cost per pose (CPU microseconds, one thread), and as the reference in the same run the certified lookup without
other IK branches (``branch_seeds=0``: only the corners' own configurations). ``--diagnose`` asks IK at two
more poses per check pose, the exact position with the direction of the nearest orientation bin and the voxel
centre with that direction (the cell itself), and splits the nearest-cell lookup's disagreements into
orientation binning, voxel boundary, build misses and the truth's own misses.

``--colliding N`` also checks the certified lookup on N tool poses of random configurations in self-collision (the
check poses above take only collision-free ones), with its default and with ``collided_branch_seeds=0``: poses
near self-collision, often reachable free by another configuration than the stored ones lead to.

Prints one JSON document; ``--table PATH`` also writes the markdown table the docs include.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import platform
import resource
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import octoreach
from octoreach import arms, robots
from octoreach.testing import reach_truth

PANEL = [("pr2", "right_arm"), ("pr2", "left_arm"), ("panda", "arm"), ("ur5", "arm"), ("ur10", "arm"),
         ("xarm7", "xarm7"), ("kinova", "end_effector"), ("tiago", "arm"), ("talos_reduced", "l_arm"),
         ("z1", "arm"), ("so101", "arm"), ("baxter", "right_arm")]
# Arms held out of the panel: the first six were never looked at while the lookup was designed; the branch seeds
# (CertifiedLookupOptions.branch_seeds) were then designed on two of them (icub, g1), and the last six were never
# looked at before that design was fixed.
HOLD_OUT = [("ur3", "arm"), ("romeo", "right_arm"), ("icub", "l_arm"), ("g1_29dof_with_hand_rev_1_0", "left_arm"),
            ("tiago_pro", "left_arm"), ("centauro", "right_arm"),
            ("alex_nub_hands", "right_arm"), ("tiago_dual", "right_arm"), ("talos_full_v2", "r_arm"),
            ("hextilt_flying_arm_5", "arm"), ("anymal-kinova", "arm"), ("b1-z1", "arm")]
TARGETS = {"agreement_percent_min": 99.0, "false_positive_percent_max": 0.5, "false_negative_percent_max": 0.5,
           "certified_us_per_pose_max": 2.0}
TRUTH_ROUNDS, TRUTH_ATTEMPTS = 5, 20


def cpu_seconds() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def shares(answer: np.ndarray, truth: np.ndarray) -> dict:
    n = len(answer)
    agree = float((answer == truth).mean())
    return {
        "agreement_percent": round(100 * agree, 3),
        "agreement_standard_error_percent": round(100 * float(np.sqrt(agree * (1 - agree) / n)), 3),
        "false_positive_percent": round(100 * float((answer & ~truth).mean()), 3),
        "false_negative_percent": round(100 * float((~answer & truth).mean()), 3),
        "map_reachable_percent": round(100 * float(answer.mean()), 3),
    }


def load_arm(robot_name: str, arm_name: str):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # SRDF entries of other variants (talos) are left out, as MoveIt does
        robot = robots.from_urdf(Path(robot_name)) if robot_name.endswith(".urdf") else robots.load(robot_name)
    spec = tuple(arm_name.split("/")) if "/" in arm_name else arm_name  # base_link/tip_link: the arm by its links
    arm = octoreach.Arm.resolve(robot, spec)
    return robot, arm, robot.chain(arm.base_link, arm.tip_link), arms.default_reference(robot, spec)


def truth_of(robot, arm, chain, reference, n: int, seed: int, cache_dir: Path):
    """(poses, Truth) of an arm: from the cache when the model, the arm and the parameters match."""
    key = hashlib.sha256(json.dumps([robot.model_hash, arm.base_link, arm.tip_link, list(arm.approach_axis),
                                     list(np.round(reference, 12)), n, seed, TRUTH_ROUNDS, TRUTH_ATTEMPTS,
                                     reach_truth.POSITION_TOLERANCE, reach_truth.ORIENTATION_TOLERANCE],
                                    default=float).encode()).hexdigest()[:16]
    path = cache_dir / f"{robot.name}_{arm.tip_link}_{key}.npz"
    if path.exists():
        z = np.load(path)
        return z["poses"], reach_truth.Truth(z["reachable"], z["solutions"], z["round"], z["known"]), True
    poses, known = reach_truth.check_poses(robot, chain, reference, n, seed)
    truth = reach_truth.ik_truth(chain, poses, arm.approach_axis, reference, known, TRUTH_ROUNDS, TRUTH_ATTEMPTS,
                                 seed)
    cache_dir.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.npz")
    np.savez_compressed(tmp, poses=poses, reachable=truth.reachable, solutions=truth.solutions, round=truth.round,
                        known=truth.known)
    os.replace(tmp, path)
    return poses, truth, False


def truth_summary(truth) -> dict:
    rounds = np.bincount(truth.round[truth.round >= 0], minlength=TRUTH_ROUNDS)
    return {"reachable_percent": round(100 * float(truth.reachable.mean()), 2),
            "box_half_reachable_percent": round(100 * float(truth.reachable[~truth.known].mean()), 2),
            "first_reached_in_round": rounds.tolist(),
            "ik_missed_known": truth.ik_missed_known,
            "rounds": TRUTH_ROUNDS, "attempts_per_round": TRUTH_ATTEMPTS}


def cell_poses(cmap, poses: np.ndarray, at_centre: bool) -> np.ndarray:
    """The poses with the rotation of their nearest orientation bin, at the voxel centre when `at_centre`."""
    axis = np.asarray(cmap.approach_axis)
    d = poses[:, :3, :3] @ axis
    nearest = np.array([cmap.orientations.nearest_direction(v) for v in d])
    rot = np.array([cmap.orientations.rotation(o, axis) for o in range(len(cmap.orientations))])
    out = poses.copy()
    out[:, :3, :3] = rot[nearest]
    if at_centre:
        r = cmap.resolution
        out[:, :3, 3] = (np.floor(poses[:, :3, 3] / r) + 0.5) * r
    return out


def diagnose(cmap, chain, arm, reference, poses, truth, seed: int) -> dict:
    """Where the nearest-cell lookup's disagreements lie (shares of all poses)."""
    T = truth.reachable
    binned = reach_truth.ik_truth(chain, cell_poses(cmap, poses, False), arm.approach_axis, reference,
                                  rounds=3, seed=seed + 11).reachable
    cell = reach_truth.ik_truth(chain, cell_poses(cmap, poses, True), arm.approach_axis, reference,
                                rounds=3, seed=seed + 12).reachable
    answer = cmap.reachable(poses, lookup="nearest_cell")
    wrong = answer != T
    orientation = wrong & (binned != T)
    position = wrong & (binned == T) & (cell != binned)
    build = wrong & (binned == T) & (cell == binned) & (answer != cell)

    def pct(mask):
        return round(100 * float(mask.mean()), 3)
    return {
        "nearest_cell_errors_percent": pct(wrong),
        "orientation_binning": pct(orientation),
        "voxel_boundary": pct(position),
        "build_misses": pct(build & cell),
        "build_false_cells": pct(build & ~cell),
        "truth_misses_at_the_cell": pct(answer & ~cell),
        "cells_ik_disagrees_with_map": pct(answer != cell),
    }


def colliding_poses(robot, chain, reference, n: int, seed: int) -> np.ndarray:
    """Tool poses of up to n random configurations in self-collision (the joints off the chain at `reference`)."""
    found = []
    for k in range(10):  # an arm that seldom collides gives fewer
        Q = chain.random_configurations(20 * n, seed + 1000 + k)
        found += [q for q in Q if robot.in_self_collision(chain.to_robot_configuration(q, reference))]
        if len(found) >= n:
            break
    return chain.fk_batch(np.array(found[:n])) if found else np.zeros((0, 4, 4))


def colliding_figures(cmap, robot, reference, poses, truth) -> dict:
    """The certified lookup on tool poses of configurations in self-collision, and without the collided budget."""
    out = {"poses": len(poses), "truth_reachable_percent": round(100 * float(truth.mean()), 3)}
    for name, kw in (("certified", {}), ("collided_branch_seeds_0", {"collided_branch_seeds": 0})):
        out[name] = shares(octoreach.CertifiedLookup(cmap, robot, reference=reference, **kw).reachable(poses), truth)
    return out


def certified_figures(cmap, robot, chain, reference, poses, truth) -> dict:
    """The certified lookup's answers and cost on the check poses and on uniform random poses in the map box."""
    if not hasattr(octoreach, "CertifiedLookup"):
        return {}
    check = octoreach.CertifiedLookup(cmap, robot, reference=reference)
    c0 = cpu_seconds()
    answer = check.reachable(poses, threads=1)
    seconds = cpu_seconds() - c0
    certain = check.certain(poses)
    out = {"lookup": "certified", **shares(answer, truth.reachable),
           "ik_share_percent": round(100 * float(1 - certain.mean()), 3),
           "errors_where_certain_percent": round(100 * float(((answer != truth.reachable) & certain).mean()), 3),
           "us_per_pose_check_poses": round(1e6 * seconds / len(poses), 3)}
    lo, hi = cmap.bounds
    rng = np.random.default_rng(12345)
    n = 20000
    uniform = np.tile(np.eye(4), (n, 1, 1))
    uniform[:, :3, :3] = reach_truth.random_rotations(n, rng)
    uniform[:, :3, 3] = rng.uniform(lo, hi, size=(n, 3))
    c0 = cpu_seconds()
    check.reachable(uniform, threads=1)
    out["us_per_pose_uniform_in_map_box"] = round(1e6 * (cpu_seconds() - c0) / n, 3)
    out["ik_share_uniform_percent"] = round(100 * float(1 - check.certain(uniform).mean()), 3)
    # the reference in the same run: the corners' own configurations only (no other branches)
    seeds_only = octoreach.CertifiedLookup(cmap, robot, reference=reference, branch_seeds=0)
    c0 = cpu_seconds()
    seeds_only.reachable(uniform, threads=1)
    us = round(1e6 * (cpu_seconds() - c0) / n, 3)
    out["seeds_only"] = {**shares(seeds_only.reachable(poses, threads=1), truth.reachable),
                         "us_per_pose_uniform_in_map_box": us}
    return out


def run_arm(robot_name, arm_name, resolutions, n, seed, cache_dir, do_diagnose, progress, map_cache=None,
            loaded=None, colliding=0) -> list[dict]:
    """The rows of one arm; `loaded`: load_arm's answer when the caller has it; `colliding`: poses near
    self-collision to check too."""
    robot, arm, chain, reference = loaded or load_arm(robot_name, arm_name)
    if colliding:
        near = colliding_poses(robot, chain, reference, colliding, seed)
        near_truth = reach_truth.ik_truth(chain, near, arm.approach_axis, reference, None, TRUTH_ROUNDS,
                                          TRUTH_ATTEMPTS, seed).reachable if len(near) else np.zeros(0, bool)
    t0 = time.perf_counter()
    poses, truth, cached = truth_of(robot, arm, chain, reference, n, seed, cache_dir)
    base = {"robot": robot_name, "arm": arm_name, "chain": [arm.base_link, arm.tip_link], "dof": chain.dof,
            "approach_axis": [float(v) for v in arm.approach_axis], "poses": n,
            "truth": {**truth_summary(truth), "cached": cached, "seconds": round(time.perf_counter() - t0, 1)}}
    rows = []
    for res in resolutions:
        c0, w0 = cpu_seconds(), time.perf_counter()
        cmap = arms.capability_map(robot, arm, resolution=res, progress=progress, cache=map_cache)
        row = dict(base, resolution_m=res, build={"cpu_seconds": round(cpu_seconds() - c0, 2), "map_cache": map_cache,
                                                  "wall_seconds": round(time.perf_counter() - w0, 2),
                                                  **{k: int(v) for k, v in cmap.stats.items() if k != "seconds"}})
        row["lookups"] = {}
        for lookup in ("nearest_cell", "vote"):
            row["lookups"][lookup] = shares(cmap.reachable(poses, lookup=lookup), truth.reachable)
        cert = certified_figures(cmap, robot, chain, reference, poses, truth)
        if cert:
            row["lookups"]["certified"] = cert
        if do_diagnose:
            row["diagnosis"] = diagnose(cmap, chain, arm, reference, poses, truth, seed)
        if colliding and len(near):
            row["colliding"] = colliding_figures(cmap, robot, reference, near, near_truth)
        rows.append(row)
        print(f"{robot_name}:{arm_name} {res} m: " + ", ".join(
            f"{k} {v['agreement_percent']:.2f}%" for k, v in row["lookups"].items()), file=sys.stderr)
        del cmap
    return rows


def markdown_table(rows: list[dict]) -> str:
    """The docs' table: one line per arm and resolution, the certified lookup's figures first."""
    lines = ["| arm | DOF | resolution | certified: agreement % | FP % | FN % | to IK % | vote % | nearest cell % | "
             "build CPU s | certified µs/pose | without other branches: FN % | µs/pose |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        c, v, n = (r["lookups"].get(k, {}) for k in ("certified", "vote", "nearest_cell"))
        cert = (f"{c['agreement_percent']:.2f} | {c['false_positive_percent']:.2f} | {c['false_negative_percent']:.2f} | "
                f"{c['ik_share_percent']:.1f}" if c else " | | | ")
        cost = f"{c['us_per_pose_uniform_in_map_box']:.1f}" if c else ""
        base = c.get("seeds_only") if c else None
        cost += (f" | {base['false_negative_percent']:.2f} | {base['us_per_pose_uniform_in_map_box']:.1f}" if base
                 else " | | ")
        lines.append(f"| {r['robot']} {r['arm']} | {r['dof']} | {r['resolution_m']:g} m | {cert} | "
                     f"{v['agreement_percent']:.2f} | {n['agreement_percent']:.2f} | {r['build']['cpu_seconds']:.1f} | "
                     f"{cost} |")
    return "\n".join(lines) + "\n"


def parse_arms(text: str) -> list[tuple[str, str]]:
    out = []
    for item in text.split(","):
        robot, _, arm = item.strip().rpartition(":")
        if not robot or not arm:
            raise SystemExit(f"--arms takes robot:arm items separated by commas, got {item!r}")
        out.append((robot, arm))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--arms", type=parse_arms, default=None, help="robot:arm,... (default: the panel)")
    ap.add_argument("--hold-out", action="store_true", help="the arms held out of the panel instead")
    ap.add_argument("--resolutions", type=float, nargs="+", default=[0.05])
    ap.add_argument("--poses", type=int, default=4000, help="check poses per arm (half FK, half box)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--diagnose", action="store_true", help="split the nearest-cell errors by cause")
    ap.add_argument("--truth-cache", type=Path, default=Path(__file__).resolve().parent / "out" / "panel_truth")
    ap.add_argument("--table", default="", help="also write the markdown table to this file")
    ap.add_argument("--jsonl", default="", help="also append each arm's figures to this file as they come")
    ap.add_argument("--map-cache", default=None,
                    help="a map cache directory (octoreach.cache): maps built once serve reruns (build figures are "
                         "then those of a load)")
    ap.add_argument("--colliding", type=int, default=0, metavar="N",
                    help="also check the certified lookup on N tool poses of configurations in self-collision, with "
                         "and without its collided branch budget (collided_branch_seeds=0)")
    ap.add_argument("--progress", action="store_true")
    args = ap.parse_args(argv)
    if args.poses < 2:
        ap.error(f"--poses must be at least 2 (half from forward kinematics, half uniform), got {args.poses}")
    panel = args.arms or (HOLD_OUT if args.hold_out else PANEL)
    loaded = []
    for robot_name, arm_name in panel:  # every arm first: a wrong one stops the run before any work
        try:
            loaded.append(load_arm(robot_name, arm_name))
        except (ValueError, OSError) as e:  # a wrong robot, URDF or arm: its message, not a traceback
            ap.error(f"--arms {robot_name}:{arm_name}: {e}")
    rows = []
    for (robot_name, arm_name), arm_loaded in zip(panel, loaded):
        new = run_arm(robot_name, arm_name, args.resolutions, args.poses, args.seed, args.truth_cache, args.diagnose,
                      args.progress, args.map_cache, arm_loaded, args.colliding)
        rows += new
        if args.jsonl:
            with open(args.jsonl, "a") as f:
                for row in new:
                    f.write(json.dumps(row) + "\n")
    out = {"benchmark": "arm_panel", "octoreach": octoreach.__version__, "targets": TARGETS, "arms": rows,
           "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform(),
                       "load_average": [round(x, 2) for x in os.getloadavg()]}}
    if args.table:
        Path(args.table).parent.mkdir(parents=True, exist_ok=True)
        Path(args.table).write_text(markdown_table(rows))
        out["table"] = args.table
    json.dump(out, sys.stdout, indent=2)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
