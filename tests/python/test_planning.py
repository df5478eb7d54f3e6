"""Task planning with surface maps (octoreach.planning): the attachments, the grounding planner, continual
planning in the simulation. One coarse room (0.1 m maps, 50 directions) built once for the module."""
from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("unified_planning")
pytest.importorskip("up_fast_downward")

from octoreach import arms  # noqa: E402
from octoreach.planning import (Attachments, Planner, Scene, Task, Unsolvable, predefined_poses,  # noqa: E402
                                run_task)
from octoreach.rooms import Room  # noqa: E402

H = 0.72


@pytest.fixture(scope="module")
def world(pr2):
    """Two paper tables 3 m apart and a 1.8 x 1.8 m table whose centre no arm reaches from any pose."""
    room = Room()
    room.add_table("table_1", 1.4, 0.65, H, x=0.0, y=0.0)
    room.add_table("table_2", 1.4, 0.65, H, x=0.0, y=3.0)
    room.add_table("wide", 1.8, 1.8, H, x=3.5, y=1.5)
    caps = {a: arms.capability_map(pr2, a, resolution=0.1, directions=50, progress=False)
            for a in ("left_arm", "right_arm")}
    return Attachments.build(pr2, room, resolution=0.1, caps=caps)


def task(att, poses, items, surfaces=("table_1",)):
    arm_names = list(att.caps)
    return Task(poses=dict(poses), at="start", surfaces=list(surfaces), arms=arm_names,
                held={a: None for a in arm_names}, items={o: s for o, (s, _) in items.items()},
                positions={o: np.asarray(p, float) for o, (_, p) in items.items()}, searched=set(surfaces))


START = (-2.0, 1.5, 0.0, 0.0)
HAND_POSE = (0.0, -0.325 - 0.45, 0.0, math.pi / 2)  # middle of table_1's south side, facing it
CUP = ("table_1", (0.1, -0.15, H))


def test_one_object_task_with_a_hand_given_pose(world):
    world.reset(0)
    t = task(world, {"start": START, "hand": HAND_POSE}, {"cup": CUP})
    result = Planner(world, sampling=False).plan(t)
    kinds = [a[0] for a in result.plan]
    assert kinds == ["move-robot", "pickup-object", "inspect-object", "putdown-object"]
    assert result.plan[0][1:] == ("start", "hand") and result.plan[1][1:3] == ("hand", "cup")
    assert result.calls == 1 and result.sampled == 0


def test_grounding_adds_poses_until_a_two_pose_task_is_solved(world):
    world.reset(1)
    items = {"cup": CUP, "mug": ("table_2", (-0.1, 3.1, H))}
    surfaces = ("table_1", "table_2")
    with pytest.raises(Unsolvable, match="out of reach from every pose"):
        Planner(world, sampling=False).plan(task(world, {"start": START}, items, surfaces))
    t = task(world, {"start": START}, items, surfaces)
    result = Planner(world, sampling=True, budget=8).plan(t)
    assert result.sampled >= 2 and result.calls >= 2
    picks = {a[2]: a[1] for a in result.plan if a[0] == "pickup-object"}
    assert set(picks) == {"cup", "mug"}
    assert picks["cup"].startswith("table_1/sample_") and picks["mug"].startswith("table_2/sample_")
    assert len({a[2] for a in result.plan if a[0] == "move-robot"}) >= 2
    # the poses were drawn with the discount: the sampler of a surface remembers all of them
    assert len(world.sampler("table_1").history) == sum(p.startswith("table_1/") for p in t.poses)


def test_out_of_reach_object_ends_as_unsolvable(world):
    world.reset(2)
    t = task(world, {"start": START}, {"far": ("wide", (3.5, 1.5, H))}, ("wide",))
    with pytest.raises(Unsolvable, match=r"unsolvable: object far is out of reach from every pose with R_S > 0"):
        Planner(world, sampling=True, budget=3).plan(t)
    assert len(world.sampler("wide").history) == 3  # the whole budget, no more


def test_condition_prunes_a_pose_with_zero_reachability_before_any_ik(world):
    world.reset(3)
    away = (6.0, -4.0, 0.0, 0.0)  # far from every table: R_S 0
    assert world.condition(away, "table_1") == 0.0
    before, pruned = world.ik_calls, world.pruned
    assert world.reach(away, CUP[1], "table_1") == {}
    assert world.ik_calls == before and world.pruned == pruned + 1
    t = task(world, {"start": START, "away": away, "hand": (0.05, -0.775, 0.0, math.pi / 2)}, {"cup": CUP})
    Planner(world, sampling=False).write_facts(t)
    assert ("away", "table_1") not in t.usable and not any(r[0] == "away" for r in t.reach)
    assert any(r[0] == "hand" for r in t.reach)
    assert world.ik_calls > before  # the usable pose was checked by IK, the other one never


def test_grounding_discounts_against_every_earlier_pose_across_calls(world):
    world.reset(4)
    first = world.ground("table_2", 1)[0]
    second = world.ground("table_2", 2)
    history = world.sampler("table_2").history
    assert len(history) == 3 and np.allclose(history[0], first) and np.allclose(history[1:], second)
    assert world.sampler("table_2").discount(first) == 0.0  # a pose drawn before counts against new candidates
    assert all(world.condition(p, "table_2") > 0 for p in history)


@pytest.fixture(scope="module")
def scene(world):
    start = np.array(START)
    predefined = {s: predefined_poses(world.room, s, start) for s in world.room.surfaces}
    return Scene("test", world.room, start, ["table_1", "table_2"], predefined)


def _strip(record):
    return (record.solved, record.message, record.replans, record.moves, record.other, record.sampled,
            record.failures, round(record.execution, 6), [(e.action, e.outcome, round(e.time, 6)) for e in record.log])


@pytest.mark.parametrize("strategy", ["sampling", 2])
def test_simulation_is_deterministic_for_a_seed(world, scene, strategy):
    objects = {"cup": CUP, "mug": ("table_2", (-0.1, 3.1, H))}
    a = run_task(scene, world, objects, strategy, seed=5)
    b = run_task(scene, world, objects, strategy, seed=5)
    assert _strip(a) == _strip(b)
    assert a.moves >= 2 and a.T > a.execution > 0 and a.t_p > 0
    found = [e for e in a.log if e.action[0] == "inspect-surface" and "found" in e.outcome]
    assert found, "objects are unknown until a surface is inspected"
    if strategy == "sampling":
        assert a.solved, a.message
