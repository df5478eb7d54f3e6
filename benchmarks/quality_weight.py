"""Surface maps with and without the quality weighting: what `quality_weight=True` costs.

The PR2 right arm's capability map (0.05 m, with joint solutions; built once, or read from --map), a
1.2 x 0.8 m table at 0.72 m, one thread; the paper's surface map (quality_weight=False, the reference) and
the weighted one are built alternately, --repeats each, and timed in CPU seconds of this process (one
thread, so a busy machine changes them less than wall seconds). Prints JSON: both medians, their ratio
(target: at most 1.2) and both maps' best R_S.

    .venv/bin/python benchmarks/quality_weight.py --repeats 5
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import time

import octoreach
from octoreach import arms

TARGET_RATIO = 1.2


def cpu_seconds() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5, help="builds of each map (medians reported)")
    p.add_argument("--map", default=None, help="a saved PR2 right-arm capability map with solutions to use")
    a = p.parse_args()
    robot = octoreach.robots.pr2()
    t = time.perf_counter()
    cap = (octoreach.CapabilityMap.load(a.map) if a.map else
           arms.capability_map(robot, "right_arm", resolution=0.05, progress=False))
    cap_seconds = time.perf_counter() - t
    table = octoreach.Surface.rectangle(1.2, 0.8, 0.72, x=0.0, y=0.0)
    runs = {"plain": [], "weighted": []}
    best = {}
    for _ in range(a.repeats):
        for name, weight in (("plain", False), ("weighted", True)):
            c0 = cpu_seconds()
            smap = octoreach.SurfaceMap.build(robot, cap, table, quality_weight=weight, threads=1, progress=False)
            runs[name].append(round(cpu_seconds() - c0, 3))
            best[name] = round(float(smap.max_reachability), 4)
    median = {k: statistics.median(v) for k, v in runs.items()}
    ratio = median["weighted"] / median["plain"]
    print(json.dumps({
        "what": "SurfaceMap.build of the PR2 right arm, 1.2 x 0.8 m table, one thread, CPU seconds",
        "capability_map": {"resolution_m": cap.resolution, "seconds": round(cap_seconds, 2), "loaded": bool(a.map)},
        "runs_cpu_seconds": runs, "median_cpu_seconds": median, "ratio_weighted_to_plain": round(ratio, 3),
        "target_ratio_max": TARGET_RATIO, "target_met": ratio <= TARGET_RATIO, "best_rs": best,
        "machine": {"cpus": len(os.sched_getaffinity(0)), "python": platform.python_version(),
                    "load_average_after": [round(x, 2) for x in os.getloadavg()]},
    }, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
