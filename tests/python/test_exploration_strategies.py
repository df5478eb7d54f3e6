"""Exploration harness: the observable-interior oracle against hand reasoning, generated USAR scenes,
every strategy terminates with a stop reason, "nothing to explore", no chosen view reaches through
unknown space, the visibility model's expected count against the seen count, pictures, bad input.
Coarse maps (5 cm) and small images keep this to about a minute on two cores."""
import numpy as np
import pytest

from octoreach import DepthCamera, ExplorationMap, NbvOptions, Scene
from octoreach import exploration as ex
from octoreach import testing

FOV = np.deg2rad(58.0)
RES = 0.05


def _floor(s, half=2.0):
    s.add_box((-half, -half, -0.05), (half, half, 0.0))


def _sealed_box(s, lo, hi, wall):
    """A box closed on every side (six slabs of thickness `wall`); its inside is recorded as an interior."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    for axis in range(3):
        for side in (0, 1):
            a, b = lo.copy(), hi.copy()
            if side == 0:
                b[axis] = lo[axis] + wall
            else:
                a[axis] = hi[axis] - wall
            s.add_box(a, b)
    s.add_interior(lo + wall, hi - wall)


def _inside(points, box):
    lo, hi = map(np.asarray, box)
    return np.all((points >= lo) & (points <= hi), axis=1)


def test_oracle_sealed_box_unobservable_open_crate_observable_from_above():
    s = Scene()
    _floor(s)
    # walls thicker than a cell: no cell holding an inside point can hold the outer surface
    _sealed_box(s, (0.6, -0.35, 0.0), (0.95, -0.05, 0.35), 0.07)
    s.add_crate((0.6, 0.1, 0.0), (0.95, 0.45, 0.25), 0.02)
    obs = testing.observable_cells(s, resolution=RES, joint_samples=300, aimed_samples=300, width=48, height=36)
    assert obs.poses_valid > 100
    sealed, crate = (_inside(obs.points, box) for box in s.interiors)
    assert sealed.sum() > 10 and crate.sum() > 50
    assert not obs.observable[sealed].any()  # nothing sees into a sealed box
    assert obs.observable[crate].mean() > 0.95  # the crate's inside is seen from above
    # the kept poses are the oracle's answer: what each one's capture sees, together, is what is observable
    assert obs.poses.shape == (obs.poses_valid, 4, 4)
    union = np.zeros(len(obs.points), bool)
    for T in obs.poses:
        union |= obs.sees(T, s)
    np.testing.assert_array_equal(union, obs.observable)
    # an exploration map that knows nothing sees nothing; one that knows everything sees all that is observable
    empty = ExplorationMap(resolution=RES)
    assert obs.share(empty) == 0.0 and obs.seen_unobservable(empty) == 0


def test_oracle_honours_the_arm_reach():
    # two boxes beyond the shoulder's reach in x; walls thicker than a cell. One opens towards the robot
    # (-x): a camera held in front of the opening sees in. The other opens away (+x): the camera would
    # have to stand behind it, 1.3 m from the shoulder, so its inside is unobservable.
    s = Scene()
    _floor(s)
    s.add_closed_box((1.0, -0.45, 0.0), (1.35, -0.1, 0.35), 0.07, "-x", 0.16, 0.16)
    s.add_closed_box((1.0, 0.1, 0.0), (1.35, 0.45, 0.35), 0.07, "+x", 0.16, 0.16)
    obs = testing.observable_cells(s, resolution=RES, joint_samples=300, aimed_samples=600, width=48, height=36)
    towards, away = (_inside(obs.points, box) for box in s.interiors)
    assert towards.sum() > 10 and away.sum() > 10
    assert obs.observable[towards].mean() > 0.3
    assert not obs.observable[away].any()


def test_a_robot_standing_on_the_floor_is_not_in_collision_with_it():
    """example-robot-data's Panda at the origin: its base link's bottom lies at z = 0, on the scene's floor
    (touching it). The checks of views against the true scene test the links the arm moves
    (Chain.moved_links), so the oracle finds the open crate observable from above (before: no pose at
    all was collision-free), while the arm itself still may not touch the floor or the crate."""
    from octoreach import Obstacles, robots

    robot = robots.load("panda")
    chain = robot.chain("panda_link0", "panda_hand")
    moved = chain.moved_links
    assert "panda_link0" not in moved and {"panda_link7", "panda_hand"} <= set(moved)
    # the chain's own answer (C++, also the search's ground check) against the masks link by link
    assert moved == [n for n in robot.collision_links if chain.link_mask(n) != 0]
    # a chain from link 2 moves neither link 1 nor link 2 (its first joint is joint 3), but all beyond
    assert robot.chain("panda_link2", "panda_hand").moved_links == [n for n in moved
                                                                   if n not in ("panda_link1", "panda_link2")]
    s = Scene()
    _floor(s)
    s.add_crate((0.4, -0.15, 0.0), (0.65, 0.15, 0.2), 0.02)
    floor = Obstacles()
    floor.add_box((4.0, 4.0, 0.05), np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, -0.025], [0, 0, 0, 1.0]]))
    assert robot.in_collision(robot.home(), floor)  # all links: the base touches the floor
    assert not robot.in_collision(robot.home(), floor, links=moved)
    base = robot.link_poses(robot.home())[chain.base_link]
    obs = testing.observable_cells(s, chain=chain, robot=robot, base_pose=base, resolution=RES, joint_samples=300,
                              aimed_samples=300, width=48, height=36)
    assert obs.poses_valid > 50 and obs.fraction > 0.8
    # the arm itself still may not touch the floor: the hand's flange 2 cm above it, looking down
    down = chain.ik(ex.look_at((0.5, 0.0, 0.02), (0.5, 0.0, -1.0)), mode="approach", attempts=20)
    assert down is not None
    assert robot.in_collision(chain.to_robot_configuration(down), floor, links=moved)


def test_usar_scenes_are_seeded_and_hide_the_target_in_a_container():
    a, b, c = testing.usar_scene(3), testing.usar_scene(3), testing.usar_scene(4)
    assert [tuple(map(tuple, x)) for x in a.scene.boxes] == [tuple(map(tuple, x)) for x in b.scene.boxes]
    assert [tuple(map(tuple, x)) for x in a.scene.boxes] != [tuple(map(tuple, x)) for x in c.scene.boxes]
    for seed in range(6):
        u = testing.usar_scene(seed)
        assert len(u.containers) >= 1 and len(u.scene.interiors) == len(u.containers)
        lo, hi = u.target
        inner = u.scene.interiors[u.target_container]
        assert np.all(lo >= np.asarray(inner[0]) - 1e-9) and np.all(hi <= np.asarray(inner[1]) + 1e-9)
        assert u.scene.solid(((lo + hi) / 2)[None])[0]
        if any(c["kind"] == "closed_box" for c in u.containers):
            assert u.containers[u.target_container]["kind"] == "closed_box"
        faces = {c["face"] for c in u.containers}
        assert faces <= set(testing.usar_scenes.FACES)
    faces = {c["face"] for s in range(12) for c in testing.usar_scene(s).containers if c["kind"] == "closed_box"}
    assert len(faces) >= 3  # openings on different faces
    # a point on the target counts, the floor next to it does not
    u = testing.usar_scene(0)
    lo, hi = u.target
    on_top = np.array([[(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2]]])
    beside = np.array([[lo[0] - 0.01, lo[1], lo[2]]])
    assert u.target_points(on_top) == 1 and u.target_points(beside) == 0
    with pytest.raises(ValueError, match="containers"):
        testing.usar_scene(0, containers=0)
    with pytest.raises(ValueError, match="target"):
        ex.points_on(np.zeros(3), on_top)


def _small_run(scene, strategy, **kw):
    cam = DepthCamera(80, 60, FOV, 3.0, noise=0.002, seed=1)
    start = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    opts = dict(robot=True, strategy=strategy, resolution=RES, max_views=4, candidates=60, max_valid_poses=10,
                score_size=(24, 18))
    opts.update(kw)
    return ex.explore(scene, cam, start, **opts)


def _skeleton_points(robot, chain, q, root):
    """Points along the arm's links (between consecutive joint frames, 6 cm kept clear of each joint)."""
    poses = robot.link_poses(chain.to_robot_configuration(q))
    names = [chain.base_link] + [n for n in robot.link_names if n in poses]
    origins = [root @ poses[n] for n in names]
    pts = []
    for A, B in zip(origins, origins[1:]):
        a, b = A[:3, 3], B[:3, 3]
        L = np.linalg.norm(b - a)
        if L > 0.13:
            for t in np.arange(0.06, L - 0.06, 0.01):
                pts.append(a + (b - a) * t / L)
    return np.array(pts).reshape(-1, 3)


@pytest.mark.parametrize("strategy", ex.STRATEGIES)
def test_every_strategy_terminates_and_its_views_stay_in_observed_space(strategy):
    scene = ex.paper_scene(1)
    robot, chain = ex.explorer_robot()
    base = ex.arm_base_pose(robot, chain)
    root = ex.physics.robot_root(robot, chain, base)
    region = ex.scene_region(scene)
    checked = []

    def on_view(row, emap, info):
        if info["best_pose"] is None:
            return
        eye = np.asarray(info["best_pose"])[:3, 3]
        if _inside(eye[None], region)[0]:
            assert emap.state(eye[None])[0] == 1  # in the search space the camera stands in observed-free space
        if info.get("q") is not None:
            pts = _skeleton_points(robot, chain, np.asarray(info["q"]), root)
            inside = _inside(pts, region)
            assert not np.any(emap.state(pts[inside]) == 0), "an arm link passes through unknown space"
        checked.append(row.view)

    r = _small_run(scene, strategy, on_view=on_view)
    assert r.stop_reason in ex.STOP_REASONS and r.strategy == strategy
    assert 1 <= len(r.rows) <= 4
    if r.stop_reason == "view budget":
        assert len(r.rows) == 4
    assert checked, r.table()
    assert r.rows[-1].void_seen is None  # the last chosen view was never taken
    assert all(x.void_seen is not None and x.void_seen >= 0 for x in r.rows[:-1])
    assert all(x.expected_void >= 0 and x.valid_candidates <= x.candidates for x in r.rows)
    shares = [x.interior_share for x in r.rows]
    assert shares == sorted(shares)
    assert "stopped:" in r.table()


def test_min_utility_stops_early_and_says_so():
    r = _small_run(ex.paper_scene(1), "frontier_void", min_utility=1e9, patience=1)
    assert len(r.rows) == 1 and r.stop_reason == "utility below min_utility"
    r = _small_run(ex.paper_scene(1), "frontier_void", min_utility=1e9, patience=2)  # the low view is taken once
    assert len(r.rows) == 2 and r.stop_reason == "utility below min_utility" and r.rows[0].void_seen is not None
    with pytest.raises(ValueError, match="patience"):
        _small_run(ex.paper_scene(1), "frontier_void", patience=0)


def test_a_scene_without_void_ends_at_once():
    """A bare floor: no void cell at first. Frontier-void with the paper's voids only ends at once; with views
    beyond the voids (the default) its views are the ones beyond them (the unknown cells of the search space above
    the floor) until none expects more than the stop threshold (a few cells under the floor's surface may turn void
    on the way, seen from above at a slant)."""
    s = Scene()
    _floor(s)
    cam = DepthCamera(80, 60, FOV, 3.0)
    start = ex.look_at((0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    region = np.array([[0.3, -0.5, 0.0], [1.5, 0.5, 0.5]])
    r = ex.explore(s, cam, start, robot=True, resolution=RES, search_space=region, beyond_voids=False)
    assert r.stop_reason == "nothing to explore" and len(r.rows) == 1
    assert r.rows[0].void_total == 0 and r.rows[0].expected_void == 0
    r = ex.explore(s, cam, start, robot=True, resolution=RES, search_space=region)
    assert r.stop_reason == "nothing to explore" and len(r.rows) < 10, r.table()
    assert r.rows[0].void_total == 0 and sum(row.expected_void for row in r.rows) < 10
    assert r.observed_share > 0.9, r.table()


def test_a_small_scene_ends_by_itself():
    """One open crate in front of the robot: frontier-void stops on its own criterion (utility 0 or
    below a small threshold, or nothing left to explore) well before a generous budget, having seen
    most of the crate's inside."""
    s = Scene()
    _floor(s)
    s.add_crate((0.55, -0.2, 0.0), (0.9, 0.2, 0.25), 0.02)
    r = _small_run(s, "frontier_void", max_views=15, min_utility=5.0)
    assert r.stop_reason in ("utility 0", "utility below min_utility", "nothing to explore"), r.table()
    assert len(r.rows) < 15
    assert r.interior_share > 0.8, r.table()


def test_a_missed_view_lowers_the_seeability_of_what_it_expected_unless_a_seen_surface_explains_it():
    """A sealed box's inside is void behind walls. Three maps take the same first view; then the view from
    the +y side is taken unannounced, announced, or announced and its capture lost (an empty cloud). The
    announced view sees only the +y wall: the void cells it expected stay unknown, but its rays, walked
    again through the updated map, now stop at that wall, so the miss is explained and says nothing about
    other sides: a view from above (through the still unknown top) expects as much as in the unannounced
    map. The lost capture explains nothing: those cells lose seeability, the view from above expects less,
    and the map counts the missed cells."""
    from octoreach import _core

    s = Scene()
    _floor(s)
    _sealed_box(s, (0.6, -0.2, 0.0), (1.0, 0.2, 0.4), 0.02)
    cam = DepthCamera(80, 60, FOV, 4.0)
    side = ex.look_at((0.8, 0.9, 0.25), (0.8, 0.0, 0.2))
    above = ex.look_at((0.8, 0.0, 1.2), (0.8, 0.0, 0.2))
    maps = []
    for mode in ("plain", "announced", "lost"):
        emap = ExplorationMap(resolution=RES, search_space=np.array([[0.5, -0.3, 0.0], [1.1, 0.3, 0.45]]))
        T = ex.look_at((0.0, 0.0, 0.3), (0.8, 0.0, 0.2))
        emap.insert(cam.capture(s, T), T[:3, 3], 4.0)
        assert emap.void_cell_count > 50
        if mode != "plain":
            # announced with p = 1 (every cell on a ray fully expected: a miss rules it out from then on)
            _core.expect_view(emap, cam, side, score_width=24, score_height=18, unknown_pass_probability=1.0)
        cloud = cam.capture(s, side) if mode != "lost" else np.zeros((0, 3))
        emap.insert(cloud, side[:3, 3], 4.0)
        maps.append(emap)
    # a fixed pass probability: the seeability alone (the learned curve also learns from the announced view)
    plain, announced, lost = (_core.view_gains(m, cam, above, 24, 18, 1.0) for m in maps)
    assert _core.missed_cells(maps[0]) == 0 and _core.missed_cells(maps[2]) > 50
    assert _core.missed_cells(maps[1]) < _core.missed_cells(maps[2])
    assert plain.void_cells == announced.void_cells > 0  # the same map, the same raw count
    assert announced.expected_void > 0.95 * plain.expected_void, (plain, announced)
    assert lost.expected_void < 0.9 * plain.expected_void, (plain, lost)
    with pytest.raises(ValueError):
        _core.expect_view(maps[1], cam, np.full((4, 4), np.nan))


def test_expected_void_against_the_void_cells_a_view_turns_known():
    """A pipe seen only from its sides and from behind, with a wall behind its far end: its inside is void, empty
    in reality. A camera in front of its near end casts the score grid's rays (one per pixel) through the void to
    the wall. With unknown space transparent (p = 1) the expected count is the count of void cells those rays
    cross that end on a known surface, so it equals what a capture along the same rays turns known; the learned
    p (< 1) expects less (the void's far cells are weighted down), and a fixed p between scales the count between
    the two."""
    from octoreach import _core

    s = Scene()
    _floor(s)
    for lo, hi in (((0.6, -0.15, 0.38), (1.0, 0.15, 0.4)), ((0.6, -0.15, 0.1), (1.0, 0.15, 0.12)),
                   ((0.6, -0.15, 0.1), (1.0, -0.13, 0.4)), ((0.6, 0.13, 0.1), (1.0, 0.15, 0.4))):
        s.add_box(lo, hi)
    s.add_box((1.6, -1.0, 0.0), (1.62, 1.0, 1.0))
    emap = ExplorationMap(resolution=0.03, search_space=np.array([[0.5, -0.3, 0.0], [1.1, 0.3, 0.5]]))
    low = DepthCamera(160, 120, FOV, 3.0)
    for eye, at in (((0.8, -0.9, 0.3), (0.8, 0.0, 0.25)), ((0.8, 0.9, 0.3), (0.8, 0.0, 0.25)),
                    ((1.3, -0.6, 0.3), (1.6, 0.0, 0.25)), ((1.3, 0.6, 0.3), (1.6, 0.0, 0.25))):
        T = ex.look_at(eye, at)
        emap.insert(low.capture(s, T), T[:3, 3], 3.0)
    assert emap.void_cell_count > 50
    w, h = 80, 60
    T = ex.look_at((0.2, 0.0, 0.25), (0.8, 0.0, 0.25))
    cam = DepthCamera(w, h, FOV, 3.0)

    def gains(p):
        return _core.score_views(emap, cam, np.array([T]), score_width=w, score_height=h, unknown_is_obstacle=False,
                                 unknown_pass_probability=p)

    clear, learned, half = gains(1.0), gains(None), gains(0.5)
    before = emap.centers(emap.void_keys())
    emap.insert(cam.capture(s, T), T[:3, 3], 4.0)
    seen = int(np.count_nonzero(emap.state(before) != 0))
    assert clear.void_cells[0] > 1000 and clear.expected_void[0] <= clear.void_cells[0]
    assert seen == pytest.approx(clear.expected_void[0], rel=0.05), (seen, clear.expected_void[0])
    assert learned.pass_probability < 1.0
    assert 0 < learned.expected_void[0] < clear.expected_void[0]
    assert half.expected_void[0] < clear.expected_void[0]


def test_pictures(tmp_path):
    scene = ex.paper_scene(2)
    emap = ExplorationMap(resolution=RES, search_space=ex.scene_region(scene))
    cam = DepthCamera(80, 60, FOV, 3.0)
    T = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    emap.insert(cam.capture(scene, T), T[:3, 3], 3.0)
    from octoreach.exploration import plots  # a submodule: imported, not an attribute of the package until then

    quads, normals = plots.voxel_faces(np.array([[0, 0, 0], [RES, 0, 0]], float), RES)
    assert len(quads) == 10 and np.allclose(np.abs(normals).sum(1), 1)  # two cubes side by side: 10 faces
    png = ex.plot_map(emap, tmp_path / "v.png", poses=[T], next_pose=ex.look_at((0.3, -0.5, 0.9), (0.9, 0, 0)),
                      camera=cam, region=ex.scene_region(scene))
    assert png.stat().st_size > 10000
    png = ex.plot_coverage({"paper_1": {"frontier_void": [[0.2, 0.9]], "random": [[0.1, 0.4, 0.5]]},
                            "paper_2": {"frontier_void": [[0.3]]}}, tmp_path / "c.png")
    assert png.stat().st_size > 5000
    assert ex.views_to_reach([0.2, 0.95], 0.9) == 2 and ex.views_to_reach([0.2], 0.9) is None
    assert ex.coverage_after([0.2, 0.5], 5) == 0.5


def test_bad_input():
    scene = ex.closed_box_scene()
    cam = DepthCamera(40, 30, FOV, 3.0)
    T = ex.look_at((0.3, 0.0, 1.0), (0.8, 0.0, 0.2))
    with pytest.raises(ValueError, match="frontier_void, random, frontiers, unknown"):
        ex.explore(scene, cam, T, strategy="greedy")
    with pytest.raises(ValueError, match="max_views"):
        ex.explore(scene, cam, T, max_views=0)
    with pytest.raises(ValueError, match="min_utility"):
        ex.explore(scene, cam, T, min_utility=float("nan"))
    with pytest.raises(ValueError, match="start_pose must be a 4x4 pose"):
        ex.explore(scene, cam, np.eye(3))
    with pytest.raises(ValueError, match="start_pose holds NaN or inf"):
        ex.explore(scene, cam, np.full((4, 4), np.nan))
    robot, chain = ex.explorer_robot()
    with pytest.raises(ValueError, match="base_pose holds NaN or inf"):
        ex.Explorer(cam, ex.scene_region(scene), robot=robot, chain=chain, base_pose=np.full((4, 4), np.nan))
    far = np.array([[5.0, 5.0, 0.0], [6.0, 6.0, 1.0]])  # beyond the arm's reach plus the camera's 3 m
    with pytest.raises(ValueError, match="search_space lies .* from the nearest chain base"):
        ex.Explorer(cam, far, robot=True)
    with pytest.raises(ValueError, match="search_space lies"):  # millimetres
        ex.Explorer(cam, 1000 * ex.scene_region(scene), robot=True)
    ex.Explorer(cam, far, robot=True, base_moves=[ex.look_at((5.0, 4.0, 0.0), (5.5, 5.5, 0.0))])  # a base near it
    with pytest.raises(ValueError, match=r"base_moves\[0\]"):
        ex.Explorer(cam, ex.scene_region(scene), robot=robot, chain=chain, base_pose=np.eye(4),
                    base_moves=[np.eye(3)])
    with pytest.raises(ValueError, match="target"):
        ex.explore(scene, cam, T, target=(1, 2, 3))
    with pytest.raises(ValueError, match="resolution"):
        testing.observable_cells(scene, resolution=0.0)


def test_the_visibility_curve_learns_from_announced_views_what_rays_see():
    """Two empty crates seen only from low at their sides: their insides are voids that let rays through
    all the way to the floor, which the geometric model (one pass probability per unknown cell) does not
    expect. A view from above into crate A is announced and taken; the map's learned curve (per unknown
    depth, non-increasing) then expects of the view from above into crate B about what that view sees,
    closer than the geometric weight with the map's void pass probability does."""
    from octoreach import _core

    s = Scene()
    _floor(s)
    s.add_crate((0.6, -0.6, 0.0), (1.0, -0.2, 0.3), 0.02)
    s.add_crate((0.6, 0.2, 0.0), (1.0, 0.6, 0.3), 0.02)
    emap = ExplorationMap(resolution=0.03, search_space=np.array([[0.5, -0.7, 0.0], [1.1, 0.7, 0.35]]))
    cam = DepthCamera(160, 120, FOV, 4.0)
    for eye in ((0.0, 0.0, 0.2), (0.8, -1.3, 0.2), (0.8, 1.3, 0.2), (1.8, 0.0, 0.2)):
        T = ex.look_at(eye, (0.8, 0.0, 0.15))
        emap.insert(cam.capture(s, T), T[:3, 3], 4.0)
    assert emap.void_cell_count > 200
    curve = _core.visibility_curve(emap)
    assert curve["void_expected"].sum() == 0 and len(curve["void_share"]) == 128  # nothing announced yet
    top_a = ex.look_at((0.8, -0.4, 0.9), (0.8, -0.4, 0.0))
    _core.expect_view(emap, cam, top_a)
    emap.insert(cam.capture(s, top_a), top_a[:3, 3], 4.0)
    curve = _core.visibility_curve(emap)
    assert curve["void_expected"].sum() > 50 and curve["void_seen"].sum() > 0
    share = curve["void_share"]
    assert np.all(np.diff(share) <= 1e-12) and 0 < share[0] <= 1  # non-increasing in the depth
    top_b = ex.look_at((0.8, 0.4, 0.9), (0.8, 0.4, 0.0))
    p, pv = emap.pass_probability, emap.void_pass_probability
    geometric = _core.view_gains(emap, cam, top_b, 48, 36, pv).expected_void
    learned = _core.view_gains(emap, cam, top_b, 48, 36).expected_void
    seen = emap.insert(cam.capture(s, top_b), top_b[:3, 3], 4.0)["void_removed"]
    assert seen > 50 and pv < 1 and p < 1
    assert abs(learned / seen - 1) < abs(geometric / seen - 1), (geometric, learned, seen)
    assert 0.67 < learned / seen < 1.5, (geometric, learned, seen)


def _box_seen_once():
    """A closed box with a 16 cm opening in its lid seen once (5 cm cells, a 64 x 48 camera) and
    ExploreOptions with a small search around it: (map, camera, options)."""
    from octoreach import ExplorationMap, ExploreOptions

    scene = ex.closed_box_scene("+z", 0.16)
    emap = ExplorationMap(resolution=0.05, search_space=ex.scene_region(scene))
    cam = DepthCamera(64, 48, np.deg2rad(58.0), 3.0)
    T = ex.look_at((0.3, -0.5, 0.9), (0.8, 0.0, 0.2))
    emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    o = ExploreOptions()
    o.search.workspace_sphere, o.search.max_valid_poses, o.aimed_poses = ((0.8, 0.0, 0.4), 1.0), 20, 60
    return emap, cam, o


def test_views_near_a_failed_view_are_not_chosen_again():
    """After a view that could not be taken (ChoiceMemory.failed_views), the choice keeps FAILED_VIEW_RADIUS
    away from its camera."""
    from octoreach._core import ChoiceMemory, choose_view

    emap, cam, o = _box_seen_once()
    first = choose_view(emap, cam, np.eye(4)[None], 0, o, ChoiceMemory())
    memory = ChoiceMemory()
    memory.failed_views = first.view.pose[:3, 3][None]
    again = choose_view(emap, cam, np.eye(4)[None], 0, o, memory)
    assert again.found and np.linalg.norm(again.view.pose[:3, 3] - first.view.pose[:3, 3]) > ex.FAILED_VIEW_RADIUS


def test_a_low_view_that_saw_more_than_the_threshold_breaks_the_row_of_low_views():
    """The stop rule weighs what a view saw over what it was expected to see: with patience 3 and every view
    low, a memory holding two low views stops at the next choice, unless the last view taken turned more void
    cells known than the threshold (ChoiceMemory.last_void_seen): then the row starts again and this low view
    is its first. The choice reads and clears it; the other baselines' utility counts other cells, so it does
    not apply to them. Explorer.integrate adds up what its inserts took off the void set."""
    from octoreach._core import ChoiceMemory, choose_view

    emap, cam, o = _box_seen_once()
    o.min_utility, o.patience = 1e6, 3

    def choice(seen, strategy="frontier_void"):
        memory = ChoiceMemory()
        memory.low_views, memory.last_void_seen = 2, seen
        c = choose_view(emap, cam, np.eye(4)[None], 0, o, memory, strategy)
        assert memory.last_void_seen is None
        return c, memory

    for seen in (None, 0, 10 ** 6):  # at most the threshold: the row goes on, and ends here
        c, memory = choice(seen)
        assert c.found and c.stop and c.stop_reason == "utility below min_utility", (seen, c.stop_reason)
    for strategy in ("frontier_void", "random"):
        c, memory = choice(10 ** 6 + 1, strategy)
        assert c.found and not c.stop and memory.low_views == 1, strategy
    c, memory = choice(10 ** 6 + 1, "frontiers")
    assert c.stop and memory.low_views == 3

    explorer = ex.Explorer(cam, ex.scene_region(ex.closed_box_scene("+z", 0.16)), resolution=0.05)
    assert explorer._core.memory.last_void_seen is None
    scene = ex.closed_box_scene("+z", 0.16)
    removed = []
    for eye in ((0.3, -0.5, 0.9), (0.8, 0.0, 1.2), (1.3, 0.5, 0.8)):
        T = ex.look_at(eye, (0.8, 0.0, 0.2))
        removed.append(explorer.integrate(cam.capture(scene, T), T)["void_removed"])
    assert removed[1] > 0 and removed[2] > 0, removed
    assert explorer._core.memory.last_void_seen == sum(removed)  # every view so far: none was chosen in between


def test_the_ground_is_an_obstacle_for_the_arm_in_the_loop():
    """The Panda looking straight down with its hand 7 cm above a ground the map has never seen (the map
    knows only the air in front of a wall, seen from the side): the ground lies below the search space,
    where unknown cells are no obstacles, so the pose is a valid view, unless ground_is_obstacle (on in the
    loop's preset) makes the ground an obstacle for the links the arm moves (its fingers reach below z = 0;
    the base, standing on the floor, is not tested against it). 12 cm up the pose is valid either way. The
    ground is the lower of the robot's root (panda_link0 at z = 0) and the search space's floor: a search
    space over a table top (floor 0.3 m) keeps it at 0, a map without a search space has it too, and a Panda on
    a pedestal over the floor's search space reaches below its root."""
    from octoreach import _core, robots

    assert NbvOptions.exploration_loop().ground_is_obstacle and not NbvOptions().ground_is_obstacle
    robot = robots.load("panda")
    chain = robot.chain("panda_link0", "panda_hand")
    s = Scene()
    s.add_box((1.0, -1.0, 0.0), (1.05, 1.0, 0.6))  # a wall, no floor: the map never sees the ground
    cam = DepthCamera(64, 48, FOV, 3.0)

    def mapped(search_space):
        emap = ExplorationMap(resolution=RES, search_space=search_space)
        for z in (0.07, 0.2, 0.35):
            T = ex.look_at((0.0, 0.0, z), (1.0, 0.0, z))
            emap.insert(cam.capture(s, T), T[:3, 3], 3.0)
        return emap

    common = dict(chain=chain, chain_base=np.eye(4), unknown_is_obstacle=False, seed=3)
    low = ex.look_at((0.5, 0.0, 0.07), (0.5, 0.0, -1.0))[None]
    high = ex.look_at((0.5, 0.0, 0.12), (0.5, 0.0, -1.0))[None]
    under_the_layer = ex.look_at((0.5, 0.0, 0.2), (0.5, 0.0, -1.0))[None]  # below a floor of 0.3 m, above the ground
    floor = mapped(np.array([[0.2, -0.5, 0.0], [1.1, 0.5, 0.6]]))
    assert _core.score_views(floor, cam, low, **common).status == ["valid"]
    assert _core.score_views(floor, cam, low, ground_is_obstacle=True, **common).status == ["arm_collision"]
    assert _core.score_views(floor, cam, high, ground_is_obstacle=True, **common).status == ["valid"]
    layer = mapped(np.array([[0.2, -0.5, 0.3], [1.1, 0.5, 0.6]]))
    assert _core.score_views(layer, cam, low, ground_is_obstacle=True, **common).status == ["arm_collision"]
    assert _core.score_views(layer, cam, under_the_layer, ground_is_obstacle=True, **common).status == ["valid"]
    free = mapped(None)
    assert _core.score_views(free, cam, low, **common).status == ["valid"]
    assert _core.score_views(free, cam, low, ground_is_obstacle=True, **common).status == ["arm_collision"]
    pedestal = np.eye(4)
    pedestal[2, 3] = 0.5  # the Panda on a 0.5 m pedestal over the floor search space: the ground stays at 0
    below_the_root = ex.look_at((0.4, 0.0, 0.2), (0.4, 0.0, -1.0))[None]  # the hand 0.3 m below the pedestal's top
    assert _core.score_views(floor, cam, below_the_root, ground_is_obstacle=True, chain=chain, chain_base=pedestal,
                             unknown_is_obstacle=False, seed=3).status == ["valid"]
