"""Beyond the voids: the unknown cells of the search space outside the hull of the occupied cells (the layer above
a table's objects) draw views (ExploreOptions.beyond_voids) where a view expects more unknown cells of the search
space (voids included) than frontier-void's view expects void cells, and once the voids are spent, counted only
where a ray through them can return; a view beyond the voids that saw nothing closes the way. Coarse maps, small
images."""
import numpy as np
import pytest

from octoreach import DepthCamera, ExplorationMap, ExploreOptions, Scene, view_gains
from octoreach._core import ChoiceMemory, choose_view
from octoreach import exploration as ex

FOV = np.deg2rad(58.0)
RES = 0.05
SPACE = np.array([[0.55, -0.35, 0.35], [1.05, 0.35, 0.85]])  # the layer above the table top


def _table(post=True):
    """A table top (0.6-1.0 x -0.3-0.3 m at 0.4 m) floating over nothing, a post on its far edge."""
    s = Scene()
    s.add_box((0.6, -0.3, 0.37), (1.0, 0.3, 0.4))
    if post:
        s.add_box((0.95, -0.03, 0.4), (1.0, 0.03, 0.8))
    return s


def _mapped(scene, eye=(0.0, 0.0, 0.9)):
    emap = ExplorationMap(resolution=RES, search_space=SPACE)
    cam = DepthCamera(96, 72, FOV, 3.0)
    side = ex.look_at(eye, (0.9, 0.0, 0.55))
    emap.insert(cam.capture(scene, side), side[:3, 3], cam.max_range)
    return emap, cam


def test_an_unknown_cell_outside_the_voids_counts_only_where_its_ray_can_return():
    """A depth camera clears only the cells in front of what a ray returns from. With p = 1 no unknown cell can
    stop a ray, so an unknown cell outside the voids counts only in front of an occupied cell: looking over the
    table into nothing counts none of them, the same look with a wall known behind counts those in front of it, and
    a look down onto the table top counts the layer above it."""
    over = ex.look_at((0.2, 0.0, 0.82), (1.0, 0.0, 0.82))  # level, over the table (its lowest rays pass its edge)
    down = ex.look_at((0.8, 0.0, 1.6), (0.8, 0.0, 0.4))
    open_map, cam = _mapped(_table(post=False))
    walled, _ = _mapped(_table(post=False))
    wall = Scene()
    wall.add_box((1.6, -1.5, 0.0), (1.65, 1.5, 1.5))
    near_wall = ex.look_at((1.3, 0.0, 0.8), (1.6, 0.0, 0.8))  # the wall seen from behind the table: S stays unknown
    walled.insert(cam.capture(wall, near_wall), near_wall[:3, 3], cam.max_range)

    def outside_voids(emap, pose):
        g = view_gains(emap, cam, pose, 24, 18, pass_probability=1.0)
        return g.expected_unknown - g.expected_void, g.unknown_cells - g.void_cells

    counted, met = outside_voids(open_map, over)
    assert met > 50 and counted == 0
    counted_walled, met_walled = outside_voids(walled, over)
    assert counted_walled > 50 and met_walled > 50  # those in front of the part of the wall the map knows
    counted_down, _ = outside_voids(open_map, down)
    assert counted_down > 50


def test_the_loop_looks_beyond_spent_voids():
    """A table top with low objects and a search space reaching 0.45 m above it: the hull of what the views see
    ends at the objects' tops, the layer above them is not void. Once the voids are spent frontier-void with
    beyond_voids takes views beyond them and knows nearly all of the layer before it stops by itself; without, the
    loop ends when the voids are spent."""
    s = _table(post=False)
    s.add_box((-2.0, -2.0, -0.05), (2.0, 2.0, 0.0))  # the floor
    for x in (0.6, 0.96):
        for y in (-0.3, 0.26):
            s.add_box((x, y, 0.0), (x + 0.04, y + 0.04, 0.37))
    s.add_crate((0.65, -0.25, 0.4), (0.8, -0.05, 0.55), 0.02)
    s.add_box((0.82, 0.05, 0.4), (0.95, 0.2, 0.5))
    cam = DepthCamera(64, 48, FOV, 3.0, noise=0.002, seed=1)
    runs, beyond = {}, {False: [], True: []}
    for on in (False, True):
        runs[on] = ex.explore(s, cam, ex.look_at((0.3, 0.0, 1.0), (0.8, 0.0, 0.45)), robot=True, resolution=RES,
                              search_space=SPACE, beyond_voids=on, max_views=20, max_valid_poses=20,
                              score_size=(24, 18), aimed_poses=60, low_aimed_poses=60, last_poses=300, seed=0,
                              on_view=lambda row, emap, info, on=on: beyond[on].append(bool(info.get("beyond"))))
    r = runs[True]
    assert r.stop_reason != "view budget", r.table()
    assert any(beyond[True]) and [row.beyond for row in r.rows] == beyond[True], r.table()
    assert not any(beyond[False])
    assert r.observed_share > 0.9 > runs[False].observed_share + 0.1, (r.table(), runs[False].table())


def test_a_view_beyond_the_voids_competes_with_the_voids_view_at_every_choice():
    """While voids remain, beyond_voids takes the view beyond them (the unknown strategy's sampled poses, the same
    seed, ranked by a coarse first score as the aimed looks are) where it expects more unknown cells of the search
    space (voids included) than frontier-void's view expects void cells, and frontier-void's view otherwise: a small
    crate under a tall layer (the layer wins) and a large crate under a thin one. The memory says which was taken;
    the choice counts once. The layer's unknown cells draw the view beyond; under the thin layer the rule decides
    either way (the views beyond see the crate's void too)."""
    setups = {"layer": ((0.65, -0.25, 0.4), (0.8, -0.05, 0.55), [[0.55, -0.35, 0.35], [1.05, 0.35, 0.85]]),
              "void": ((0.62, -0.28, 0.4), (0.98, 0.28, 0.58), [[0.6, -0.3, 0.4], [1.0, 0.3, 0.65]])}
    taken = {}
    for name, (lo, hi, space) in setups.items():
        s = _table(post=False)
        s.add_crate(lo, hi, 0.02)
        emap = ExplorationMap(resolution=RES, search_space=np.array(space))
        cam = DepthCamera(96, 72, FOV, 3.0)
        side = ex.look_at((0.0, 0.0, 0.9), (0.8, 0.0, 0.5))
        emap.insert(cam.capture(s, side), side[:3, 3], cam.max_range)
        assert emap.void_cell_count > emap.sealed_void_cell_count
        opts, base = ExploreOptions(), np.eye(4)[None]
        assert opts.beyond_voids  # on by default
        opts.beyond_voids = False
        voids_view = choose_view(emap, cam, base, 0, opts, ChoiceMemory())
        unknown_view = choose_view(emap, cam, base, 0, opts, ChoiceMemory(), "unknown")
        opts.beyond_voids, m = True, ChoiceMemory()
        c = choose_view(emap, cam, base, 0, opts, m)
        assert m.choices == 1 and m.last_beyond == c.beyond and m.beyond_misses == 0
        assert voids_view.found and not voids_view.stop and unknown_view.found and not c.stop
        threshold = opts.stop_threshold(cam, RES)
        assert m.low_views == (voids_view.utility <= threshold)  # the row counts frontier-void's utility
        if c.beyond:  # its utility is its expected unknown cells of the search space, scored in full
            assert c.utility > max(voids_view.utility, threshold), name
            assert c.utility == pytest.approx(c.view.expected_unknown) and c.view.expected_unknown > 0, name
            # on these maps the coarse first score finds the view that scoring every sampled pose in full finds
            assert np.allclose(c.view.pose, unknown_view.view.pose) and c.utility == unknown_view.utility, name
        else:
            assert np.allclose(c.view.pose, voids_view.view.pose) and c.utility == voids_view.utility, name
        taken[name] = c.beyond
    assert taken["layer"]


def test_a_view_beyond_the_voids_that_saw_nothing_closes_the_way():
    """The way beyond the voids stays open while its views see more than the stop threshold of the search space's
    unknown cells: after `patience` in a row that saw none the choice is frontier-void's own (a bare floor has no
    void: the loop ends), and a view that saw more opens the way again."""
    s = Scene()
    s.add_box((-2.0, -2.0, -0.05), (2.0, 2.0, 0.0))
    emap = ExplorationMap(resolution=RES, search_space=np.array([[0.3, -0.5, 0.0], [1.5, 0.5, 0.5]]))
    cam = DepthCamera(64, 48, FOV, 3.0)
    first = ex.look_at((0.0, -1.0, 1.0), (0.5, -0.8, 0.0))  # sees a corner of the space
    emap.insert(cam.capture(s, first), first[:3, 3], cam.max_range)
    assert emap.void_cell_count == 0
    opts, m, base = ExploreOptions(), ChoiceMemory(), np.eye(4)[None]
    opts.beyond_voids = False  # the paper's voids only: none, so nothing to explore
    c = choose_view(emap, cam, base, 0, opts, m)
    assert c.stop and c.stop_reason == "nothing to explore"
    opts.beyond_voids, m = True, ChoiceMemory()
    for _ in range(opts.patience):
        c = choose_view(emap, cam, base, 0, opts, m)
        assert c.beyond and not c.stop and m.last_beyond and c.view.expected_void == 0
        m.last_space_seen = 0  # that view saw nothing
    c = choose_view(emap, cam, base, 0, opts, m)
    assert c.stop and c.stop_reason == "nothing to explore" and m.beyond_misses == opts.patience
    m.last_space_seen = 1000  # a view saw plenty
    c = choose_view(emap, cam, base, 0, opts, m)
    assert c.beyond and m.beyond_misses == 0


def test_no_view_beyond_the_voids_of_an_unbounded_search_space():
    """A map without a search space has no bounded space to look at beyond its voids: the choice is frontier-void's
    own, not an error."""
    s = Scene()
    s.add_box((-2.0, -2.0, -0.05), (2.0, 2.0, 0.0))
    emap = ExplorationMap(resolution=RES)
    cam = DepthCamera(64, 48, FOV, 3.0)
    first = ex.look_at((0.0, -1.0, 1.0), (0.5, -0.8, 0.0))
    emap.insert(cam.capture(s, first), first[:3, 3], cam.max_range)
    opts = ExploreOptions()
    assert opts.beyond_voids
    c = choose_view(emap, cam, np.eye(4)[None], 0, opts, ChoiceMemory())
    assert not c.beyond
