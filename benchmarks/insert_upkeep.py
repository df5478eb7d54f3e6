"""Seconds the inserts take over a long exploration, while the map grows; prints JSON.

explore(strategy="frontier_void") on paper scene 2 with the explorer robot, its coarse capability map, a 320 x 240
camera and 2.5 cm cells for --views views without the stop rule (min_utility 0, so every run takes the same views):
the sum and median of ViewRow.integration_s (the insert with its frontier, void and surface upkeep) over all views
and the sum over the later half, where the map is large and each view changes little of it. benchmarks/exploration.py
times one insert into an empty map; this is the cost that grows with the map.

With --reference DIR, the package found in DIR (PYTHONPATH=DIR, a child process) runs too, alternating with this one
--repeats times, so both see the machine in the same state; "reference" holds its figures.

Run: .venv/bin/python benchmarks/insert_upkeep.py [--views 60] [--repeats 3] [--reference DIR] > upkeep.json
"""
from __future__ import annotations

import argparse
import json
import os
import statistics

import numpy as np

import octoreach
from octoreach import DepthCamera
from octoreach import exploration as ex
from octoreach.exploration.camera import look_at

from child_runs import run_child  # the sibling module: one way to run a build in a child process


def _one_run(views: int) -> dict:
    """One exploration's insert seconds (see the module)."""
    cmap = ex.explorer_capability_map(ex.explorer_robot()[1])
    cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, seed=0)
    r = ex.explore(ex.paper_scene(2), cam, look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0)), max_views=views,
                   resolution=0.025, seed=0, robot=True, capability_map=cmap, min_utility=0)
    t = [x.integration_s for x in r.rows]
    return {"views": len(t), "total_s": sum(t), "later_half_s": sum(t[len(t) // 2:]), "median_s": statistics.median(t),
            "octoreach": os.path.dirname(octoreach.__file__)}


def _summary(runs: list) -> dict:
    return {k: {"min": min(r[k] for r in runs), "median": statistics.median(r[k] for r in runs),
                "max": max(r[k] for r in runs)} for k in ("total_s", "later_half_s", "median_s")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--views", type=int, default=60)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--reference", default="", help="a directory holding the octoreach package to compare with")
    ap.add_argument("--one", action="store_true", help=argparse.SUPPRESS)  # one run, this process
    a = ap.parse_args(argv)
    if a.views < 2 or a.repeats < 1:
        ap.error("--views must be >= 2 and --repeats >= 1")
    if a.one:
        print(json.dumps(_one_run(a.views)))
        return 0
    this, ref = [], []
    for _ in range(a.repeats):
        if a.reference:
            ref.append(run_child(__file__, ["--views", a.views, "--one"], a.reference))
        this.append(run_child(__file__, ["--views", a.views, "--one"]))
    out = {"views": a.views, "repeats": a.repeats, "cores": os.cpu_count(), "load_average": list(os.getloadavg()),
           "octoreach": this[0]["octoreach"], "runs": this, **_summary(this)}
    if a.reference:
        out["reference"] = {"path": os.path.abspath(a.reference), "runs": ref, **_summary(ref)}
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
