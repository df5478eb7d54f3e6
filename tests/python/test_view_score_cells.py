"""A search reads the map's cells through a directory made once per map version (score_views, next_best_view);
view_gains reads them from the map's own tables: the same gains to the bit, with missed cells' seeability in play,
and after the next insert the directory is made again."""
import numpy as np

from octoreach import DepthCamera, score_views, view_gains
from octoreach import exploration as ex
from octoreach._core import missed_cells
from octoreach.exploration.explorer import Explorer

FOV = np.deg2rad(58.0)


def _gains_agree(explorer, cam, poses):
    sv = score_views(explorer.map, cam, poses, gain="unknown", unknown_is_obstacle=False)
    for i, pose in enumerate(poses):
        g = view_gains(explorer.map, cam, pose)
        for name in ("expected_unknown", "expected_void", "expected_frontier", "unknown_cells", "void_cells",
                     "frontier_cells"):
            assert getattr(sv, name)[i] == getattr(g, name), (name, i)
    return sv


def test_a_search_reads_the_same_cells_as_the_map():
    scene = ex.closed_box_scene("-x", 0.16)
    cam = DepthCamera(80, 60, FOV, 3.0, noise=0.002, seed=3)
    explorer = Explorer(cam, ex.scene_region(scene), resolution=0.04, seed=3)
    target = (0.8, 0.0, 0.2)
    poses = np.array([ex.look_at(eye, target) for eye in [(0.2, 0.0, 0.3), (0.8, -0.6, 0.6), (1.3, 0.4, 0.5)]])
    before = None
    for eye in [(0.0, -0.3, 0.9), (0.0, 0.4, 0.7), (1.4, 0.0, 0.8)]:
        pose = ex.look_at(eye, target)
        explorer.integrate(cam.capture(scene, pose), pose)
        sv = _gains_agree(explorer, cam, poses)
        if before is not None:  # the insert changed the map: the directory of the earlier version is not read
            assert not np.array_equal(sv.expected_unknown, before)
        before = sv.expected_unknown.copy()
    assert missed_cells(explorer.map) > 0  # seeability below 1 took part
