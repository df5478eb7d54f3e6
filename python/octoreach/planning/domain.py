"""The mobile pick-and-place PDDL domain of the surface-map paper (Section V), built with the Unified Planning
framework and solved by Fast Downward (``OneshotPlanner(name="fast-downward")``).

Types: pose, surface, item, arm. Actions (costs are the durations of ``durations.py``, in seconds):

* ``move-robot(?from ?to)``: the base drives between two poses (cost: ``move_duration``);
* ``inspect-surface(?p ?s)``: at a pose usable for the surface (condition attachment, R_S > 0) that it was not
  inspected from yet, the head camera looks at the surface: it is searched (the planner's optimistic belief:
  the simulation says afterwards what was really seen);
* ``pickup-object(?p ?o ?s ?a)``: a free arm grasps a known item on a surface, from a pose where that arm
  reaches it (reachability attachment: IK, asked only where the condition holds); its cost is the expected
  duration with retries after failed grasps (``expected_pickup_duration``: harder grasps cost more, so the
  planner prefers a pose from which the grasp is easy, as the paper's cost attachments do);
* ``inspect-object(?o ?a)``: the held item is held in front of the camera;
* ``putdown-object(?p ?o ?s ?a)``: the item goes back where it was (reached by that arm from that pose).

Goal: the task's ``Goal`` (``task.py``; by default every surface searched, every known item inspected and back on
its surface), without the items and surfaces the task gave up on. The attachments are evaluated when the task is
written down (``Task``): a pose/surface pair whose R_S is 0 never reaches the planner, so no IK is asked for it.
"""
from __future__ import annotations

import re
import time
from dataclasses import dataclass

from .durations import duration, move_duration
from .task import Goal, Task

__all__ = ["Goal", "Task", "PlannerMissing", "solve", "require_planner", "SEARCH"]

#: Fast Downward search: A* with the (inadmissible) FF heuristic: cost-aware, plans near the cheapest, and within
#: 0.2-0.6 s per call on our tasks (lazy greedy search was as fast but drove between poses needlessly).
SEARCH = "eager_wastar([ff()],w=1)"


class PlannerMissing(ImportError):
    """The Unified Planning framework or its Fast Downward engine is not installed."""


def require_planner():
    """The ``unified_planning.shortcuts`` module, after checking that Fast Downward is there."""
    try:
        import unified_planning.shortcuts as up
        import up_fast_downward  # noqa: F401
    except ImportError as e:
        raise PlannerMissing(f"the task planner needs the 'planning' extra (unified-planning and up-fast-downward): "
                             f"pip install 'octoreach[planning]' ({e})") from None
    up.get_environment().credits_stream = None
    return up


def _ident(prefix: str, names) -> dict:
    """PDDL-safe identifiers for arbitrary names (shelf boards are 'shelf/0')."""
    return {n: f"{prefix}{i}_{re.sub(r'[^A-Za-z0-9]', '_', str(n))}" for i, n in enumerate(names)}


def _actions(up, types, f, move_cost, pick_cost):
    """The five actions of the domain over the types (pose, surface, item, arm) and fluents `f`, with their
    costs: {action: cost (an int, a float of seconds or a cost fluent)}."""
    Pose, Surf, Item, Arm = types
    move = up.InstantaneousAction("move_robot", a=Pose, b=Pose)
    a, b = move.parameters
    move.add_precondition(f["at"](a))
    move.add_precondition(up.Not(up.Equals(a, b)))
    move.add_effect(f["at"](a), False)
    move.add_effect(f["at"](b), True)

    look = up.InstantaneousAction("inspect_surface", p=Pose, s=Surf)
    p, s = look.parameters
    for c in (f["at"](p), f["usable"](p, s), up.Not(f["viewed"](p, s))):
        look.add_precondition(c)
    look.add_effect(f["searched"](s), True)
    look.add_effect(f["viewed"](p, s), True)

    pick = up.InstantaneousAction("pickup_object", p=Pose, o=Item, s=Surf, a=Arm)
    p, o, s, arm = pick.parameters
    for c in (f["at"](p), f["on"](o, s), f["reach"](p, o, arm), f["free"](arm), f["searched"](s)):
        pick.add_precondition(c)
    pick.add_effect(f["on"](o, s), False)
    pick.add_effect(f["free"](arm), False)
    pick.add_effect(f["holding"](arm, o), True)

    inspect = up.InstantaneousAction("inspect_object", o=Item, a=Arm)
    o, arm = inspect.parameters
    inspect.add_precondition(f["holding"](arm, o))
    inspect.add_effect(f["inspected"](o), True)

    put = up.InstantaneousAction("putdown_object", p=Pose, o=Item, s=Surf, a=Arm)
    p, o, s, arm = put.parameters
    for c in (f["at"](p), f["holding"](arm, o), f["home"](o, s), f["reach"](p, o, arm)):
        put.add_precondition(c)
    put.add_effect(f["holding"](arm, o), False)
    put.add_effect(f["free"](arm), True)
    put.add_effect(f["on"](o, s), True)

    a, b = move.parameters
    p, o, _, arm = pick.parameters
    return {move: move_cost(a, b), look: duration("inspect-surface"), pick: pick_cost(p, o, arm),
            inspect: duration("inspect-object"), put: duration("putdown-object")}


def _add_objects(up, problem, task: Task, types):
    """Adds the task's poses, surfaces, items and arms as objects; returns ({identifier: task name},
    {kind: {task name: object}}) with kinds "p", "s", "o", "a"."""
    names = {}
    objs = {}
    for kind, typ, items in zip("psoa", types, (task.poses, task.surfaces, task.items, task.arms)):
        for name, ident in _ident(kind, items).items():
            objs[(kind, name)] = up.Object(ident, typ)
            names[ident] = name
    problem.add_objects(list(objs.values()))
    by_kind = {kind: {n: objs[(kind, n)] for n in items}
               for kind, items in zip("psoa", (task.poses, task.surfaces, task.items, task.arms))}
    return names, by_kind


def _set_initial_state(problem, task: Task, f, move_cost, pick_cost, objects) -> None:
    """The task's facts as the problem's initial values (what is not set is false)."""
    P, S, O, A = (objects[k] for k in "psoa")
    problem.set_initial_value(f["at"](P[task.at]), True)
    for pa in task.poses:
        for pb in task.poses:
            if pa != pb:
                cost = int(round(move_duration(task.poses[pa], task.poses[pb])))
                problem.set_initial_value(move_cost(P[pa], P[pb]), cost)
    for pn, sn in task.usable:
        problem.set_initial_value(f["usable"](P[pn], S[sn]), True)
    for pn, sn in task.viewed:
        problem.set_initial_value(f["viewed"](P[pn], S[sn]), True)
    for sn in task.searched:
        problem.set_initial_value(f["searched"](S[sn]), True)
    held = {o: arm for arm, o in task.held.items() if o}
    for on, sn in task.items.items():
        problem.set_initial_value(f["home"](O[on], S[sn]), True)
        if on in held:
            problem.set_initial_value(f["holding"](A[held[on]], O[on]), True)
        else:
            problem.set_initial_value(f["on"](O[on], S[sn]), True)
        if on in task.inspected:
            problem.set_initial_value(f["inspected"](O[on]), True)
    for pn, on, an in task.reach:
        problem.set_initial_value(f["reach"](P[pn], O[on], A[an]), True)
        if (pn, on, an) in task.pick_costs:
            problem.set_initial_value(pick_cost(P[pn], O[on], A[an]), int(round(task.pick_costs[(pn, on, an)])))
    for an in task.arms:
        if not task.held.get(an):
            problem.set_initial_value(f["free"](A[an]), True)


def build_problem(task: Task):
    """The Unified Planning problem of a Task, and a map from its object names back to the task's names."""
    up = require_planner()
    types = Pose, Surf, Item, Arm = tuple(up.UserType(n) for n in ("pose", "surface", "item", "arm"))
    f = {name: up.Fluent(name, up.BoolType(), **params) for name, params in {
        "at": {"p": Pose}, "usable": {"p": Pose, "s": Surf}, "viewed": {"p": Pose, "s": Surf},
        "searched": {"s": Surf}, "on": {"o": Item, "s": Surf}, "home": {"o": Item, "s": Surf},
        "reach": {"p": Pose, "o": Item, "a": Arm}, "free": {"a": Arm}, "holding": {"a": Arm, "o": Item},
        "inspected": {"o": Item}}.items()}
    move_cost = up.Fluent("move_cost", up.IntType(), a=Pose, b=Pose)
    pick_cost = up.Fluent("pick_cost", up.IntType(), p=Pose, o=Item, a=Arm)
    costs = _actions(up, types, f, move_cost, pick_cost)

    problem = up.Problem("tidy_up")
    for fl in f.values():
        problem.add_fluent(fl, default_initial_value=False)
    problem.add_fluent(move_cost, default_initial_value=0)
    problem.add_fluent(pick_cost, default_initial_value=int(round(duration("pickup-object"))))
    for action in costs:
        problem.add_action(action)
    names, objects = _add_objects(up, problem, task, types)
    _set_initial_state(problem, task, f, move_cost, pick_cost, objects)

    S, O = objects["s"], objects["o"]
    for sn in task.goal_surfaces():
        problem.add_goal(f["searched"](S[sn]))
    for on in task.goal_items():
        if task.goal.inspect:
            problem.add_goal(f["inspected"](O[on]))
        if task.goal.put_back:
            problem.add_goal(f["on"](O[on], S[task.items[on]]))
    problem.add_quality_metric(up.MinimizeActionCosts({k: (v if not isinstance(v, float) else int(round(v)))
                                                        for k, v in costs.items()}))
    return problem, names


_ACTION_NAMES = {"move_robot": "move-robot", "inspect_surface": "inspect-surface", "pickup_object": "pickup-object",
                 "inspect_object": "inspect-object", "putdown_object": "putdown-object"}


@dataclass
class Solution:
    """A plan (list of ``(action, *arguments)`` tuples with the task's names; None when none was found) and the
    seconds the call took (problem writing, translation and search)."""

    plan: list | None
    seconds: float
    status: str


def solve(task: Task, search: str = SEARCH, timeout: float = 30.0) -> Solution:
    """Plans for a task with Fast Downward; a task already done gives the empty plan without a call."""
    t0 = time.perf_counter()
    if task.done():
        return Solution([], 0.0, "done")
    up = require_planner()
    problem, names = build_problem(task)
    with up.OneshotPlanner(name="fast-downward", params={"fast_downward_search_config": search}) as planner:
        result = planner.solve(problem, timeout=timeout)
    status = result.status.name
    if result.plan is None:
        return Solution(None, time.perf_counter() - t0, status)
    plan = [(_ACTION_NAMES[ai.action.name], *(names[str(x)] for x in ai.actual_parameters))
            for ai in result.plan.actions]
    return Solution(plan, time.perf_counter() - t0, status)
