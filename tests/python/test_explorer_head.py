"""Exploration with a pan/tilt head: a robot written here (own_robot.py: mobile base, torso lift, 6-DOF arm,
pan/tilt head whose camera_optical_frame is a ROS optical frame, no SRDF) explores a table with two open boxes
with its head camera. The head (torso lift + pan + tilt: 3 joints) cannot place its camera, so the search aims it
at void cells (look-at); the exploration stops by itself. Coarse map, small images."""
import os
import sys

import numpy as np
import pytest

from octoreach import DepthCamera, ExplorationMap, Robot, Scene, score_views
from octoreach import exploration as ex
from octoreach.testing.oracle import observable_cells

sys.path.insert(0, os.path.dirname(__file__))
from own_robot import urdf  # noqa: E402

RESOLUTION = 0.04
SETTINGS = dict(max_valid_poses=30, max_candidate_cells=200, aimed_poses=120, low_aimed_poses=120, last_poses=300,
                score_size=(24, 18), max_views=40, resolution=RESOLUTION, seed=0)


def _camera() -> DepthCamera:
    return DepthCamera(64, 48, np.deg2rad(58.0), 3.0, seed=1)


def _table_scene() -> Scene:
    """A table (top 0.45 m high) 0.45-1.15 m in front of the robot with two open boxes on it."""
    s = Scene()
    s.add_box((-2, -2, -0.05), (2, 2, 0.0))
    s.add_box((0.45, -0.5, 0.41), (1.15, 0.5, 0.45))  # table top
    for x, y in ((0.47, -0.48), (1.09, -0.48), (0.47, 0.44), (1.09, 0.44)):
        s.add_box((x, y, 0.0), (x + 0.04, y + 0.04, 0.41))  # legs
    s.add_crate((0.55, -0.42, 0.45), (0.85, -0.12, 0.65), 0.02)
    s.add_crate((0.65, 0.1, 0.45), (1.0, 0.4, 0.62), 0.02)
    return s


@pytest.fixture(scope="module")
def head(tmp_path_factory):
    path = tmp_path_factory.mktemp("own") / "own_robot.urdf"
    path.write_text(urdf(optical=True))
    robot = Robot.from_urdf(path)  # a pathlib.Path, as a user passes it
    return robot, robot.chain("base_footprint", "camera_optical_frame")


def test_urdf_paths_may_be_pathlib_paths(head, tmp_path):
    robot, _ = head
    path = tmp_path / "own.urdf"
    path.write_text(urdf(optical=True))
    assert Robot.from_urdf(path).urdf_hash == Robot.from_urdf(str(path)).urdf_hash == robot.urdf_hash
    assert Robot.from_urdf(path, package_dirs=[tmp_path]).urdf_hash == robot.urdf_hash
    with pytest.raises(TypeError, match="urdf must be a path"):
        Robot.from_urdf(3)


def test_the_head_aims_its_optical_axis(head):
    _, chain = head
    assert chain.dof == 3  # torso lift, pan, tilt
    target = np.array([0.8, -0.2, 0.5])
    q = chain.aim(target)
    assert q is not None and chain.aim_error(q, target) < 1e-3
    T = chain.fk(q)
    ray = target - T[:3, 3]
    assert np.linalg.norm(np.cross(T[:3, 2], ray / np.linalg.norm(ray))) < 1e-3
    assert chain.aim(np.array([0.0, 0.0, 0.3])) is None  # straight down: beyond the tilt's limit


@pytest.fixture(scope="module")
def oracle(head):
    robot, chain = head
    return observable_cells(_table_scene(), chain=chain, base_pose=np.eye(4), robot=robot, resolution=RESOLUTION,
                            max_range=3.0, joint_samples=12000, aimed_samples=0, seed=0)


@pytest.mark.parametrize("first", ["at the table", "level, seeing nothing"])
def test_head_camera_explores_the_boxes_and_stops_by_itself(head, oracle, first):
    robot, chain = head
    scene = _table_scene()
    region = ex.scene_region(scene)
    # the head looks at the table first, or level with the torso up: past the table (the first cloud is empty)
    q0 = chain.aim(np.array([0.8, 0.0, 0.45])) if first == "at the table" else np.array([0.3, 0.0, 0.0])
    start = chain.fk(q0)
    r = ex.explore(scene, _camera(), start, robot=robot, chain=chain, base_pose=np.eye(4), search_space=region,
                   **SETTINGS)
    assert r.stop_reason in ("utility below min_utility", "utility 0", "nothing to explore"), r.table()
    assert len(r.rows) < SETTINGS["max_views"]
    assert all(row.physically_valid for row in r.rows)
    assert oracle.count > 100 and oracle.seen_unobservable(r.map) <= 2
    share = oracle.share(r.map)
    print(f"head camera ({first}): {share:.1%} of the observable interior ({oracle.fraction:.0%} of the interiors "
          f"is observable), {len(r.rows)} views, stop: {r.stop_reason}")
    assert share >= 0.8, r.table()


def test_the_explorer_takes_a_head_and_can_be_told_to_place_the_camera(head):
    robot, chain = head
    scene = _table_scene()
    e = ex.Explorer(_camera(), ex.scene_region(scene), robot=robot, chain=chain, base_pose=np.eye(4), **SETTINGS)
    start = chain.fk(chain.aim(np.array([0.8, 0.0, 0.45])))
    e.integrate(_camera().capture(scene, start), start)
    view = e.next_view()
    assert not view.stop and view.q is not None and len(view.q) == 3
    assert np.allclose(view.camera_pose, chain.fk(view.q), atol=1e-9)  # the pose the head reaches
    forced = ex.Explorer(_camera(), ex.scene_region(scene), robot=robot, chain=chain, base_pose=np.eye(4),
                         aiming="pose", **SETTINGS)
    forced.integrate(_camera().capture(scene, start), start)
    refused = forced.next_view()
    assert refused.stop_reason == "no valid view"  # 6D poses the head cannot reach
    assert "no_ik" in forced.stop_message(refused), forced.stop_message(refused)
    with pytest.raises(ValueError, match="aiming"):
        ex.Explorer(_camera(), ex.scene_region(scene), robot=robot, chain=chain, aiming="aim")


def test_a_search_space_around_the_robot_stops_with_the_rejection_counts(head):
    """A search space that holds the head and the arm the lift carries: its unknown cells count as obstacles for
    the camera (and the links the chain moves), so no view is valid, and the stop says which checks refused them:
    the camera's clearance, which comes first."""
    robot, chain = head
    scene = _table_scene()
    region = ex.scene_region(scene)
    region[0, 0], region[1, 2] = -0.5, 1.3  # back past the robot, up past its camera (0.89 m)
    start = chain.fk(chain.aim(np.array([0.8, 0.0, 0.45])))
    e = ex.Explorer(_camera(), region, robot=robot, chain=chain, base_pose=np.eye(4), **SETTINGS)
    e.integrate(_camera().capture(scene, start), start)
    view = e.next_view()
    assert view.stop and view.stop_reason == "no valid view"
    message = e.stop_message(view)
    r = view.choice.search
    assert message.startswith(f"no valid view ({r.candidate_cells} candidate cells; rejected: ")
    assert r.camera_not_clear > 0 and f"{r.camera_not_clear} camera_not_clear" in message, message
    assert r.arm_collisions == 0 or f"{r.arm_collisions} arm_collision" in message, message
    result = ex.explore(scene, _camera(), start, robot=robot, chain=chain, base_pose=np.eye(4), search_space=region,
                        **SETTINGS)
    assert result.stop_reason == "no valid view" and len(result.rows) == 1
    assert result.stop_message.startswith("no valid view (") and "camera_not_clear" in result.stop_message
    assert result.table().endswith(f"stopped: {result.stop_message} (frontier_void)")
    going = ex.Explorer(_camera(), ex.scene_region(scene), robot=robot, chain=chain, base_pose=np.eye(4), **SETTINGS)
    going.integrate(_camera().capture(scene, start), start)
    assert ex.stop_message(going.next_view()) == ""


def test_a_head_whose_view_was_not_taken_says_why_it_stops(head):
    """A pan/tilt head's views share its eye, so after one view not taken (view_failed) every view lies within
    failed_view_radius of that camera: the stop says so, not only that nothing was scored. (This head rides a
    torso lift, so the radius here holds every eye the lift reaches.)"""
    robot, chain = head
    scene = _table_scene()
    e = ex.Explorer(_camera(), ex.scene_region(scene), robot=robot, chain=chain, base_pose=np.eye(4),
                    failed_view_radius=1.0, **SETTINGS)
    start = chain.fk(chain.aim(np.array([0.8, 0.0, 0.45])))
    e.integrate(_camera().capture(scene, start), start)
    assert not e.next_view().stop
    e.view_failed()
    view = e.next_view()
    assert view.stop and view.stop_reason == "no valid view"
    assert "failed_view_radius" in e.stop_message(view), e.stop_message(view)


def test_the_joints_off_the_chain_stand_at_the_given_reference(head):
    """The head's chain starts at the base, so the torso lift carries the arm, which sticks forward at home into
    a search space that reaches up to 1.3 m: the exploration runs out of valid views. With the arm folded up
    (reference=, the joints off the chain) the same exploration goes on until its stop rule ends it."""
    robot, chain = head
    scene = _table_scene()
    region = ex.scene_region(scene)
    region[1, 2] = 1.3
    start = chain.fk(chain.aim(np.array([0.8, 0.0, 0.45])))
    runs = {}
    for name, reference in (("home", None), ("folded", robot.configuration({"shoulder_lift_joint": -1.5}))):
        runs[name] = ex.explore(scene, _camera(), start, robot=robot, chain=chain, base_pose=np.eye(4),
                                search_space=region, reference=reference, **SETTINGS)
    assert runs["home"].stop_reason == "no valid view" and "arm_collision" in runs["home"].stop_message
    assert runs["folded"].stop_reason not in ("no valid view", "view budget"), runs["folded"].table()
    assert len(runs["folded"].rows) > len(runs["home"].rows)
    with pytest.raises(ValueError, match="reference must be a vector of 11"):  # when made, not at the first view
        ex.Explorer(_camera(), region, robot=robot, chain=chain, base_pose=np.eye(4), reference=np.zeros(3),
                    **SETTINGS)


def test_score_views_aims_a_head_at_what_each_pose_looks_at(head):
    """The head cannot place its camera, so score_views aims it at the point half the camera's range along each
    given pose's optical axis and checks and scores the pose it reaches; aiming="pose" asks IK for the whole pose
    (which the head reaches only where it already is). The robot stands turned and moved off the origin."""
    robot, chain = head
    scene, cam = _table_scene(), _camera()
    c, s = np.cos(0.2), np.sin(0.2)
    base = np.array([[c, -s, 0, 0.1], [s, c, 0, -0.05], [0, 0, 1, 0], [0, 0, 0, 1.0]])

    def head_looking_at(point):
        return base @ chain.fk(chain.aim((np.linalg.inv(base) @ np.append(point, 1.0))[:3]))

    start = head_looking_at([0.8, 0.0, 0.45])
    emap = ExplorationMap(resolution=RESOLUTION)
    emap.insert(cam.capture(scene, start), start[:3, 3])
    reachable = head_looking_at([0.9, 0.3, 0.5])
    elsewhere = ex.look_at((2.0, -1.5, 1.6), (0.8, -0.3, 0.5))  # where no head camera can be
    down = ex.look_at((0.05, 0.0, 0.9), (0.05, 0.0, -1.0))      # straight down: past the tilt's limit
    poses = np.array([reachable, elsewhere, down])
    kw = dict(chain=chain, chain_base=base, seed=4, unknown_is_obstacle=False)  # one scan: unknown all round
    sv = score_views(emap, cam, poses, score_invalid=False, **kw)
    assert sv.status[2] == "no_ik", sv.status
    for i in (0, 1):
        assert sv.status[i] == "valid", sv.status
        point = poses[i][:3, 3] + 0.5 * cam.max_range * poses[i][:3, 2]
        T = np.asarray(sv.pose[i])
        np.testing.assert_allclose(T, base @ chain.fk(sv.q[i]), atol=1e-9)  # the pose the head reaches
        ray = (point - T[:3, 3]) / np.linalg.norm(point - T[:3, 3])
        assert np.arccos(min(1.0, T[:3, 2] @ ray)) <= 0.1 + 1e-9  # look_at_tolerance
    assert np.linalg.norm(np.asarray(sv.pose[1])[:3, 3] - elsewhere[:3, 3]) > 1.0
    assert np.isfinite(sv.expected_gain[:2]).all() and np.isnan(sv.expected_gain[2])  # the invalid one not scored
    placed = score_views(emap, cam, poses, aiming="pose", **kw)
    assert placed.status[1] == "no_ik" and placed.status[2] == "no_ik", placed.status


def test_a_chain_without_joints_is_refused_when_the_explorer_is_made(head):
    """A chain of fixed joints (the camera link to its optical frame) can neither move nor aim the camera: the
    explorer says so at once, naming the chain, instead of stopping at its first view with every pose "no_ik"."""
    robot, _ = head
    fixed = robot.chain("camera_link", "camera_optical_frame")
    assert fixed.dof == 0
    for capability_map in (None, "auto"):  # "auto" does not try to build a map of it first
        with pytest.raises(ValueError, match="chain camera_link -> camera_optical_frame has no movable joint"):
            ex.Explorer(_camera(), ex.scene_region(_table_scene()), robot=robot, chain=fixed, base_pose=np.eye(4),
                        capability_map=capability_map)


def test_the_chain_may_be_named_by_its_links_and_a_bad_chain_or_target_is_refused(head):
    robot, chain = head
    scene = _table_scene()
    region = ex.scene_region(scene)
    by_pair = ex.Explorer(_camera(), region, robot=robot, chain=("base_footprint", "camera_optical_frame"), **SETTINGS)
    by_name = ex.Explorer(_camera(), region, robot=robot, chain="camera_optical_frame", **SETTINGS)  # from the root
    assert robot.root_link == "base_footprint"
    for e in (by_pair, by_name):
        assert (e.chain.base_link, e.chain.dof) == (chain.base_link, chain.dof)
    with pytest.raises(ValueError, match="pass the robot too"):
        ex.Explorer(_camera(), region, chain="camera_optical_frame")
    with pytest.raises(TypeError, match="chain must be a Chain"):
        ex.Explorer(_camera(), region, robot=robot, chain=3)
    start = chain.fk(chain.aim(np.array([0.8, 0.0, 0.45])))
    with pytest.raises(ValueError, match="lo <= hi"):
        ex.explore(scene, _camera(), start, robot=robot, chain=chain, search_space=region,
                   target=[[0.9, 0.1, 0.5], [0.8, 0.0, 0.6]], **SETTINGS)
