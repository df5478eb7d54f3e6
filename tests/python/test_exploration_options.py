"""The next-best-view seam: the loop's settings are one C++ preset read by Python, explore()'s keywords map
onto it, and the results of next_best_view, score_views and view_gains are read-only classes with the same
field names everywhere and to_dict(). Coarse maps, small images."""
import numpy as np
import pytest

from octoreach import DepthCamera, ExplorationMap, ExploreOptions, NbvOptions, next_best_view, score_views, view_gains
from octoreach import exploration as ex
from octoreach.exploration._options import explore_options

FOV = np.deg2rad(58.0)
VIEW_FIELDS = ("void_cells", "unknown_cells", "frontier_cells", "expected_void", "expected_unknown",
               "expected_frontier", "expected_enclosed_void", "expected_gain", "utility_dm3")


def test_the_loop_reads_its_settings_from_the_cpp_preset():
    loop, paper = NbvOptions.exploration_loop(), NbvOptions()
    assert (loop.max_valid_poses, loop.max_candidate_cells) == (100, 800)
    assert (loop.enclosure_power, loop.unexposed_weight, loop.min_distance) == (2.0, 0.2, 0.05)
    assert (paper.enclosure_power, paper.unexposed_weight, paper.min_distance) == (0.0, 1.0, 0.0)
    o = ExploreOptions()
    assert o.search.max_valid_poses == loop.max_valid_poses and o.search.enclosure_power == loop.enclosure_power
    # the stop rule is on by default, its threshold from the sensor and the cell size, the same for the benchmark
    assert (o.min_utility, o.patience) == (None, 3) == (ex.STOP_UTILITY, ex.STOP_PATIENCE)
    assert o.stop_threshold(DepthCamera(64, 48, FOV, 4.0), 0.025) == pytest.approx(48 * 36 * 0.025 / 4.0)
    b = ExploreOptions.benchmark()
    assert (b.min_utility, b.patience) == (o.min_utility, o.patience)
    p = ExploreOptions.paper_stop()  # the paper's rule: utility 0
    assert (p.min_utility, p.patience) == (0.0, 1) and p.stop_threshold(DepthCamera(64, 48, FOV, 4.0), 0.025) == 0.0
    assert ex.FAILED_VIEW_RADIUS == o.failed_view_radius
    assert not hasattr(ex, "LOOP_ENCLOSURE_POWER")


def test_explore_keywords_map_onto_the_options():
    base = ExploreOptions.benchmark()
    base.min_utility = 10.0
    o = explore_options(base, max_valid_poses=20, candidates=60, score_size=(24, 18), seed=4, min_utility=2.0,
                        workspace_box=None, second_look=False)
    assert (o.search.max_valid_poses, o.sampled_poses, o.search.score_width, o.search.score_height) == (20, 60, 24, 18)
    assert (o.search.seed, o.min_utility, o.second_look, o.patience) == (4, 2.0, False, 3)
    assert base.search.max_valid_poses == 100 and base.min_utility == 10.0  # a copy: the caller's stays
    with pytest.raises(TypeError, match="bogus"):
        explore_options(bogus=1)
    with pytest.raises(TypeError, match="options"):
        explore_options({"max_views": 3})
    for bad, match in ((dict(max_views=0), "max_views"), (dict(max_views=True), "max_views"),
                       (dict(patience=1.5), "patience"), (dict(min_utility=-1.0), "min_utility"),
                       (dict(candidates=0), "sampled_poses"), (dict(unexposed_share=2.0), "unexposed_share"),
                       (dict(aimed_distance=(1.0, 0.3)), "aimed_distance")):
        with pytest.raises(ValueError, match=match):
            explore_options(**bad)


def test_explore_with_an_options_object_is_explore_with_keywords():
    scene = ex.paper_scene(1)
    start = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    kw = dict(resolution=0.08, robot=True, capability_map=None)
    o = ExploreOptions.benchmark()
    o.max_views, o.search.max_valid_poses, o.search.score_width, o.search.score_height = 2, 5, 16, 12
    o.aimed_poses, o.low_aimed_poses, o.last_poses = 40, 40, 40
    a = ex.explore(scene, DepthCamera(64, 48, FOV, 3.0), start, o, **kw)
    b = ex.explore(scene, DepthCamera(64, 48, FOV, 3.0), start, max_views=2, max_valid_poses=5, score_size=(16, 12),
                   min_utility=ex.STOP_UTILITY, patience=ex.STOP_PATIENCE, aimed_poses=40, low_aimed_poses=40,
                   last_poses=40, **kw)
    assert [r.pose for r in a.rows] == [r.pose for r in b.rows] and a.stop_reason == b.stop_reason
    assert o.search.chain is None and o.max_views == 2  # explore works on a copy


def _small_map():
    scene = ex.closed_box_scene("+y", 0.16)
    emap = ExplorationMap(resolution=0.05, search_space=ex.scene_region(scene))
    cam = DepthCamera(80, 60, FOV, 3.0)
    for eye in ((0.0, -0.3, 0.9), (1.6, -0.3, 0.9)):
        T = ex.look_at(eye, (0.8, 0.0, 0.2))
        emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    return emap, cam


def test_results_are_read_only_classes_with_the_same_fields_everywhere():
    emap, cam = _small_map()
    r = next_best_view(emap, cam, NbvOptions.exploration_loop(), workspace_sphere=((0.8, 0.0, 0.3), 1.2))
    assert r.ranked and r.best is not None and r.gain == "frontier_void"
    with pytest.raises(AttributeError):
        r.best.expected_void = 0.0
    for f in VIEW_FIELDS:  # the best view's fields under the same names
        assert getattr(r, f) == getattr(r.best, f), f
    # the ranking is the one order: ranks_before holds between neighbours, best_by picks its first
    from octoreach import _core
    assert all(not _core.ranks_before(b, a) for a, b in zip(r.ranked, r.ranked[1:]))
    most = max(v.expected_void for v in r.ranked)
    assert r.best_by("expected_void").expected_void == most and r.best_by().expected_gain == r.best.expected_gain
    with pytest.raises(ValueError, match="expected_void"):
        r.best_by("volume")
    d = r.to_dict()
    assert d["expected_gain"] == r.expected_gain and d["ranked"][0]["expected_enclosed_void"] == r.best.expected_enclosed_void
    np.testing.assert_array_equal(d["best_pose"], r.best_pose)
    # score_views: the same fields, per pose as arrays and one by one; the best valid view is the search's order
    far = np.eye(4)
    far[:3, 3] = (5.0, 5.0, 5.0)  # outside the workspace sphere
    poses = np.array([v.pose for v in r.ranked[:6]] + [far])
    sv = score_views(emap, cam, poses, NbvOptions.exploration_loop(), workspace_sphere=((0.8, 0.0, 0.3), 1.2))
    assert len(sv) == 7 and sv.status[-1] == "outside_workspace" and list(sv.valid) == [v.valid for v in sv]
    for f in VIEW_FIELDS:
        np.testing.assert_array_equal(getattr(sv, f), [getattr(v, f) for v in sv], err_msg=f)
    assert sv.best_by().expected_gain == max(v.expected_gain for v in sv if v.valid)
    assert set(sv.to_dict()) >= set(VIEW_FIELDS) | {"valid", "status", "pose", "q", "gain", "pass_probability"}
    assert sv[-1].status == sv.status[-1] and sv[0].q is None
    with pytest.raises(IndexError):
        sv[7]
    # view_gains: the gains and the p it used, the same names
    g = view_gains(emap, cam, r.best_pose)
    assert g.void_cells == r.void_cells and g.expected_void == pytest.approx(r.expected_void)
    assert g.expected_enclosed_void == g.expected_void  # no void weights in view_gains
    assert set(g.to_dict()) == {"void_cells", "unknown_cells", "frontier_cells", "expected_void", "expected_unknown",
                                "expected_frontier", "expected_enclosed_void", "pass_probability",
                                "void_pass_probability"}
