"""How frontier-void chooses a view: its rays end at the box of the void cells with the very
same void figures, void cells with no observed free neighbour weigh less (unexposed_weight), and the
second look aims along lines of sight at the exposed faces of voids. Coarse maps, small images."""
import numpy as np
import pytest

from octoreach import DepthCamera, ExplorationMap, Scene, score_views
from octoreach import exploration as ex
from octoreach.exploration import candidate_poses
from octoreach.exploration.candidate_poses import aimed_poses, in_line_of_sight, sample_poses

FOV = np.deg2rad(58.0)


def _surveyed(scene, eyes, target, res=0.05, image=(120, 90)):
    cam = DepthCamera(image[0], image[1], FOV, 3.0)
    emap = ExplorationMap(resolution=res, search_space=ex.scene_region(scene))
    for eye in eyes:
        T = ex.look_at(eye, target)
        emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    return emap, cam


def _crate_and_block():
    """An open crate and a solid block beside it, seen from three sides (as the enclosure test)."""
    scene = Scene()
    scene.add_box((-2, -2, -0.05), (2, 2, 0))
    scene.add_crate((0.6, -0.2, 0), (1.0, 0.2, 0.3), 0.02)
    scene.add_box((0.6, 0.5, 0), (0.85, 0.75, 0.35))
    emap, cam = _surveyed(scene, [(0.0, 0.0, 0.5), (0.8, -0.9, 0.45), (0.0, 0.6, 0.5)], (0.8, 0.0, 0.15), res=0.03,
                          image=(160, 120))
    return scene, emap, cam


def test_frontier_void_rays_end_at_the_void_box_with_the_same_void_figures():
    """With the frontier_void gain a ray ends where it leaves the box of the map's void cells: the void
    figures of every pose are bit for bit those of whole rays (gain "unknown" walks whole rays), the
    unknown figures count less (what lies beyond is not walked), and a map with no void cell expects
    nothing."""
    scene = ex.paper_scene(1)
    region = ex.scene_region(scene)
    emap, cam = _surveyed(scene, [(0.45, 0.0, 1.1), (0.7, 0.9, 0.8)], (0.9, 0.0, 0.0))
    P = sample_poses(np.random.default_rng(0), region, box=np.array([region[0] - 0.6, region[1] + 0.6]), n=120)
    clipped = score_views(emap, cam, P, gain="frontier_void", unknown_is_obstacle=False)
    whole = score_views(emap, cam, P, gain="unknown", unknown_is_obstacle=False)
    assert np.count_nonzero(whole.void_cells) > 30
    np.testing.assert_array_equal(clipped.void_cells, whole.void_cells)
    np.testing.assert_array_equal(clipped.expected_void, whole.expected_void)
    assert np.all(clipped.unknown_cells <= whole.unknown_cells)
    assert np.sum(clipped.unknown_cells) < 0.8 * np.sum(whole.unknown_cells)
    # the ranking gain at enclosure power 0 is the plain expected void, clipped or not
    np.testing.assert_array_equal(clipped.expected_gain, whole.expected_void)
    # no void: nothing counts for this gain (the unknown gain still sees the unknown space)
    floor = Scene()
    floor.add_box((-2, -2, -0.05), (2, 2, 0))
    free = ExplorationMap(resolution=0.05, search_space=region)
    T = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    free.insert(cam.capture(floor, T), T[:3, 3], cam.max_range)
    assert free.void_cell_count == 0
    none = score_views(free, cam, P[:5], gain="frontier_void", unknown_is_obstacle=False)
    assert np.all(none.expected_void == 0) and np.all(none.unknown_cells == 0)
    assert np.any(score_views(free, cam, P[:5], gain="unknown", unknown_is_obstacle=False).unknown_cells > 0)


def test_exposed_cells_by_hand():
    """_core.exposed_cells: a cell with an observed free cell among its 26 neighbours (checked one neighbour at a
    time); the inside of a solid block seen from outside has none, the crate's void (seen from the sides
    only) has some next to the air the views saw through its open top."""
    from octoreach import _core

    scene, emap, _ = _crate_and_block()
    keys = np.asarray(emap.void_keys())
    C = np.asarray(emap.centers(keys))
    e = np.asarray(_core.exposed_cells(emap, keys))
    assert e.dtype == bool and len(e) == len(keys)
    # by hand: the 26 neighbour centres, one at a time
    some = np.random.default_rng(1).choice(len(C), 200, replace=False)
    for i in some:
        nb = [C[i] + emap.resolution * (np.array(d) - 1) for d in np.ndindex(3, 3, 3) if d != (1, 1, 1)]
        assert e[i] == bool(np.any(np.asarray(emap.state(np.array(nb))) == 1))
    block = np.all((C > (0.66, 0.56, 0.06)) & (C < (0.79, 0.69, 0.29)), axis=1)  # a cell deep inside the block
    lo, hi = map(np.asarray, scene.interiors[0])
    crate = np.all((C > lo) & (C < hi), axis=1)
    assert block.sum() >= 8 and crate.sum() > 50
    assert not e[block].any() and 0.1 < e[crate].mean() < 1


def test_unexposed_void_cells_weigh_less_in_the_ranking():
    """unexposed_weight w scales the void cells with no observed free neighbour: the ranking gain is
    linear in w, equal to the enclosure-weighted gain at w = 1 (the default); both views see exposed and
    unexposed cells, and the view of the solid block's unseen side keeps under half its gain at w = 0.
    The plain expected void cells do not change; values outside [0, 1] are refused."""
    _, emap, cam = _crate_and_block()
    views = np.stack([ex.look_at((0.8, 0.0, 0.9), (0.8, 0.0, 0.0)),      # down into the crate
                      ex.look_at((1.5, 0.62, 0.3), (0.7, 0.62, 0.15))])   # at the block's unseen +x side
    g = {w: score_views(emap, cam, views, enclosure_power=2.0, unexposed_weight=w, unknown_is_obstacle=False)
         for w in (0.0, 0.5, 1.0)}
    default = score_views(emap, cam, views, enclosure_power=2.0, unknown_is_obstacle=False)
    np.testing.assert_array_equal(g[1.0].expected_gain, default.expected_gain)
    np.testing.assert_allclose(g[0.5].expected_gain, 0.5 * (g[0.0].expected_gain + g[1.0].expected_gain),
                               rtol=1e-9)
    for w in (0.0, 0.5):
        np.testing.assert_array_equal(g[w].expected_void, g[1.0].expected_void)
    kept = g[0.0].expected_gain / g[1.0].expected_gain
    assert np.all(g[1.0].expected_gain > 0) and np.all((kept > 0) & (kept < 1)) and kept[1] < 0.5, kept
    for bad in (-0.1, 1.5, float("nan")):
        with pytest.raises(ValueError, match="unexposed_weight"):
            score_views(emap, cam, views, unexposed_weight=bad)


def test_aimed_poses_see_their_target_past_no_known_surface(monkeypatch):
    """in_line_of_sight by hand (a wall the map has seen between target and eye: no; beside it: yes;
    unknown cells on the way do not block), and the cameras of the second look meet unknown space
    before any known surface along their optical axes.""" 
    scene = Scene()
    scene.add_box((-2, -2, -0.05), (2, 2, 0))
    scene.add_box((0.7, -0.4, 0.0), (0.75, 0.4, 0.6))  # a wall
    scene.add_crate((0.8, -0.2, 0.0), (1.1, 0.2, 0.3), 0.02)  # behind it
    emap, cam = _surveyed(scene, [(0.0, 0.0, 0.8), (0.9, -1.0, 0.9), (0.9, 1.0, 0.9)], (0.9, 0.0, 0.15))
    target = np.array([[0.95, 0.0, 0.1]])
    assert not in_line_of_sight(emap, target, [[0.2, 0.0, 0.2]])[0]    # through the wall
    assert in_line_of_sight(emap, target, [[0.95, 0.0, 1.0]])[0]       # from above, through the open top
    assert len(in_line_of_sight(emap, np.zeros((0, 3)), np.zeros((0, 3)))) == 0
    def unknown_first(P):
        """Share of the poses whose optical axis meets unknown space before any known surface."""
        t = np.arange(0.0, 1.0, 0.25 * emap.resolution)
        first = [np.asarray(emap.state(T[:3, 3] + t[:, None] * T[:3, 2])) for T in P]
        return np.mean([s[np.argmax(s != 1)] == 0 for s in first])

    P = aimed_poses(np.random.default_rng(0), emap, sphere=((0.6, 0.0, 0.6), 1.0), n=150)
    assert len(P) > 20
    # without the line of sight (every direction passes): far more cameras look at a known surface first
    monkeypatch.setattr(candidate_poses, "in_line_of_sight", lambda m, a, b: np.ones(len(a), bool))
    blind = aimed_poses(np.random.default_rng(0), emap, sphere=((0.6, 0.0, 0.6), 1.0), n=150)
    assert unknown_first(P) > 0.8 and unknown_first(P) > unknown_first(blind) + 0.15, \
        (unknown_first(P), unknown_first(blind))


def test_a_view_is_low_only_when_none_on_offer_expects_more():
    """With the ranking weighted (enclosure, unexposed cells at 0) the view it ranks first may expect fewer
    void cells than another valid view: when every view is low (widen_below above them all), the choice
    is the view with the most expected void cells among the search's ranked views and the aimed poses,
    after the harder look (ExploreOptions.low_aimed_poses more aimed poses); its gains are those of its pose."""
    from octoreach import next_best_view
    from octoreach.exploration.strategies import choose_view
    from test_exploration import _box_seen_from_three_sides, view_settings

    emap, cam, region, sphere_of = _box_seen_from_three_sides()
    options = dict(min_distance=0.05, enclosure_power=2.0, unexposed_weight=0.0)
    r = next_best_view(emap, cam, view_settings(**options).search, seed=3, workspace_sphere=sphere_of(None))
    ranked = [v.expected_void for v in r.ranked]
    assert len(ranked) > 5 and max(ranked) > ranked[0]  # the weighted ranking's first is not the largest
    assert r.best_by("expected_void").expected_void == max(ranked)
    c = choose_view("frontier_void", emap, cam, [None], 0, sphere_of, view_settings(1e9, **options), 3, region)
    assert c.details.get("harder") and c.utility >= max(ranked)
    again = score_views(emap, cam, c.pose[None], workspace_sphere=sphere_of(None), min_distance=0.05)
    assert again.valid[0] and again.expected_void[0] == pytest.approx(c.utility)
    # not low: the ranking gain decides as before (no harder look)
    high = choose_view("frontier_void", emap, cam, [None], 0, sphere_of, view_settings(0.0, **options), 3, region)
    assert not high.details.get("harder") and high.rank_gain >= r.ranked[0].expected_enclosed_void


def test_the_search_tests_the_links_the_arm_moves_against_the_map():
    """example-robot-data's xArm 7 at the origin, its base standing on the floor. Once the map has seen the
    floor under the base, the base touches the floor's occupied cells in every configuration: the search
    tested every link against the map and found no valid view at all. It
    now tests the links the arm moves, as the loop's physical check and the oracle do, so a pose above an
    open crate is a view, while the arm is still refused where its moved links meet a seen surface."""
    from octoreach import Obstacles, robots

    robot = robots.load("xarm7")
    chain = robot.chain("link_base", "link_eef")
    scene = Scene()
    scene.add_box((-2, -2, -0.05), (2, 2, 0))
    scene.add_crate((0.35, -0.15, 0.0), (0.6, 0.15, 0.2), 0.02)
    emap, cam = _surveyed(scene, [(0.5, 0.6, 0.9), (0.5, -0.6, 0.9), (0.9, 0.0, 0.9)], (0.0, 0.0, 0.0))
    assert emap.state(np.array([[0.0, 0.0, -0.02]]))[0] == 2  # the floor under the base is seen
    floor_cells = Obstacles()
    floor_cells.add_points(emap.cells("occupied"), emap.resolution)
    home = robot.home()
    assert robot.in_collision(home, floor_cells)  # every link: the base touches the seen floor
    assert not robot.in_collision(home, floor_cells, links=chain.moved_links)
    common = dict(chain=chain, chain_base=np.eye(4), unknown_is_obstacle=False, min_distance=0.05, seed=3)
    above = ex.look_at((0.47, 0.0, 0.55), (0.47, 0.0, 0.0))[None]
    r = score_views(emap, cam, above, **common)
    assert r.status == ["valid"], r.status
    q = chain.to_robot_configuration(np.asarray(r.q[0]))
    assert robot.in_collision(q, floor_cells) and not robot.in_collision(q, floor_cells, links=chain.moved_links)
    # poses all around: the moved links still meet the seen floor and crate in some of them
    P = sample_poses(np.random.default_rng(0), ex.scene_region(scene), sphere=((0.0, 0.0, 0.27), 0.7), n=200)
    status = list(score_views(emap, cam, P, score_invalid=False, **common).status)
    assert status.count("valid") > 10 and status.count("arm_collision") > 10, status


def test_the_last_low_view_before_the_loop_would_stop_gets_the_rays_out_of_every_void_cell():
    """The loop's memory counts low views in a row (the choice takes the last chance when a low view would end
    the loop, patience's last): with patience 3 and every view low, the first two low views are taken and the
    third ends the loop."""
    from test_exploration_strategies import _small_run

    r = _small_run(ex.paper_scene(1), "frontier_void", min_utility=1e9, patience=3, max_views=5)
    assert r.stop_reason == "utility below min_utility" and len(r.rows) == 3, (r.stop_reason, len(r.rows))


def test_a_choice_that_ends_the_loop_has_taken_the_last_chance():
    """A run that ends because the choice found no valid view (or only one of utility 0) has taken the last
    chance first, as a run ending on its last low view does: replayed into a session with patience 1 (every
    low choice takes the last chance, same seeds), the same map gives the same stop. A closed box of the
    scene families: its run takes views that only the looks before a low view found (more aims, rays out of
    the box's void cells) and ends when they find none."""
    from octoreach import testing
    from octoreach.exploration.robot import explorer_capability_map, explorer_robot
    from octoreach.testing import scene_families

    inst = testing.family_instances("closed_boxes", 1, 3)[0]
    cam = DepthCamera(160, 120, FOV, 4.0, noise=0.0, seed=0)
    settings = dict(robot=True, resolution=0.025, seed=0, capability_map=explorer_capability_map(explorer_robot()[1]))
    r = ex.explore(inst.scene, cam, scene_families.start_pose(), search_space=inst.search_space, max_views=60,
                   **settings)
    assert r.stop_reason in ("no valid view", "utility 0", "utility below min_utility"), r.stop_reason
    assert all(row.physically_valid for row in r.rows)  # every view was taken: the replay is the same session
    replay = ex.Explorer(cam, inst.search_space, patience=1, **settings)
    for pose in r.poses:
        replay.integrate(cam.capture(inst.scene, pose), pose)
    view = replay.next_view()
    assert view.stop and view.stop_reason == r.stop_reason, (view.stop_reason, view.expected_gain, r.stop_reason)
