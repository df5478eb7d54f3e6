"""Seconds per choice of a view (the exploration loop's whole choice: search, second looks, last chance)
on the paper scenes and one instance of every scene family; prints JSON.

Runs explore(strategy="frontier_void") with the explorer robot, its coarse capability map and the
benchmark's stop rule (ExploreOptions.benchmark()) for --views views, and times each call of the loop's
choose_view: wall seconds and CPU seconds of the process (all threads: on a shared machine the CPU time
is the figure that does not depend on the other jobs). With --families-from DIR (a checkout's
python/octoreach/testing), the families are loaded from there, so an older build without them can be
timed on the same scenes in the same run.

Run: .venv/bin/python benchmarks/view_choice_times.py [--views 12] [--families-from DIR] > times.json
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import sys
import time

import numpy as np

from octoreach import DepthCamera
from octoreach import exploration as ex
from octoreach.exploration import loop
from octoreach.exploration.camera import look_at


def _families(src):
    """The scene_families module: octoreach.testing's, or loaded from `src` into octoreach.testing."""
    if src is None:
        from octoreach.testing import scene_families
        return scene_families
    import octoreach.testing as t
    for name in ("scene_parts", "family_containers", "family_debris", "scene_families"):
        spec = importlib.util.spec_from_file_location(f"octoreach.testing.{name}", f"{src}/{name}.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod
        spec.loader.exec_module(mod)
        setattr(t, name, mod)
    return sys.modules["octoreach.testing.scene_families"]


def _timed(times):
    choose = loop.choose_view

    def wrapped(*args, **kw):
        w, c = time.perf_counter(), time.process_time()
        out = choose(*args, **kw)
        times.append((time.perf_counter() - w, time.process_time() - c))
        return out
    return wrapped


def _stats(xs) -> dict:
    return {"median": float(np.median(xs)), "p90": float(np.percentile(xs, 90)), "max": float(np.max(xs))} if xs else {}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--views", type=int, default=12)
    ap.add_argument("--families-from", default=None)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args(argv)
    fams = _families(a.families_from)
    _, chain = ex.explorer_robot()
    cmap = ex.explorer_capability_map(chain)
    bench = ex.ExploreOptions.benchmark()
    paper_start = look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))  # the demo's first view
    scenes = [(f"paper_{k}", ex.paper_scene(k), paper_start, None) for k in (1, 2)]
    for fam in fams.FAMILIES:
        inst = fams.family_scene(fam, 0)
        scenes.append((inst.name, inst.scene, fams.start_pose(), inst.search_space))
    out = {"views": a.views, "scenes": {}}
    all_w, all_c = [], []
    for name, scene, start, space in scenes:
        times = []
        loop.choose_view = _timed(times)
        cam = DepthCamera(160, 120, np.deg2rad(58.0), 4.0, seed=a.seed)
        r = ex.explore(scene, cam, start, robot=True, capability_map=cmap, search_space=space, max_views=a.views,
                       seed=a.seed, min_utility=bench.min_utility, patience=bench.patience)
        w, c = [t[0] for t in times], [t[1] for t in times]
        all_w += w
        all_c += c
        out["scenes"][name] = {"wall": _stats(w), "cpu": _stats(c), "choices": len(times), "stop": r.stop_reason,
                               "interior": r.interior_share}
        print(f"# {name}: {len(times)} choices, cpu median {np.median(c):.3f} max {np.max(c):.3f}", file=sys.stderr)
    out["all"] = {"wall": _stats(all_w), "cpu": _stats(all_c), "choices": len(all_w)}
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
