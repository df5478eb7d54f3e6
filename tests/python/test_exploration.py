"""Frontier-void exploration: incremental == from scratch, the closed-box case, a short exploration,
bad inputs. Coarse resolutions and small images keep this under a minute on two cores."""
import numpy as np
import pytest

from octoreach import DepthCamera, ExplorationMap, Scene, next_best_view, score_views, view_gains, view_utility
from octoreach import exploration as ex

FOV = np.deg2rad(58.0)


def survey(emap, scene, cam, eyes, target):
    for eye in eyes:
        T = ex.look_at(eye, target)
        emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
        yield T


def test_incremental_equals_from_scratch_after_each_insert():
    scene = ex.paper_scene(2)
    emap = ExplorationMap(resolution=0.05, search_space=ex.scene_region(scene))
    cam = DepthCamera(120, 90, FOV, 3.0, noise=0.002, seed=1)
    eyes = [(0.2, -0.5, 1.0), (0.3, 0.6, 0.9), (1.6, 0.0, 1.0), (0.9, -1.2, 0.8), (0.9, 0.0, 1.5)]
    sizes = []
    for _ in survey(emap, scene, cam, eyes, (0.9, 0.0, 0.1)):
        inc, ref = emap.snapshot(), emap.recompute_from_scratch()
        assert len(inc["frontier_cells"]) > 0
        np.testing.assert_array_equal(inc["frontier_cells"], ref["frontier_cells"])
        assert len(inc["frontier_clusters"]) == len(ref["frontier_clusters"])
        for a, b in zip(inc["frontier_clusters"], ref["frontier_clusters"]):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(inc["void_cells"], ref["void_cells"])
        # clusters partition the void cells
        assert sum(c.size for c in emap.void_clusters()) == len(inc["void_cells"])
        sizes.append(len(inc["void_cells"]))
    assert max(sizes) > 0


def test_same_occupancy_as_stock_octomap():
    import octoreach_bench as _bench

    scene = ex.cluttered_scene()
    cam = DepthCamera(160, 120, FOV, 4.0)
    T = ex.look_at((-0.5, 0.0, 1.2), (1.5, 0.0, 0.0))
    pts = cam.capture(scene, T)
    emap = ExplorationMap(resolution=0.05)
    emap.insert(pts, T[:3, 3], 4.0)
    ref = _bench.stock_insert_point_cloud(pts, T[:3, 3], 4.0, 0.05)
    mine = emap.occupancy_digest()
    assert mine["occupied"] > 100
    assert (mine["free"], mine["occupied"], mine["hash"]) == (ref["free"], ref["occupied"], ref["hash"])


def test_closed_box_one_void_behind_one_frontier_and_the_view_looks_in():
    scene = ex.closed_box_scene("+y", 0.16)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    cam = DepthCamera(160, 120, FOV, 3.0)
    centre = (0.8, 0.0, 0.2)
    # look at the box from outside all round, so only its inside stays unknown
    eyes = [(0.0, -0.3, 0.9), (1.6, -0.3, 0.9), (0.8, -0.9, 0.9), (0.0, 0.6, 0.9), (1.6, 0.6, 0.9)]
    list(survey(emap, scene, cam, eyes, centre))
    lo, hi = map(np.asarray, scene.interiors[0])
    clusters = emap.void_clusters()
    big = max(range(len(clusters)), key=lambda i: clusters[i].size)
    v = clusters[big]
    assert np.all(v.centroid > lo) and np.all(v.centroid < hi)
    assert v.size >= 0.9 * emap.void_cell_count  # one void: the box's inside
    assert v.size >= 0.5 * np.prod((hi - lo) / 0.04)
    fv = [f for f in emap.frontier_voids() if f["void_index"] == big]
    assert len(fv) == 1 and len(fv[0]["frontier_clusters"]) == 1  # behind one frontier cluster
    assert fv[0]["utility"] == pytest.approx(v.size * 0.04 ** 3)
    r = next_best_view(emap, cam, workspace_sphere=((0.8, 0.0, 0.3), 1.0), min_distance=0.05)
    assert r.void_cells > 100 and r.ranked[0].void_cells == r.void_cells
    assert 0 < r.expected_void <= r.void_cells and r.expected_gain == r.expected_void
    assert r.utility_dm3 == pytest.approx(r.expected_void * 0.04 ** 3 * 1000)
    P = r.best_pose
    eye, axis = P[:3, 3], P[:3, 2]
    # the camera stands outside the box in space seen free, no point of an occupied cell nearer than min_distance
    assert not (np.all(eye > lo) and np.all(eye < hi))
    assert emap.state(eye[None])[0] == 1
    gap = np.maximum(np.abs(emap.cells("occupied") - eye) - emap.resolution / 2, 0.0)
    assert np.linalg.norm(gap, axis=1).min() >= 0.05
    d = scene.raycast(eye, axis, 3.0)
    hit = eye + d * axis
    # the optical axis passes through the opening and ends on an inner wall
    assert np.all(hit > lo - 0.03) and np.all(hit < hi + 0.03)
    assert axis[1] < -0.7  # looking into the +y opening
    # the ranked list is ordered by the expected gain and its scores are what view_gains / view_utility give
    gains = [c.expected_gain for c in r.ranked]
    assert gains == sorted(gains, reverse=True)
    assert view_utility(emap, cam, P)[0] == r.void_cells
    g = view_gains(emap, cam, P)
    assert g.void_cells == r.void_cells and g.expected_void == pytest.approx(r.expected_void)


def test_exploration_observes_the_crate_interiors():
    scene = ex.paper_scene(1)
    cam = DepthCamera(160, 120, FOV, 4.0)
    start = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    result = ex.explore(scene, cam, start, robot=True, max_views=6, resolution=0.05, max_valid_poses=20,
                        max_candidate_cells=150)
    shares = [r.interior_share for r in result.rows]
    assert shares == sorted(shares)  # observed space only grows
    # both crates are within the arm's reach from above: most of their inside gets seen
    assert result.interior_share > 0.8, result.table()
    assert result.rows[0].void_total > 0
    assert all(r.integration_s >= 0 and r.search_s >= 0 for r in result.rows)
    assert "utility dm3" in result.table()


def test_plots_and_bt_export(tmp_path):
    scene = ex.closed_box_scene()
    emap = ExplorationMap(resolution=0.05, search_space=ex.scene_region(scene))
    cam = DepthCamera(80, 60, FOV, 3.0)
    poses = list(survey(emap, scene, cam, [(0.1, -0.4, 0.9)], (0.8, 0.0, 0.2)))
    png = ex.plot_map(emap, tmp_path / "map.png", poses=poses)
    assert png.stat().st_size > 10000
    emap.write_bt(str(tmp_path / "map.bt"))
    back = ExplorationMap.from_file(str(tmp_path / "map.bt"))
    assert back.occupancy_digest()["occupied"] == emap.occupancy_digest()["occupied"]
    world = Scene()
    world.load_octomap(str(tmp_path / "map.bt"))  # a .bt file as the world
    T = poses[0]
    assert len(cam.capture(world, T)) > 0.5 * len(cam.capture(scene, T))


def test_bad_inputs():
    emap = ExplorationMap(resolution=0.05)
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        emap.insert(np.zeros((5, 2)), (0, 0, 0), 4.0)
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        emap.insert(np.zeros(3), (0, 0, 0), 4.0)
    with pytest.raises(ValueError, match="finite"):
        emap.insert(np.ones((2, 3)), (np.nan, 0, 0), 4.0)
    with pytest.raises(ValueError, match="outside the map bounds"):
        emap.insert(np.ones((2, 3)), (1e5, 0, 0), 4.0)
    st = emap.insert(np.zeros((0, 3)), (0, 0, 0), 4.0)  # empty cloud: documented no-op
    assert st["points"] == 0 and emap.occupancy_digest()["free"] == 0
    st = emap.insert(np.array([[1.0, 0, 0], [np.nan, 0, 0], [np.inf, 1, 1]]), (0, 0, 0), 4.0)
    assert st["dropped"] == 2 and st["points"] == 1
    assert list(emap.state(np.array([[1.0, 0, 0], [0.5, 0, 0], [-1, 0, 0]]))) == [2, 1, 0]
    with pytest.raises(ValueError, match="resolution"):
        ExplorationMap(resolution=0.0)
    with pytest.raises(OSError):
        Scene().load_octomap("/nonexistent/world.bt")
    with pytest.raises(OSError):
        ExplorationMap.from_file("/nonexistent/map.bt")
    with pytest.raises(ValueError):
        DepthCamera(0, 10, 1.0, 4.0)
    with pytest.raises(ValueError):
        Scene().add_box((1, 0, 0), (0, 1, 1))
    with pytest.raises(ValueError, match="face"):
        Scene().add_closed_box((0, 0, 0), (1, 1, 1), 0.02, "up", 0.1, 0.1)


def test_same_occupancy_as_stock_fine_resolution_noisy_clouds():
    import octoreach_bench as _bench

    scene = ex.cluttered_scene()
    cam = DepthCamera(320, 240, FOV, 4.0, noise=0.003, seed=5)
    for eye, rng in (((-0.8, 0.0, 1.2), 4.0), ((0.3, -1.5, 0.7), 2.5), ((2.0, 1.0, 1.6), -1.0)):
        T = ex.look_at(eye, (1.5, 0.0, 0.0))
        pts = cam.capture(scene, T)
        emap = ExplorationMap(resolution=0.02)
        emap.insert(pts, T[:3, 3], rng)
        ref = _bench.stock_insert_point_cloud(pts, T[:3, 3], rng, 0.02)
        mine = emap.occupancy_digest()
        assert (mine["free"], mine["occupied"], mine["hash"]) == (ref["free"], ref["occupied"], ref["hash"])


def test_capability_map_prunes_view_cells_and_ik_stays_the_final_check():
    from octoreach import CapabilityMap

    scene = ex.paper_scene(1)
    robot, chain = ex.explorer_robot()
    base = robot.link_poses(robot.home())[chain.base_link]
    cmap = CapabilityMap.build(chain, resolution=0.15, directions=20, approach_axis=(0.0, 0.0, 1.0), progress=False)
    cam = DepthCamera(120, 90, FOV, 3.0)
    emap = ExplorationMap(resolution=0.05, search_space=ex.scene_region(scene))
    T = ex.look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    kw = dict(max_valid_poses=10, max_candidate_cells=60, workspace_sphere=((0.0, 0.0, 0.5), 3.0), chain=chain,
              chain_base=base)
    plain = next_best_view(emap, cam, **kw)
    pruned = next_best_view(emap, cam, capability_map=cmap, capability_base=base, capability_orientations=False, **kw)
    assert plain.capability_pruned == 0
    assert pruned.capability_rejected == 0
    # the 3 m sphere lets far cells through; the capability map removes them, and only them
    assert pruned.capability_pruned > 0
    assert pruned.candidate_cells + pruned.capability_pruned == plain.candidate_cells
    assert pruned.best_pose is not None
    inv = np.linalg.inv(base)
    r = cmap.resolution
    for v in pruned.ranked:
        p_arm = (inv @ v.pose)[:3, 3]
        # a cell is pruned only where none of the 8 voxels around it reaches any orientation
        around = (np.floor(p_arm / r - 0.5) + np.array(list(np.ndindex(2, 2, 2))) + 0.5) * r
        assert (cmap.reachability(around) > 0).any()
        assert v.q is not None and len(v.q) == chain.dof  # IK still settled the pose
    # with the orientation check, poses whose optical axis no cell around them reaches (lookup "any") skip IK;
    # every pose kept still has its IK solution
    fast = next_best_view(emap, cam, capability_map=cmap, capability_base=base, **kw)
    assert fast.capability_rejected > 0 and fast.best_pose is not None
    for v in fast.ranked:
        assert v.q is not None and cmap.reachable((inv @ v.pose)[None], lookup="any")[0]
    # an arm standing 10 m away reaches none of the cells
    far = base.copy()
    far[:3, 3] += (10.0, 0.0, 0.0)
    none = next_best_view(emap, cam, capability_map=cmap, capability_base=far, **kw)
    assert none.candidate_cells == 0 and none.best_pose is None
    with pytest.raises(ValueError):
        next_best_view(emap, cam, capability_map=cmap, min_reachability=1.5)


def test_the_capability_map_rejects_a_view_only_where_every_cell_around_it_does():
    """A coarse map's vote drops poses between its cells that IK reaches: the view checks ask the map's "any"
    lookup, so a pose with a reachable cell around it goes on to IK and only one with none is not_reachable."""
    from octoreach import CapabilityMap

    robot, chain = ex.explorer_robot()
    base = robot.link_poses(robot.home())[chain.base_link]
    cmap = CapabilityMap.build(chain, resolution=0.15, directions=20, approach_axis=(0.0, 0.0, 1.0), progress=False)
    rng = np.random.default_rng(4)
    lo, hi = cmap.bounds
    arm = np.array([ex.look_at(e, e + d) for e, d in zip(rng.uniform(lo, hi, (3000, 3)), rng.normal(size=(3000, 3)))])
    vote, anyc = cmap.reachable(arm), cmap.reachable(arm, lookup="any")
    own_voxel_empty = cmap.reachability(arm[:, :3, 3]) == 0
    between = np.flatnonzero(anyc & ~vote)[:40]
    beside = np.flatnonzero(anyc & own_voxel_empty)[:20]  # the voxel holding the camera reaches nothing
    outside = np.flatnonzero(~anyc)[:40]
    assert len(between) == 40 and len(beside) == 20 and len(outside) == 40
    emap = ExplorationMap(resolution=0.05)
    cam = DepthCamera(40, 30, FOV, 3.0)
    kw = dict(capability_map=cmap, capability_base=base, chain=chain, chain_base=base, unknown_is_obstacle=False,
              arm_collisions=False)
    world = base @ arm
    got = np.array(score_views(emap, cam, world[between], **kw).status)
    assert set(got) <= {"valid", "no_ik"}
    # the descents from the solutions of the cells around the poses reach every one that IK with 40 random
    # restarts reaches (free of self-collision: the view check here checks no collision at all)
    _, truth = chain.ik_batch(arm[between], mode="approach", approach_axis=(0.0, 0.0, 1.0), attempts=40,
                              position_tolerance=1e-3, orientation_tolerance=1e-2, self_collision=True, rng_seed=1)
    assert truth.sum() >= 4 and (got[truth] == "valid").all()
    assert set(score_views(emap, cam, world[beside], **kw).status) <= {"valid", "no_ik"}
    assert set(score_views(emap, cam, world[outside], **kw).status) == {"not_reachable"}


def test_views_whose_arm_touches_occupied_cells_are_rejected():
    from octoreach import Obstacles

    scene = ex.paper_scene(2)
    robot, chain = ex.explorer_robot()
    base = robot.link_poses(robot.home())[chain.base_link]
    root = base @ np.linalg.inv(robot.link_poses(robot.home())[chain.base_link])  # footprint at the origin
    cam = DepthCamera(160, 120, FOV, 3.0)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    for T in survey(emap, scene, cam, [(0.45, 0.0, 1.1), (0.4, -0.6, 0.9)], (0.9, 0.0, 0.1)):
        pass
    obstacles = Obstacles()
    obstacles.add_points(emap.cells("occupied"), emap.resolution)  # the same cells, checked independently

    def colliding(result):
        n = 0
        for v in result.ranked:
            q = robot.home().copy()
            q[: chain.dof] = v.q  # the explorer's configuration is its arm's
            n += robot.in_collision(q, obstacles, root)
        return n

    kw = dict(max_valid_poses=40, max_candidate_cells=300, chain=chain, chain_base=base,
              workspace_sphere=((0.2, 0.0, 0.3), 1.1))
    free = next_best_view(emap, cam, **kw)
    loose = next_best_view(emap, cam, arm_collisions=False, **kw)
    assert loose.arm_collisions == 0 and colliding(loose) > 0  # the check is needed here
    assert free.arm_collisions > 0 and colliding(free) == 0
    assert free.best_pose is not None


def _explorer_at_scene_2(resolution, image, eyes):
    """The explorer robot (robot, chain, its base pose), a camera of `image` (w, h) pixels and a map of
    paper scene 2 at `resolution` that has seen the scene from `eyes` (looking at its middle)."""
    scene = ex.paper_scene(2)
    robot, chain = ex.explorer_robot()
    base = robot.link_poses(robot.home())[chain.base_link]
    cam = DepthCamera(image[0], image[1], FOV, 3.0)
    emap = ExplorationMap(resolution=resolution, search_space=ex.scene_region(scene))
    list(survey(emap, scene, cam, eyes, (0.9, 0.0, 0.1)))
    return robot, chain, base, cam, emap


def test_views_whose_arm_touches_itself_are_rejected():
    # Camera poses of self-colliding arm configurations: IK may find another, clear solution for a few;
    # no view the search calls valid may have the arm touching the robot itself.
    from octoreach import Obstacles

    robot, chain, base, cam, emap = _explorer_at_scene_2(0.04, (160, 120), [(0.45, 0.0, 1.1), (0.4, -0.6, 0.9)])
    nothing = Obstacles()

    def self_colliding(q):
        return robot.in_collision(chain.to_robot_configuration(q), nothing, self_collision=True)

    Q = [q for q in chain.random_configurations(400, seed=3) if self_colliding(q)]
    assert len(Q) > 20
    sv = score_views(emap, cam, np.array([base @ chain.fk(q) for q in Q]), chain=chain, chain_base=base,
                     unknown_is_obstacle=False)
    valid = [q for st, q in zip(sv.status, sv.q) if st == "valid"]
    assert sv.status.count("arm_collision") > len(Q) / 2
    assert not any(self_colliding(q) for q in valid)


def test_score_views_can_skip_the_ray_casting_of_invalid_poses():
    # score_invalid=False: the same statuses, q and gains for the valid poses; the others are not ray
    # cast (NaN gains, 0 cells). Without it every pose is scored.
    robot, chain, base, cam, emap = _explorer_at_scene_2(0.05, (80, 60), [(0.45, 0.0, 1.1)])
    rng = np.random.default_rng(5)
    poses = np.array([ex.look_at(rng.uniform((0.0, -0.8, 0.3), (1.2, 0.8, 1.4)), (0.9, 0.0, 0.1)) for _ in range(60)])
    kw = dict(chain=chain, chain_base=base, seed=2)
    full = score_views(emap, cam, poses, **kw)
    some = score_views(emap, cam, poses, score_invalid=False, **kw)
    assert some.status == full.status
    v = np.asarray(full.valid)
    assert 0 < v.sum() < len(v)
    for key in ("expected_void", "expected_unknown", "expected_frontier", "void_cells", "unknown_cells"):
        np.testing.assert_array_equal(np.asarray(getattr(some, key))[v], np.asarray(getattr(full, key))[v])
    assert np.isnan(np.asarray(some.expected_unknown)[~v]).all()
    assert (np.asarray(some.unknown_cells)[~v] == 0).all()
    assert np.isfinite(np.asarray(full.expected_unknown)).all() and (np.asarray(full.unknown_cells)[~v] > 0).any()
    np.testing.assert_array_equal(np.asarray(some.q)[v], np.asarray(full.q)[v])
    with pytest.raises(TypeError):  # a bool, not anything truthy
        score_views(emap, cam, poses, score_invalid=None, **kw)


def test_nbv_options_object_and_keywords_are_one_thing():
    from octoreach import _core

    o = _core.NbvOptions()
    assert (o.max_valid_poses, o.orientations_per_cell, o.max_candidate_cells, o.score_width, o.score_height) == (
        50, 8, 400, 48, 36)
    assert (o.ik_attempts, o.ik_position_tolerance, o.ik_orientation_tolerance) == (8, 1e-3, 1e-2)
    assert o.workspace_sphere is None and o.chain is None and o.chain_base is None
    scene = ex.paper_scene(2)
    emap = ExplorationMap(resolution=0.08, search_space=ex.scene_region(scene))
    cam = DepthCamera(80, 60, FOV, 3.0)
    list(survey(emap, scene, cam, [(0.2, -0.5, 1.0)], (0.9, 0.0, 0.1)))
    o.workspace_sphere = ((0.9, 0.0, 0.3), 1.2)
    o.max_valid_poses = 5
    a = next_best_view(emap, cam, options=o, seed=3)
    b = next_best_view(emap, cam, workspace_sphere=((0.9, 0.0, 0.3), 1.2), max_valid_poses=5, seed=3)
    assert a.void_cells == b.void_cells and a.poses_scored == b.poses_scored
    assert o.seed == 0  # keywords change a copy, not the caller's options
    with pytest.raises(TypeError, match="bogus"):
        next_best_view(emap, cam, bogus=1)
    with pytest.raises(ValueError, match="workspace_box"):
        next_best_view(emap, cam, workspace_box=np.zeros((3, 3)))


def _unknown_cells_of_search_space(emap, region):
    """Centres of the unknown cells of a bounded search space (every cell that shares volume with it: the cells
    unknown_is_obstacle turns into obstacles), found cell by cell with ExplorationMap.state."""
    res = emap.resolution
    axes = [(np.arange(np.floor(region[0][i] / res), np.ceil(region[1][i] / res)) + 0.5) * res for i in range(3)]
    pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    return pts[emap.state(pts) == 0]


def test_safe_views_keep_the_arm_and_the_camera_in_observed_space():
    from octoreach import Obstacles

    scene = ex.paper_scene(2)
    region = ex.scene_region(scene)
    robot, chain = ex.explorer_robot()
    base = ex.arm_base_pose(robot, chain)
    cam = DepthCamera(160, 120, FOV, 3.0)
    emap = ExplorationMap(resolution=0.04, search_space=region)
    for T in survey(emap, scene, cam, [(0.45, 0.0, 1.1), (0.4, -0.6, 0.9)], (0.9, 0.0, 0.1)):
        pass
    unknown = _unknown_cells_of_search_space(emap, region)
    assert len(unknown) > 1000
    blocked = Obstacles()  # occupied and unknown cells, checked independently of the search
    blocked.add_points(np.vstack([emap.cells("occupied"), unknown]), emap.resolution)

    def touching_unknown(result):
        n = 0
        for v in result.ranked:
            q = robot.home().copy()
            q[: chain.dof] = v.q
            n += robot.in_collision(q, blocked)
        return n

    kw = dict(max_valid_poses=40, max_candidate_cells=300, chain=chain, chain_base=base,
              workspace_sphere=((0.2, 0.0, 0.3), 1.1), min_distance=0.05)
    safe = next_best_view(emap, cam, **kw)
    loose = next_best_view(emap, cam, unknown_is_obstacle=False, **kw)
    assert touching_unknown(loose) > 0  # without the rule some views reach through unknown space
    assert safe.best_pose is not None and touching_unknown(safe) == 0
    margin = 0.05
    for v in safe.ranked:
        eye = v.pose[:3, 3]
        # the camera sits in a free cell, or in an unknown cell outside the search space and above its
        # floor (the rule counts only the search space's unknown cells as obstacles; utility vectors pass
        # the others, so candidate cells may lie there)
        state = emap.state(eye[None])[0]
        outside = np.any(eye < region[0]) or np.any(eye > region[1])
        assert state == 1 or (state == 0 and outside and eye[2] >= region[0][2]), (eye, state)
        # no point of an unknown cell within the margin
        gap = np.maximum(np.abs(unknown - eye) - emap.resolution / 2, 0.0)
        assert np.linalg.norm(gap, axis=1).min() >= margin
    # score_views agrees on the camera checks (its IK restarts differ, so a solution may differ) and on
    # the gains of the poses its arm reaches
    poses = np.array([v.pose for v in safe.ranked[:5]])
    sv = score_views(emap, cam, poses, **kw)
    assert set(sv.status) <= {"valid", "no_ik", "arm_collision"} and "valid" in sv.status
    for i in np.flatnonzero(sv.valid):
        assert sv.expected_void[i] == pytest.approx(view_gains(emap, cam, sv.pose[i]).expected_void)
    # a camera inside the closed box at -x (never seen inside) is not a view
    inside = ex.look_at((0.9, -0.47, 0.2), (1.0, -0.47, 0.1))
    sv = score_views(emap, cam, inside[None], **kw)
    assert sv.status == ["camera_not_clear"] and not sv.valid[0]
    assert np.isnan(sv.q).all() and sv.q.shape == (1, chain.dof)


def test_score_views_statuses_gains_and_bad_input():
    scene = ex.closed_box_scene("-x", 0.16)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    cam = DepthCamera(160, 120, FOV, 3.0)
    list(survey(emap, scene, cam, [(0.0, -0.3, 0.9), (0.0, 0.4, 0.7)], (0.8, 0.0, 0.2)))
    poses = np.array([ex.look_at((0.2, 0.0, 0.3), (0.8, 0.0, 0.2)), ex.look_at((3.0, 0.0, 0.3), (0.8, 0.0, 0.2))])
    sv = score_views(emap, cam, poses, workspace_box=((-1, -1, 0), (1, 1, 1.5)), unknown_is_obstacle=False)
    assert sv.status == ["valid", "outside_workspace"] and sv.q is None
    assert sv.gain == "frontier_void" and np.array_equal(sv.expected_gain, sv.expected_void)
    # gains are computed for every pose; with p = 1 (within 1.5 m a coarse ray's beam covers at most one cell of
    # 4 cm) an unknown cell, void or not, counts 1 where its ray ends on an occupied cell and 0 where it ends on
    # none (no unknown cell can stop that ray: it returns nothing, the cell stays unknown); the box's far inside
    # is not seen yet, so some rays into it end on no known surface
    near = DepthCamera(160, 120, FOV, 1.5)
    raw = score_views(emap, near, poses[:1], unknown_pass_probability=1.0, unknown_is_obstacle=False)
    assert 0 < raw.expected_void[0] < raw.void_cells[0] and raw.expected_void[0] == int(raw.expected_void[0])
    assert raw.expected_void[0] <= raw.expected_unknown[0] <= raw.unknown_cells[0]
    opaque = score_views(emap, near, poses[:1], unknown_pass_probability=0.0, unknown_is_obstacle=False)
    assert 0 < opaque.expected_unknown[0] < raw.expected_unknown[0]
    assert opaque.unknown_cells[0] == raw.unknown_cells[0]  # the raw counts do not depend on p
    unk = score_views(emap, cam, poses[:1], gain="unknown", unknown_is_obstacle=False)
    assert unk.gain == "unknown" and unk.expected_gain[0] == unk.expected_unknown[0]
    assert score_views(emap, cam, np.zeros((0, 4, 4))).valid.shape == (0,)
    bad = poses.copy()
    bad[1, 0, 3] = np.nan
    with pytest.raises(ValueError, match="finite"):
        score_views(emap, cam, bad)
    with pytest.raises(ValueError, match=r"\(N, 4, 4\)"):
        score_views(emap, cam, poses[:, :3])
    with pytest.raises(ValueError, match="gain must be"):
        score_views(emap, cam, poses, gain="volume")
    with pytest.raises(ValueError, match="gain must be"):
        next_best_view(emap, cam, gain="volume")
    with pytest.raises(ValueError, match="unknown_pass_probability"):
        score_views(emap, cam, poses, unknown_pass_probability=1.5)
    with pytest.raises(TypeError, match="unexpected keyword"):
        score_views(emap, cam, poses, gains="unknown")


def test_ray_statistics_learn_a_pass_probability():
    scene = ex.paper_scene(1)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    assert emap.pass_probability == 0.5 and emap.void_pass_probability == 0.5  # the priors before any ray
    cam = DepthCamera(160, 120, FOV, 3.0)
    list(survey(emap, scene, cam, [(0.45, 0.0, 1.1), (0.4, -0.6, 0.9)], (0.9, 0.0, 0.1)))
    st = emap.ray_statistics()
    assert st["unknown_to_free"] > st["unknown_to_occupied"] > 0 and st["void_to_free"] + st["void_to_occupied"] > 0
    assert 0.5 < st["pass_probability"] < 1 and st["pass_probability"] == emap.pass_probability
    assert 0 < st["void_pass_probability"] < 1
    r = next_best_view(emap, cam, workspace_sphere=((0.5, 0.0, 0.6), 0.8), min_distance=0.05)
    assert r.pass_probability == emap.pass_probability
    assert r.void_pass_probability == emap.void_pass_probability
    for gain in ("frontiers", "unknown"):
        g = next_best_view(emap, cam, workspace_sphere=((0.5, 0.0, 0.6), 0.8), min_distance=0.05, gain=gain)
        key = {"frontiers": "expected_frontier", "unknown": "expected_unknown"}[gain]
        assert g.best_pose is not None and g.expected_gain == getattr(g, key) > 0
        assert [v.expected_gain for v in g.ranked] == sorted([v.expected_gain for v in g.ranked], reverse=True)


def test_utility_rays_clipped_to_the_workspace_give_the_same_search():
    # The utility vectors are summed only inside the workspace's box and sphere (the walk ends where a
    # ray leaves them); the same workspace given as an opaque filter sums everywhere and prunes after.
    scene = ex.paper_scene(1)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    cam = DepthCamera(160, 120, FOV, 3.0)
    list(survey(emap, scene, cam, [(0.45, 0.0, 1.1), (0.4, -0.6, 0.9)], (0.9, 0.0, 0.1)))
    c, rad = np.array([0.5, 0.0, 0.6]), 0.8
    lo, hi = np.array([0.0, -0.5, 0.2]), np.array([1.2, 0.5, 1.4])
    in_sphere = lambda P: list(np.linalg.norm(np.asarray(P) - c, axis=1) <= rad)  # noqa: E731
    in_box = lambda P: list(np.all((np.asarray(P) >= lo) & (np.asarray(P) <= hi), axis=1))  # noqa: E731
    both = lambda P: [a and b for a, b in zip(in_sphere(P), in_box(P))]  # noqa: E731
    cases = [(dict(workspace_sphere=(c, rad)), in_sphere), (dict(workspace_box=(lo, hi)), in_box),
             (dict(workspace_sphere=(c, rad), workspace_box=(lo, hi)), both)]
    for gain in ("frontier_void", "frontiers", "unknown"):
        for clipped_kw, fn in cases:
            kw = dict(min_distance=0.05, gain=gain, max_valid_poses=10, seed=5)
            a = next_best_view(emap, cam, **clipped_kw, **kw)
            b = next_best_view(emap, cam, workspace=fn, **kw)
            assert a.candidate_cells == b.candidate_cells > 0
            assert a.utility_cells < b.utility_cells  # the clipped walk summed fewer cells
            assert len(a.ranked) == len(b.ranked) > 0
            for x, y in zip(a.ranked, b.ranked):
                np.testing.assert_array_equal(x.pose, y.pose)
                assert x.expected_gain == y.expected_gain


def test_incremental_void_clusters_equal_clusters_from_scratch_after_every_insert():
    """void_clusters() re-grows only the clusters an insert can reach; the partition, the order and the
    ellipsoids equal the clustering from scratch of the same void cells after every insert."""
    for sid in (1, 2):
        scene = ex.paper_scene(sid)
        cam = DepthCamera(200, 150, FOV, 3.0, noise=0.004, seed=sid)
        emap = ExplorationMap(resolution=0.03, search_space=ex.scene_region(scene), seed=5)
        eyes = [(0.45, 0.0, 1.1), (0.4, -0.6, 0.9), (0.3, 0.6, 0.9), (1.5, 0.0, 1.0), (0.9, -0.9, 0.8),
                (0.9, 0.9, 1.2), (0.6, 0.0, 0.7)]
        sizes = []
        for T in survey(emap, scene, cam, eyes, (0.9, 0.0, 0.1)):
            inc, scratch = emap.void_clusters(), emap.void_clusters_from_scratch()
            assert len(inc) == len(scratch) > 0
            for a, b in zip(inc, scratch):
                assert np.array_equal(a.keys, b.keys)
                assert np.allclose(a.centroid, b.centroid) and np.allclose(a.eigenvalues, b.eigenvalues)
                assert a.score == pytest.approx(b.score)
            assert sum(c.size for c in inc) == emap.void_cell_count
            sizes.append(emap.void_cell_count)
        assert len(set(sizes)) > 2  # the void cells did change along the way


def _pipe_scene(back_wall):
    """A pipe along x (0.6-1.0 m, 0.3 m square, 2 cm walls) above the floor, and a wall behind its far end if asked."""
    scene = Scene()
    scene.add_box((-2, -2, -0.05), (2, 2, 0))
    scene.add_box((0.6, -0.15, 0.38), (1.0, 0.15, 0.4))
    scene.add_box((0.6, -0.15, 0.1), (1.0, 0.15, 0.12))
    scene.add_box((0.6, -0.15, 0.1), (1.0, -0.13, 0.4))
    scene.add_box((0.6, 0.13, 0.1), (1.0, 0.15, 0.4))
    if back_wall:
        scene.add_box((1.6, -1, 0), (1.62, 1, 1.0))
    return scene


@pytest.mark.parametrize("back_wall", [True, False])
def test_visibility_model_expects_what_the_view_sees_when_nothing_hides_in_the_unknown(back_wall):
    """A pipe seen from its sides, above and behind: its inside is void, and nothing occupies it. A view into one
    end with pass probability 1 (unknown cells let rays through, as they do here) expects what its image turns
    known, with the score grid at the image's rays. With a wall behind the far end every ray ends on a known
    surface, so every void cell a ray meets counts, but for the few rays that pass just over the pipe's top edge
    (the part of the edge's cells the board does not fill) and go on to the part of the wall no view has seen;
    without it the rays through the far opening return nothing and clear nothing, and count nothing. A learned
    p < 1 expects fewer."""
    scene = _pipe_scene(back_wall)
    cam = DepthCamera(160, 120, FOV, 3.0)
    emap = ExplorationMap(resolution=0.03, search_space=np.array([[0.5, -0.3, 0.0], [1.1, 0.3, 0.5]]))
    for eye, at in (((0.8, -0.9, 0.3), (0.8, 0, 0.25)), ((0.8, 0.9, 0.3), (0.8, 0, 0.25)),
                    ((0.8, 0, 0.9), (0.8, 0, 0.25)), ((1.3, -0.6, 0.3), (1.6, 0, 0.25)),
                    ((1.3, 0.6, 0.3), (1.6, 0, 0.25))):
        T = ex.look_at(eye, at)
        emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    front = ex.look_at((0.2, 0.0, 0.25), (0.8, 0.0, 0.25))
    clear = view_gains(emap, cam, front, 160, 120, pass_probability=1.0)
    learned = view_gains(emap, cam, front, 160, 120)
    assert clear.void_cells > 1000
    assert learned.void_pass_probability < 1 and learned.expected_void < clear.expected_void
    if back_wall:
        assert clear.void_cells >= clear.expected_void > 0.98 * clear.void_cells
    else:  # about a third of the met void cells lie only on rays out through the far opening
        assert clear.expected_void < 0.8 * clear.void_cells
    seen = emap.insert(cam.capture(scene, front), front[:3, 3], cam.max_range)["void_removed"]
    # (without the wall, a few rays that end on the inside of the pipe's walls, which no view has seen, cross the
    # unknown cells the walls fill in part, leave past the pipe's end and are expected to return nothing)
    assert seen == pytest.approx(clear.expected_void, rel=0.05 if back_wall else 0.1)


def test_clipped_rays_learn_whether_they_return_as_whole_rays():
    """Frontier-void's score clips its rays to the box of the void cells and walks them on past it, counting
    nothing, only to learn whether they return: the same figures as whole rays (view_gains). A pipe seen from its
    sides and from behind, no wall behind it: rays through its far opening meet only unknown cells of the search
    space, whose top (0.5 m) cuts a 3 cm cell, so the search space's cells reach above it."""
    scene = _pipe_scene(back_wall=False)
    emap = ExplorationMap(resolution=0.03, search_space=np.array([[0.5, -0.3, 0.0], [1.1, 0.3, 0.5]]))
    survey_cam = DepthCamera(160, 120, FOV, 3.0)
    for eye, at in (((0.8, -0.9, 0.3), (0.8, 0, 0.25)), ((0.8, 0.9, 0.3), (0.8, 0, 0.25)),
                    ((1.3, -0.6, 0.3), (1.6, 0, 0.25)), ((1.3, 0.6, 0.3), (1.6, 0, 0.25))):
        T = ex.look_at(eye, at)
        emap.insert(survey_cam.capture(scene, T), T[:3, 3], survey_cam.max_range)
    cam = DepthCamera(80, 60, FOV, 3.0)
    front = ex.look_at((0.2, 0.0, 0.25), (0.8, 0.0, 0.25))
    for p in (1.0, 0.9, None):
        whole = view_gains(emap, cam, front, 80, 60, pass_probability=p)
        clipped = score_views(emap, cam, front[None], score_width=80, score_height=60, unknown_is_obstacle=False,
                              unknown_pass_probability=p)
        assert whole.void_cells > 1000 and clipped.void_cells[0] == whole.void_cells
        assert clipped.expected_void[0] == pytest.approx(whole.expected_void, rel=1e-9), p


def test_space_outside_the_search_space_hides_nothing_from_a_view():
    """Before any capture has reached it, the space between a camera and the search space is unknown but outside
    the search space: the view is taken to see through it (a head whose first capture returned no point, looking at
    the sky, must still expect the table). A camera farther back along the same line expects about as much: its
    rays stand for more cells each and meet fewer."""
    space = np.array([[0.8, -0.3, 0.0], [1.4, 0.3, 0.4]])
    emap = ExplorationMap(resolution=0.025, search_space=space)
    cam = DepthCamera(48, 36, FOV, 4.0)
    near = view_gains(emap, cam, ex.look_at((0.0, 0.0, 0.2), (1.1, 0.0, 0.2)), pass_probability=0.5)
    far = view_gains(emap, cam, ex.look_at((-0.8, 0.0, 0.2), (1.1, 0.0, 0.2)), pass_probability=0.5)
    assert near.unknown_cells > 100 and far.unknown_cells > 100
    # not worn down by the 32 unknown cells outside the search space in front of it
    assert far.expected_unknown > 0.5 * near.expected_unknown > 100


def test_a_view_in_front_of_an_opening_outside_the_search_space_is_found():
    """A closed box opens towards the robot (-x) just inside the search space; the first view, from above,
    saw the box's top and the floor in front of it but not the space the camera needs in front of the
    opening, which lies outside the search space (x < 0.55) and is unknown. Utility vectors pass unknown
    cells outside the search space (as the safe-view rule does not count them as obstacles either), so a
    view from there into the opening is found; they stop at the ground below the search space."""
    from octoreach import _core

    s = Scene()
    s.add_box((-2, -2, -0.05), (2, 2, 0))
    s.add_closed_box((0.6, -0.2, 0.0), (1.0, 0.2, 0.3), 0.02, "-x", 0.14, 0.14)
    region = np.array([[0.55, -0.3, 0.0], [1.1, 0.3, 0.35]])
    emap = ExplorationMap(resolution=0.05, search_space=region)
    above = DepthCamera(80, 60, np.deg2rad(40), 4.0)
    T = ex.look_at((0.8, 0.0, 1.0), (0.8, 0.01, 0.0))
    emap.insert(above.capture(s, T), T[:3, 3], 4.0)
    assert emap.void_cell_count > 100
    pos, _ = _core.accumulate_utility(emap, 4.0)
    outside = pos[:, 0] < region[0, 0]
    assert np.count_nonzero(outside & (emap.state(pos) == 0)) > 100  # unknown cells in front, outside S
    assert np.all(pos[:, 2] >= region[0, 2])  # none below the search space's floor
    cam = DepthCamera(80, 60, FOV, 4.0)
    r = next_best_view(emap, cam, workspace_box=np.array([[0.2, -0.3, 0.02], [0.4, 0.3, 0.4]]))
    assert r.best_pose is not None, r.candidate_cells
    assert r.best_pose[0, 3] <= 0.4 and r.ranked[0].expected_void > 10


def test_rays_pass_the_part_of_an_opening_the_cells_of_its_rim_leave_free():
    """An opening 5 cm across whose rims lie mid-cell keeps one free column of 2.5 cm cells in the map: a line
    at 55 degrees to the wall crosses no free column through the 2 cm board, yet real rays pass. The cells of the
    rim hold the box of the points that hit them, and a ray past that box passes: the oblique view expects the
    void behind the opening and its capture sees into it. A view of the box's solid side expects none of it."""
    s = Scene()
    lo, hi = np.array([0.6, -0.1875, 0.0125]), np.array([0.9, 0.2125, 0.3125])
    s.add_closed_box(lo, hi, 0.02, "-x", 0.05, 0.05)  # opening y 0.0125 +- 0.025, z 0.1625 +- 0.025
    emap = ExplorationMap(resolution=0.025, search_space=np.array([lo - 0.05, hi + 0.05]))
    cam = DepthCamera(160, 120, FOV, 3.0, seed=1)
    hole = np.array([0.61, 0.0125, 0.1625])
    for eye, at in [((0.1, 0.0125, 0.1625), hole), ((0.75, 0.0, 0.9), (0.75, 0.01, 0.2)),
                    ((1.4, 0.0, 0.3), (0.75, 0.0, 0.16)), ((0.75, -0.7, 0.3), (0.75, 0.0, 0.16)),
                    ((0.75, 0.7, 0.3), (0.75, 0.0, 0.16))]:
        T = ex.look_at(eye, at)
        emap.insert(cam.capture(s, T), T[:3, 3], cam.max_range)
    assert emap.void_cell_count > 100
    rim = emap.state(np.array([[0.61, 0.0125, 0.1625], [0.61, -0.0125, 0.1625], [0.61, 0.0375, 0.1625]]))
    assert list(rim) == [1, 2, 2]  # one free column between occupied rims
    a = np.deg2rad(55.0)
    oblique = ex.look_at(hole + 0.3 * np.array([-np.cos(a), -np.sin(a), 0.0]), hole)
    g = view_gains(emap, cam, oblique)
    assert g.void_cells > 10 and g.expected_void > 1
    voids = emap.cells("void")
    emap.insert(cam.capture(s, oblique), oblique[:3, 3], cam.max_range)
    assert np.count_nonzero(emap.state(voids) != 0) > 5  # what it expected is there to see
    side = ex.look_at(np.array([0.75, 0.0, 0.16]) + 0.4 * np.array([np.cos(a), -np.sin(a), 0.0]), (0.75, 0.0, 0.16))
    assert view_gains(emap, cam, side).void_cells == 0


def test_void_enclosure_by_hand_and_the_ranking_it_weighs():
    """An open crate seen from the sides and a solid block beside it. A void cell in the middle of the
    crate meets the four walls (closed: 2 halves each), free space above it (open: 0) and unknown space
    below it to the range (the crate's floor was never seen: 1 half): 9 of 12 halves. The crate's inside
    is more enclosed than the shadows around it. With enclosure_power, the ranking gain is the expected
    void cells each weighted by enclosure^power (at 0: the plain expected void cells)."""
    from octoreach import _core

    scene = Scene()
    scene.add_box((-2, -2, -0.05), (2, 2, 0))
    scene.add_crate((0.6, -0.2, 0), (1.0, 0.2, 0.3), 0.02)
    scene.add_box((0.6, 0.5, 0), (0.75, 0.65, 0.3))
    cam = DepthCamera(160, 120, FOV, 2.0)
    emap = ExplorationMap(resolution=0.03, search_space=ex.scene_region(scene))
    list(survey(emap, scene, cam, [(0.0, 0.0, 0.5), (0.8, -0.9, 0.45), (1.7, 0.0, 0.45), (0.0, 0.6, 0.5)],
                (0.8, 0.0, 0.15)))
    keys, enc = _core.void_enclosure(emap)
    np.testing.assert_array_equal(keys, emap.void_keys())
    assert np.all((enc >= 0) & (enc <= 1))
    middle = np.flatnonzero(keys == emap.key_of((0.8, 0.0, 0.15)))
    assert len(middle) == 1 and enc[middle[0]] == pytest.approx(9 / 12)
    C = emap.centers(keys)
    lo, hi = map(np.asarray, scene.interiors[0])
    crate = np.all((C > lo) & (C < hi), axis=1)
    block = np.all((C > (0.6, 0.5, 0.0)) & (C < (0.75, 0.65, 0.3)), axis=1)
    shadows = ~crate & ~block
    assert crate.sum() > 300 and shadows.sum() > 300
    assert np.median(enc[crate]) == pytest.approx(9 / 12) and np.median(enc[shadows]) <= 5 / 12
    # within one cell all six neighbours of the middle cell are unknown (1/2 each); within 1 m its walls
    # still close four directions, the free space above opens one and below stays unknown
    assert _core.void_enclosure(emap, 0.03)[1][middle[0]] == pytest.approx(0.5)
    assert _core.void_enclosure(emap, 1.0)[1][middle[0]] == pytest.approx(9 / 12)
    top = ex.look_at((0.8, 0.0, 0.9), (0.8, 0.0, 0.0))
    plain = score_views(emap, cam, top[None])
    weighted = score_views(emap, cam, top[None], enclosure_power=2.0)
    assert plain.expected_gain[0] == pytest.approx(plain.expected_void[0])
    assert weighted.expected_void[0] == pytest.approx(plain.expected_void[0])
    # into the crate (its cells weigh (9/12)^2 = 0.56, the shadows around it less) against down into the
    # shadow behind the block: the crate keeps more than twice the share of its expected void cells
    shadow = ex.look_at((0.95, 0.58, 0.8), (0.85, 0.58, 0.0))
    behind = score_views(emap, cam, shadow[None], enclosure_power=2.0)
    share_crate = weighted.expected_gain[0] / weighted.expected_void[0]
    share_shadow = behind.expected_gain[0] / behind.expected_void[0]
    assert behind.expected_void[0] > 20 and share_crate < 9 / 16 and share_crate > 2 * share_shadow
    # the unknown and frontier gains do not change (their rays are whole; frontier_void's end at the void box)
    assert score_views(emap, cam, top[None], gain="unknown", enclosure_power=2.0).expected_gain[0] == \
        pytest.approx(score_views(emap, cam, top[None], gain="unknown").expected_unknown[0])
    r = next_best_view(emap, cam, workspace_sphere=((0.8, 0.0, 0.3), 1.0), min_distance=0.05, enclosure_power=2.0)
    gains = [c.expected_gain for c in r.ranked]
    assert gains == sorted(gains, reverse=True)
    assert r.ranked and all(c.expected_gain == pytest.approx(c.expected_enclosed_void) for c in r.ranked)
    assert all(c.expected_enclosed_void < c.expected_void for c in r.ranked)
    for bad in (dict(enclosure_power=-1.0), dict(enclosure_power=float("nan")), dict(enclosure_range=0.0)):
        with pytest.raises(ValueError, match="enclosure_"):
            score_views(emap, cam, top[None], **bad)
    with pytest.raises(ValueError, match="range"):
        _core.void_enclosure(emap, -1.0)


def test_aimed_poses_look_at_void_cells_from_inside_the_reach():
    """The second look's poses: each looks at a void cell from 0.3-1.0 m, not from below, inside the
    given sphere and above the floor; a map without voids gives none."""
    from octoreach.exploration.candidate_poses import aimed_poses

    scene = ex.closed_box_scene("+y", 0.16)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    cam = DepthCamera(120, 90, FOV, 3.0)
    list(survey(emap, scene, cam, [(0.0, -0.3, 0.9), (1.6, -0.3, 0.9)], (0.8, 0.0, 0.2)))
    sphere = ((0.3, 0.0, 0.8), 0.9)
    P = aimed_poses(np.random.default_rng(0), emap, sphere=sphere, n=100)
    assert 0 < len(P) <= 100
    eyes, axes = P[:, :3, 3], P[:, :3, 2]
    assert np.all(np.linalg.norm(eyes - sphere[0], axis=1) <= sphere[1] + 1e-9) and np.all(eyes[:, 2] >= 0.05)
    void = set(np.asarray(emap.void_keys()).tolist())
    for eye, axis in zip(eyes, axes):  # the optical axis passes through a void cell 0.3-1.0 m ahead
        hits = {int(emap.key_of(eye + t * axis)) for t in np.arange(0.29, 1.01, 0.005)}
        assert hits & void
    assert len(aimed_poses(np.random.default_rng(0), ExplorationMap(resolution=0.04), n=10)) == 0


def _box_seen_from_three_sides():
    """The second look's tests: a closed box opening on +y, seen from -x, +x and -y (its inside is void),
    a camera, the search space and a reach sphere around the box: (emap, cam, region, sphere_of)."""
    scene = ex.closed_box_scene("+y", 0.16)
    region = ex.scene_region(scene)
    emap = ExplorationMap(resolution=0.04, search_space=region)
    cam = DepthCamera(120, 90, FOV, 3.0)
    list(survey(emap, scene, cam, [(0.0, -0.3, 0.9), (1.6, -0.3, 0.9), (0.8, -0.9, 0.9)], (0.8, 0.0, 0.2)))
    return emap, cam, region, lambda _: ((0.8, 0.0, 0.3), 1.0)


def view_settings(widen_below=None, **search):
    """ExploreOptions for choose_view: its search NbvOptions() (the C++ defaults, not the loop's) with the
    `search` fields set; a second look with min_utility `widen_below` (None: no second look); frontier-void's
    own choice (no view beyond the voids)."""
    from octoreach import ExploreOptions, NbvOptions

    s = ExploreOptions()
    s.beyond_voids = False
    s.search = NbvOptions()
    for k, v in search.items():
        setattr(s.search, k, v)
    s.second_look = widen_below is not None
    s.min_utility = 0.0 if widen_below is None else widen_below
    return s


def test_the_second_look_finds_the_view_a_narrow_search_missed():
    """next_best_view limited to one candidate cell and one orientation finds a poor view of the closed
    box's inside or none; with a second look below a min_utility above its utility, poses aimed at the void cells are scored
    too and a view expecting more is taken (details["aimed"]); without it the narrow answer stays."""
    from octoreach.exploration.strategies import choose_view

    emap, cam, region, sphere_of = _box_seen_from_three_sides()
    options = dict(min_distance=0.05, max_valid_poses=1, max_candidate_cells=1, orientations_per_cell=1)
    narrow = choose_view("frontier_void", emap, cam, [None], 0, sphere_of, view_settings(**options), 3, region)
    wide = choose_view("frontier_void", emap, cam, [None], 0, sphere_of,
                       view_settings(narrow.utility + 1.0, **options), 3, region)
    assert "aimed" not in narrow.details
    assert wide.details.get("aimed") and wide.pose is not None
    assert wide.utility > max(2 * narrow.utility, 20.0), (narrow.utility, wide.utility)
    # the aimed view is a real view: its gains are what score_views gives for its pose
    again = score_views(emap, cam, wide.pose[None], workspace_sphere=sphere_of(None), min_distance=0.05)
    assert again.valid[0] and again.expected_void[0] == pytest.approx(wide.expected_void)


def test_the_second_look_on_every_view_takes_the_better_view_by_the_ranking_gain():
    """Not only at low views: with min_utility below the narrow search's utility (its best is not low),
    the aimed poses are still scored and the view with the larger ranking gain (expected_gain, with the
    enclosure weighting) is taken; its rank_gain is what score_views gives for its pose."""
    from octoreach.exploration.strategies import choose_view

    emap, cam, region, sphere_of = _box_seen_from_three_sides()
    options = dict(min_distance=0.05, max_valid_poses=1, max_candidate_cells=8, orientations_per_cell=1,
                   enclosure_power=2.0)
    narrow = choose_view("frontier_void", emap, cam, [None], 0, sphere_of, view_settings(**options), 3, region)
    assert narrow.pose is not None and narrow.utility > 0 and narrow.rank_gain > 0
    wide = choose_view("frontier_void", emap, cam, [None], 0, sphere_of, view_settings(0.0, **options), 3, region)
    assert wide.details.get("aimed") and wide.rank_gain > narrow.rank_gain, (narrow.rank_gain, wide.rank_gain)
    again = score_views(emap, cam, wide.pose[None], workspace_sphere=sphere_of(None), min_distance=0.05,
                        gain="frontier_void", enclosure_power=2.0)
    assert again.valid[0] and again.expected_gain[0] == pytest.approx(wide.rank_gain)
    assert again.expected_void[0] == pytest.approx(wide.expected_void)


def test_observed_share_names_an_argument_of_the_wrong_type():
    """The scene is the second argument and the regions the third: a region passed as the scene is refused by
    name (it failed deep inside with an AttributeError)."""
    scene = ex.closed_box_scene("+z", 0.16)
    emap = ExplorationMap(resolution=0.05)
    assert ex.observed_share(emap, scene) == 0.0
    with pytest.raises(TypeError, match="scene must be a Scene"):
        ex.observed_share(emap, ex.scene_region(scene))
    with pytest.raises(TypeError, match="emap must be an ExplorationMap"):
        ex.observed_share(scene, scene)
