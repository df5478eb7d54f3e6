"""Surface-map benchmark: the paper's setting (PR2, both arms, 1.4 x 0.65 m table, 0.05 m, 2 pi / 16).

Prints JSON. References: the paper (2.5 days at 0.05 m, 2 h at 0.1 m) and the original authors' build
logs (GKIFreiburg inverse_capability_map: 521,540 s per arm at 0.05 m, 18,511 s at 0.1 m, a 3.19 MB
combined map file). Capability maps are built first and timed apart (benchmarks/capability_map.py covers
them in depth); the surface-map figure includes the point maps and the surface maps of both arms and
their combination, as the issue asks.

    .venv/bin/python benchmarks/surface_map.py               # 0.05 m and 0.1 m
    .venv/bin/python benchmarks/surface_map.py --quick       # 0.1 m only

Build cost on a shared machine: ``--reference PYTHONPATH`` builds the capability maps once (this octoreach,
saved with solutions), then the point maps, surface maps and combination of both arms in child processes,
alternately with the octoreach found on PYTHONPATH (e.g. main's build) and with this one (``--repeats``
each), and reports CPU seconds (user + sys) and wall seconds of each child, their medians, the ratio, and
whether both builds wrote the same bytes (SHA-256 of every map file):

    .venv/bin/python benchmarks/surface_map.py --reference /path/to/main/py --repeats 3
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

import numpy as np

import octoreach
from octoreach import arms

from child_runs import run_child, this_build  # the sibling module: a build run in a child process

TABLE = dict(size_x=1.4, size_y=0.65, height=0.72, x=0.0, y=0.0)
ANCHORS = {
    "paper_build": {"0.05": "2.5 days", "0.1": "2 hours"},
    "authors_build_logs_s_per_arm": {"0.05": 521540, "0.1": 18511},
    "authors_combined_file_bytes": 3.19e6,
    "paper_candidate_poses_0.05": 20e6,
}
TARGETS = {"both_arms_s": {"0.05": 60, "0.1": 10}, "file_bytes": 1e6, "lookup_us": 0.2, "sample_ms_median": 1.0}


def timed(fn):
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def run(res: float, directions: int, samples: int) -> dict:
    robot = octoreach.robots.pr2()
    table = octoreach.Surface.rectangle(TABLE["size_x"], TABLE["size_y"], TABLE["height"], TABLE["x"], TABLE["y"])
    table.add_legs()
    out = {"resolution_m": res, "theta_bins": 16, "directions": directions, "table": TABLE,
           "surface_points": int(len(table.points(res)))}
    caps, refs = {}, {}
    for arm in ("right_arm", "left_arm"):
        refs[arm] = arms.default_reference(robot, arm)
        caps[arm], t = timed(lambda: arms.capability_map(robot, arm, resolution=res, directions=directions,
                                                         progress=False))
        out[f"capability_map_{arm}_s"] = round(t, 2)
    maps, t_total = {}, 0.0
    for arm in ("right_arm", "left_arm"):
        pm, t_pm = timed(lambda: octoreach.InversePointMap.build(robot, caps[arm], reference_frame="base_footprint",
                                                                 reference=refs[arm], progress=False))
        sm, t_sm = timed(lambda: octoreach.SurfaceMap.build(robot, caps[arm], table, resolution=res, z_range=(0, 0),
                                                            reference=refs[arm], progress=False))
        maps[arm] = sm
        t_total += t_pm + t_sm
        with tempfile.TemporaryDirectory() as d:
            pm.save(os.path.join(d, "point.orpm"))
            pm_bytes = os.path.getsize(os.path.join(d, "point.orpm"))
        out[arm] = {"point_map_s": round(t_pm, 3), "point_map_poses": int(pm.pose_count),
                    "point_map_voxels": int(pm.voxel_count), "point_map_file_bytes": pm_bytes,
                    "surface_map_s": round(t_sm, 2), **sm.stats}
    combined, t_c = timed(lambda: octoreach.SurfaceMap.combine([maps["right_arm"], maps["left_arm"]], "max"))
    both, _ = timed(lambda: octoreach.SurfaceMap.combine([maps["right_arm"], maps["left_arm"]], "min"))
    t_total += t_c
    out["both_arms_point_and_surface_maps_s"] = round(t_total, 2)
    out["candidate_poses_both_arms"] = int(sum(maps[a].stats["candidate_poses"] for a in maps))
    out["valid_poses_both_arms"] = int(sum(maps[a].stats["valid_poses"] for a in maps))
    out["combined_max_reachability"] = round(combined.max_reachability, 3)
    out["both_hands_max_reachability"] = round(both.max_reachability, 3)
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table.orsm")
        combined.save(path)
        out["combined_file_bytes"] = os.path.getsize(path)

    # Lookups: a million random poses in the map's bounds.
    lo, hi = combined.bounds
    rng = np.random.default_rng(0)
    n = 1_000_000
    poses = np.column_stack([rng.uniform(lo[0], hi[0], n), rng.uniform(lo[1], hi[1], n), np.zeros(n),
                             rng.uniform(-np.pi, np.pi, n)])
    times = [timed(lambda: combined.reachability(poses))[1] for _ in range(5)]
    out["lookup_us_per_pose"] = round(statistics.median(times) / n * 1e6, 4)

    # Sampling with all three checks: R_S, a navigation cost map of the room, FCL collision of the
    # whole robot with the table (top and legs) and the room's walls.
    cells = int(8.0 / 0.05)
    grid = np.zeros((cells, cells), np.float32)
    xs = -4.0 + (np.arange(cells) + 0.5) * 0.05
    X, Y = np.meshgrid(xs, xs)
    grid[(np.abs(X) < TABLE["size_x"] / 2 + 0.3) & (np.abs(Y) < TABLE["size_y"] / 2 + 0.3)] = 0.8  # inflated table
    grid[(np.abs(X) > 3.5) | (np.abs(Y) > 3.5)] = 1.0  # walls
    cost = octoreach.CostMap(grid, origin=np.array([-4.0, -4.0]), resolution=0.05)
    world = table.obstacles()
    sampler = octoreach.PoseSampler(combined, candidates=40, seed=1, is_free=cost,
                                    in_collision=(robot, world, refs["right_arm"]))
    durations = []
    for _ in range(samples):
        _, t = timed(sampler.sample)
        durations.append(t)
    out["sample_ms_median"] = round(statistics.median(durations) * 1e3, 3)
    out["sample_ms_p90"] = round(float(np.percentile(durations, 90)) * 1e3, 3)
    out["samples"] = samples
    key = f"{res:g}"
    out["ratios"] = {
        "authors_per_arm_s_over_ours_per_arm":
            round(ANCHORS["authors_build_logs_s_per_arm"].get(key, float("nan")) / (t_total / 2), 1)
            if key in ANCHORS["authors_build_logs_s_per_arm"] else None,
        "authors_file_over_ours": round(ANCHORS["authors_combined_file_bytes"] / out["combined_file_bytes"], 2),
        "candidate_poses_over_paper_20M": round(out["candidate_poses_both_arms"] / ANCHORS["paper_candidate_poses_0.05"], 3),
    }
    out["targets_met"] = {
        "both_arms_time": t_total <= TARGETS["both_arms_s"].get(key, float("inf")),
        "file_size": out["combined_file_bytes"] <= TARGETS["file_bytes"],
        "lookup": out["lookup_us_per_pose"] <= TARGETS["lookup_us"],
        "sample": out["sample_ms_median"] <= TARGETS["sample_ms_median"],
    }
    return out


def cpu_seconds() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def child_build(res: float, caps_dir: str, out_dir: str) -> dict:
    """Point maps, surface maps and their combination for both arms from saved capability maps (the child of
    compare_builds): wall and CPU seconds, and the SHA-256 of every map file written."""
    robot = octoreach.robots.pr2()
    table = octoreach.Surface.rectangle(TABLE["size_x"], TABLE["size_y"], TABLE["height"], TABLE["x"], TABLE["y"])
    table.add_legs()
    caps = {arm: octoreach.CapabilityMap.load(os.path.join(caps_dir, f"{arm}.map")) for arm in ("right_arm", "left_arm")}
    refs = {arm: arms.default_reference(robot, arm) for arm in caps}
    t0, c0 = time.perf_counter(), cpu_seconds()
    points, maps = {}, {}
    for arm in caps:
        points[arm] = octoreach.InversePointMap.build(robot, caps[arm], reference_frame="base_footprint",
                                                      reference=refs[arm], progress=False)
        maps[arm] = octoreach.SurfaceMap.build(robot, caps[arm], table, resolution=res, z_range=(0, 0),
                                               reference=refs[arm], progress=False)
    combined = octoreach.SurfaceMap.combine([maps["right_arm"], maps["left_arm"]], "max")
    wall, cpu = time.perf_counter() - t0, cpu_seconds() - c0
    digests = {}
    for name, m in [*((f"{a}.orpm", points[a]) for a in points), *((f"{a}.orsm", maps[a]) for a in maps),
                    ("combined.orsm", combined)]:
        path = os.path.join(out_dir, name)
        m.save(path)
        with open(path, "rb") as f:
            digests[name] = hashlib.sha256(f.read()).hexdigest()
    return {"wall": wall, "cpu": cpu, "sha256": digests, "octoreach": os.path.dirname(octoreach.__file__)}


def compare_builds(reference_path: str, res: float, directions: int, repeats: int) -> dict:
    """Surface-map builds with the octoreach on `reference_path` and with this one, interleaved, in child
    processes, from the same capability maps (built once here)."""
    robot = octoreach.robots.pr2()
    with tempfile.TemporaryDirectory() as work:
        caps_dir = os.path.join(work, "caps")
        os.makedirs(caps_dir)
        for arm in ("right_arm", "left_arm"):
            arms.capability_map(robot, arm, resolution=res, directions=directions, progress=False).save(
                os.path.join(caps_dir, f"{arm}.map"), with_solutions=True)

        def run(pythonpath: str, n: int) -> dict:
            out_dir = os.path.join(work, f"out{n}")
            os.makedirs(out_dir)
            return run_child(__file__, ["--child-build", "--resolution", res, "--caps", caps_dir, "--out", out_dir],
                             pythonpath)

        runs = {"reference": [], "this": []}
        for i in range(repeats):
            runs["reference"].append(run(reference_path, 2 * i))
            runs["this"].append(run(this_build(), 2 * i + 1))
    med = {k: {m: round(statistics.median(r[m] for r in v), 2) for m in ("wall", "cpu")} for k, v in runs.items()}
    digests = [r["sha256"] for v in runs.values() for r in v]
    return {
        "reference_pythonpath": reference_path,
        "resolution_m": res,
        "directions": directions,
        "repeats": repeats,
        "interleaved": True,
        "timed": "point maps + surface maps of both arms + their combination (capability maps given)",
        "runs": {k: [{"wall": round(r["wall"], 2), "cpu": round(r["cpu"], 2), "octoreach": r["octoreach"]} for r in v]
                 for k, v in runs.items()},
        "median_seconds": med,
        "speedup_cpu": round(med["reference"]["cpu"] / med["this"]["cpu"], 3),
        "speedup_wall": round(med["reference"]["wall"] / med["this"]["wall"], 3),
        "same_bytes": all(d == digests[0] for d in digests),
        "sha256": digests[0],
        "load_average_after": [round(x, 2) for x in os.getloadavg()],
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="0.1 m only, fewer directions")
    p.add_argument("--directions", type=int, default=200)
    p.add_argument("--samples", type=int, default=200)
    p.add_argument("--reference", default=None, metavar="PYTHONPATH",
                   help="compare surface-map builds with the octoreach on this PYTHONPATH (e.g. main's build), "
                        "interleaved in child processes, instead of the full benchmark")
    p.add_argument("--repeats", type=int, default=3, help="builds per side with --reference (medians reported)")
    p.add_argument("--resolution", type=float, default=0.05, help="resolution of the --reference comparison")
    p.add_argument("--child-build", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--caps", help=argparse.SUPPRESS)
    p.add_argument("--out", help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child_build:
        json.dump(child_build(args.resolution, args.caps, args.out), sys.stdout)
        return
    if args.reference is not None:
        result = {"benchmark": "surface_map", "machine": {"cpus": os.cpu_count(), "platform": platform.platform(),
                                                          "octoreach": octoreach.__version__},
                  "compare": compare_builds(args.reference, args.resolution, args.directions, args.repeats)}
        print(json.dumps(result, indent=2))
        return
    resolutions = [0.1] if args.quick else [0.05, 0.1]
    result = {"benchmark": "surface_map", "anchors": ANCHORS, "targets": TARGETS,
              "machine": {"cpus": os.cpu_count(), "platform": platform.platform(), "octoreach": octoreach.__version__},
              "runs": {}}
    for res in resolutions:
        result["runs"][f"{res:g}"] = run(res, 100 if args.quick else args.directions, args.samples)
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
