"""Surface maps and the base-pose sampler, checked against brute force (IK + collision checks)."""
from __future__ import annotations

import numpy as np
import pytest

import octoreach
from octoreach import robots, surface_maps
from octoreach import testing

THETA = 2 * np.pi / 16


@pytest.fixture(scope="module")
def arm_setup():
    robot = octoreach.robots.test_arm()
    chain = robot.chain("base_link", "tool0")
    cap = octoreach.CapabilityMap.build(chain, resolution=0.1, directions=48, progress=False, seed=3)
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    sm = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, z_range=(0, 0), progress=False)
    return robot, cap, table, sm


@pytest.fixture(scope="module")
def pr2_setup(pr2):
    ref = octoreach.arms.default_reference(pr2, "right_arm")
    cap = octoreach.arms.capability_map(pr2, "right_arm", resolution=0.2, directions=50, progress=False)
    table = octoreach.Surface.rectangle(1.4, 0.65, 0.72, x=0.0, y=0.0)
    sm = octoreach.SurfaceMap.build(pr2, cap, table, resolution=0.2, z_range=(0, 0), reference=ref, progress=False)
    return pr2, cap, table, sm, ref


def _sample_poses(sm, n, seed):
    centres, values = sm.voxels()
    rng = np.random.default_rng(seed)
    idx = rng.choice(len(centres), size=min(n, len(centres)), replace=False)
    theta = rng.integers(0, sm.theta_bins, size=len(idx)) * 2 * np.pi / sm.theta_bins
    return np.column_stack([centres[idx, 0], centres[idx, 1], np.zeros(len(idx)), theta])


def _compare(map_values, brute):
    diff = map_values - brute
    # The map validates one stored IK solution per capability cell and treats any arm point below the
    # surface inside its outline as passing through it; brute force searches many solutions and checks
    # the exact slab. So the map may only be a little more pessimistic, never more optimistic.
    assert np.max(diff) <= 0.05, f"map above brute force by {np.max(diff):.3f}"
    # The mean over 20 poses varies by about 0.01 with the draw of poses and the capability map's seed (0.064 to
    # 0.083 for seeds 3-6 and two draws), so the bound leaves that much above the typical 0.07.
    assert np.mean(np.abs(diff)) <= 0.085, f"mean |map - brute force| = {np.mean(np.abs(diff)):.3f}"
    assert np.corrcoef(map_values, brute)[0, 1] >= 0.9


def test_test_arm_matches_brute_force(arm_setup):
    robot, cap, table, sm = arm_setup
    poses = _sample_poses(sm, 20, seed=1)
    brute = testing.direct_reachability(robot, cap, table, poses, attempts=20)
    _compare(sm.reachability(poses), brute)
    assert brute.max() > 0.2  # the comparison is not between two zero vectors


def test_pr2_matches_brute_force(pr2_setup):
    pr2, cap, table, sm, ref = pr2_setup
    poses = _sample_poses(sm, 8, seed=2)
    brute = testing.direct_reachability(pr2, cap, table, poses, reference=ref, resolution=0.2, attempts=10)
    _compare(sm.reachability(poses), brute)
    assert brute.max() > 0.1


def test_under_the_table_and_far_away_give_zero(arm_setup, pr2_setup):
    # The test arm under the table's centre: the map rejects every grasp, since the arm would have to
    # pass below the board inside its outline. (Brute force finds a few grasps that snake around the
    # board's edge without touching it: the map is deliberately stricter there.)
    robot, cap, table, sm = arm_setup
    under_and_far = np.array([[0.55, 0.0, 0.0, 0.0], [0.55, 0.0, 0.0, np.pi / 2], [5.0, 5.0, 0.0, 0.0]])
    assert np.all(sm.reachability(under_and_far) == 0)
    assert testing.direct_reachability(robot, cap, table, under_and_far[2:])[0] == 0
    # The PR2 under the table: its body hits the board, for the map and for brute force alike.
    pr2, pr2_cap, pr2_table, pr2_map, ref = pr2_setup
    under = np.array([[0.0, 0.0, 0.0, 0.0], [0.3, 0.1, 0.0, np.pi / 2]])
    assert np.all(pr2_map.reachability(under) == 0)
    assert np.all(testing.direct_reachability(pr2, pr2_cap, pr2_table, under, reference=ref, resolution=0.2) == 0)
    assert pr2_map.reachability(np.array([[6.0, 0.0, 0.0, 0.0]]))[0] == 0


def test_reachability_is_r_s_in_unit_interval(arm_setup):
    _, _, _, sm = arm_setup
    _, values = sm.voxels()
    assert values.min() >= 0 and values.max() <= 1 and values.max() > 0.3
    assert sm.stats["surface_points"] == 24  # 0.6 x 0.4 m at 0.1 m
    assert sm.stats["valid_poses"] <= sm.stats["candidate_poses"]


def test_combine_max_and_min(arm_setup):
    # Two "arms" for the same table: capability maps with other direction sets stand in for them.
    robot, cap, table, sm = arm_setup
    cap2 = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.1, directions=24,
                                         progress=False, seed=5)
    other = octoreach.SurfaceMap.build(robot, cap2, table, resolution=0.1, z_range=(0, 0), progress=False)
    assert not np.allclose(other.reachability(_sample_poses(sm, 30, 5)), sm.reachability(_sample_poses(sm, 30, 5)))
    hi = octoreach.SurfaceMap.combine([sm, other], "max")
    lo = octoreach.SurfaceMap.combine([sm, other], "min")
    poses = np.vstack([_sample_poses(sm, 30, 5), _sample_poses(other, 30, 6)])
    a, b = sm.reachability(poses), other.reachability(poses)
    assert np.allclose(hi.reachability(poses), np.maximum(a, b), atol=1e-6)
    assert np.allclose(lo.reachability(poses), np.minimum(a, b), atol=1e-6)
    with pytest.raises(ValueError, match="mode"):
        octoreach.SurfaceMap.combine([sm, other], "mean")


def test_combine_rejects_mismatched_maps(arm_setup, pr2_setup):
    robot, cap, table, sm = arm_setup
    coarse = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.2, z_range=(0, 0), progress=False)
    with pytest.raises(ValueError, match="resolution"):
        octoreach.SurfaceMap.combine([sm, coarse], "max")
    with pytest.raises(ValueError, match="robots"):
        octoreach.SurfaceMap.combine([sm, pr2_setup[3]], "max")
    fewer = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, theta_bins=8, z_range=(0, 0), progress=False)
    with pytest.raises(ValueError, match="theta"):
        octoreach.SurfaceMap.combine([sm, fewer], "max")
    elsewhere = octoreach.SurfaceMap.build(robot, cap, octoreach.Surface.rectangle(0.4, 0.4, 0.4, x=-0.5),
                                           resolution=0.1, z_range=(0, 0), progress=False)
    with pytest.raises(ValueError, match="surfaces"):
        octoreach.SurfaceMap.combine([sm, elsewhere], "max")


def test_bad_polygons():
    with pytest.raises(ValueError, match="three vertices"):
        octoreach.Surface(np.array([[0, 0, 0.7], [1, 0, 0.7]]))
    with pytest.raises(ValueError, match="not planar"):
        octoreach.Surface(np.array([[0, 0, 0.7], [1, 0, 0.7], [1, 1, 0.9], [0, 1, 0.7]]))
    with pytest.raises(ValueError, match="self-intersecting"):
        octoreach.Surface(np.array([[0, 0, 0.7], [1, 1, 0.7], [1, 0, 0.7], [0, 1, 0.7]]))
    with pytest.raises(ValueError, match="finite"):
        octoreach.Surface(np.array([[0, 0, np.nan], [1, 0, 0.7], [1, 1, 0.7]]))
    with pytest.raises(ValueError):
        octoreach.Surface(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="self-intersecting"):  # a vertex touching another edge
        octoreach.Surface(np.array([[0, 0, 0.7], [2, 0, 0.7], [2, 2, 0.7], [1, 0, 0.7], [0, 2, 0.7]]))
    with pytest.raises(ValueError, match="self-intersecting"):  # a spike folding back
        octoreach.Surface(np.array([[0, 0, 0.7], [2, 0, 0.7], [2, 2, 0.7], [2, 1, 0.7], [2, 3, 0.7], [0, 3, 0.7]]))


def test_non_convex_and_tilted_surfaces(arm_setup):
    robot, cap, _, _ = arm_setup
    ell = octoreach.Surface(np.array([[0.3, -0.4, 0.4], [0.9, -0.4, 0.4], [0.9, 0.4, 0.4], [0.6, 0.4, 0.4],
                                      [0.6, -0.1, 0.4], [0.3, -0.1, 0.4]]))
    pts = ell.points(0.1)
    assert len(pts) > 0 and ell.contains(pts).all()
    assert not ell.contains(np.array([[0.45, 0.2, 0.4]]))[0]  # the notch of the L
    sm = octoreach.SurfaceMap.build(robot, cap, ell, resolution=0.1, z_range=(0, 0), progress=False)
    assert sm.voxel_count > 0
    tilted = octoreach.Surface(np.array([[0.4, -0.2, 0.3], [0.8, -0.2, 0.5], [0.8, 0.2, 0.5], [0.4, 0.2, 0.3]]))
    assert tilted.normal[2] > 0 and abs(tilted.normal[0]) > 0.3
    assert octoreach.SurfaceMap.build(robot, cap, tilted, resolution=0.1, z_range=(0, 0), progress=False).voxel_count > 0


def test_out_of_reach_polygon_gives_an_empty_map_that_says_so(arm_setup):
    robot, cap, _, _ = arm_setup
    far = octoreach.Surface.rectangle(0.5, 0.5, 3.0, x=0.0)
    sm = octoreach.SurfaceMap.build(robot, cap, far, resolution=0.1, z_range=(0, 0), progress=False)
    assert sm.voxel_count == 0 and sm.empty_reason
    with pytest.raises(ValueError, match="empty"):
        octoreach.PoseSampler(sm)


def test_save_load_and_damaged_files(arm_setup, tmp_path):
    _, _, _, sm = arm_setup
    path = tmp_path / "table.orsm"
    sm.save(str(path))
    back = octoreach.SurfaceMap.load(str(path))
    c1, v1 = sm.voxels()
    c2, v2 = back.voxels()
    assert np.array_equal(c1, c2) and np.array_equal(v1, v2)
    assert np.allclose(back.polygon, sm.polygon) and back.z_range == sm.z_range
    data = path.read_bytes()
    (tmp_path / "cut.orsm").write_bytes(data[: len(data) // 2])
    with pytest.raises(OSError, match="truncated"):
        octoreach.SurfaceMap.load(str(tmp_path / "cut.orsm"))
    (tmp_path / "noise.orsm").write_bytes(np.random.default_rng(0).bytes(4096))
    with pytest.raises(OSError):
        octoreach.SurfaceMap.load(str(tmp_path / "noise.orsm"))
    with pytest.raises(OSError, match="capability"):
        octoreach.CapabilityMap.load(str(path))  # a surface map is not a capability map
    sm.export_octovis(str(tmp_path / "table.ot"))
    assert (tmp_path / "table.ot").read_bytes().startswith(b"# Octomap OcTree file")


def test_lookup_shapes(arm_setup):
    _, _, _, sm = arm_setup
    pose = _sample_poses(sm, 1, 9)
    below = pose.copy()
    below[0, 2] = -1e-12  # a floor robot's height after a transform: clipped into the z range
    assert sm.reachability(below)[0] == sm.reachability(pose)[0] > 0
    turned = pose.copy()
    turned[0, 3] += 2 * np.pi * 1000
    assert sm.reachability(turned)[0] == pytest.approx(sm.reachability(pose)[0])
    with pytest.raises(ValueError, match=r"\(N, 4\)"):
        sm.reachability(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="not finite"):  # never R_S 0 for a NaN pose
        sm.reachability(np.array([[np.nan, 0, 0, 0]]))


def test_discount_spreads_samples(arm_setup):
    _, _, _, sm = arm_setup
    plain = octoreach.PoseSampler(sm, seed=4, discount_sigma=(1e-9, 1e-9, 1e-9, 1e-9))
    spread = octoreach.PoseSampler(sm, seed=4)
    a, b = plain.sample(30), spread.sample(30)

    def mean_gap(p):
        d = p[:, None, :2] - p[None, :, :2]
        return np.linalg.norm(d, axis=-1)[np.triu_indices(len(p), 1)].mean()

    assert mean_gap(b) > 1.2 * mean_gap(a)
    assert np.all(sm.reachability(b) > 0)
    assert len(spread.history) == 30
    # Eq. (3) by hand for one candidate.
    c = b[-1] + np.array([0.1, 0.0, 0.0, 0.3])
    w = 1.0
    for p in spread.history:
        d = c - p
        d[3] = (d[3] + np.pi) % (2 * np.pi) - np.pi
        w *= min(1.0, np.linalg.norm(d / np.array([0.5, 0.5, 0.5, np.pi / 4])))
    assert spread.discount(c) == pytest.approx(w)
    spread.reset()
    assert len(spread.history) == 0 and np.allclose(spread.sample(30), b)


def test_cost_map_and_collision_rejections(arm_setup):
    robot, _, table, sm = arm_setup
    # Free only where x < 0.3: every sample must lie there.
    grid = np.ones((60, 60), dtype=np.float32)
    grid[:, :33] = 0.0  # origin -1.5, 0.05 m cells: columns < 36 are x < 0.3
    cost = octoreach.CostMap(grid, origin=np.array([-1.5, -1.5]), resolution=0.05)
    s = octoreach.PoseSampler(sm, seed=1, is_free=cost)
    poses = s.sample(10)
    assert np.all(poses[:, 0] < 0.15 + 1e-9)
    assert s.last_counts["not_free"] > 0
    # A wall box at x in [-0.3, -0.1]: the robot (at home, straight up) must never stand in it.
    walls = octoreach.Obstacles()
    pose = np.eye(4)
    pose[:3, 3] = [-0.2, 0.0, 0.5]
    walls.add_box(np.array([0.2, 3.0, 1.0]), pose)
    s = octoreach.PoseSampler(sm, seed=2, in_collision=(robot, walls))
    poses = s.sample(20)
    for x, y, z, th in poses:
        B = np.eye(4)
        B[:3, :3] = [[np.cos(th), -np.sin(th), 0], [np.sin(th), np.cos(th), 0], [0, 0, 1]]
        B[:3, 3] = [x, y, z]
        assert not robot.in_collision(robot.home(), walls, base_pose=B)
    # A Python callable works too.
    s = octoreach.PoseSampler(sm, seed=3, is_free=lambda p: p[1] > 0.0)
    assert np.all(s.sample(5)[:, 1] > 0)


def test_sampler_respects_the_floor_height(pr2_setup):
    _, _, _, sm, _ = pr2_setup
    poses = octoreach.PoseSampler(sm, seed=0).sample(5)
    assert np.all(poses[:, 2] == 0.0)


# ----------------------------------------------------------------- arm placement, options, one source of truth


def test_named_arms_and_default_reference_come_from_cpp(pr2):
    base, tip, axis = octoreach.arms.resolve(pr2, "right_arm")
    assert (base, tip) == ("torso_lift_link", "r_gripper_tool_frame") and np.allclose(axis, [1, 0, 0])
    with pytest.raises(ValueError, match="has no arm"):
        octoreach.arms.resolve(pr2, "third_arm")
    with pytest.raises(ValueError, match="has no link"):
        octoreach.arms.resolve(pr2, ("torso_lift_link", "no_such_link"))
    # The reference posture rule: home with every SRDF tuck* state applied that does not move the arm.
    chain = pr2.chain(base, tip)
    values = {}
    for name, joints in sorted(pr2.named_states.items()):
        if name.startswith("tuck") and not set(joints) & set(chain.joint_names):
            values.update(joints)
    expected = pr2.configuration(values)
    assert np.array_equal(octoreach.default_reference(pr2, chain), expected)
    assert np.array_equal(octoreach.arms.default_reference(pr2, "right_arm"), expected)


def test_link_roles_and_grasp_orientations(pr2):
    chain = pr2.chain(*octoreach.arms.resolve(pr2, "left_arm")[:2])
    roles = octoreach.link_roles(pr2, chain)
    assert sorted(roles["body"] + roles["arm"] + roles["tool"]) == sorted(pr2.collision_links)
    assert "l_gripper_palm_link" in roles["tool"] and "base_link" in roles["body"]
    s = octoreach.OrientationSet.sphere(30, rolls=3)
    assert octoreach.grasp_orientations(s, [4, 1]) == [3, 4, 5, 12, 13, 14]
    B = octoreach.base_pose([1.0, 2.0, 0.5, np.pi / 2])
    assert np.allclose(B[:3, 3], [1, 2, 0.5]) and np.allclose(B[:3, 0], [0, 1, 0])


def test_options_objects_equal_keywords(arm_setup):
    robot, cap, table, sm = arm_setup
    o = octoreach.SurfaceMapOptions()
    assert o.resolution == 0 and o.grasps == "upper_hemisphere" and o.reference is None
    o.resolution, o.z_range = 0.1, (0, 0)
    again = octoreach.SurfaceMap.build(robot, cap, table, options=o, progress=False)
    assert np.array_equal(again.voxels()[1], sm.voxels()[1])
    assert octoreach.CapabilityMapOptions().resolution == 0.05
    with pytest.raises(TypeError, match="unexpected keyword argument 'grasp_heigth'"):
        octoreach.SurfaceMap.build(robot, cap, table, grasp_heigth=0.1, progress=False)
    by_tuple = octoreach.SurfaceMap.build(robot, ("base_link", "tool0"), table, resolution=0.3, directions=12,
                                          z_range=(0, 0), progress=False)
    assert by_tuple.arms == "base_link->tool0"
    assert sm.model_hash != 0 and cap.model_hash == sm.model_hash


def test_surface_maps_record_the_approach_axis(tmp_path):
    # Every map file's header names the approach axis it was built with.
    robot = robots.test_arm()
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, 0.55)
    smap = octoreach.SurfaceMap.build(robot, ("base_link", "tool0", (0, 0, 1)), table, resolution=0.2, directions=24,
                                      approach_axis=(1, 0, 0), theta_bins=4, progress=False)
    assert smap.approach_axes == "1 0 0" and smap.parameters["approach_axes"] == "1 0 0"
    smap.save(str(tmp_path / "t.orsm"))
    assert octoreach.SurfaceMap.load(str(tmp_path / "t.orsm")).approach_axes == "1 0 0"
    both = octoreach.SurfaceMap.combine([smap, smap], "max")
    assert both.approach_axes == "1 0 0 max 1 0 0"
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.2, directions=24, progress=False)
    with pytest.raises(ValueError, match="approach_axis"):
        octoreach.SurfaceMap.build(robot, cap, table, approach_axis=(1, 0, 0), progress=False)


@pytest.mark.parametrize("kwargs, message", [
    ({"resolution": "x"}, "keyword 'resolution' must be float, got str"),
    ({"theta_bins": "x"}, "keyword 'theta_bins' must be int, got str"),
    ({"approach_axis": "x"}, "approach_axis must be 3 numbers"),
])
def test_wrong_option_types_name_the_keyword(kwargs, message):
    # Never pybind11's "Unable to cast Python instance" message: a TypeError naming the keyword and the type.
    robot = robots.test_arm()
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, 0.55)
    with pytest.raises(TypeError, match=message):
        octoreach.SurfaceMap.build(robot, ("base_link", "tool0", (0, 0, 1)), table, progress=False, **kwargs)


def test_a_robot_whose_frame_is_not_at_its_feet_is_told_its_height():
    # Baxter's 'base' sits on top of its pedestal and a humanoid's root is its pelvis: on the floor
    # (the default z = 0) such a robot would stand in it, and its map would look plausible and be wrong.
    xml = (robots.project_urdf("test_arm")).read_text().replace(
        '<link name="tool0"/>',
        '<link name="tool0"/>\n  <link name="pedestal"><collision><origin xyz="0 0 -0.3"/>'
        '<geometry><box size="0.3 0.3 0.6"/></geometry></collision></link>\n'
        '  <joint name="pedestal_fixed" type="fixed"><parent link="base_link"/><child link="pedestal"/></joint>')
    robot = octoreach.Robot.from_urdf(xml)
    z, link = robot.lowest_point(robot.home())
    assert z == pytest.approx(-0.6) and link == "pedestal"
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.1, directions=48,
                                        progress=False, seed=3)
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.9, x=0.55)
    with pytest.raises(ValueError, match=r"0\.60 m deep in the floor.*'pedestal'.*z_range=\(0\.60, 0\.60\)"):
        octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, progress=False)
    raised = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, z_range=(0.6, 0.6), progress=False)
    assert raised.max_reachability > 0
    # The plain test arm stands on its base plate.
    plain = robots.test_arm()
    assert plain.lowest_point(plain.home())[0] >= -1e-9


def _wall(y, x=0.0, z=0.5, size=(2.0, 0.05, 1.0)):
    walls = octoreach.Obstacles()
    pose = np.eye(4)
    pose[:3, 3] = [x, y, z]
    walls.add_box(np.array(size), pose, "wall")
    return walls


def _file_bytes(sm, path):
    sm.save(str(path))
    return path.read_bytes()


@pytest.mark.parametrize("tilted", [False, True])
def test_arm_checks_with_obstacles_do_not_depend_on_threads(arm_setup, tmp_path, tilted):
    # The arm checks read per-cell data built in parallel (low sets, arm boxes) and per-bin caches of
    # link poses: the map must be the same bytes whatever the thread count, upright or tilted surface.
    robot, cap, _, _ = arm_setup
    if tilted:
        table = octoreach.Surface(np.array([[0.4, -0.2, 0.3], [0.8, -0.2, 0.5], [0.8, 0.2, 0.5], [0.4, 0.2, 0.3]]))
    else:
        table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)  # the fixture's table, with legs
        table.add_legs()
    wall = _wall(0.35)
    build = lambda threads: octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, z_range=(0, 0),
                                                       obstacles=wall, threads=threads, progress=False)
    one, two = build(1), build(2)
    assert one.voxel_count > 0
    assert _file_bytes(one, tmp_path / "one.orsm") == _file_bytes(two, tmp_path / "two.orsm")
    open_map = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, z_range=(0, 0), progress=False)
    assert one.stats["arm_rejections"] > open_map.stats["arm_rejections"]


def test_an_obstacle_out_of_the_arms_reach_changes_no_value(arm_setup):
    # Obstacles far from every arm box are culled before any check: the values must equal the map without them.
    robot, cap, table, sm = arm_setup
    far = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.1, z_range=(0, 0), progress=False,
                                     obstacles=_wall(0.0, x=0.0, z=50.0))
    (c0, v0), (c1, v1) = sm.voxels(), far.voxels()
    assert np.array_equal(c0, c1) and np.array_equal(v0, v1)
    assert far.stats["arm_rejections"] == sm.stats["arm_rejections"]


@pytest.mark.parametrize("resolution", [-0.1, float("nan"), float("inf")])
def test_a_resolution_that_is_no_length_names_the_value(arm_setup, resolution):
    robot, cap, table, _ = arm_setup
    with pytest.raises(ValueError, match=r"resolution must be a number of metres above 0 \(0 or None: the capability "
                                         r"map's\), got (-0\.1|nan|inf)"):
        octoreach.SurfaceMap.build(robot, cap, table, resolution=resolution, progress=False)
