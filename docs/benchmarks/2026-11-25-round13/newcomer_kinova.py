"""Newcomer try (round 13): a robot the docs never mention (Kinova Jaco j2s6s200 from example-robot-data), the
camera on its end-effector frame (j2s6s200_end_effector; the loop looks along the chain tip's +z, which on
this arm points out of the side of the wrist, see `octoreach robot kinova`), in a scene built by hand and
never tuned on: a closed box opening upwards (+z, 10 cm) standing on a solid block, a closed box opening
low towards the robot (-x, 8 cm), and an open crate. Frontier-void (round 13: the last-chance look, stop
at 10 expected void cells) against random reachable views, two seeds each, coverage of the observable
interior (oracle). Run: .venv/bin/python docs/benchmarks/2026-11-25-round13/newcomer_kinova.py"""
import time

import numpy as np

import octoreach
from octoreach import DepthCamera, Scene
from octoreach import exploration as ex

robot = octoreach.robots.load("kinova")
chain = robot.chain("base", "j2s6s200_end_effector")
s = Scene()
s.add_box((-2, -2, -0.05), (2, 2, 0))
s.add_box((0.35, 0.2, 0.0), (0.6, 0.45, 0.15))                       # a solid block ...
s.add_closed_box((0.35, 0.2, 0.15), (0.6, 0.45, 0.4), 0.02, "+z", 0.1, 0.1)  # ... with a closed box on it
s.add_closed_box((0.4, -0.2, 0.0), (0.65, 0.1, 0.2), 0.02, "-x", 0.08, 0.08)
s.add_crate((0.2, -0.5, 0.0), (0.45, -0.3, 0.2), 0.02)
cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, noise=0.002, seed=0)
start = ex.look_at((0.0, 0.0, 0.9), (0.45, 0.0, 0.1))
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
              f"median search {np.median([x.search_s for x in r.rows]):.2f} s, max {max(x.search_s for x in r.rows):.2f} s",
              flush=True)
