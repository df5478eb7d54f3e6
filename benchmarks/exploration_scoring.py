"""CPU seconds of view scoring, for A/B runs of two builds on a shared machine; prints JSON.

The benchmark's cluttered scene after one 640 x 480 image (as benchmarks/exploration.py), then
score_views of 300 fixed camera poses on one thread (the visibility model's ray casting alone: no
IK, no safe-view obstacles) and next_best_view, each --repeats times; medians of process CPU time.
Alternate the builds in one shell loop, e.g.
  for i in 1 2; do for p in /tmp/ref_main /tmp/py_NAME; do PYTHONPATH=$p .venv/bin/python benchmarks/exploration_scoring.py; done; done
"""
from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

from exploration import cluttered_first_view  # benchmarks/exploration.py
from octoreach import ExplorationMap, _core, next_best_view
from octoreach import exploration as ex


def _field(result, name):
    """A field of a result: an attribute (bound result classes) or a key (the dicts of earlier builds, A/B)."""
    return result[name] if isinstance(result, dict) else getattr(result, name)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--poses", type=int, default=300)
    a = ap.parse_args()
    scene, cam, T, res, rng = cluttered_first_view()
    emap = ExplorationMap(resolution=res)
    emap.insert(cam.capture(scene, T), T[:3, 3], rng)
    r = np.random.default_rng(0)
    poses = np.array([ex.look_at(r.uniform((-0.3, -1, 0.4), (0.8, 1, 1.3)), r.uniform((0.5, -1.2, 0), (2.5, 1.2, 0.4)))
                      for _ in range(a.poses)])
    score, nbv = [], []
    for _ in range(a.repeats):
        t = time.process_time()
        s = _core.score_views(emap, cam, poses, threads=1, unknown_is_obstacle=False)
        score.append(time.process_time() - t)
    for _ in range(a.repeats):
        t = time.process_time()
        n = next_best_view(emap, cam, workspace_sphere=((0.5, 0.0, 0.5), 1.0), min_distance=0.05)
        nbv.append((time.process_time() - t, *(_field(n, k) for k in ("seconds", "seconds_vectors", "seconds_score"))))
    med = statistics.median
    print(json.dumps({
        "poses": a.poses, "repeats": a.repeats,
        "score_views_cpu_s": med(score),
        "expected_void_sum": float(np.sum(_field(s, "expected_void"))),
        "next_best_view_cpu_s": med(x[0] for x in nbv), "next_best_view_s": med(x[1] for x in nbv),
        "next_best_view_vectors_s": med(x[2] for x in nbv), "next_best_view_score_s": med(x[3] for x in nbv),
        "note": "process CPU seconds; compare builds only alternated in one run",
    }, indent=1))


if __name__ == "__main__":
    main()
