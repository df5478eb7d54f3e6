"""octoreach.planning without maps: the PDDL domain with hand-written facts, the missing-planner error, the
scenes' predefined poses, the head camera and the durations."""
from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from octoreach import Obstacles, arms
from octoreach.planning import PlannerMissing, Task, require_planner, scenes, solve
from octoreach.planning.durations import BASE_SPEED, DURATIONS, duration, move_duration
from octoreach.planning.head_camera import HeadCamera


def test_missing_planner_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "up_fast_downward", None)  # as if not installed
    with pytest.raises(PlannerMissing, match=r"'planning' extra.*pip install 'octoreach\[planning\]'"):
        require_planner()


def test_domain_with_hand_written_facts():
    pytest.importorskip("up_fast_downward")
    poses = {"start": (-2, 0, 0, 0), "a": (0, -0.8, 0, 1.57), "b": (0, 0.8, 0, -1.57), "c": (3, 0, 0, 0)}
    t = Task(poses=poses, at="start", surfaces=["t1", "t2"], arms=["left", "right"], held={"left": None, "right": None},
             items={"o1": "t1", "o2": "t1"}, usable={("a", "t1"), ("b", "t1"), ("c", "t2")},
             reach={("a", "o1", "right"), ("b", "o2", "left")}, searched={"t1"})
    plan = solve(t).plan
    assert plan is not None
    kinds = [p[0] for p in plan]
    assert kinds.count("pickup-object") == 2 and kinds.count("inspect-object") == 2
    assert kinds.count("putdown-object") == 2 and kinds.count("inspect-surface") == 1
    assert ("inspect-surface", "c", "t2") in plan  # t2 is searched from the only pose usable for it
    # a task whose object no pose reaches has no plan
    t.reach = {("a", "o1", "right")}
    assert solve(t).plan is None
    # a task already done needs no planner call
    done = Task(poses={"start": (0, 0, 0, 0)}, at="start", surfaces=["t1"], arms=["left"], searched={"t1"})
    assert solve(done).plan == []


def test_predefined_poses_are_where_a_person_would_put_them():
    sc = scenes.scene("paper")
    poses = sc.predefined["table_1"]
    assert poses.shape == (4, 4)
    x, y = -0.9, -1.0  # table_1's centre; 1.4 x 0.65 m
    # long sides first (the one nearer the start first), then the ends; all facing the table centre
    assert np.allclose(poses[0, :2], (x, y + 0.325 + scenes.STANDOFF))
    assert np.allclose(poses[1, :2], (x, y - 0.325 - scenes.STANDOFF))
    assert {round(abs(p[0] - x), 3) for p in poses[2:]} == {round(0.7 + scenes.STANDOFF, 3)}
    for p in poses:
        to_centre = math.atan2(y - p[1], x - p[0])
        assert abs((p[3] - to_centre + math.pi) % (2 * math.pi) - math.pi) < 1e-9


def test_chairs_stand_on_predefined_poses():
    sc = scenes.scene("chairs")
    obstacles = sc.room.obstacles()
    blocked = [not scenes._pose_free(obstacles, p) for p in sc.predefined["table_1"]]
    assert sum(blocked) == 3  # both long sides and the east end; the west end is free


def test_object_placement_is_seeded_and_inside():
    sc = scenes.scene("corners")
    a = scenes.place_objects(sc, 4, np.random.default_rng(3))
    b = scenes.place_objects(sc, 4, np.random.default_rng(3))
    assert a.keys() == b.keys() and all(np.allclose(a[k][1], b[k][1]) for k in a)
    for surface, p in a.values():
        assert sc.room.surfaces[surface].contains(p[None])[0] and sc.allowed[surface](p)
    with pytest.raises(ValueError, match="unknown scene 'kitchen'"):
        scenes.scene("kitchen")


def test_head_camera_sees_past_nothing_but_obstacles(pr2):
    camera = HeadCamera(pr2, arms.default_reference(pr2, "right_arm"))
    pose = (0.0, 0.0, 0.0, 0.0)
    eye = camera.position(pose)
    assert 1.0 < eye[2] < 1.8  # the PR2's head
    target = np.array([[1.5, 0.0, 0.5]])
    assert camera.visible(pose, target, Obstacles())[0]
    wall = Obstacles()
    wall.add_box((0.05, 2.0, 3.0), np.array([[1, 0, 0, 0.8], [0, 1, 0, 0], [0, 0, 1, 1.5], [0, 0, 0, 1]], float))
    assert not camera.visible(pose, target, wall)[0]
    assert not camera.visible(pose, np.array([[9.0, 0.0, 0.5]]), Obstacles())[0]  # out of range
    with pytest.raises(ValueError, match="no link named .eye."):
        HeadCamera(pr2, arms.default_reference(pr2, "right_arm"), frame="eye")


def test_durations():
    assert move_duration((0, 0, 0, 0), (BASE_SPEED * 10, 0, 0, 0)) == pytest.approx(DURATIONS["move-robot"][0] + 10)
    assert move_duration((0, 0, 0, 3.0), (0, 0, 0, -3.0)) < DURATIONS["move-robot"][0] + 0.3  # turns the short way
    assert duration("pickup-object") > 0
    with pytest.raises(KeyError, match="no duration for action 'fly'"):
        duration("fly")
