"""Seconds per choice of a view, the loop's (a coarse first score, NbvOptions.rescore_best of the exploration
loop's search) against every valid pose scored with the full grid (rescore_best 0, the paper's search), both on the
same map at every view of the same runs; prints JSON.

Runs explore(strategy="frontier_void") with the explorer robot, its coarse capability map and the default stop
rule for --views views on the paper scenes and --instances instances of every scene family (320 x 240 images,
2.5 cm cells, as the family record). At each view both choices are made on the map as it stands, in alternating
order (the first of the two fills the map's caches), each with a copy of the Explorer's memory and the seed
next_view uses; the Explorer's own answer (the loop's default) drives the run. Per call: wall seconds and CPU
seconds of the process (all threads: on a shared machine the CPU time is the figure that does not depend on the
other jobs), the void cells each chosen view expects (the choice's utility), and whether the two chose the same
camera pose or both stop. `utility_ratio` is the loop's utility over the full score's (1: as good a view; the
second look's aims and the last chance may find a better one either way).

With --reference DIR, every scene runs first with the octoreach package found in DIR (a build to compare with,
PYTHONPATH=DIR, in a child process) and then with this one, so both see the machine in the same state; "reference"
holds its figures.

With --head, the camera is the pan/tilt head of the guides' rover (docs/examples/rover.urdf, standing at the
origin) instead of the explorer robot's arm: a chain that only aims its camera (NbvOptions.aiming "auto"), whose
first view looks at the search space's centre.

Run: .venv/bin/python benchmarks/view_choice_times.py [--views 40] [--instances 1] [--reference DIR] [--beyond-voids 0]
[--head] > times.json
"""
from __future__ import annotations

import argparse
import copy
import json
import os
import sys
import time

import numpy as np

import octoreach
from octoreach import DepthCamera, Robot
from octoreach import exploration as ex
from octoreach.exploration import strategies
from octoreach.exploration.camera import look_at
from octoreach.exploration.explorer import Explorer
from octoreach.testing import scene_families

from child_runs import run_child  # the sibling module: one way to run a build in a child process


ROVER = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "docs", "examples", "rover.urdf")


def _clock(fn):
    """(fn(), wall seconds, CPU seconds of the process)."""
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def _full_score(o):
    """A copy of ExploreOptions `o` whose search scores every valid pose with the full grid."""
    full = copy.copy(o)
    search = full.search
    search.rescore_best = 0
    full.search = search
    return full


def _timed(calls: list):
    """Explorer.next_view, also making both choices on the same map (alternately first and second)."""
    next_view = Explorer.next_view

    def timed(self):
        o = self.options
        seed = o.search.seed + self.views  # next_view's seed for this view
        sphere_of = (lambda b: (np.asarray(b, float)[:3, 3], self.reach)) if self.reach > 0 else None

        def choice(opts):
            return lambda: strategies.choose_view(self.strategy, self.map, self._keep[0], self.bases,
                                                  self.current_base, sphere_of, opts,
                                                  seed, memory=copy.copy(self._core.memory))
        order = [("loop", o), ("full", _full_score(o))]
        if len(calls) % 2:
            order.reverse()
        got = {name: _clock(choice(opts)) for name, opts in order}
        (a, aw, ac), (b, bw, bc) = got["loop"], got["full"]
        same = (a.pose is None and b.pose is None) or (
            a.pose is not None and b.pose is not None and np.allclose(a.pose, b.pose, atol=1e-9))
        calls.append({"loop": (aw, ac), "full": (bw, bc), "same": bool(same),
                      "utility": (float(a.expected_void or 0.0), float(b.expected_void or 0.0)),
                      "stop": (bool(a.stop), bool(b.stop))})
        return next_view(self)
    return timed


def _stats(xs) -> dict:
    return {"median": float(np.median(xs)), "mean": float(np.mean(xs)), "p90": float(np.percentile(xs, 90)),
            "max": float(np.max(xs))} if xs else {}


def _summary(calls: list) -> dict:
    out = {"choices": len(calls), "same_view": sum(c["same"] for c in calls),
           "same_stop": sum(c["stop"][0] == c["stop"][1] for c in calls)}
    for key in ("loop", "full"):
        out[key] = {"wall": _stats([c[key][0] for c in calls]), "cpu": _stats([c[key][1] for c in calls])}
    ratios = [c["utility"][0] / c["utility"][1] for c in calls if c["utility"][1] > 0]
    out["utility_ratio"] = {"median": float(np.median(ratios)), "min": float(np.min(ratios)),
                            "below_0.9": int(sum(r < 0.9 for r in ratios))} if ratios else {}
    return out


def _head(scene, space):
    """explore()'s robot keywords for the rover's pan/tilt head at the origin, and its first view: the camera
    aimed at the search space's centre."""
    rover = Robot.from_urdf(ROVER)
    head = rover.chain("base_footprint", "camera_link")
    region = ex.scene_region(scene) if space is None else np.asarray(space, float)
    q = head.aim(region.mean(axis=0))
    if q is None:
        raise RuntimeError("the rover's head cannot aim at the search space's centre")
    return dict(robot=rover, chain=head, base_pose=np.eye(4)), head.fk(q)


def _reference(a, name: str) -> dict:
    """The figures of scene `name` with the package in a.reference (a child process, PYTHONPATH=a.reference)."""
    args = ["--views", a.views, "--instances", a.instances, "--seed", a.seed, "--scenes", name,
            "--beyond-voids", a.beyond_voids] + (["--head"] if a.head else [])
    return run_child(__file__, args, a.reference)["scenes"][name]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--views", type=int, default=40)
    ap.add_argument("--instances", type=int, default=1, help="instances per scene family")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--scenes", default="", help="comma-separated scene names to run (default: all)")
    ap.add_argument("--reference", default="", help="a directory holding the octoreach package to compare with")
    ap.add_argument("--beyond-voids", type=int, choices=(0, 1), default=int(ex.BEYOND_VOIDS),
                    help="frontier_void: views beyond the voids (ExploreOptions.beyond_voids)")
    ap.add_argument("--head", action="store_true", help="the rover's pan/tilt head camera, not the explorer's arm")
    a = ap.parse_args(argv)
    cmap = None if a.head else ex.explorer_capability_map(ex.explorer_robot()[1])  # the arm's, which --head does not use
    paper_start = look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))  # the demo's first view
    scenes = [(f"paper_{k}", ex.paper_scene(k), paper_start, None) for k in (1, 2)]
    for fam in scene_families.FAMILIES:
        for inst in scene_families.family_instances(fam, a.instances):
            scenes.append((inst.name, inst.scene, scene_families.start_pose(), inst.search_space))
    if a.scenes:
        wanted = [w.strip() for w in a.scenes.split(",") if w.strip()]
        unknown = sorted(set(wanted) - {s[0] for s in scenes})
        if unknown:
            ap.error(f"no scene named {', '.join(unknown)}; the scenes are {', '.join(s[0] for s in scenes)}")
        scenes = [s for s in scenes if s[0] in wanted]
    out = {"views": a.views, "beyond_voids": bool(a.beyond_voids), "head": bool(a.head), "cores": os.cpu_count(), "load_average": list(os.getloadavg()),
           "octoreach": os.path.dirname(octoreach.__file__), "scenes": {}}
    if a.reference:
        out["reference"] = {"path": os.path.abspath(a.reference), "scenes": {}}
    every = []
    Explorer.next_view = _timed(every)
    for name, scene, start, space in scenes:
        if a.reference:
            ref = out["reference"]["scenes"][name] = _reference(a, name)
            print(f"# {name} (reference): wall median loop {ref['loop']['wall']['median']:.3f}", file=sys.stderr,
                  flush=True)
        first = len(every)
        cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, seed=a.seed)
        robot_kw = dict(robot=True, capability_map=cmap)
        if a.head:
            robot_kw, start = _head(scene, space)
        r = ex.explore(scene, cam, start, search_space=space, max_views=a.views, resolution=0.025, seed=a.seed,
                       beyond_voids=bool(a.beyond_voids), **robot_kw)
        s = _summary(every[first:])
        out["scenes"][name] = dict(s, stop=r.stop_reason, views=len(r.rows),
                                   loop_wall=[c["loop"][0] for c in every[first:]])
        print(f"# {name}: {s['choices']} choices, wall median loop {s['loop']['wall']['median']:.3f} "
              f"full {s['full']['wall']['median']:.3f}, same view {s['same_view']}", file=sys.stderr, flush=True)
    out["all"] = _summary(every)
    if a.reference:
        walls = [w for sc in out["reference"]["scenes"].values() for w in sc["loop_wall"]]
        out["reference"]["all_loop_wall"] = _stats(walls)
    out["load_average_after"] = list(os.getloadavg())
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
