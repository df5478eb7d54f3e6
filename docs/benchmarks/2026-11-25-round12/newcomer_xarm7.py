"""Newcomer try (round 12): a robot the docs never mention (UFactory xArm 7 from example-robot-data), the
camera at its flange (link_eef, +z out of the flange, as `octoreach robot xarm7` reports), in a scene built by
hand and never tuned on: a crate standing on a solid block (its inside 0.2-0.4 m up), a closed box opening
sideways (+y), a solid block beside it and a low open crate, all within the arm's reach. Frontier-void
(round 12) against random reachable views, two seeds each, coverage of the observable interior (oracle).
Run: .venv/bin/python docs/benchmarks/2026-11-25-round12/newcomer_xarm7.py"""
import time

import numpy as np

import octoreach
from octoreach import DepthCamera, Scene
from octoreach import exploration as ex

robot = octoreach.robots.load("xarm7")
chain = robot.chain("link_base", "link_eef")
s = Scene()
s.add_box((-2, -2, -0.05), (2, 2, 0))
s.add_box((0.35, 0.15, 0.0), (0.6, 0.45, 0.2))             # a solid block ...
s.add_crate((0.35, 0.15, 0.2), (0.6, 0.45, 0.4), 0.02)      # ... with a crate on it
s.add_closed_box((0.4, -0.35, 0.0), (0.65, -0.05, 0.25), 0.02, "+y", 0.1, 0.08)
s.add_box((0.7, -0.3, 0.0), (0.85, -0.1, 0.3))              # a solid block
s.add_crate((0.15, -0.55, 0.0), (0.4, -0.35, 0.15), 0.02)   # a low open crate
cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, noise=0.002, seed=0)
start = ex.look_at((0.0, 0.0, 0.8), (0.45, 0.0, 0.1))
base_pose = robot.link_poses(robot.home())[chain.base_link]
t0 = time.time()
orc = ex.observable_cells(s, chain=chain, robot=robot, base_pose=base_pose)
print(f"oracle {time.time() - t0:.1f} s: observable {orc.fraction:.1%} of {len(orc.points)} interior points")
for strategy in ("frontier_void", "random"):
    for seed in (0, 1):
        t0 = time.time()
        cover = []
        r = ex.explore(s, cam, start, robot=robot, chain=chain, strategy=strategy, min_utility=ex.STOP_UTILITY,
                       patience=ex.STOP_PATIENCE, max_views=40, resolution=0.025, capability_map="auto", seed=seed,
                       on_view=lambda row, emap, info: cover.append(orc.share(emap)))
        rat = ex.seen_expected_ratios(r.rows)
        print(f"{strategy} seed {seed}: {r.stop_reason} after {len(r.rows)} views, {time.time() - t0:.0f} s, "
              f"observable seen after 5/10/end {ex.coverage_after(cover, 5):.1%} / {ex.coverage_after(cover, 10):.1%} / "
              f"{cover[-1]:.1%}, views to 90 % {ex.views_to_reach(cover, 0.9)}, under 0.1: {sum(x < 0.1 for x in rat)} "
              f"of {len(rat)}, invalid {sum(not x.physically_valid for x in r.rows)}, "
              f"median search {np.median([x.search_s for x in r.rows]):.2f} s", flush=True)
