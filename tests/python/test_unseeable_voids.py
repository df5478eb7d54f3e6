"""Void cells no view can reveal stop drawing views: a void component that touches only occupied cells (the
inside of a solid whose faces have been seen) is sealed, a box with a slit is not; and the default stop rule
ends a scene of solids by itself. Coarse maps, small images."""
import numpy as np

from octoreach import DepthCamera, ExplorationMap, ExploreOptions, Scene, score_views
from octoreach._core import ChoiceMemory, choose_view, expect_view
from octoreach import exploration as ex

FOV = np.deg2rad(58.0)
RES = 0.05
LO, HI = np.array([0.6, -0.2, 0.1]), np.array([1.0, 0.2, 0.5])  # the block / box, floating above nothing
CENTRE = (LO + HI) / 2
EYES = [CENTRE + 0.9 * d for d in np.vstack([np.eye(3), -np.eye(3)])]  # all six sides


def _mapped(scene, margin=0.1):
    emap = ExplorationMap(resolution=RES, search_space=np.array([LO - margin, HI + margin]))
    cam = DepthCamera(96, 72, FOV, 3.0)
    for eye in EYES:
        T = ex.look_at(eye, CENTRE, 0.0) if abs(eye[0] - CENTRE[0]) + abs(eye[1] - CENTRE[1]) > 1e-9 else \
            ex.look_at(eye, CENTRE + np.array([1e-3, 0, 0]))
        emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    return emap, cam


def _around(n=120, seed=0):
    """Cameras all around the box, 0.5-0.9 m from its centre, looking at it."""
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return np.array([ex.look_at(CENTRE + r * u, CENTRE) for u, r in zip(d, rng.uniform(0.5, 0.9, n))])


def test_the_inside_of_a_solid_block_is_never_worth_a_view():
    s = Scene()
    s.add_box(LO, HI)
    emap, cam = _mapped(s)
    assert emap.void_cell_count > 0 and emap.sealed_void_cell_count == emap.void_cell_count
    v = score_views(emap, cam, _around(), unknown_is_obstacle=False, unknown_pass_probability=1.0)
    assert np.nanmax(np.where(v.valid, v.expected_void, 0.0)) == 0.0
    voids_only = ExploreOptions()
    voids_only.beyond_voids = False
    c = choose_view(emap, cam, np.eye(4)[None], 0, voids_only, ChoiceMemory())
    assert c.stop and c.stop_reason == "nothing to explore"
    # the search space reaches 0.1 m around the block, and the rays of the six views that passed beside the block
    # returned nothing: that margin is still unknown, so frontier-void (by default) looks beyond the voids, never
    # at the inside
    opts = ExploreOptions()
    c = choose_view(emap, cam, np.eye(4)[None], 0, opts, ChoiceMemory())
    assert not c.stop and c.beyond and c.view.expected_void == 0 and c.utility > 0
    # a search space that is the block itself (and a centimetre): nothing to explore
    emap, cam = _mapped(s, margin=0.01)
    assert emap.sealed_void_cell_count == emap.void_cell_count > 0
    c = choose_view(emap, cam, np.eye(4)[None], 0, opts, ChoiceMemory())
    assert c.stop and c.stop_reason == "nothing to explore" and not c.beyond


def test_the_inside_of_a_box_with_a_slit_is_worth_a_view():
    s = Scene()
    s.add_closed_box(LO, HI, 0.02, "+z", 0.3, 0.12)  # a slit in the lid, 2 cells wide
    emap, cam = _mapped(s)
    assert emap.void_cell_count > 0 and emap.sealed_void_cell_count == 0
    v = score_views(emap, cam, _around(), unknown_is_obstacle=False, unknown_pass_probability=1.0)
    assert np.nanmax(np.where(v.valid, v.expected_void, 0.0)) > 5.0


def test_a_scene_of_solids_stops_by_itself_with_the_defaults():
    s = Scene()
    s.add_box((-1.0, -1.0, -0.05), (2.0, 1.0, 0.0))  # the floor
    s.add_box((0.6, -0.15, 0.0), (0.9, 0.15, 0.3))
    cam = DepthCamera(64, 48, FOV, 3.0)
    r = ex.explore(s, cam, ex.look_at((0.3, 0.0, 0.8), (0.75, 0.0, 0.1)), robot=True, resolution=RES,
                   max_views=12, max_valid_poses=20, score_size=(24, 18), aimed_poses=60, low_aimed_poses=60,
                   last_poses=200)
    assert r.stop_reason != "view budget", r.table()
    assert len(r.rows) <= 6, r.table()


def test_a_line_of_sight_that_returned_nothing_draws_no_view_along_it():
    """A table top with a post on its far edge and nothing under or behind them: the camera's rays over the top end
    on nothing, so its inserts leave the void cells above the top unknown. After one view from the side that
    expected them and missed, views from that eye or from farther back along the same lines count them 0; a view
    from nearer along them (its rays reach farther past the cells) and a view from above, whose rays end on the
    top, still count them. (Before, each miss only lowered their seeability by the ray weight.)"""
    s = Scene()
    s.add_box((0.6, -0.3, 0.37), (1.0, 0.3, 0.4))
    s.add_box((0.95, -0.03, 0.4), (1.0, 0.03, 0.8))
    emap = ExplorationMap(resolution=RES, search_space=np.array([[0.55, -0.35, 0.35], [1.05, 0.35, 0.85]]))
    cam = DepthCamera(96, 72, FOV, 3.0)
    side, above = ex.look_at((0.0, 0.0, 0.9), (0.9, 0.0, 0.55)), ex.look_at((0.8, 0.05, 1.6), (0.8, 0.0, 0.4))
    emap.insert(cam.capture(s, side), side[:3, 3], cam.max_range)
    turned = ex.look_at((0.0, 0.0, 0.9), (0.9, 0.1, 0.6))  # the same eye, turned: the same lines
    back, nearer = (ex.look_at(e, (0.9, 0.0, 0.55)) for e in ((-0.3, 0.0, 0.99), (0.3, 0.0, 0.81)))

    def expected():
        poses = np.array([side, turned, back, nearer, above])
        return score_views(emap, cam, poses, unknown_is_obstacle=False).expected_void

    first = expected()
    assert emap.void_cell_count > 20 and first.min() > 5
    expect_view(emap, cam, side)
    emap.insert(cam.capture(s, side), side[:3, 3], cam.max_range)
    after = expected()
    # the seeability alone keeps a third of the side's expectation; the lines leave only the cells that have the
    # table behind them (a pixel's ray may have missed them)
    assert after[:3].max() < 0.2 * first[:3].min(), (first, after)
    assert after[3] > 2 * after[2] and after[4] > 1, (first, after)  # nearer (its rays reach farther); above
