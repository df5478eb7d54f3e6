"""The Explorer: exploration in the user's own loop (clouds or depth images in, next views out). Bad input is
refused with the explorer unchanged; a replayed recording gives the views explore() took. Coarse maps, small
images."""
import os
import re
import sys

import numpy as np
import pytest

from octoreach import ExplorationMap
from octoreach import exploration as ex

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "examples"))
import replay_exploration  # noqa: E402


def _explorer():
    scene = ex.closed_box_scene("+z", 0.16)
    e = ex.Explorer(replay_exploration.camera(), ex.scene_region(scene), **replay_exploration.SETTINGS)
    return scene, e


def test_bad_input_is_refused_and_the_explorer_stays_unchanged():
    scene, e = _explorer()
    T = ex.look_at((0.3, -0.5, 0.9), (0.8, 0.0, 0.2))
    e.integrate(replay_exploration.camera().capture(scene, T), T)
    before = (e.views, e.map.void_cell_count, e.map.frontier_cell_count)
    pts = np.array([[0.8, 0.0, 0.2], [np.nan, 0.0, 0.2]])
    with pytest.raises(ValueError, match="points row 1 is not finite .* drop those rows, or integrate the depth image"):
        e.integrate(pts, T)
    with pytest.raises(ValueError, match="points row 0"):
        e.integrate(np.array([[np.inf, 0.0, 0.0]]), T)
    bent = T.copy()
    bent[:3, :3] *= 1.1
    with pytest.raises(ValueError, match="camera_pose"):
        e.integrate(pts[:1], bent)
    with pytest.raises(ValueError, match="depth image must be 60 x 80"):
        e.integrate(depth=np.ones((48, 64), np.float32), camera_pose=T)
    with pytest.raises(ValueError, match="depth image pixel"):
        e.integrate(depth=np.full((60, 80), np.nan, np.float32), camera_pose=T)
    with pytest.raises(ValueError, match="must hold metres as floats, got dtype uint16"):  # a 16UC1 image, in mm
        e.integrate(depth=np.full((60, 80), 1500, np.uint16), camera_pose=T)
    assert (e.views, e.map.void_cell_count, e.map.frontier_cell_count) == before
    with pytest.raises(ValueError, match="search_space must be finite"):
        ex.Explorer(replay_exploration.camera(), [[0, 0, 0], [np.nan, 1, 1]])
    for box, got in ((np.zeros(6), "(6,)"), (np.zeros((3, 3)), "(3, 3)"), (np.zeros((2, 3, 1)), "(2, 3, 1)")):
        for make in (lambda b: ex.Explorer(replay_exploration.camera(), b), lambda b: ExplorationMap(search_space=b)):
            with pytest.raises(ValueError, match=rf"search_space must have shape \(2, 3\): rows lo and hi, got shape {re.escape(got)}"):
                make(box)
    with pytest.raises(TypeError, match="'max_view': not a field of ExploreOptions.*did you mean 'max_views'"):
        ex.Explorer(replay_exploration.camera(), ex.scene_region(scene), max_view=15)


def test_a_depth_image_is_the_cloud_it_shows():
    """A wall 1 m in front of the camera: the depth image integrates as the cloud of its pixels would."""
    _, a = _explorer()
    _, b = _explorer()
    T = ex.look_at((0.8, -1.2, 0.4), (0.8, 0.0, 0.4))
    depth = np.ones((60, 80), np.float32)
    depth[:5] = 0.0  # no return
    a.integrate(depth=depth, camera_pose=T)
    f = 0.5 * 80 / np.tan(0.5 * np.deg2rad(58.0))
    v, u = np.mgrid[5:60, 0:80]
    rays = np.stack([(u + 0.5 - 40) / f, (v + 0.5 - 30) / f, np.ones_like(u, float)], -1).reshape(-1, 3)
    pts = rays @ T[:3, :3].T + T[:3, 3]
    b.integrate(pts, T)
    occupied_a, occupied_b = a.map.cells("occupied"), b.map.cells("occupied")
    assert len(occupied_a) > 50 and np.array_equal(occupied_a, occupied_b)
    assert np.allclose(occupied_a[:, 1], -0.2, atol=0.05)  # on the wall 1 m ahead, y = -0.2


def test_a_replayed_recording_gives_the_views_explore_took(tmp_path):
    path = str(tmp_path / "recording.npz")
    result = replay_exploration.record(path)
    proposed = replay_exploration.replay(path)
    assert len(proposed) == len(result.poses)
    for view, pose in zip(proposed[:-1], result.poses[1:]):
        np.testing.assert_allclose(view.camera_pose, pose, atol=1e-9)
    assert proposed[-1].stop and proposed[-1].stop_reason == result.stop_reason
    assert result.stop_reason != "view budget", result.table()  # the defaults stop by themselves


@pytest.mark.parametrize("first", ["nothing", "an empty cloud"])
def test_before_anything_is_seen_no_camera_stands_in_the_search_space(first):
    """Safe views: every cell of the search space no insert has reached is unknown, so a view asked for before a
    capture (or after one that returned no point) puts the camera outside the search space, never in it."""
    scene = ex.closed_box_scene("+z", 0.16)
    region = ex.scene_region(scene)
    robot, chain = ex.explorer_robot()
    e = ex.Explorer(replay_exploration.camera(), region, robot=robot, chain=chain, base_pose=np.eye(4),
                    resolution=0.05, max_valid_poses=20)
    start = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    if first == "an empty cloud":
        e.integrate(np.zeros((0, 3)), start)
    view = e.next_view()
    assert not view.stop and view.camera_pose is not None  # a view from outside, into the unseen search space
    eye = view.camera_pose[:3, 3]
    margin = 0.05  # NbvOptions.unknown_margin
    assert np.any(eye < region[0] - margin) or np.any(eye > region[1] + margin), (eye, region)
