"""Why a frontier-void exploration stopped short; prints JSON.

After one run (the benchmark's camera, robot, stop rule and budget), the oracle's own collision-free camera
poses are ranked by how many of the observable interior points the run left unknown each would see, and
the best --top of them are scored on the run's final map with the loop's very checks (score_views: camera
in observed-free space, capability map, IK, the arm against occupied and unknown cells and itself). Valid
ones that expect many void cells are views the search missed; the others say which check stands between
the planner and what is left.

Run: .venv/bin/python benchmarks/exploration_missed_views.py --scene paper_2 --seed 4 [--no-second-look]
"""
from __future__ import annotations

import argparse
import collections
import json
import time

import numpy as np

from octoreach import DepthCamera, _core
from octoreach import exploration as ex
from octoreach import testing

START = ((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))  # the benchmark's first view


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="paper_2", help="paper_1, paper_2 or usar_K")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--views", type=int, default=70)
    ap.add_argument("--top", type=int, default=40, help="oracle poses scored on the final map")
    ap.add_argument("--no-second-look", action="store_true")
    ap.add_argument("--enclosure-power", type=float, default=ex.ExploreOptions().search.enclosure_power)
    a = ap.parse_args()
    if a.scene.startswith("paper_"):
        scene = ex.paper_scene(int(a.scene.split("_")[1]))
    else:
        scene = testing.usar_scene(int(a.scene.split("_")[1])).scene
    t0 = time.perf_counter()
    robot, chain = ex.explorer_robot()
    cmap = ex.explorer_capability_map(chain)
    oracle = testing.observable_cells(scene, resolution=0.025)
    cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, noise=0.002, seed=a.seed)
    r = ex.explore(scene, cam, ex.look_at(*START), robot=True, max_views=a.views, resolution=0.025, seed=a.seed,
                   capability_map=cmap, min_utility=ex.STOP_UTILITY, patience=ex.STOP_PATIENCE,
                   second_look=not a.no_second_look, enclosure_power=a.enclosure_power)
    left = oracle.points[oracle.observable & (r.map.state(oracle.points) == 0)]
    sees = np.array([np.count_nonzero(oracle.sees(T, scene, left)) for T in oracle.poses]) if len(left) else \
        np.zeros(len(oracle.poses), int)
    best = np.argsort(-sees, kind="stable")[:a.top]
    best = best[sees[best] > 0]
    base = ex.arm_base_pose(robot, chain)
    scored = _core.score_views(r.map, cam, oracle.poses[best], chain=chain, chain_base=base, capability_map=cmap,
                               capability_base=base, min_distance=0.05, seed=a.seed,
                               enclosure_power=a.enclosure_power) if len(best) else None
    rows = [] if scored is None else [
        {"left_points_seen": int(sees[i]), "status": scored.status[j],
         "expected_void": round(float(scored.expected_void[j]), 1), "camera": np.round(oracle.poses[i][:3, 3], 3).tolist()}
        for j, i in enumerate(best)]
    valid = [x for x in rows if x["status"] == "valid"]
    out = {
        "scene": a.scene, "seed": a.seed, "second_look": not a.no_second_look, "enclosure_power": a.enclosure_power,
        "stop_reason": r.stop_reason, "views": len(r.rows), "observable_seen": oracle.share(r.map),
        "last_chosen_expected_void": r.rows[-1].expected_void if r.rows else None,
        "observable_points_left": int(len(left)), "oracle_poses_seeing_some": int(np.count_nonzero(sees)),
        "top_scored": len(rows), "status_counts": dict(collections.Counter(x["status"] for x in rows)),
        "valid_expected_void_max": max((x["expected_void"] for x in valid), default=None),
        "top": rows[:15], "seconds": time.perf_counter() - t0,
    }
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
