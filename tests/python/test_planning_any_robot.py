"""The planner loop with a robot written here (own_robot.py: mobile base, torso lift, 6-DOF arm, pan/tilt head with a
camera link, no SRDF): the camera link found from the URDF, partial success with an object out of reach, tasks
checked before planning, the goal a part of the Task, predefined poses for any polygon and none behind a wall."""
from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("unified_planning")
pytest.importorskip("up_fast_downward")

from octoreach import arms, base_pose, robots  # noqa: E402
from octoreach.planning import (Attachments, Goal, Planner, Scene, Task, predefined_poses, run_task,  # noqa: E402
                                scenes, solve)
from octoreach.rooms import Room  # noqa: E402

from own_robot import urdf  # noqa: E402

H = 0.75


@pytest.fixture(scope="module")
def own_world(tmp_path_factory):
    """The own robot in a room with a small table and a 1.8 x 1.8 m table whose middle no pose reaches."""
    path = tmp_path_factory.mktemp("own") / "own_robot.urdf"
    path.write_text(urdf())
    robot = robots.from_urdf(path)
    room = Room()
    room.add_table("table", 1.0, 0.6, H, x=0.0, y=0.0)
    room.add_table("wide", 1.8, 1.8, H, x=3.0, y=0.0)
    caps = {a.name: arms.capability_map(robot, a, resolution=0.1, directions=40, progress=False)
            for a in arms.find_arms(robot)}
    att = Attachments.build(robot, room, resolution=0.1, caps=caps)
    start = np.array([-2.0, 1.5, 0.0, 0.0])
    predefined = {s: predefined_poses(room, s, start) for s in room.surfaces}
    return att, Scene("own", room, start, ["table", "wide"], predefined)


def test_run_task_does_the_reachable_object_and_reports_the_other(own_world):
    att, scene = own_world
    objects = {"cup": ("table", (0.1, -0.2, H)), "far": ("wide", (3.0, 0.0, H))}
    rec = run_task(scene, att, objects, "sampling", seed=1, budget=3)
    assert not rec.solved and list(rec.unreachable) == ["far"], rec.message
    assert "out of reach from every pose" in rec.unreachable["far"] and "far" in rec.message
    # the poses counted are those of its surface, the sampled ones against the per-surface budget
    assert "at wide" in rec.unreachable["far"] and "budget 3 per surface" in rec.unreachable["far"]
    assert rec.done == ["cup"] and rec.searched == ["table", "wide"]
    done = [e.action for e in rec.log if e.outcome == "ok"]
    assert ("inspect-object", "cup") in [a[:2] for a in done]
    assert any(a[0] == "putdown-object" and a[2] == "cup" for a in done)
    assert not any(e.action[0] == "pickup-object" and e.action[2] == "far" for e in rec.log)
    assert rec.missed == 0 and rec.calls >= 2  # the failed call that proved `far` out of reach counts


def test_camera_link_is_a_parameter_and_an_unknown_one_is_named(own_world):
    att, scene = own_world
    objects = {"cup": ("table", (0.1, -0.2, H))}
    rec = run_task(scene, att, objects, 2, seed=0, camera_link="head_tilt_link")
    assert rec.objects == 1
    with pytest.raises(ValueError, match="no_camera"):
        run_task(scene, att, objects, 2, seed=0, camera_link="no_camera")


def test_objects_and_tasks_are_checked_before_planning(own_world):
    att, scene = own_world
    with pytest.raises(ValueError, match=r"object 'cup'.*not on surface 'wide'.*outside its outline"):
        run_task(scene, att, {"cup": ("wide", (0.1, -0.2, H))}, "sampling")  # the table's coordinates
    with pytest.raises(ValueError, match=r"object 'cup': scene 'own' has no surface 'island'"):
        run_task(scene, att, {"cup": ("island", (0.1, -0.2, H))}, "sampling")
    with pytest.raises(ValueError, match=r"object 'cup'.*above its top"):
        run_task(scene, att, {"cup": ("table", (0.1, -0.2, H + 0.3))}, "sampling")
    task = Task(poses={"start": scene.start}, at="start", surfaces=["table"], arms=list(att.caps),
                items={"cup": "table"}, positions={"cup": np.array([3.0, 0.0, H])})
    with pytest.raises(ValueError, match=r"item 'cup'.*not on surface 'table'"):
        Planner(att).plan(task)
    for bad, match in ((dict(items={"cup": "wide"}), r"item 'cup': its surface 'wide' is not one of"),
                       (dict(at="nowhere"), r"the robot's pose 'nowhere'"),
                       (dict(held={"left": None}), r"held: 'left' is not one of the task's arms"),
                       (dict(held={"arm": "mug"}), r"held: arm 'arm' holds 'mug', which is not"),
                       (dict(goal=Goal(search=["shelf"])), r"goal: surface 'shelf'")):
        kwargs = dict(poses={"start": scene.start}, at="start", surfaces=["table"], arms=list(att.caps))
        kwargs.update(bad)
        with pytest.raises(ValueError, match=match):
            Task(**kwargs).check()


def test_the_goal_is_part_of_the_task():
    poses = {"start": (-2, 0, 0, 0), "a": (0, -0.8, 0, 1.57)}
    kw = dict(poses=poses, at="start", surfaces=["t1"], arms=["arm"], held={"arm": None}, items={"o1": "t1"},
              usable={("a", "t1")}, reach={("a", "o1", "arm")}, searched={"t1"})
    full = [p[0] for p in solve(Task(**kw)).plan]
    assert full.count("pickup-object") == 1 and full.count("putdown-object") == 1
    keep = [p[0] for p in solve(Task(**kw, goal=Goal(put_back=False))).plan]
    assert "inspect-object" in keep and "putdown-object" not in keep
    nothing = Task(**kw, goal=Goal(inspect=False, put_back=False))
    assert nothing.done() and solve(nothing).plan == []
    given_up = Task(**kw)
    assert given_up.give_up(item="o1", reason="out of reach") and not given_up.give_up(item="o1")
    assert given_up.goal_items() == [] and given_up.done()


def _regular(n: int, radius: float, h: float, x: float = 0.0, y: float = 0.0) -> list:
    return [[x + radius * math.cos(2 * math.pi * k / n), y + radius * math.sin(2 * math.pi * k / n), h]
            for k in range(n)]


def test_predefined_poses_around_a_twelve_sided_table():
    room = Room()
    room.add_surface("round", _regular(12, 0.5, H))  # sides of 0.26 m, under MIN_SIDE
    poses = predefined_poses(room, "round", (-3.0, 0.0, 0.0, 0.0))
    assert poses.shape == (4, 4)
    for p in poses:  # around the outline, each facing the centre
        assert abs(np.hypot(p[0], p[1]) - (0.5 * math.cos(math.pi / 12) + scenes.STANDOFF)) < 0.05
        to_centre = math.atan2(-p[1], -p[0])
        assert abs((p[3] - to_centre + math.pi) % (2 * math.pi) - math.pi) < 1e-6
    angles = sorted(math.atan2(p[1], p[0]) % (2 * math.pi) for p in poses)
    assert np.allclose(np.diff(angles), math.pi / 2, atol=1e-6)  # spread evenly
    # a rectangle keeps its poses: the middles of the sides
    room.add_table("rect", 1.4, 0.65, H, x=3.0)
    assert predefined_poses(room, "rect", (3.0, 2.0, 0, 0)).shape == (4, 4)


def test_no_predefined_pose_behind_a_wall():
    """A counter against a wall (a thin one, as a room file draws it): no pose on the wall's far side; the front
    keeps its pose (the ends stand in the wall)."""
    room = Room()
    room.add_surface("counter", [[-1.0, 0.0, 0.9], [1.0, 0.0, 0.9], [1.0, 0.6, 0.9], [-1.0, 0.6, 0.9]])
    room.add_box("wall", (4.0, 0.02, 2.5), (0.0, 0.61, 1.25))
    poses = predefined_poses(room, "counter", (0.0, -2.0, 0.0, 0.0))
    assert len(poses) >= 1 and all(p[1] < 0.6 for p in poses)
    assert np.allclose(poses[0, :2], (0.0, -scenes.STANDOFF))
    room.add_box("pillar", (0.1, 0.1, 2.5), (0.0, -0.2, 1.25))  # between the front pose and the counter
    assert all(abs(p[0]) > 0.1 for p in predefined_poses(room, "counter", (0.0, -2.0, 0.0, 0.0)))


def test_a_scene_searches_its_object_surfaces_unless_told_otherwise(own_world):
    att, scene = own_world
    only_table = Scene("own", scene.room, scene.start, ["table"], scene.predefined)
    assert only_table.searched_surfaces() == ["table"]
    rec = run_task(only_table, att, {"cup": ("table", (0.1, -0.2, H))}, 2, seed=0)
    assert rec.solved and rec.searched == ["table"] and rec.done == ["cup"] and not rec.unsearched, rec.message
    assert not any(e.action[0] == "inspect-surface" and e.action[2] == "wide" for e in rec.log)
    wider = Scene("own", scene.room, scene.start, ["table"], scene.predefined, search=["table", "wide"])
    assert wider.searched_surfaces() == ["table", "wide"]
    with pytest.raises(ValueError, match="no surface 'shelf'"):
        Scene("own", scene.room, scene.start, ["table"], scene.predefined, search=["shelf"]).searched_surfaces()
    assert set(scenes.scene("chairs").searched_surfaces()) == {"table_1", "table_2"}  # built-in: the whole room


def test_sampled_poses_keep_the_robot_clear_in_its_posture(own_world):
    """By default the body the surface map recorded (its posture off the arm) is checked; with a reference
    posture the whole robot, arm included, in that posture."""
    att, _ = own_world
    robot, obstacles = att.robot, att.room.obstacles()
    assert np.allclose(att.posture(), arms.default_reference(robot, next(iter(att.caps))))
    default = Attachments(robot, att.room, att.caps, att.maps, seed=3)
    poses = default.ground("table", 4)
    assert len(poses) == 4 and not att.maps["table"].room.body_collides(poses).any()
    home = robot.home()  # the own robot's arm at 0 stands out of its base
    posed = Attachments(robot, att.room, att.caps, att.maps, seed=3, reference=home)
    assert np.array_equal(posed.posture(), home)
    poses = posed.ground("table", 4)
    assert len(poses) == 4
    assert not any(robot.in_collision(home, obstacles, base_pose=base_pose(p)) for p in poses)
    with pytest.raises(ValueError, match="reference must be a robot configuration"):
        Attachments.build(robot, att.room, caps=att.caps, reference=[0.0, 1.0])
    lifted = Attachments(robot, att.room, att.caps, att.maps, reference={"torso_lift_joint": 0.1})
    assert lifted.posture()[robot.joint_names.index("torso_lift_joint")] == 0.1


def test_built_attachments_rate_every_map_in_their_posture(tmp_path):
    """Attachments.build with a reference posture builds the arms' capability maps in it too, so the cells
    the maps rate are the ones the sampler checks."""
    path = tmp_path / "own_robot.urdf"
    path.write_text(urdf())
    robot = robots.from_urdf(path)
    room = Room()
    room.add_table("table", 0.6, 0.4, H, x=0.0, y=0.0)
    posture = robot.configuration({"torso_lift_joint": 0.1})
    att = Attachments.build(robot, room, resolution=0.2, directions=20, reference=posture)
    assert np.array_equal(att.posture(), posture)
    for cap in att.caps.values():
        assert np.array_equal(cap.reference, posture)
