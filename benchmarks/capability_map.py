#!/usr/bin/env python3
"""Capability map of the PR2 right arm: build time, file size, agreement with IK, lookup speed.

Reference: the figures Hertle and Nebel / Zacharias et al. report for their PR2 capability map
(printed as "anchors" next to ours): 24 min 54 s to build at 0.05 m, a 401 KB file, 93.9 %
agreement with IK and 4.8 % false positives, 3 h 7 min at 0.025 m, ~0.7 us per lookup.

Map: the call users make, ``arms.capability_map(pr2, "right_arm", resolution=...)``: chain torso_lift_link ->
r_gripper_tool_frame (7 joints), approach axis +x of the gripper frame (inferred), self-collision checked with
the left arm tucked (the arm's default reference posture, SRDF state "tuck_left_arm"), 200 approach directions
(any roll), joint solutions kept (what surface maps need), 0.05 m voxels by default.

Agreement: N random tool poses (default 10,000, seed 0). Positions uniform in the axis-aligned box
`map.bounds` (the box of the voxels with D > 0, i.e. of the arm's forward-kinematics reach, snapped to
voxel edges, in the torso_lift_link frame); rotations uniform on SO(3) (unit quaternions from four
normal deviates), so the approach direction R @ (1, 0, 0) is uniform on the sphere and the roll about
it uniform. Truth: chain.ik_batch(mode='approach', approach_axis=(1, 0, 0), self_collision=True,
reference=tucked posture, attempts=20, position_tolerance=1e-3, orientation_tolerance=1e-2) at the
exact pose. The map answers map.reachable(pose) with its default lookup (CapabilityMap.DEFAULT_LOOKUP,
the vote: the 8 voxel centres around the position, each asked with the direction nearest the pose's
approach axis, weighted trilinearly; yes when the reachable ones weigh at least one half). A false
positive is "map yes, IK no", a false negative "map no, IK yes"; both are given as a share of all poses
and of the poses whose voxel has D > 0. ``nearest_cell_lookup`` gives the same figures for the
nearest-cell rule (map.reachable(pose, lookup="nearest_cell"): the cell of the voxel holding the
position), and a second truth, IK at that cell itself (voxel centre, nearest direction), separates its
errors into the map's own and the discretisation's (a pose is not its cell's centre):
``error_sources_percent_of_all_poses``, with the agreement of IK at the cell taken as the answer (the
ceiling of any nearest-cell lookup).

The certified lookup (``octoreach.CertifiedLookup(map, robot)``: the map where the 8 cells around a pose agree,
IK where they do not) is measured on the same poses (``certified``), with the share of poses it sends to IK and
its mean cost per pose in CPU microseconds on one thread (20,000 uniform poses in the map's box).

Lookups: map.reachable (vote and nearest cell) on one numpy batch of 1,000,000 such poses and
map.reachability on 1,000,000 such points, median of 5 runs, wall clock per item (the batch runs on every
core).

Build cost on a shared machine: ``--reference PYTHONPATH`` builds the same map with another octoreach
(e.g. main's build) in child processes, interleaved with builds of this one (``--repeats`` each, child
processes so that neither warms the other), and reports the medians of wall and CPU seconds (user +
system of the child's build) and their ratios: CPU seconds and the ratio are what a loaded machine
measures fairly; the wall-clock target needs a quiet one. The children's maps are compared byte for
byte (``same_bytes``: sha256 of the saved file). ``--compare-only`` runs only this comparison (at
``--resolution``; e.g. ``--resolution 0.025 --compare-only --reference ... --repeats 1``).

Lookup cost on a shared machine: with ``--reference`` the saved map (with solutions) is also loaded by child
processes of each octoreach in turn (``--repeats`` each) that time the plain lookups (as above, wall clock, every
core) and the certified lookup (CPU microseconds per uniform pose, one thread) on the same poses:
``lookup_comparison`` gives each side's medians, the ratios, and whether both sides gave the same answers.

Prints one JSON document. ``--quick`` runs at 0.1 m with fewer poses; ``--also-fine`` adds the 0.025 m build (its
agreement is measured on the same poses).
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import platform
import resource
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import octoreach
from octoreach import arms, plots, robots

from child_runs import ChildFailed, run_child, this_build  # the sibling module: a build run in a child process

APPROACH = (1.0, 0.0, 0.0)
IK_TRUTH = dict(mode="approach", approach_axis=APPROACH, self_collision=True, attempts=20,
                position_tolerance=1e-3, orientation_tolerance=1e-2)

ANCHORS = {
    "source": "Hertle & Nebel (capability map of Zacharias et al.), PR2 right arm",
    "build_seconds_0.05": 24 * 60 + 54,
    "build_seconds_0.025": 3 * 3600 + 7 * 60,
    "file_bytes_0.05": 401 * 1000,
    "agreement_percent": 93.9,
    "false_positive_percent": 4.8,
    "lookup_us_per_pose": 0.7,
}
TARGETS = {  # build times on a 2-core machine
    "build_seconds_0.05": 5,
    "build_seconds_0.025": 90,
    "agreement_percent_min": 98.0,  # the plain lookup (vote)
    "false_positive_percent_max": 1.0,
    "certified_agreement_percent_min": 99.0,
    "certified_false_percent_max": 0.5,  # false positives and false negatives each
    "certified_us_per_uniform_pose_max": 2.0,
    "lookup_us_per_pose_max": 0.05,  # the plain nearest-cell lookup
    "file_bytes_0.05_max": 400 * 1000,
}


def random_poses(lo, hi, n: int, rng) -> np.ndarray:
    """(n, 4, 4) poses: positions uniform in the box [lo, hi], rotations uniform on SO(3)."""
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    T = np.zeros((n, 4, 4))
    T[:, 0, 0] = 1 - 2 * (y * y + z * z)
    T[:, 0, 1] = 2 * (x * y - z * w)
    T[:, 0, 2] = 2 * (x * z + y * w)
    T[:, 1, 0] = 2 * (x * y + z * w)
    T[:, 1, 1] = 1 - 2 * (x * x + z * z)
    T[:, 1, 2] = 2 * (y * z - x * w)
    T[:, 2, 0] = 2 * (x * z - y * w)
    T[:, 2, 1] = 2 * (y * z + x * w)
    T[:, 2, 2] = 1 - 2 * (x * x + y * y)
    T[:, :3, 3] = rng.uniform(lo, hi, size=(n, 3))
    T[:, 3, 3] = 1
    return T


def median_seconds(fn, repeats: int = 5) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def shares(map_yes: np.ndarray, ik_yes: np.ndarray) -> dict:
    n = len(map_yes)
    if n == 0:
        return {"poses": 0}
    return {
        "poses": int(n),
        "ik_reachable_percent": round(100 * ik_yes.mean(), 3),
        "map_reachable_percent": round(100 * map_yes.mean(), 3),
        "agreement_percent": round(100 * (map_yes == ik_yes).mean(), 3),
        # sampling error of the agreement estimate (binomial, one standard error)
        "agreement_standard_error_percent": round(100 * float(np.sqrt((map_yes == ik_yes).mean() *
                                                                      (map_yes != ik_yes).mean() / n)), 3),
        "false_positive_percent": round(100 * (map_yes & ~ik_yes).mean(), 3),
        "false_negative_percent": round(100 * (~map_yes & ik_yes).mean(), 3),
    }


def cell_poses(cmap, poses: np.ndarray) -> np.ndarray:
    """The cells of `poses`: voxel centres and the rotation of the nearest orientation."""
    r = cmap.resolution
    out = np.tile(np.eye(4), (len(poses), 1, 1))
    out[:, :3, 3] = (np.floor(poses[:, :3, 3] / r) + 0.5) * r
    D = cmap.orientations.directions
    approach = poses[:, :3, :3] @ np.asarray(APPROACH)
    nearest = np.argmax(approach @ D.T, axis=1)
    rot = np.array([cmap.orientations.rotation(o, APPROACH) for o in range(len(D))])
    out[:, :3, :3] = rot[nearest]
    return out


def cpu_seconds() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def build_map(robot, resolution, directions, threads, seed, progress=False):
    """The PR2 right-arm map as users build it (arms.capability_map: the arm's axis and reference, solutions kept)."""
    return arms.capability_map(robot, "right_arm", resolution=resolution, directions=directions, seed=seed,
                               threads=threads, progress=progress)


def map_paths(workdir, resolution):
    """The files build_and_measure saves the map to: without and with its joint solutions."""
    return os.path.join(workdir, f"pr2_{resolution}.map"), os.path.join(workdir, f"pr2_{resolution}_solutions.map")


def build_and_measure(robot, resolution, directions, threads, seed, workdir, progress):
    t0, c0 = time.perf_counter(), cpu_seconds()
    cmap = build_map(robot, resolution, directions, threads, seed, progress)
    wall, cpu = time.perf_counter() - t0, cpu_seconds() - c0
    plain, full = map_paths(workdir, resolution)
    cmap.save(plain)
    cmap.save(full, with_solutions=True)
    stats = dict(cmap.stats)
    return cmap, {
        "resolution_m": resolution,
        "directions": len(cmap.orientations),
        "build_seconds": round(wall, 2),
        "build_cpu_seconds": round(cpu, 2),
        "stats": stats,
        "bounds_m": [np.round(b, 4).tolist() for b in cmap.bounds],
        "file_bytes": os.path.getsize(plain),
        "file_bytes_with_solutions": os.path.getsize(full),
    }


def child_build(resolution, directions, threads, seed) -> dict:
    """One build of the PR2 right-arm map in this process (the child of compare_builds): wall and CPU seconds."""
    robot = robots.pr2()
    t0, c0 = time.perf_counter(), cpu_seconds()
    cmap = build_map(robot, resolution, directions, threads, seed)
    wall, cpu = time.perf_counter() - t0, cpu_seconds() - c0
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "map.map")
        cmap.save(path, with_solutions=True)
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
    return {"wall": wall, "cpu": cpu, "ik_calls": int(cmap.stats["ik_calls"]), "sha256": digest,
            "reachable_cells": int(cmap.stats["reachable_cells"]), "octoreach": os.path.dirname(octoreach.__file__)}


def lookup_calls(cmap, lo, hi, n: int, seed: int) -> dict:
    """The timed plain lookups (figure name -> call) on n uniform poses in [lo, hi] and their positions, warmed up."""
    big = random_poses(lo, hi, n, np.random.default_rng(seed + 3))
    points = np.ascontiguousarray(big[:, :3, 3])
    cmap.reachable(big[:1000])
    return {"reachable_us_per_pose": lambda: cmap.reachable(big),
            "reachable_nearest_cell_us_per_pose": lambda: cmap.reachable(big, lookup="nearest_cell"),
            "reachability_us_per_point": lambda: cmap.reachability(points)}


def certified_poses(lo, hi, seed: int) -> np.ndarray:
    """The 20,000 uniform poses in [lo, hi] the certified lookup's cost is measured on."""
    return random_poses(lo, hi, 20000, np.random.default_rng(seed + 4))


def certified_cpu_us(check, uniform):
    """CPU microseconds per pose of check.reachable(uniform) on one thread, and its answers."""
    c0 = cpu_seconds()
    yes = check.reachable(uniform, threads=1)
    return 1e6 * (cpu_seconds() - c0) / len(uniform), yes


def child_lookups(map_path, lookups, seed) -> dict:
    """The lookups of the map at `map_path` in this process (the child of compare_lookups): microseconds per item."""
    cmap = octoreach.CapabilityMap.load(map_path)
    lo, hi = cmap.bounds
    answers = hashlib.sha256()
    out = {}
    for name, fn in lookup_calls(cmap, lo, hi, lookups, seed).items():
        out[name] = 1e6 * median_seconds(fn) / lookups
        answers.update(np.ascontiguousarray(fn()).tobytes())
    check = octoreach.CertifiedLookup(cmap, robots.pr2())
    uniform = certified_poses(lo, hi, seed)
    runs = [certified_cpu_us(check, uniform) for _ in range(3)]
    out["certified_cpu_us_per_uniform_pose"] = statistics.median(us for us, _ in runs)
    answers.update(runs[-1][1].tobytes())
    out["answers_sha256"] = answers.hexdigest()
    return out


def compare_children(reference_path, child_args, repeats) -> dict:
    """Runs this script with `child_args` under this octoreach and the one on `reference_path`, interleaved.
    Raises ChildFailed with the child's error when one fails (e.g. a reference build too old for the call)."""
    runs = {"reference": [], "this": []}
    for _ in range(repeats):
        runs["reference"].append(run_child(__file__, child_args, reference_path))
        runs["this"].append(run_child(__file__, child_args, this_build()))
    return runs


def compare_lookups(reference_path, map_path, lookups, seed, repeats) -> dict:
    """The lookups of one saved map with this octoreach and with the one on `reference_path`, interleaved."""
    runs = compare_children(reference_path, ["--child-lookups", map_path, "--lookups", str(lookups),
                                             "--seed", str(seed)], repeats)
    figures = [k for k in runs["this"][0] if k != "answers_sha256"]
    med = {k: {f: statistics.median(r[f] for r in v) for f in figures} for k, v in runs.items()}
    return {
        "reference_pythonpath": reference_path,
        "repeats": repeats,
        "interleaved": True,
        "runs": {k: [{f: round(r[f], 4) for f in figures} for r in v] for k, v in runs.items()},
        "median": {k: {f: round(x, 4) for f, x in m.items()} for k, m in med.items()},
        "speedup": {f: round(med["reference"][f] / med["this"][f], 3) for f in figures},
        "same_answers": len({r["answers_sha256"] for v in runs.values() for r in v}) == 1,
        "load_average_after": [round(x, 2) for x in os.getloadavg()],
    }


def compare_builds(reference_path, resolution, directions, threads, seed, repeats) -> dict:
    """Builds with this octoreach and with the one on `reference_path`, interleaved, in child processes."""
    runs = compare_children(reference_path, ["--child-build", "--resolution", str(resolution), "--directions",
                                             str(directions), "--threads", str(threads), "--seed", str(seed)], repeats)
    med = {k: {m: round(statistics.median(r[m] for r in v), 2) for m in ("wall", "cpu")} for k, v in runs.items()}
    return {
        "reference_pythonpath": reference_path,
        "repeats": repeats,
        "interleaved": True,
        "runs": {k: [{m: round(r[m], 2) if isinstance(r[m], float) else r[m] for m in r} for r in v]
                 for k, v in runs.items()},
        "median_seconds": med,
        "same_bytes": len({r["sha256"] for v in runs.values() for r in v}) == 1,
        "speedup_cpu": round(med["reference"]["cpu"] / med["this"]["cpu"], 3),
        "speedup_wall": round(med["reference"]["wall"] / med["this"]["wall"], 3),
        "load_average_after": [round(x, 2) for x in os.getloadavg()],
    }


def agreement(cmap, poses, truth, cell_truth):
    D = cmap.reachability(poses[:, :3, 3])
    answer = cmap.reachable(poses)  # the map's own answer: its default lookup
    inside = D > 0
    out = {
        "lookup": cmap.DEFAULT_LOOKUP.name,
        "all_poses": shares(answer, truth),
        "poses_in_voxels_with_D_gt_0": shares(answer[inside], truth[inside]),
    }
    yes = cmap.reachable(poses, lookup="nearest_cell")
    nearest = out["nearest_cell_lookup"] = {"all_poses": shares(yes, truth)}
    if cell_truth is not None:
        nearest["against_ik_at_the_cell"] = shares(yes, cell_truth)
        # Where the disagreements come from: the map's own errors (its answer differs from IK at the
        # cell) or the discretisation (IK at the cell differs from IK at the exact pose).
        nearest["error_sources_percent_of_all_poses"] = {
            "false_positive_map_error": round(100 * float((yes & ~truth & ~cell_truth).mean()), 3),
            "false_positive_discretisation": round(100 * float((yes & ~truth & cell_truth).mean()), 3),
            "false_negative_map_error": round(100 * float((~yes & truth & cell_truth).mean()), 3),
            "false_negative_discretisation": round(100 * float((~yes & truth & ~cell_truth).mean()), 3),
            # the best any nearest-cell lookup can do: IK at the cell taken as the answer for the pose
            "nearest_cell_ceiling_agreement": round(100 * float((cell_truth == truth).mean()), 3),
        }
    return out


def certified(cmap, robot, poses, truth, lo, hi, seed) -> dict:
    """The certified lookup on the agreement poses, and its cost on uniform poses in the map's box (one thread)."""
    check = octoreach.CertifiedLookup(cmap, robot)
    out = {"all_poses": shares(check.reachable(poses), truth),
           "ik_share_percent": round(100 * float(1 - check.certain(poses).mean()), 3)}
    uniform = certified_poses(lo, hi, seed)
    out["cpu_us_per_uniform_pose"] = round(certified_cpu_us(check, uniform)[0], 3)
    out["ik_share_uniform_percent"] = round(100 * float(1 - check.certain(uniform).mean()), 3)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--resolution", type=float, default=0.05, help="voxel edge (m), default 0.05")
    ap.add_argument("--directions", type=int, default=200, help="approach directions, default 200")
    ap.add_argument("--also-fine", action="store_true", help="also build at 0.025 m")
    ap.add_argument("--quick", action="store_true", help="0.1 m, 2000 poses, 100,000 lookups: a smoke run")
    ap.add_argument("--poses", type=int, default=10000, help="random poses for the IK agreement")
    ap.add_argument("--lookups", type=int, default=1_000_000, help="batch size of the lookup timing")
    ap.add_argument("--threads", type=int, default=0, help="build threads (0: every core)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--plot", default="benchmarks/out/pr2_capability_slices.png", help="slice plot PNG ('' for none)")
    ap.add_argument("--progress", action="store_true", help="progress bars on stderr")
    ap.add_argument("--reference", default=None, metavar="PYTHONPATH",
                    help="also build with the octoreach found on this PYTHONPATH (e.g. main's build) and time the "
                         "lookups of the saved map with it, interleaved")
    ap.add_argument("--repeats", type=int, default=3,
                    help="builds and lookup runs per side with --reference (medians reported)")
    ap.add_argument("--compare-only", action="store_true",
                    help="only the interleaved build comparison with --reference (no agreement, lookups, plot)")
    ap.add_argument("--child-build", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--child-lookups", metavar="MAP", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child_build:
        json.dump(child_build(args.resolution, args.directions, args.threads, args.seed), sys.stdout)
        return 0
    if args.child_lookups:
        json.dump(child_lookups(args.child_lookups, args.lookups, args.seed), sys.stdout)
        return 0
    if args.quick:
        args.resolution, args.poses, args.lookups = 0.1, 2000, 100_000
    if args.compare_only:
        if not args.reference:
            ap.error("--compare-only needs --reference")
        out = {"benchmark": "capability_map", "resolution_m": args.resolution, "directions": args.directions,
               "octoreach": octoreach.__version__,
               "build_comparison": compare_builds(args.reference, args.resolution, args.directions, args.threads,
                                                  args.seed, args.repeats)}
        if abs(args.resolution - 0.025) < 1e-9:
            out["targets_met"] = {"build_0.025": out["build_comparison"]["median_seconds"]["this"]["wall"]
                                  <= TARGETS["build_seconds_0.025"]}
        json.dump(out, sys.stdout, indent=2)
        sys.stdout.write("\n")
        return 0

    robot = robots.pr2()
    chain = robot.chain("torso_lift_link", "r_gripper_tool_frame")
    tucked = robot.configuration(robot.named_states["tuck_left_arm"])
    rng = np.random.default_rng(args.seed)
    out = {
        "benchmark": "capability_map",
        "robot": robot.name,
        "chain": [chain.base_link, chain.tip_link],
        "approach_axis": list(APPROACH),
        "reference_posture": "tuck_left_arm (SRDF group state), other joints at robot.home()",
        "octoreach": octoreach.__version__,
    }
    with tempfile.TemporaryDirectory() as workdir:
        cmap, main_run = build_and_measure(robot, args.resolution, args.directions, args.threads, args.seed,
                                           workdir, args.progress)
        out["map"] = main_run

        # Agreement with IK on random poses in the map's box.
        lo, hi = cmap.bounds
        poses = random_poses(lo, hi, args.poses, rng)
        t0 = time.perf_counter()
        _, truth = chain.ik_batch(poses, reference=tucked, rng_seed=args.seed + 1, **IK_TRUTH)
        ik_seconds = time.perf_counter() - t0
        _, cell_truth = chain.ik_batch(cell_poses(cmap, poses), reference=tucked, rng_seed=args.seed + 2, **IK_TRUTH)
        out["agreement"] = {
            "sampling": "positions uniform in map.bounds (box of voxels with D > 0, torso_lift_link frame); "
                        "rotations uniform on SO(3) (approach direction uniform on the sphere, uniform roll)",
            "truth": "chain.ik_batch(mode='approach', approach_axis=(1,0,0), self_collision=True, reference=tucked, "
                     "attempts=20, position_tolerance=1e-3, orientation_tolerance=1e-2) at the exact pose",
            "ik_seconds": round(ik_seconds, 2),
            **agreement(cmap, poses, truth, cell_truth),
            "certified": certified(cmap, robot, poses, truth, lo, hi, args.seed),
        }

        # Lookup speed.
        calls = lookup_calls(cmap, lo, hi, args.lookups, args.seed)
        out["lookups"] = {"batch": args.lookups, "repeats": 5, "threads": os.cpu_count(),
                          **{name: round(1e6 * median_seconds(fn) / args.lookups, 4) for name, fn in calls.items()}}
        del calls
        if args.reference:
            try:
                out["lookup_comparison"] = compare_lookups(args.reference, map_paths(workdir, args.resolution)[1],
                                                           args.lookups, args.seed, args.repeats)
            except ChildFailed as e:  # the run's other figures are kept
                out["lookup_comparison"] = {"error": str(e)}

        if args.also_fine:
            fine_map, fine = build_and_measure(robot, 0.025, args.directions, args.threads, args.seed, workdir,
                                               args.progress)
            fine["agreement"] = agreement(fine_map, poses, truth, None)
            out["fine_map"] = fine
            del fine_map

    if args.reference:
        try:
            out["build_comparison"] = compare_builds(args.reference, args.resolution, args.directions, args.threads,
                                                     args.seed, args.repeats)
        except ChildFailed as e:
            out["build_comparison"] = {"error": str(e)}

    if args.plot:
        Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        heights = plots.default_heights(cmap, 4)
        out["plot"] = {"path": plots.capability_slices(cmap, heights, args.plot), "heights_m": heights}

    res = main_run["resolution_m"]
    agree = out["agreement"]["all_poses"]
    out["anchors"] = ANCHORS
    out["targets"] = TARGETS
    cert = out["agreement"]["certified"]
    met = {
        "agreement": agree["agreement_percent"] >= TARGETS["agreement_percent_min"],
        "false_positives": agree["false_positive_percent"] <= TARGETS["false_positive_percent_max"],
        "certified_agreement": cert["all_poses"]["agreement_percent"] >= TARGETS["certified_agreement_percent_min"],
        "certified_false": max(cert["all_poses"]["false_positive_percent"],
                               cert["all_poses"]["false_negative_percent"]) <= TARGETS["certified_false_percent_max"],
        "certified_cost": cert["cpu_us_per_uniform_pose"] <= TARGETS["certified_us_per_uniform_pose_max"],
        "lookup": out["lookups"]["reachable_nearest_cell_us_per_pose"] <= TARGETS["lookup_us_per_pose_max"],
    }
    if abs(res - 0.05) < 1e-9:
        met["build_0.05"] = main_run["build_seconds"] <= TARGETS["build_seconds_0.05"]
        met["file_0.05"] = main_run["file_bytes"] <= TARGETS["file_bytes_0.05_max"]
    if "fine_map" in out:
        met["build_0.025"] = out["fine_map"]["build_seconds"] <= TARGETS["build_seconds_0.025"]
    out["targets_met"] = {k: bool(v) for k, v in met.items()}
    out["machine"] = {"cpu_count": os.cpu_count(), "platform": platform.platform(),
                      "python": platform.python_version(), "numpy": np.__version__,
                      "load_average": [round(x, 2) for x in os.getloadavg()]}
    json.dump(out, sys.stdout, indent=2)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
