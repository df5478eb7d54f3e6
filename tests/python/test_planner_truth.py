"""The planner says what happened: a Fast Downward timeout is reported as a timeout with its budget (never as
"unsolvable"), an object that does not lie on its surface is refused, and the reachability check counts no
grasp whose gripper is inside the surface slab."""
from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("unified_planning")
pytest.importorskip("up_fast_downward")

import octoreach  # noqa: E402
from octoreach.planning import (Attachments, Planner, PlannerTimeout, Task, Unsolvable,  # noqa: E402
                                run_task)
from octoreach.planning.attachments import ON_SURFACE  # noqa: E402
from octoreach.rooms import Room  # noqa: E402
from octoreach.surface_maps import GraspCheck  # noqa: E402

TOP = 0.4


@pytest.fixture(scope="module")
def world():
    robot = octoreach.robots.test_arm()
    room = Room()
    room.add_table("t", 0.6, 0.4, TOP, x=0.55, legs=None)
    att = Attachments.build(robot, room, resolution=0.2, directions=16)
    poses = {"start": np.array([-1.0, 0.0, 0.0, 0.0])}
    for i, p in enumerate(att.ground("t", 3)):
        poses[f"p{i}"] = p
    return att, poses


def task(att, poses, items):
    arm = list(att.caps)
    return Task(poses=dict(poses), at="start", surfaces=["t"], arms=arm, held={a: None for a in arm},
                items={k: "t" for k in items}, positions={k: np.asarray(p, float) for k, p in items.items()},
                searched={"t"})


def test_a_timeout_is_a_timeout_with_its_budget(world):
    att, poses = world
    t = task(att, poses, {"cup": (0.55, 0.0, TOP)})
    assert Planner(att, sampling=False).plan(t).plan  # solvable with time
    with pytest.raises(PlannerTimeout, match=r"within its budget of 0.001 s .*not known to be unsolvable") as e:
        Planner(att, sampling=True, timeout=0.001).plan(task(att, poses, {"cup": (0.55, 0.0, TOP)}))
    assert not isinstance(e.value, Unsolvable) and "unsolvable:" not in str(e.value)
    with pytest.raises(ValueError, match="timeout must be positive"):
        Planner(att, timeout=0)


def test_run_task_records_a_timeout_as_such(world, monkeypatch):
    from octoreach.planning import continual, scenes

    att, poses = world

    class Quiet:  # the simulation of the PR2 (its head camera) is not needed to see what run_task records
        log, clock, failures = [], 0.0, 0

        def __init__(self, *args, **kwargs):
            pass

    real = continual.Planner
    monkeypatch.setattr(continual, "Planner", lambda *a, **k: real(*a, **k, timeout=0.001))
    monkeypatch.setattr(continual, "Simulation", Quiet)
    scene = scenes.Scene("t", att.room, poses["start"], ["t"], {"t": [poses["p0"]]})
    record = run_task(scene, att, {}, "sampling", seed=1)
    assert not record.solved and "within its budget" in record.message and "unsolvable:" not in record.message


@pytest.mark.parametrize("point, fragment", [
    ((0.55, 0.0, TOP - 0.22), "0.220 m under its top"),
    ((0.55, 0.0, TOP + 0.3), "above its top"),
    ((2.0, 0.0, TOP), "outside its outline"),
    ((0.55, float("nan"), TOP), "3 finite numbers"),
])
def test_objects_must_lie_on_their_surface(world, point, fragment):
    att, poses = world
    with pytest.raises(ValueError, match=fragment):
        att.reach(poses["p0"], point, "t")
    t = task(att, poses, {"cup": point})
    with pytest.raises(ValueError, match=f"cup'?: .*{fragment}"):
        Planner(att, sampling=False).plan(t)
    att.check_position((0.55, 0.0, TOP + ON_SURFACE * 0.9), "t")  # a little off, within the tolerance


def test_no_grasp_with_the_gripper_inside_the_slab_counts(pr2):
    cap = octoreach.arms.capability_map(pr2, "right_arm", resolution=0.2, directions=16, progress=False)
    table = Room()
    table.add_table("t", 1.4, 0.65, 0.72, legs=None)
    surface = table.surfaces["t"]
    pose = np.array([0.0, -0.325 - 0.45, 0.0, math.pi / 2])  # facing the middle of its long side
    inside = np.array([[0.1, -0.15, 0.72 - 0.10 + 0.05]])  # the grasp point of an object 10 cm under the top
    on_top = np.array([[0.1, -0.15, 0.72 + 0.05]])
    plain = GraspCheck(pr2, cap, surface, attempts=10)
    slab = GraspCheck(pr2, cap, surface, attempts=10, tool_checks_slab=True)
    assert plain.shares(pose, inside)[0] > 0  # the surface maps' check lets the gripper touch the slab
    assert slab.shares(pose, inside)[0] == 0.0
    assert slab.shares(pose, on_top)[0] == plain.shares(pose, on_top)[0] > 0
