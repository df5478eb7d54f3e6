"""Robot diagnostics: where allowed-collision pairs come from, how often random configurations collide, the joints a
map build holds still, the camera link, and the one-line warnings of suspicious map builds; `octoreach robot`
prints them. The robot is written here (own_robot.py): mobile base, torso lift, 6-DOF arm, pan/tilt head, no SRDF."""
from __future__ import annotations
import struct

import warnings

import numpy as np
import pytest

import octoreach
from octoreach import Robot, arm_report, camera_link, find_camera_link, robots, self_collision_report
from octoreach.cli import main

from octoreach.cache import MapCache
from octoreach.testing.reach_truth import check_poses, ik_truth
from own_robot import _joint, _link, box, urdf


@pytest.fixture(scope="module")
def own(tmp_path_factory):
    """(path, Robot) of the healthy robot, allowed collisions sampled as `octoreach robot --urdf` does."""
    path = tmp_path_factory.mktemp("own") / "own_robot.urdf"
    path.write_text(urdf())
    return path, robots.from_urdf(path)


@pytest.fixture(scope="module")
def bad_elbow(tmp_path_factory):
    path = tmp_path_factory.mktemp("bad") / "bad_elbow.urdf"
    path.write_text(urdf("bad_elbow", bad_elbow=True))
    return path


def test_allowed_pairs_say_where_they_came_from(own):
    _, robot = own
    sources = robot.allowed_collision_sources
    assert [(a, b) for a, b, _ in sources] == robot.allowed_collisions
    reasons = {why for _, _, why in sources}
    assert "adjacent" in reasons and reasons <= {"adjacent", "never in collision", "always in collision",
                                                 "in collision at home"}
    assert ("base_link", "torso_link", "adjacent") in sources
    given = Robot.from_urdf(urdf()).with_allowed_collisions([("base_link", "head_tilt_link")])  # nothing sampled
    assert ("base_link", "head_tilt_link", "given") in given.allowed_collision_sources
    assert 'reason="User"' in given.srdf_text() and 'reason="Adjacent"' in given.srdf_text()


def test_srdf_pairs_are_marked_as_such():
    pr2 = robots.pr2()
    reasons = {why for _, _, why in pr2.allowed_collision_sources}
    assert {"adjacent", "SRDF"} <= reasons


def test_self_collision_report_counts_the_colliding_elbow(own, bad_elbow):
    """Among the arm's own links the sound arm is free in most configurations, the bad elbow's upper arm and forearm
    collide in about 60 %; over the whole robot both collide often (the arm reaches into the torso and the head)."""
    _, good = own
    bad = Robot.from_urdf(str(bad_elbow))
    r_good = arm_report(good, "arm", samples=400).self_collision
    r_bad = arm_report(bad, "arm", samples=400).self_collision
    assert r_good.samples == 400 and not r_good.suspicious, r_good.pairs[:3]
    assert r_bad.suspicious and r_bad.free_share < octoreach.SelfCollisionReport.FREE_SHARE_HINT
    top = r_bad.pairs[0]
    assert {top.link_a, top.link_b} == {"upper_arm_link", "forearm_link"}
    assert 0.45 < top.hits / r_bad.samples < 0.75
    whole = self_collision_report(bad, samples=400)
    assert whole.free_share < r_bad.free_share and whole.pairs[0].hits >= top.hits
    # the same on one thread and on every core, and for the same seed
    one, every = (self_collision_report(bad, samples=400, threads=t) for t in (1, 0))
    assert (one.free, [(p.link_a, p.link_b, p.hits) for p in one.pairs]) == \
        (every.free, [(p.link_a, p.link_b, p.hits) for p in every.pairs])
    only = self_collision_report(bad, samples=400, links=["upper_arm_link", "forearm_link"])
    assert [(p.link_a, p.link_b) for p in only.pairs] == [("upper_arm_link", "forearm_link")]


def test_self_collision_report_bad_input(own):
    _, robot = own
    with pytest.raises(ValueError, match="samples must be at least 1"):
        self_collision_report(robot, samples=0)
    with pytest.raises(ValueError, match="no_such_joint"):
        self_collision_report(robot, joints=["no_such_joint"])
    with pytest.raises(ValueError, match="does not move"):
        self_collision_report(robot, joints=["base_joint"])
    with pytest.raises(ValueError, match="reference configuration has 2 entries"):
        self_collision_report(robot, reference=np.zeros(2))


def test_arm_report_names_the_torso_lift_held_still(own):
    _, robot = own
    (arm,) = octoreach.find_arms(robot)
    r = arm_report(robot, arm, samples=200)
    assert r.moving == ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint",
                        "wrist_3_joint"]
    assert [(h.name, h.value) for h in r.held] == [("torso_lift_joint", 0.0)]
    assert r.base_to_include_held == "base_link"
    # the hint works: an arm from base_link moves the lift too
    longer = arm_report(robot, (r.base_to_include_held, arm.tip_link), samples=50)
    assert longer.moving[0] == "torso_lift_joint" and not longer.held


def test_camera_link_is_found_given_or_asked_for(tmp_path):
    robot = Robot.from_urdf(urdf())
    found = find_camera_link(robot)
    assert found.link == "camera_link" and "camera" in found.reason
    assert camera_link(robot, "head_tilt_link").reason == "given"
    with pytest.raises(ValueError, match="nearest|did you mean|head_tilt_link"):
        camera_link(robot, "head_tilt")
    # no camera link: the end of the head
    assert find_camera_link(Robot.from_urdf(urdf(camera=False))).link == "head_tilt_link"
    # the head's camera wins over cameras elsewhere
    assert find_camera_link(Robot.from_urdf(urdf(extra_cameras=True))).link == "camera_link"
    # cameras on the base and the gripper, no head: ambiguous; no camera, no head: nothing to find
    for text in (urdf(head=False, extra_cameras=True), urdf(head=False)):
        with pytest.raises(ValueError, match="no link that is unambiguously its camera.*camera_link='LINK'"):
            find_camera_link(Robot.from_urdf(text))
    # the PR2: a camera on its head
    pr2 = find_camera_link(robots.pr2())
    assert pr2.link.startswith("head") or "kinect" in pr2.link or "stereo" in pr2.link, pr2


def test_cli_robot_prints_the_diagnostics(own, capsys):
    path, _ = own
    assert main(["robot", "--urdf", str(path), "--samples", "300"]) == 0
    out = capsys.readouterr().out
    assert "allowed-collision pairs:" in out and "adjacent" in out and "never in collision" in out
    assert "self-collision, every joint drawn:" in out and "% of 300 random configurations free" in out
    assert "holds still" in out and "torso_lift_joint at 0" in out and "--base base_link --tip tool_frame" in out
    assert "free among its own links" in out
    assert "camera link: camera_link" in out
    assert "hint: under 75 % free" not in out


def test_cli_robot_hints_at_a_self_colliding_elbow(bad_elbow, capsys):
    assert main(["robot", "--urdf", str(bad_elbow), "--samples", "300"]) == 0
    out = capsys.readouterr().out
    assert "hint: under 75 % free" in out
    hint = next(line for line in out.splitlines() if "hint: under 75 % free" in line)
    assert "upper_arm_link" in hint and "forearm_link" in hint and "<disable_collisions" in hint


def test_capability_map_of_a_blocked_wrist_warns_once(bad_elbow):
    """The self-colliding elbow makes a thin shell of a map: its best voxel reaches few directions, and the build
    says so in one MapWarning naming what to try; a healthy arm's build says nothing."""
    bad = Robot.from_urdf(str(bad_elbow))
    (arm,) = octoreach.find_arms(bad)
    cap, ours = _map_and_warnings(bad, arm)
    assert cap.warning and len(ours) == 1 and str(ours[0].message) == cap.warning
    assert "`octoreach robot`" in cap.warning and "approach directions" in cap.warning
    _, d = cap.voxels()
    assert d.max() < octoreach.CapabilityMap.FEW_DIRECTIONS


def test_capability_map_of_a_sound_arm_does_not_warn(own):
    _, robot = own
    with warnings.catch_warnings():
        warnings.simplefilter("error", octoreach.MapWarning)
        cap = octoreach.CapabilityMap.build_for_arm(robot, octoreach.find_arms(robot)[0], resolution=0.1,
                                                    directions=50, progress=False)
    assert cap.warning == ""


def _own_urdf(tmp_path, name: str, parts: list[str]) -> tuple:
    """(path, Robot) of a URDF of `parts` written under tmp_path."""
    path = tmp_path / f"{name}.urdf"
    path.write_text(f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "".join(parts) + "</robot>\n")
    return path, Robot.from_urdf(str(path))


def _map_and_warnings(robot, arm, **options) -> tuple:
    """(capability map at 0.1 m and 50 directions, the MapWarnings its build emitted)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cap = octoreach.CapabilityMap.build_for_arm(robot, arm, resolution=0.1, directions=50, progress=False,
                                                    **options)
    return cap, [w for w in caught if issubclass(w.category, octoreach.MapWarning)]


def _planar_arm() -> list[str]:
    """Two pitch joints and a wrist roll on a box: nothing turns the arm about the vertical."""
    parts = [_link("base", box(0.2, 0.2, 0.2), (0, 0, 0.1)),
             _link("upper", box(0.3, 0.05, 0.05), (0.15, 0, 0)),
             _joint("shoulder", "revolute", "base", "upper", (0, 0, 0.3), (0, 1, 0), (-1.5, 1.5)),
             _link("fore", box(0.25, 0.04, 0.04), (0.125, 0, 0)),
             _joint("elbow", "revolute", "upper", "fore", (0.3, 0, 0), (0, 1, 0), (-2.2, 2.2)),
             _link("hand"),
             _joint("wrist_roll", "revolute", "fore", "hand", (0.25, 0, 0), (1, 0, 0), (-3.0, 3.0))]
    return parts


def test_a_reach_thinner_than_a_voxel_warns_and_gives_no_surface_map(tmp_path):
    """An arm with no joint that turns it about the vertical reaches one plane (y = 0 of its base), which no
    voxel centre lies on: the map holds mixed cells only. The build says why in one MapWarning, and a surface map
    of it is an error naming the map, not a map of zeros or a complaint about joint solutions."""
    _, robot = _own_urdf(tmp_path, "planar", _planar_arm())
    cap, ours = _map_and_warnings(robot, ("base", "hand", (1.0, 0.0, 0.0)))
    assert cap.stats["reachable_cells"] == 0 and cap.stats["mixed_cells"] > 0 and cap.voxel_count > 0
    assert len(ours) == 1 and str(ours[0].message) == cap.warning
    assert "no voxel centre is reachable" in cap.warning and "single plane" in cap.warning
    table = octoreach.Surface.rectangle(0.4, 0.3, 0.3)
    for check_arm in (True, False):
        with pytest.raises(ValueError, match="base -> hand reaches no voxel"):
            octoreach.SurfaceMap.build(robot, cap, table, check_arm=check_arm)


def _five_joint_arm() -> list[str]:
    """A hobby arm: a base turning about the vertical, three pitch joints and a wrist roll."""
    parts = [_link("base", box(0.15, 0.15, 0.1), (0, 0, 0.05)),
             _link("turret"),
             _joint("yaw", "revolute", "base", "turret", (0, 0, 0.1), (0, 0, 1), (-2.8, 2.8)),
             _link("upper", box(0.25, 0.04, 0.04), (0.125, 0, 0)),
             _joint("shoulder", "revolute", "turret", "upper", (0, 0, 0.05), (0, 1, 0), (-1.5, 1.5)),
             _link("fore", box(0.2, 0.035, 0.035), (0.1, 0, 0)),
             _joint("elbow", "revolute", "upper", "fore", (0.25, 0, 0), (0, 1, 0), (-2.0, 2.0)),
             _link("wrist"),
             _joint("wrist_pitch", "revolute", "fore", "wrist", (0.2, 0, 0), (0, 1, 0), (-1.6, 1.6)),
             _link("hand"),
             _joint("wrist_roll", "revolute", "wrist", "hand", (0.06, 0, 0), (1, 0, 0), (-3.0, 3.0))]
    return parts


def test_a_map_with_more_mixed_cells_than_reachable_ones_warns_and_names_the_certified_lookup(tmp_path):
    """Five joints reach a thin set of (position, direction) pairs: most cells the arm's configurations land in are
    mixed, the plain lookups miss most of the arm's reach, and the build says so once, naming the lookup that
    answers those cells; the certified lookup agrees with saturated IK where the plain one misses."""
    _, robot = _own_urdf(tmp_path, "hobby", _five_joint_arm())
    cap, ours = _map_and_warnings(robot, ("base", "hand", (1.0, 0.0, 0.0)))
    s = cap.stats
    assert 0 < s["reachable_cells"] < s["mixed_cells"]
    assert len(ours) == 1 and str(ours[0].message) == cap.warning
    assert "mixed cells" in cap.warning and "CertifiedLookup" in cap.warning
    chain = robot.chain("base", "hand")
    poses, known = check_poses(robot, chain, cap.reference, 200, seed=5)
    truth = ik_truth(chain, poses, (1.0, 0.0, 0.0), cap.reference, known=known)
    certified = np.asarray(octoreach.CertifiedLookup(cap, robot).reachable(poses))
    plain = np.asarray(cap.reachable(poses))
    assert (certified == truth.reachable).mean() >= 0.99
    assert (plain & truth.reachable).sum() < 0.5 * truth.reachable.sum()  # the plain lookup misses most of them


def _scara() -> list[str]:
    """Two arm joints and a tool roll about the vertical and a quill sliding along it: the tool always points down."""
    parts = [_link("base", box(0.2, 0.2, 0.4), (0, 0, 0.2)),
             _link("arm1", box(0.3, 0.08, 0.05), (0.15, 0, 0)),
             _joint("j1", "revolute", "base", "arm1", (0, 0, 0.45), (0, 0, 1), (-2.5, 2.5)),
             _link("arm2", box(0.25, 0.07, 0.05), (0.125, 0, 0)),
             _joint("j2", "revolute", "arm1", "arm2", (0.3, 0, 0.06), (0, 0, 1), (-2.5, 2.5)),
             _link("quill", box(0.03, 0.03, 0.3), (0, 0, 0.15)),
             _joint("j3", "prismatic", "arm2", "quill", (0.25, 0, -0.3), (0, 0, 1), (0.0, 0.25)),
             _link("tool"),
             _joint("j4", "revolute", "quill", "tool", (0, 0, 0), (0, 0, 1), (-3.0, 3.0))]
    return parts


def test_a_scara_gets_a_map_with_the_poles_of_the_direction_set(tmp_path):
    """A SCARA's tool points straight down, along no direction of the spiral: its map reaches no cell and the
    warning says so; with poles=True the set holds -z, the plain lookup answers the tool poses of its configurations,
    a surface map builds, and a saved map keeps its poles."""
    path, robot = _own_urdf(tmp_path, "scara", _scara())
    arm = ("base", "tool", (0.0, 0.0, -1.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", octoreach.MapWarning)
        spiral = octoreach.CapabilityMap.build_for_arm(robot, arm, resolution=0.05, directions=50, progress=False)
    assert spiral.stats["reachable_cells"] == 0 and "poles=True" in spiral.warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", octoreach.MapWarning)
        cap = octoreach.CapabilityMap.build_for_arm(robot, arm, resolution=0.05, directions=50, poles=True,
                                                    progress=False)
    directions = cap.orientations.directions
    assert cap.orientations.poles and len(directions) == 50 and cap.stats["reachable_cells"] > 0
    assert np.allclose(directions[-2:], [[0, 0, 1], [0, 0, -1]])
    chain = robot.chain("base", "tool")
    poses, known = check_poses(robot, chain, cap.reference, 400, seed=1)
    truth = ik_truth(chain, poses, (0.0, 0.0, -1.0), cap.reference, known=known).reachable
    plain = np.asarray(cap.reachable(poses))
    certified = np.asarray(octoreach.CertifiedLookup(cap, robot).reachable(poses))
    assert (plain[known] == truth[known]).mean() >= 0.8 and (plain == truth).mean() >= 0.9
    assert (certified == truth).mean() >= 0.99
    table = octoreach.Surface.rectangle(0.3, 0.2, 0.3)
    smap = octoreach.SurfaceMap.build(robot, cap, table, progress=False)
    from_arm = octoreach.SurfaceMap.build(robot, arm, table, resolution=0.05, directions=50, poles=True, progress=False)
    assert smap.max_reachability > 0 and from_arm.max_reachability == smap.max_reachability
    with pytest.raises(ValueError, match="built without poles"):  # a map fixes its directions: no silent drop
        octoreach.SurfaceMap.build(robot, spiral, table, poles=True, progress=False)
    with pytest.raises(ValueError, match="holds 50 directions"):
        octoreach.SurfaceMap.build(robot, cap, table, directions=200, progress=False)
    with pytest.raises(ValueError, match="built with seed 0"):  # the map's cells come from its own seed
        octoreach.SurfaceMap.build(robot, cap, table, seed=7, progress=False)
    assert octoreach.SurfaceMap.build(robot, cap, table, directions=50, poles=True, seed=0,  # the map's own: accepted
                                      progress=False).max_reachability == smap.max_reachability
    room = octoreach.Room()
    room.add_surface("table", [[-0.15, -0.1, 0.3], [0.15, -0.1, 0.3], [0.15, 0.1, 0.3], [-0.15, 0.1, 0.3]])
    assert room.surface_maps(robot, arm, resolution=0.05, directions=50, poles=True,
                             progress=False)["table"].max_reachability > 0
    with pytest.raises(ValueError, match="built with seed 0"):
        room.surface_maps(robot, cap, seed=7, progress=False)
    cap.save(str(tmp_path / "scara.map"), with_solutions=True)
    loaded = octoreach.CapabilityMap.load(str(tmp_path / "scara.map"))
    assert loaded.orientations.poles and loaded.parameters["poles"] == "1"
    assert np.array_equal(loaded.orientations.directions, directions)
    assert "poles" not in spiral.parameters  # files of maps without them are as before
    # A file with poles is format version 3, which an older octoreach refuses (it would read the spiral without
    # the poles); the others stay version 2.
    spiral.save(str(tmp_path / "spiral.map"))
    version = {name: struct.unpack("<I", (tmp_path / name).read_bytes()[14:18])[0] for name in ("scara.map", "spiral.map")}
    assert version == {"scara.map": 3, "spiral.map": 2} and octoreach.CapabilityMap.format_version == 3
    out = tmp_path / "cli.orcm"
    assert main(["capability", "--urdf", str(path), "--base", "base", "--tip", "tool", "--approach-axis", "0", "0",
                 "-1", "--poles", "--resolution", "0.05", "--directions", "50", "--quiet", "--no-cache",
                 "--out", str(out)]) == 0
    from_cli = octoreach.CapabilityMap.load(str(out))
    assert from_cli.orientations.poles and from_cli.stats["reachable_cells"] == cap.stats["reachable_cells"]


def test_the_certified_lookup_answers_an_arm_whose_reach_is_thinner_than_a_voxel(tmp_path):
    """The planar arm's map reaches no voxel centre, but its mixed cells keep the configurations that landed in
    them: the certified lookup answers by IK from those and agrees with saturated IK, where the plain lookup says
    no everywhere. The map still counts as keeping its solutions (it was built with them)."""
    _, robot = _own_urdf(tmp_path, "planar", _planar_arm())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", octoreach.MapWarning)
        cap = octoreach.CapabilityMap.build_for_arm(robot, ("base", "hand", (1.0, 0.0, 0.0)), resolution=0.1,
                                                    directions=50, progress=False)
    assert cap.stats["reachable_cells"] == 0 and cap.has_solutions
    assert "CertifiedLookup" in cap.warning
    chain = robot.chain("base", "hand")
    poses, known = check_poses(robot, chain, cap.reference, 200, seed=3)
    truth = ik_truth(chain, poses, (1.0, 0.0, 0.0), cap.reference, known=known)
    assert truth.reachable.sum() >= 100  # the poses of collision-free configurations
    certified = np.asarray(octoreach.CertifiedLookup(cap, robot).reachable(poses))
    assert np.array_equal(certified, truth.reachable)
    assert not np.asarray(cap.reachable(poses)).any()
    # Its quality is none, not an error; a cache keeps it (it used to rebuild it at every call).
    assert cap.has_quality and cap.quality(poses[0][:3, 3], 0) is None and len(cap.voxel_quality()) == 0
    cache = MapCache(tmp_path / "cache")
    for _ in range(2):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", octoreach.MapWarning)
            cached = cache.capability_map(robot, ("base", "hand", (1.0, 0.0, 0.0)), resolution=0.1, directions=50,
                                          progress=False)
    assert (cache.builds, cache.hits, cache.rebuilt_mismatched) == (1, 1, 0) and cached.has_solutions
    # Built without solutions, the warning says what the certified lookup needs.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", octoreach.MapWarning)
        bare = octoreach.CapabilityMap.build_for_arm(robot, ("base", "hand", (1.0, 0.0, 0.0)), resolution=0.1,
                                                     directions=50, keep_solutions=False, progress=False)
    assert not bare.has_solutions and "keep_solutions=True" in bare.warning
