"""Seconds per choice of a view: Explorer.next_view() against the loop's choice as explore() made it before it
became a driver over the Explorer (strategies.choose_view, the Python wrapper over _core.choose_view), both on
the same map at every view of the same runs; prints JSON.

Runs explore(strategy="frontier_void") with the explorer robot, its coarse capability map and the benchmark's
stop rule (ExploreOptions.benchmark()) for --views views on the paper scenes and one instance of every scene
family. At each view both choices are made on the map as it stands, in alternating order (the first of the two
fills the map's caches), the loop's with a copy of the Explorer's memory and the seed next_view uses; the
Explorer's answer drives the run. Wall seconds and CPU seconds of the process (all threads: on a shared machine
the CPU time is the figure that does not depend on the other jobs) per call, and how often the two chose the
same camera pose. With --families-from DIR (a checkout's python/octoreach/testing), the families are loaded from
there, so an older build can be timed on the same scenes.

Run: .venv/bin/python benchmarks/view_choice_times.py [--views 12] [--families-from DIR] > times.json
"""
from __future__ import annotations

import argparse
import copy
import importlib.util
import json
import os
import sys
import time

import numpy as np

from octoreach import DepthCamera
from octoreach import exploration as ex
from octoreach.exploration import strategies
from octoreach.exploration.camera import look_at
from octoreach.exploration.explorer import Explorer


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


def _clock(fn):
    """(fn(), wall seconds, CPU seconds of the process)."""
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def _timed(calls: list):
    """Explorer.next_view, also making the loop's choice on the same map first or second (alternately)."""
    next_view = Explorer.next_view

    def timed(self):
        o = self.options
        seed = o.search.seed + self.views  # next_view's seed for this view
        sphere_of = (lambda b: (np.asarray(b, float)[:3, 3], self.reach)) if self.reach > 0 else None
        memory = copy.copy(self._core.memory)
        loop = lambda: strategies.choose_view(self.strategy, self.map, self._keep[0], self.bases,  # noqa: E731
                                              self.current_base, sphere_of, o, seed, memory=memory)
        first_loop = len(calls) % 2 == 0
        if first_loop:
            choice, lw, lc = _clock(loop)
        view, nw, nc = _clock(lambda: next_view(self))
        if not first_loop:
            choice, lw, lc = _clock(loop)
        same = (choice.pose is None and not view.choice.found) or (
            choice.pose is not None and view.choice.found and np.allclose(choice.pose, view.camera_pose, atol=1e-9))
        calls.append({"next_view": (nw, nc), "loop": (lw, lc), "same": bool(same)})
        return view
    return timed


def _stats(xs) -> dict:
    return {"median": float(np.median(xs)), "mean": float(np.mean(xs)), "p90": float(np.percentile(xs, 90)),
            "max": float(np.max(xs))} if xs else {}


def _summary(calls: list) -> dict:
    out = {"choices": len(calls), "same_view": sum(c["same"] for c in calls)}
    for key in ("next_view", "loop"):
        out[key] = {"wall": _stats([c[key][0] for c in calls]), "cpu": _stats([c[key][1] for c in calls])}
    return out


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
    out = {"views": a.views, "cores": os.cpu_count(), "load_average": list(os.getloadavg()), "scenes": {}}
    every = []
    Explorer.next_view = _timed(every)
    for name, scene, start, space in scenes:
        first = len(every)
        cam = DepthCamera(160, 120, np.deg2rad(58.0), 4.0, seed=a.seed)
        r = ex.explore(scene, cam, start, robot=True, capability_map=cmap, search_space=space, max_views=a.views,
                       seed=a.seed, min_utility=bench.min_utility, patience=bench.patience)
        s = _summary(every[first:])
        out["scenes"][name] = dict(s, stop=r.stop_reason, interior=r.interior_share)
        print(f"# {name}: {s['choices']} choices, cpu median next_view {s['next_view']['cpu']['median']:.3f} "
              f"loop {s['loop']['cpu']['median']:.3f}", file=sys.stderr)
    out["all"] = _summary(every)
    out["load_average_after"] = list(os.getloadavg())
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
