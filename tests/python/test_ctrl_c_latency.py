"""Ctrl-C stops every long call within half a second, and what the call used stays usable: next-best-view
search and scoring, capability sampling, polygon and surface map construction and depth capture (the other
map builds, IK, pose sampling and OctoMap loading: test_robustness.py).

Each case runs in a child process; a shell started by the child sleeps, prints the wall-clock time and sends
SIGINT to the child, which notes the time it catches KeyboardInterrupt (octoreach.Cancelled inside a call):
the difference is the latency, whatever runs on the main thread (calls that keep the GIL included). These
tests are left out under the sanitizers (`-k "not ctrl_c"`: the bound is meaningless there)."""
from __future__ import annotations

import re

from robust_util import run_python

BOUND = 0.5  # seconds from the signal to the exception

_CHILD = """
import os, signal, subprocess, sys, time
import numpy as np, octoreach as o
signal.signal(signal.SIGINT, signal.default_int_handler)
signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT])
{setup}
killer = subprocess.Popen(["sh", "-c", "sleep {delay}; date +%s.%N; kill -INT {{}}".format(os.getpid())],
                          stdout=subprocess.PIPE, text=True)
try:
{call}
    print("FINISHED", flush=True)
    sys.exit(0)
except KeyboardInterrupt as e:
    caught = time.time()
    sent = float(killer.stdout.read().strip())
    print("CANCELLED", type(e).__name__, caught - sent, flush=True)
killer.wait()
{after}
print("USABLE", flush=True)
"""


def ctrl_c_latency(setup: str, call: str, after: str, delay: float = 0.5) -> tuple[float, str]:
    """Seconds from SIGINT to KeyboardInterrupt in `call` (run after `setup`, followed by `after`); the name of
    the exception caught."""
    code = _CHILD.format(setup=setup, call="\n".join("    " + ln for ln in call.strip().splitlines()), delay=delay,
                         after=after)
    child = run_python(code, timeout=180)
    assert not child.hung, f"still running 180 s after the start (Ctrl-C at {delay} s): {child.stdout[-500:]}"
    assert "FINISHED" not in child.stdout, "the call finished before the signal: make the case longer"
    assert child.returncode == 0 and "USABLE" in child.stdout, (child.returncode, child.stdout, child.stderr[-2000:])
    m = re.search(r"CANCELLED (\w+) ([0-9.e-]+)", child.stdout)
    assert m, child.stdout
    return float(m.group(2)), m.group(1)


def assert_quick(setup: str, call: str, after: str, label: str) -> None:
    """Ctrl-C lands inside the long call (octoreach.Cancelled, not a KeyboardInterrupt raised by Python between
    two calls of a loop, which any call shorter than the bound would give) and stops it within BOUND."""
    latency, kind = ctrl_c_latency(setup, call, after)
    if latency > BOUND or kind != "Cancelled":  # once more: a loaded machine can hold a process off the CPU
        latency, kind = ctrl_c_latency(setup, call, after)
    print(f"{label}: {kind} {latency:.3f} s after SIGINT")
    assert kind == "Cancelled", f"{label}: the signal was caught by Python between calls ({kind}), not by the call"
    assert latency <= BOUND, f"{label}: {latency:.2f} s from Ctrl-C to {kind}"


_MAP = """
m = o.ExplorationMap(resolution=0.04)
rng = np.random.default_rng(0)
m.insert(rng.uniform([1, -1, 0], [2, 1, 1], (40000, 3)), [0, 0, 0.5])
cam = o.DepthCamera(64, 48, 1.0, 3.0)
"""


def test_ctrl_c_stops_next_best_view():
    assert_quick(_MAP, """
o.next_best_view(m, cam, max_candidate_cells=100000, orientations_per_cell=10, max_valid_poses=1000000,
                 score_width=256, score_height=192)
""", """
o.next_best_view(m, cam, max_candidate_cells=20, orientations_per_cell=2, max_valid_poses=5)
m.insert(rng.uniform([1, -1, 0], [2, 1, 1], (100, 3)), [0, 0, 0.5])
""", "next_best_view")


def test_ctrl_c_stops_view_scoring():
    assert_quick(_MAP + """
poses = np.repeat(o._core.look_at([0, 0, 0.5], [1.5, 0, 0.5])[None], 200000, axis=0)
""", """
o.score_views(m, cam, poses, score_width=128, score_height=96)
""", """
o.score_views(m, cam, poses[:3])
""", "score_views")


def test_ctrl_c_stops_capability_sampling():
    assert_quick("""
chain = o.robots.test_arm().chain('base_link', 'tool0')
""", """
o.CapabilityMap.build(chain, resolution=0.2, directions=8, fk_samples=2**31, progress=False)
""", """
assert o.CapabilityMap.build(chain, resolution=0.3, directions=8, progress=False).voxel_count > 0
""", "capability sampling")


def test_ctrl_c_stops_polygon_construction():
    # a comb of long teeth at the vertex limit, built again and again (the call keeps the GIL)
    assert_quick("""
n = o._core.limits['polygon_vertices']
teeth = (n - 3) // 4
comb = [(x, y) for i in range(teeth) for x, y in ((2 * i, 0.1), (2 * i, 9.0), (2 * i + 1, 9.0), (2 * i + 1, 0.1))]
comb = np.array(comb + [(2 * teeth, 0.1), (2 * teeth, 0.0), (0, 0.0)]) * [0.01, 0.1]
comb = np.c_[comb, np.full(len(comb), 0.7)]
""", """
while True:
    o.Surface(comb)
""", """
assert o.Surface.rectangle(1, 1, 0.7).area == 1
""", "polygon construction")


def test_ctrl_c_stops_depth_capture():
    # Every ray tests 32 walls and, with a 1 m range, reaches none: one capture takes over a second with no output
    # to convert (a call that returned many points would spend most of its time unpolled, in that conversion),
    # so the signal lands inside the first call's rays rather than after them.
    side = 4096
    assert_quick(f"""
scene = o.Scene()
for k in range(32):
    scene.add_box([-3 - 0.1 * k, -3, 0], [-2.95 - 0.1 * k, 3, 2])
cam = o.DepthCamera({side}, {side}, 1.5, 1.0)
aside = o._core.look_at([0, 0, 1], [0, 2, 1])
""", """
while True:
    cam.capture(scene, aside)
""", """
assert len(o.DepthCamera(32, 24, 1.0, 4.0).capture(scene, o._core.look_at([0, 0, 1], [-3, 0, 1]))) > 0
assert cam.width == 4096
""", "depth capture")


def test_ctrl_c_stops_surface_map_construction():
    assert_quick("""
robot = o.robots.test_arm()
cap = o.CapabilityMap.build(robot.chain('base_link', 'tool0'), resolution=0.1, directions=48, progress=False, seed=3)
table = o.Surface.rectangle(3.0, 3.0, 0.4)
""", """
o.SurfaceMap.build(robot, cap, table, resolution=0.02, theta_bins=32, z_range=(0, 0), progress=False)
""", """
assert o.SurfaceMap.build(robot, cap, o.Surface.rectangle(0.6, 0.4, 0.4, x=0.55), resolution=0.2, theta_bins=8,
                          z_range=(0, 0), progress=False).resolution == 0.2
""", "surface map construction")
