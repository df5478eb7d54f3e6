"""Frontier-void exploration benchmark; prints JSON.

Reference: stock OctoMap OcTree::insertPointCloud of the same cloud into a fresh tree, measured in
the same run (octoreach_bench.stock_insert_point_cloud, built beside the C++ tests), and the paper's figures (3-4.5 s per
integration, 14-100 s per next-best-view search). Cloud: one 640 x 480 depth image of a cluttered
scene (12 crates and closed boxes, a wall, a floor), 2.5 cm cells, 4 m range.
Explorations: the explorer robot with a coarse capability map (built once, timed separately), fixed
base, and for scene 2 also with the base allowed to drive to four poses around the scene.
Void clusters: a sequence of images of the cluttered scene from nearby poses; after each insert the
incrementally kept clusters (void_clusters) against the clustering from scratch of the same void cells
(void_clusters_from_scratch, the reference, measured on the same state), and whether they are equal.
Visibility model: per exploration, the void cells each chosen view was expected to see (visibility
weighted) against the void cells its image turned known.
Run: .venv/bin/python benchmarks/exploration.py [--repeats 5]
A/B against an earlier build (same machine, same session, alternated): build that commit's module
(cmake -S <worktree> -B <worktree>/build -DOCTOREACH_PYTHON=ON ...), copy python/octoreach, the built .so
files and urdf/ into a folder <dir>/octoreach, and run this script with PYTHONPATH=<dir>; `code` in the output says which build ran.
"""
from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

import octoreach
import octoreach_bench as _bench
from octoreach import DepthCamera, ExplorationMap, _core, next_best_view, score_views
from octoreach import exploration as ex


def cluttered_first_view():
    """The benchmark's cluttered scene, its 640 x 480 depth camera (58 degrees, 4 m) and first view:
    (scene, camera, camera pose, resolution, range); benchmarks/exploration_scoring.py uses it too."""
    res, rng = 0.025, 4.0
    cam = DepthCamera(640, 480, np.deg2rad(58.0), rng)
    return ex.cluttered_scene(), cam, ex.look_at((-0.8, 0.0, 1.2), (1.5, 0.0, 0.0)), res, rng


def _void_cluster_sequence(scene, cam, res, rng, poses):
    """Incremental void clusters against from scratch after each insert of a sequence of views."""
    emap = ExplorationMap(resolution=res)
    inc_s, scratch_s, voids, equal = [], [], [], True
    for T in poses:
        emap.insert(cam.capture(scene, T), T[:3, 3], rng)
        t0 = time.perf_counter()
        inc = emap.void_clusters()
        inc_s.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        ref = emap.void_clusters_from_scratch()
        scratch_s.append(time.perf_counter() - t0)
        voids.append(emap.void_cell_count)
        equal &= len(inc) == len(ref) and all(np.array_equal(x.keys, y.keys) for x, y in zip(inc, ref))
    return {"views": len(poses), "void_cells": voids, "incremental_s": inc_s, "from_scratch_s": scratch_s,
            "median_incremental_s_after_first": statistics.median(inc_s[1:]),
            "median_from_scratch_s_after_first": statistics.median(scratch_s[1:]),
            "equal_to_from_scratch_every_insert": bool(equal)}


def _void_cluster_runs(scene, cam, res, rng):
    """Two sequences after the same overview: views circling near it (their changes reach most of the
    voids) and close views of single crates and boxes (local changes)."""
    first = ex.look_at((-0.8, 0.0, 1.2), (1.5, 0.0, 0.0))
    circling = [first] + [ex.look_at((-0.8 + 0.3 * np.cos(a), 0.3 * np.sin(a), 1.2), (1.5, 0.0, 0.0))
                          for a in np.linspace(0, 2 * np.pi, 8)[1:]]
    local = [first] + [ex.look_at((x - 0.35, y + 0.2, 0.75), (x + 0.2, y + 0.2, 0.15))
                       for x, y in ((0.5, -1.2), (1.1, -0.4), (1.7, 0.4), (2.3, -1.2), (0.5, 0.4), (1.7, -1.2))]
    return {"circling": _void_cluster_sequence(scene, cam, res, rng, circling),
            "local": _void_cluster_sequence(scene, cam, res, rng, local)}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--views", type=int, default=10)
    a = ap.parse_args()
    scene, cam, T, res, rng = cluttered_first_view()
    pts = cam.capture(scene, T)
    stock, ours, ours_clusters, same = [], [], [], True
    parts = {}
    for _ in range(a.repeats):
        ref = _bench.stock_insert_point_cloud(pts, T[:3, 3], rng, res)
        stock.append(ref["seconds"])
        emap = ExplorationMap(resolution=res)
        t0 = time.perf_counter()
        st = emap.insert(pts, T[:3, 3], rng)
        emap.void_clusters()
        ours_clusters.append(time.perf_counter() - t0)
        ours.append(st["seconds"])
        for k in ("seconds_rays", "seconds_tree", "seconds_frontiers", "seconds_hull", "seconds_voids"):
            parts.setdefault(k, []).append(st[k])
        d = emap.occupancy_digest()
        same &= (d["free"], d["occupied"], d["hash"]) == (ref["free"], ref["occupied"], ref["hash"])
    # next best view on the map after the first image, free camera within 1 m of a point in front
    nbv_s, nbv, nbv_parts = [], None, {}
    for _ in range(a.repeats):
        nbv = next_best_view(emap, cam, workspace_sphere=((0.5, 0.0, 0.5), 1.0), min_distance=0.05)
        nbv_s.append(nbv.seconds)
        for k in ("seconds_vectors", "seconds_prune", "seconds_score"):
            nbv_parts.setdefault(k, []).append(getattr(nbv, k))
    med = statistics.median
    from octoreach.exploration.candidate_poses import aimed_poses
    from octoreach.exploration.strategies import choose_view

    # the loop's search (ExploreOptions.benchmark(): the search NbvOptions.exploration_loop(), the stated
    # stopping rule): void cells also weighted by their enclosure; the enclosure is computed once per map and
    # search (cached until the next insert: each repeat asks for another range so that every repeat pays
    # it), and the second look (aimed_poses poses aimed at void cells, scored)
    loop = ex.ExploreOptions.benchmark()
    loop_s, enclosure_s, aimed_s = [], [], []
    for i in range(a.repeats):
        loop_s.append(next_best_view(emap, cam, workspace_sphere=((0.5, 0.0, 0.5), 1.0), min_distance=0.05,
                                     enclosure_power=loop.search.enclosure_power,
                                     enclosure_range=0.5 + 1e-9 * (2 * i + 1)).seconds)
        t0 = time.perf_counter()
        _core.void_enclosure(emap, 0.5 + 1e-9 * (2 * i + 2))
        enclosure_s.append(time.perf_counter() - t0)
        P = aimed_poses(np.random.default_rng(i), emap, sphere=((0.5, 0.0, 0.5), 1.0))
        t0 = time.perf_counter()
        score_views(emap, cam, P, workspace_sphere=((0.5, 0.0, 0.5), 1.0), min_distance=0.05, score_invalid=False,
                    enclosure_power=loop.search.enclosure_power)
        aimed_s.append(time.perf_counter() - t0)
    # the loop's whole search per view as explore() runs it (free camera here): next_best_view with the loop's
    # search, then the second look
    view_s = []
    for i in range(a.repeats):
        settings = ex.ExploreOptions.benchmark()  # a range of its own per repeat: each pays the enclosure
        settings.search.enclosure_range = 0.5 + 1e-9 * (1000 + i)
        t0 = time.perf_counter()
        choose_view("frontier_void", emap, cam, [None], 0, lambda _: ((0.5, 0.0, 0.5), 1.0), settings, i,
                    ex.scene_region(scene))
        view_s.append(time.perf_counter() - t0)
    inc = _void_cluster_runs(scene, cam, res, rng)
    # the search with the safe-view rule off (the cost of the unknown-cell obstacles and clearance)
    loose_s = [next_best_view(emap, cam, workspace_sphere=((0.5, 0.0, 0.5), 1.0), min_distance=0.05,
                              unknown_is_obstacle=False).seconds for _ in range(a.repeats)]
    out = {
        "cloud": {"points": int(len(pts)), "image": [640, 480], "resolution_m": res, "max_range_m": rng},
        "integration": {
            "stock_insertPointCloud_s": med(stock),
            "octoreach_insert_incl_frontiers_voids_s": med(ours),
            "octoreach_insert_plus_void_clustering_s": med(ours_clusters),
            "speedup_vs_stock_insert_only": med(stock) / med(ours),
            "speedup_vs_stock_incl_void_clustering": med(stock) / med(ours_clusters),
            "same_occupancy_as_stock": bool(same),
            "parts_median_s": {k: med(v) for k, v in parts.items()},
            "free_cells": st["free_cells"], "occupied_cells": st["occupied_cells"],
            "frontier_cells": emap.frontier_cell_count, "void_cells": emap.void_cell_count,
            "void_clusters": len(emap.void_clusters()),
        },
        "next_best_view": {
            "median_s": med(nbv_s), "parts_median_s": {k: med(v) for k, v in nbv_parts.items()},
            "utility_vectors": nbv.utility_vectors,
            "candidate_cells": nbv.candidate_cells, "poses_scored": nbv.poses_scored,
            "best_void_cells": nbv.void_cells, "best_utility_dm3": nbv.utility_dm3,
            "best_expected_void": nbv.expected_void, "pass_probability": nbv.pass_probability,
            "void_pass_probability": nbv.void_pass_probability,
            "median_s_without_unknown_obstacles": med(loose_s),
            "median_s_loop_enclosure_power": med(loop_s), "loop_enclosure_power": loop.search.enclosure_power,
            "void_enclosure_s": med(enclosure_s),
            "second_look_s": med(aimed_s), "second_look_poses": loop.aimed_poses,
            "loop_view_search_s": med(view_s),
            "score_grid": [48, 36],
        },
        "void_clusters": inc,
        "paper_reference": {"integration_s": [3.0, 4.5], "nbv_search_s": [14, 100]},
        "explorations": {},
    }
    _, chain = ex.explorer_robot()
    t0 = time.perf_counter()
    cmap = ex.explorer_capability_map(chain)
    out["capability_map"] = {"build_s": time.perf_counter() - t0, "resolution_m": cmap.resolution,
                             "voxels": cmap.voxel_count}
    runs = [(1, False, "paper_scene_1"), (2, False, "paper_scene_2"), (2, True, "paper_scene_2_moving_base")]
    for sid, move, name in runs:
        r = ex.run_demo(sid, out=f"/tmp/octoreach_bench_{name}", max_views=a.views, plots=False, quiet=True,
                        export=False, capability_map=cmap, move_base=move)
        scene = ex.paper_scene(sid)
        out["explorations"][name] = {
            "views": len(r.rows), "total_s": r.total_s,
            "median_integration_s": med([x.integration_s for x in r.rows]),
            "median_search_s": med([x.search_s for x in r.rows]),
            "max_search_s": max(x.search_s for x in r.rows),
            "observed_share": r.observed_share, "interior_share": r.interior_share,
            "interior_share_per_box": [round(ex.observed_share(r.map, scene, [box]), 3) for box in scene.interiors],
            "final_utility_dm3": r.rows[-1].utility_dm3,
            "bases": [x.base for x in r.rows],
            # void cells the search expected the next view to see (visibility-weighted), those it turned
            # known, and the raw count of void cells in its frustum (unknown space taken as transparent)
            # (explore's rows carry both: void_seen is what the next view's insert turned known)
            "void_cells_expected_seen_raw": [[round(a.expected_void, 1), a.void_seen, a.void_cells]
                                             for a in r.rows if a.void_seen is not None],
        }
        ratios = ex.seen_expected_ratios(r.rows, min_expected=1e-9)
        out["explorations"][name]["seen_over_expected"] = {
            "median": med(ratios) if ratios else None,
            "share_below_0.1": sum(x < 0.1 for x in ratios) / len(ratios) if ratios else None}
    out["machine_note"] = "shared 2-core machine: medians of %d runs; timings are noisy" % a.repeats
    out["code"] = {"module": octoreach.__file__}
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
