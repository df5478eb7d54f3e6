#!/usr/bin/env python3
"""IK and FK speed and success of octoreach against plain KDL, measured in the same process.

Reference: orocos KDL (Debian's liborocos-kdl, 1.5) through the private bindings
``octoreach_bench.kdl_ik_batch`` (KDL::ChainIkSolverPos_NR_JL with ChainIkSolverVel_pinv and
ChainFkSolverPos_recursive, or KDL::ChainIkSolverPos_LMA) and ``kdl_fk_batch``
(ChainFkSolverPos_recursive), run on ``bench::to_kdl(chain)`` of the very chain octoreach solves, with the
same random restarts (same count, drawn inside the same limits) and the same success test
(position and orientation error by octoreach's Chain.fk, joints inside the limits).

Targets are tip poses (4x4, base link frame) of random joint configurations drawn inside the limits
with a fixed seed, so every target is reachable. Chains: the PR2 right arm from base_footprint (torso
included, 8 joints) and from torso_lift_link (7 joints), and the project's 6-joint test arm.

Prints one JSON document. Timings are medians over repeats (the machines are shared and noisy);
compare the ratios, not the absolute numbers. ``--quick`` runs a tiny smoke version.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time

import numpy as np

import octoreach
import octoreach_bench as _bench
from octoreach import robots

CHAINS = [
    ("pr2_right_arm_from_base_footprint", "pr2", "base_footprint", "r_wrist_roll_link"),
    ("pr2_right_arm_from_torso", "pr2", "torso_lift_link", "r_wrist_roll_link"),
    ("test_arm", "test_arm", "base_link", "tool0"),
]


def load_robot(name: str):
    return robots.pr2() if name == "pr2" else robots.test_arm()


def timed(fn, repeats: int):
    """(result of the last run, list of wall-clock seconds of each run)."""
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, times


def per_target_us(fn, targets: np.ndarray, repeats: int) -> np.ndarray:
    """Seconds -> microseconds of one call per target (median over repeats), minus the call overhead."""
    empty = np.zeros((0, 4, 4))
    _, overhead = timed(lambda: fn(empty), max(5, repeats))
    base = statistics.median(overhead)
    per = np.empty((repeats, len(targets)))
    for r in range(repeats):
        for i in range(len(targets)):
            t0 = time.perf_counter()
            fn(targets[i : i + 1])
            per[r, i] = time.perf_counter() - t0
    return np.maximum(np.median(per, axis=0) - base, 0.0) * 1e6, base * 1e6


def solve_stats(batch_fn, targets, repeats, per_target=True):
    batch_fn(targets[:4])  # warm-up: first-touch page faults and lazy symbol binding stay out of the timings
    (Q, ok), times = timed(lambda: batch_fn(targets), repeats)
    n = len(targets)
    out = {
        "success_rate": round(float(np.mean(ok)), 4) if n else None,
        "mean_us_per_solve": round(statistics.median(times) / max(n, 1) * 1e6, 2),
    }
    if per_target and n:
        us, overhead = per_target_us(batch_fn, targets, repeats)
        out["median_us_per_solve"] = round(float(np.median(us)), 2)
        out["median_us_per_solved_target"] = round(float(np.median(us[ok])), 2) if ok.any() else None
        out["call_overhead_us_subtracted"] = round(overhead, 2)
    return out, Q, ok


def check_solutions(chain, Q, ok, targets, pos_tol=1e-4, rot_tol=1e-3):
    """Counts solutions that violate the tolerances or the limits (must be 0 for every solver)."""
    bad = 0
    for q, good, T in zip(Q, ok, targets):
        if not good:
            continue
        F = chain.fk(q)
        dp = np.linalg.norm(F[:3, 3] - T[:3, 3])
        R = T[:3, :3] @ F[:3, :3].T
        angle = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))
        if dp >= pos_tol or angle >= rot_tol or not chain.within_limits(q):
            bad += 1
    return bad


def ratio(a, b):
    return round(a / b, 2) if a and b else None


def bench_chain(label, robot_name, base, tip, n, repeats, seed, attempts, quick):
    robot = load_robot(robot_name)
    chain = robot.chain(base, tip)
    Q0 = chain.random_configurations(n, seed)
    targets = chain.fk_batch(Q0)
    res = {"chain": f"{base} -> {tip}", "dof": chain.dof, "targets": n}

    solvers = {
        "octoreach_1_thread": lambda Ts: chain.ik_batch(Ts, attempts=attempts, rng_seed=seed, threads=1),
        "octoreach_all_cores": lambda Ts: chain.ik_batch(Ts, attempts=attempts, rng_seed=seed, threads=0),
        "kdl_nr_jl": lambda Ts: _bench.kdl_ik_batch(chain, Ts, "nr_jl", attempts=attempts, rng_seed=seed),
        "kdl_lma": lambda Ts: _bench.kdl_ik_batch(chain, Ts, "lma", attempts=attempts, rng_seed=seed),
    }
    for name, fn in solvers.items():
        # One call per target only makes sense single-threaded.
        stats, Q, ok = solve_stats(fn, targets, repeats, per_target=(name != "octoreach_all_cores"))
        stats["solutions_outside_tolerance_or_limits"] = check_solutions(chain, Q, ok, targets)
        res[name] = stats

    ours = res["octoreach_1_thread"]
    res["speedup"] = {
        "mean_kdl_nr_jl_over_octoreach_1_thread": ratio(res["kdl_nr_jl"]["mean_us_per_solve"], ours["mean_us_per_solve"]),
        "mean_kdl_lma_over_octoreach_1_thread": ratio(res["kdl_lma"]["mean_us_per_solve"], ours["mean_us_per_solve"]),
        "median_kdl_nr_jl_over_octoreach_1_thread": ratio(res["kdl_nr_jl"].get("median_us_per_solve"),
                                                          ours.get("median_us_per_solve")),
        "median_kdl_lma_over_octoreach_1_thread": ratio(res["kdl_lma"].get("median_us_per_solve"),
                                                        ours.get("median_us_per_solve")),
        "mean_octoreach_1_thread_over_all_cores": ratio(ours["mean_us_per_solve"],
                                                        res["octoreach_all_cores"]["mean_us_per_solve"]),
    }

    # Self-collision checking on (joints outside the chain at robot.home()). A target whose own
    # configuration collides may still have a collision-free IK solution, or none.
    free = np.array([not robot.in_self_collision(chain.to_robot_configuration(q)) for q in Q0])
    sc = {}
    for name, threads in (("octoreach_1_thread", 1), ("octoreach_all_cores", 0)):
        (Q, ok), times = timed(
            lambda: chain.ik_batch(targets, attempts=attempts, rng_seed=seed, self_collision=True, threads=threads),
            repeats)
        sc[name] = {"success_rate": round(float(np.mean(ok)), 4),
                    "mean_us_per_solve": round(statistics.median(times) / n * 1e6, 2)}
    sc["target_configurations_collision_free"] = round(float(np.mean(free)), 4)
    sc["success_rate_on_collision_free_targets"] = round(float(np.mean(ok[free])), 4) if free.any() else None
    sc["solutions_in_self_collision"] = int(sum(
        robot.in_self_collision(chain.to_robot_configuration(q)) for q, good in zip(Q, ok) if good))
    res["octoreach_self_collision"] = sc

    # Relaxed modes. Approach: the target is rolled about its z axis by a random angle, which a full
    # solution cannot follow but an approach solution (tip z axis on the target's z axis) can.
    rng = np.random.default_rng(seed + 1)
    rolled = targets.copy()
    for i, a in enumerate(rng.uniform(-np.pi, np.pi, n)):
        c, s = np.cos(a), np.sin(a)
        rolled[i] = targets[i] @ np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    modes = {}
    for mode, Ts in (("position", targets), ("approach", rolled)):
        (Q, ok), times = timed(
            lambda: chain.ik_batch(Ts, mode=mode, attempts=attempts, rng_seed=seed, threads=1), repeats)
        modes[mode] = {"success_rate": round(float(np.mean(ok)), 4),
                       "mean_us_per_solve_1_thread": round(statistics.median(times) / n * 1e6, 2)}
    res["octoreach_relaxed_modes"] = modes

    # FK: one batch call each, single-threaded, same joint rows.
    nfk = 1000 if quick else 20000
    Qfk = chain.random_configurations(nfk, seed + 2)
    Tours, t_ours = timed(lambda: chain.fk_batch(Qfk), max(repeats, 5))
    Tkdl, t_kdl = timed(lambda: _bench.kdl_fk_batch(chain, Qfk), max(repeats, 5))
    fk_ours = statistics.median(t_ours) / nfk * 1e6
    fk_kdl = statistics.median(t_kdl) / nfk * 1e6
    res["fk"] = {
        "poses": nfk,
        "octoreach_us_per_pose": round(fk_ours, 3),
        "kdl_us_per_pose": round(fk_kdl, 3),
        "speedup_kdl_over_octoreach": ratio(fk_kdl, fk_ours),
        "max_abs_difference": float(np.max(np.abs(Tours - Tkdl))),
    }
    return res


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="tiny run (a few seconds): 10 targets, 1 repeat")
    p.add_argument("--targets", type=int, default=None, help="targets per chain (default 400, quick 10)")
    p.add_argument("--repeats", type=int, default=None, help="timing repeats (default 3, quick 1)")
    p.add_argument("--attempts", type=int, default=20, help="starts per target, every solver (default 20)")
    p.add_argument("--seed", type=int, default=1, help="seed of targets and restarts")
    args = p.parse_args(argv)
    n = args.targets or (10 if args.quick else 400)
    repeats = args.repeats or (1 if args.quick else 3)

    t0 = time.perf_counter()
    out = {
        "benchmark": "ik",
        "reference": "plain orocos KDL in the same process: ChainIkSolverPos_NR_JL (+ChainIkSolverVel_pinv, "
                     "ChainFkSolverPos_recursive, default 100 iterations) and ChainIkSolverPos_LMA (default 500 "
                     "iterations, weights 1,1,1,0.25,0.25,0.25), eps 1e-5, on bench::to_kdl(chain); FK reference "
                     "ChainFkSolverPos_recursive",
        "success_test": "tip position error < 1e-4 m and rotation error < 1e-3 rad by octoreach Chain.fk, joints "
                        "inside the limits, for every solver; random restarts drawn inside the same limits",
        "timing": "time.perf_counter; mean_us_per_solve = batch time / targets (median over repeats); "
                  "median_us_per_solve = median over targets of one call per target (median over repeats, "
                  "call overhead of an empty call subtracted)",
        "settings": {"targets_per_chain": n, "repeats": repeats, "attempts": args.attempts, "seed": args.seed,
                     "octoreach_max_iterations": 100, "quick": args.quick},
        "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform(),
                    "python": platform.python_version(), "numpy": np.__version__,
                    "octoreach": octoreach.__version__},
        "chains": {},
    }
    for label, robot_name, base, tip in CHAINS:
        out["chains"][label] = bench_chain(label, robot_name, base, tip, n, repeats, args.seed, args.attempts,
                                           args.quick)
    out["runtime_s"] = round(time.perf_counter() - t0, 1)
    json.dump(out, sys.stdout, indent=2)
    print()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
