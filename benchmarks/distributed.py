#!/usr/bin/env python3
"""Distributed builds on a Ray cluster on this machine against the same builds in one process.

1. A job of 30 surfaces x 2 robots (PR2 right arm, TIAGo arm) at 0.1 m (2 capability maps, 60 surface maps,
   16 theta bins, 100 directions): `build_many(cluster="none")` (one process, every task on every core, one
   after the other) against `build_many(cluster="local")` (Ray on this machine, one task per core, each
   single-threaded). Same cores; the cache is off; every file is compared byte for byte. Ray's start-up is
   timed apart (a cluster is started once and serves many jobs).
2. The PR2 right-arm capability map at 0.05 m (``--fine``: 0.025 m) cut into blocks of 16 voxels: the block
   build in one process (`CapabilityMap.build(block_size=16)`, every core) against
   `cluster.build_capability_split` on the local cluster (one sampling task, then one task per block);
   identical bytes; per-task seconds and the peak memory (max RSS) of each worker process. ``--agreement``
   also measures the block map's agreement with direct IK beside the plain build's (the truth and the
   poses of benchmarks/capability_map.py).
3. A model of the time on N machines of c cores from the measured single-core task times: tasks are
   list-scheduled (largest ready task first onto the first free core; a surface map becomes ready when its
   capability map is done; every block after the sampling) on N*c cores, plus the driver's own time
   (job check, merge, writing files) measured here. Checked against this machine (N = 1, c = 2).

Prints one JSON document. Figures from a shared machine are noisy: run on a quiet one to quote them.
"""
from __future__ import annotations

import argparse
import heapq
import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import octoreach
from octoreach import cluster, robots

ROBOTS = [{"name": "pr2", "arms": ["right_arm"]}, {"name": "tiago", "arms": ["arm"]}]


def tables(n: int = 30) -> list[dict]:
    """n tables of a fleet's homes: sizes 0.6-1.6 x 0.4-0.9 m, tops at 0.45-0.95 m, yawed, some with legs."""
    rng = np.random.default_rng(7)
    out = []
    for i in range(n):
        entry = {"name": f"table_{i:02d}", "rectangle": {
            "size": [round(float(rng.uniform(0.6, 1.6)), 2), round(float(rng.uniform(0.4, 0.9)), 2)],
            "height": round(float(rng.uniform(0.45, 0.95)), 2), "yaw": round(float(rng.uniform(0, np.pi)), 3)}}
        if i % 2 == 0:
            entry["legs"] = 0.05
        out.append(entry)
    return out


def files(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*.or*m"))}


def schedule(tasks: list[tuple[str, float, str | None]], slots: int) -> float:
    """Makespan of list scheduling on `slots` cores: (name, seconds, dependency) tasks, those without a
    dependency first, each group largest first, each onto the core that frees first, not before its dependency."""
    done_at: dict[str, float] = {}
    free = [0.0] * slots
    for name, secs, dep in sorted(tasks, key=lambda t: (t[2] is not None, -t[1])):
        start = max(heapq.heappop(free), done_at[dep] if dep else 0.0)
        done_at[name] = start + secs
        heapq.heappush(free, start + secs)
    return max(done_at.values()) if done_at else 0.0


def model(tasks, driver_seconds: float, machines=(1, 2, 4, 8, 16, 32), cores=(2, 16)) -> dict:
    out = {}
    for c in cores:
        out[f"{c}_cores_per_machine"] = {str(n): round(driver_seconds + schedule(tasks, n * c), 1) for n in machines}
    return out


def job_benchmark(resolution: float, surfaces: int, workdir: Path) -> dict:
    job = {"robots": ROBOTS, "resolutions": [resolution], "capability": {"directions": 100},
           "surfaces": tables(surfaces), "surface": {"theta_bins": 16}}
    t0 = time.perf_counter()
    one = cluster.build_many(job, cluster="none", out=workdir / "one", cache=False, progress=False)
    t_one = time.perf_counter() - t0
    t0 = time.perf_counter()
    ray_report = cluster.build_many(job, cluster="local", out=workdir / "ray", cache=False, progress=False)
    t_ray = time.perf_counter() - t0
    same = files(workdir / "one") == files(workdir / "ray")
    tasks = []
    caps = {}
    for name, info in ray_report.tasks.items():
        parts = name.split("/")
        cap = "/".join(parts[:3])
        tasks.append((name, info["seconds"], None if len(parts) == 3 else cap))
        caps.setdefault(cap, 0)
    task_sum = sum(t[1] for t in tasks)
    driver = max(0.0, t_ray - schedule(tasks, 2))
    return {
        "job": f"{surfaces} surfaces x {len(ROBOTS)} robots at {resolution} m: {len(one.files)} maps",
        "one_process_seconds": round(t_one, 2),
        "local_cluster_seconds": round(t_ray, 2),
        "overhead_percent": round(100 * (t_ray / t_one - 1), 1),
        "identical_bytes": same,
        "task_seconds_sum_single_core": round(task_sum, 2),
        "capability_task_seconds": {n: round(i["seconds"], 2) for n, i in ray_report.tasks.items() if n.count("/") == 2},
        "surface_task_seconds_median": round(float(np.median([i["seconds"] for n, i in ray_report.tasks.items()
                                                              if n.count("/") > 2])), 3),
        "peak_worker_mb": round(max(i["peak_mb"] for i in ray_report.tasks.values()), 1),
        "driver_seconds_outside_tasks": round(driver, 2),
        "model_seconds_on_N_machines": model(tasks, driver),
        "model_check_this_machine_1x2_cores": round(driver + schedule(tasks, 2), 1),
    }


def split_benchmark(resolution: float, block_size: int, agreement: int, workdir: Path) -> dict:
    robot = robots.pr2()
    kw = dict(resolution=resolution, directions=200, seed=0)
    t0 = time.perf_counter()
    whole = octoreach.CapabilityMap.build_for_arm(robot, "right_arm", block_size=block_size, progress=False, **kw)
    t_one = time.perf_counter() - t0
    report = cluster.BuildReport()
    t0 = time.perf_counter()
    split = cluster.build_capability_split(robot, "right_arm", cluster="local", block_size=block_size, progress=False,
                                           report=report, **kw)
    t_ray = time.perf_counter() - t0
    a, b = workdir / "whole.orcm", workdir / "split.orcm"
    whole.save(str(a), with_solutions=True)
    split.save(str(b), with_solutions=True)
    blocks = {k: v for k, v in report.tasks.items() if k.startswith("block")}
    tasks = [("sample", report.tasks["sample"]["seconds"], None)] + [(k, v["seconds"], "sample") for k, v in blocks.items()]
    driver = max(0.0, t_ray - schedule(tasks, 2))
    out = {
        "map": f"PR2 right arm, {resolution} m, 200 directions, blocks of {block_size} voxels",
        "one_process_block_build_seconds": round(t_one, 2),
        "local_cluster_split_seconds": round(t_ray, 2),
        "overhead_percent": round(100 * (t_ray / t_one - 1), 1),
        "identical_bytes": a.read_bytes() == b.read_bytes(),
        "voxels": whole.voxel_count,
        "reachable_cells": whole.stats["reachable_cells"],
        "blocks_with_seeds": len(blocks),
        "sample_task_seconds": round(report.tasks["sample"]["seconds"], 2),
        "block_task_seconds": {"max": round(max(v["seconds"] for v in blocks.values()), 2),
                               "median": round(float(np.median([v["seconds"] for v in blocks.values()])), 2),
                               "sum": round(sum(v["seconds"] for v in blocks.values()), 2)},
        "peak_worker_mb": {"sampling_task": round(report.tasks["sample"]["peak_mb"], 1),
                           "block_tasks_max": round(max(v["peak_mb"] for v in blocks.values()), 1)},
        "driver_seconds_outside_tasks": round(driver, 2),
        "model_seconds_on_N_machines": model(tasks, driver),
    }
    if agreement:
        out["agreement"] = agreement_figures(robot, whole, kw, agreement)
    return out


def agreement_figures(robot, block_map, kw, n: int) -> dict:
    """Agreement with direct IK of the block map and of the plain build (benchmarks/capability_map.py's truth)."""
    sys.path.insert(0, str(Path(__file__).parent))
    import capability_map as bench  # noqa: E402  (the same poses and truth)

    plain = octoreach.CapabilityMap.build_for_arm(robot, "right_arm", progress=False, **kw)
    chain = robot.chain(plain.base_link, plain.tip_link)
    reference = octoreach.default_reference(robot, chain)
    rng = np.random.default_rng(0)
    lo, hi = plain.bounds
    poses = bench.random_poses(lo, hi, n, rng)
    _, truth = chain.ik_batch(poses, reference=reference, rng_seed=0, **bench.IK_TRUTH)
    truth = np.asarray(truth, bool)
    return {"poses": n, "plain_build": bench.shares(np.asarray(plain.reachable(poses)), truth),
            "block_build": bench.shares(np.asarray(block_map.reachable(poses)), truth)}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--resolution", type=float, default=0.1, help="job resolution (m), default 0.1")
    ap.add_argument("--surfaces", type=int, default=30, help="surfaces of the job, default 30")
    ap.add_argument("--split-resolution", type=float, default=0.05, help="split capability map resolution (m)")
    ap.add_argument("--fine", action="store_true", help="split map at 0.025 m (several minutes per build)")
    ap.add_argument("--block-size", type=int, default=16, help="voxels per block edge, default 16")
    ap.add_argument("--agreement", type=int, default=0, help="poses for the block map's IK agreement (0: skip)")
    ap.add_argument("--skip-job", action="store_true")
    ap.add_argument("--skip-split", action="store_true")
    args = ap.parse_args()
    out = {"machine": {"cores": os.cpu_count(), "python": platform.python_version(), "octoreach": octoreach.__version__},
           "note": "Ray on this machine: a local cluster of os.cpu_count() CPUs; tasks single-threaded"}
    t0 = time.perf_counter()
    cluster.connect("local", num_cpus=os.cpu_count())
    out["ray_start_seconds"] = round(time.perf_counter() - t0, 2)
    with tempfile.TemporaryDirectory(prefix="octoreach-dist-") as d:
        if not args.skip_job:
            out["job"] = job_benchmark(args.resolution, args.surfaces, Path(d) / "job")
        if not args.skip_split:
            (Path(d) / "split").mkdir()
            res = 0.025 if args.fine else args.split_resolution
            out["split"] = split_benchmark(res, args.block_size, args.agreement, Path(d) / "split")
    out["targets"] = {"job_overhead_percent_max": 15, "split_overhead_percent_max": 15, "identical_bytes": True}
    out["met"] = {k: v for k, v in {
        "job_overhead": out.get("job", {}).get("overhead_percent", 1e9) <= 15 if "job" in out else None,
        "job_identical": out.get("job", {}).get("identical_bytes"),
        "split_overhead": out["split"]["overhead_percent"] <= 15 if "split" in out else None,
        "split_identical": out.get("split", {}).get("identical_bytes")}.items() if v is not None}
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
