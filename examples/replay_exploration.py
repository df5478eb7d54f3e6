"""Exploration in a robot's own loop, replayed from a recording.

A robot's loop gives an Explorer each cloud with the camera pose it was taken from and asks for the next view.
Here the clouds come from a file: `record` runs the simulator once (explore) and saves every view's cloud and
camera pose; `replay` feeds them to an Explorer, view by view, as the robot's loop would, and returns the
views the Explorer proposes (the same views explore() took, when the settings agree).

Run: python examples/replay_exploration.py recording.npz
"""
from __future__ import annotations

import sys

import numpy as np

from octoreach import DepthCamera
from octoreach import exploration as ex

# One setup for the recording and the replay: a free camera inside a sphere around a box with an opening.
SETTINGS = dict(workspace_sphere=((0.8, 0.0, 0.4), 1.0), max_valid_poses=20, aimed_poses=60, low_aimed_poses=60,
                last_poses=200, score_size=(24, 18), max_views=12, resolution=0.05)


def camera() -> DepthCamera:
    return DepthCamera(80, 60, np.deg2rad(58.0), 3.0, seed=1)


def record(path: str):
    """Explores the scene in the simulator and saves each view's cloud and camera pose to `path` (.npz)."""
    scene = ex.closed_box_scene("+z", 0.16)
    start = ex.look_at((0.3, -0.5, 0.9), (0.8, 0.0, 0.2))
    result = ex.explore(scene, camera(), start, search_space=ex.scene_region(scene), **SETTINGS)
    cam = camera()  # a fresh camera: the same clouds, view by view
    clouds = [cam.capture(scene, np.asarray(p)) for p in result.poses]
    np.savez(path, poses=np.array(result.poses), region=ex.scene_region(scene),
             sizes=np.array([len(c) for c in clouds]), points=np.vstack(clouds))
    return result


def replay(path: str) -> list:
    """The robot's loop over a recording: integrate each cloud, ask for the next view; returns the proposed
    views (NextView) in order."""
    data = np.load(path)
    explorer = ex.Explorer(camera(), data["region"], **SETTINGS)
    clouds = np.split(data["points"], np.cumsum(data["sizes"])[:-1])
    proposed = []
    for cloud, pose in zip(clouds, data["poses"]):
        explorer.integrate(cloud, pose)
        view = explorer.next_view()
        proposed.append(view)
        print(f"view {explorer.views}: expected gain {view.expected_gain:.1f}"
              + (f", stop: {view.stop_reason}" if view.stop else ""))
        if view.stop:
            break
    return proposed


if __name__ == "__main__":
    path = sys.argv[1] if len(sys.argv) > 1 else "recording.npz"
    record(path)
    replay(path)
