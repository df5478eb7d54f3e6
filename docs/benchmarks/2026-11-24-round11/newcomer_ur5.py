"""Newcomer try (round 11): a robot the docs never mention (Universal Robots UR5 from example-robot-data),
the camera at its flange (tool0, +z out of the flange), in a scene built by hand and never tuned on: an open
crate, a closed box opening towards the robot (-x), a closed box opening on top, a low board, all within the
UR5's reach. The second look on every view (round 11) against no second look."""
import time, numpy as np, octoreach
from octoreach import DepthCamera, Scene
from octoreach import exploration as ex
robot = octoreach.robots.load("ur5")
chain = robot.chain("base_link", "tool0")
s = Scene()
s.add_box((-2, -2, -0.05), (2, 2, 0))
s.add_crate((0.35, 0.2, 0.0), (0.6, 0.5, 0.22), 0.02)
s.add_closed_box((0.45, -0.2, 0.0), (0.7, 0.1, 0.25), 0.02, "-x", 0.1, 0.1)
s.add_closed_box((0.2, -0.55, 0.0), (0.45, -0.3, 0.2), 0.02, "+z", 0.1, 0.1)
s.add_board((0.65, 0.15, 0.0), (0.7, 0.55, 0.3))
cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, noise=0.002, seed=0)
start = ex.look_at((0.0, 0.0, 0.75), (0.45, 0.0, 0.1))
base_pose = robot.link_poses(robot.home())[chain.base_link]
t0 = time.time()
orc = ex.observable_cells(s, chain=chain, robot=robot, base_pose=base_pose)
print(f"oracle {time.time()-t0:.1f} s: observable {orc.fraction:.1%} of {len(orc.points)} interior points")
for second in (True, False):
    for seed in (0, 1):
        t0 = time.time()
        cover = []
        r = ex.explore(s, cam, start, robot=robot, chain=chain, min_utility=ex.STOP_UTILITY, patience=ex.STOP_PATIENCE,
                       max_views=40, resolution=0.025, capability_map="auto", second_look=second, seed=seed,
                       on_view=lambda row, emap, info: cover.append(orc.share(emap)))
        rat = ex.seen_expected_ratios(r.rows)
        print(f"second_look={second} seed {seed}: {r.stop_reason} after {len(r.rows)} views, {time.time()-t0:.0f} s, "
              f"observable seen after 5/10/end {ex.coverage_after(cover, 5):.1%} / {ex.coverage_after(cover, 10):.1%} / "
              f"{cover[-1]:.1%}, views to 90 % {ex.views_to_reach(cover, 0.9)}, under 0.1: {sum(x < 0.1 for x in rat)} of "
              f"{len(rat)}, invalid {sum(not x.physically_valid for x in r.rows)}", flush=True)
