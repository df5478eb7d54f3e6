"""Continual planning (Section V of the surface-map paper): plan, execute action by action, and plan again
after every surprise (objects found, a surface only partly seen, a failed grasp), until the task is done. An
object the planner proves out of reach of every pose (or a surface no pose sees) is left out of the goal and the
rest is still done; the record lists what was left out and why.

``run_task(scene, attachments, objects, strategy, seed)`` runs one task in the simulation and returns its
``RunRecord`` with the figures of the paper's Table II: total time T (execution + planning), planning time
t_p, re-plans, moves and other actions.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .attachments import Attachments
from .planner import Planner, PlannerTimeout, Unsolvable
from .scenes import Scene
from .simulation import Simulation
from .task import Goal, Task

__all__ = ["RunRecord", "check_objects", "run_task"]


@dataclass
class RunRecord:
    """One run. Times in seconds: T = execution + t_p (t_p: wall time of the attachments and planner calls on
    this machine). solved: the whole task is done: every object found and done (inspected and put back, as the
    goal asks) and every surface of the goal searched; False as soon as anything was left out, even when the rest
    was done; message: why not. done: the objects that were done; unreachable {object: reason}: objects no pose
    reaches (left out, the rest was still done); unsearched {surface: reason}: surfaces no pose sees; searched:
    the surfaces searched; missed: objects never seen. replans: plans made after a surprise; calls: planner calls
    (grounding retries and calls that found no plan included); sampled: poses the grounding attachment added."""

    strategy: str
    objects: int
    seed: int
    solved: bool
    message: str
    T: float
    t_p: float
    execution: float
    replans: int
    calls: int
    moves: int
    other: int
    sampled: int
    failures: int
    missed: int
    unreachable: dict = field(default_factory=dict)
    unsearched: dict = field(default_factory=dict)
    done: list = field(default_factory=list)
    searched: list = field(default_factory=list)
    call_seconds: list = field(default_factory=list)
    log: list = field(default_factory=list, repr=False)


def check_objects(scene: Scene, attachments: Attachments, objects: dict) -> None:
    """ValueError naming the object whose entry does not fit: (surface, point) with a surface of the scene's room
    and a point (x, y, z) on it (Attachments.check_position)."""
    for name, entry in objects.items():
        try:
            surface, point = entry
        except (TypeError, ValueError):
            raise ValueError(f"object {name!r}: expected (surface, point), got {entry!r}") from None
        if surface not in scene.room.surfaces:
            raise ValueError(f"object {name!r}: scene {scene.name!r} has no surface {surface!r} "
                             f"(surfaces: {', '.join(scene.room.surfaces)})")
        try:
            attachments.check_position(point, surface)
        except ValueError as e:
            raise ValueError(f"object {name!r}: {e}") from None


def _task(scene: Scene, attachments: Attachments, strategy, goal: Goal | None) -> tuple[Task, dict]:
    """The task at the start (the predefined poses of the strategy, the scene's searched surfaces some pose
    reaches: ``Scene.searched_surfaces``, by default its object surfaces) and
    {surface: reason} of the surfaces no base pose reaches (left out of the task)."""
    poses = {"start": np.asarray(scene.start, float)}
    if strategy != "sampling":
        for s, rows in scene.predefined.items():
            for i, pose in enumerate(rows[:strategy]):
                poses[f"{s}/pose_{i + 1}"] = pose
    wanted = scene.searched_surfaces()
    surfaces = [s for s in wanted if attachments.maps[s].max_reachability > 0.0]
    unreached = {s: "no base pose reaches it (its surface map is empty)" for s in wanted if s not in surfaces}
    arms = list(attachments.caps)
    task = Task(poses=poses, at="start", surfaces=surfaces, arms=arms, held={a: None for a in arms},
                goal=goal if goal is not None else Goal())
    return task, unreached


def run_task(scene: Scene, attachments: Attachments, objects: dict, strategy="sampling", seed: int = 0,
             budget: int = 8, max_replans: int = 60, camera_link: str | None = None, goal: Goal | None = None) -> RunRecord:
    """One tidy-up task: `objects` {name: (surface, point)} (``scenes.place_objects``; checked first: ValueError
    naming an object whose surface the room lacks or whose point is not on it); `strategy` 'sampling' (no poses
    given, the grounding attachment adds them) or k in 1..4 (the first k predefined poses of each surface, nothing
    sampled); `camera_link` the robot's camera (None: ``octoreach.find_camera_link``); `goal` what the task must
    achieve (None: ``Goal()``, every surface of the scene's task searched, ``Scene.searched_surfaces``: its object
    surfaces unless ``Scene.search`` says otherwise; every item inspected and put back). An object no pose
    reaches, or a surface no pose sees, is left out and the rest is done: the record lists them with the reason
    (``RunRecord.unreachable``, ``unsearched``) beside the objects done (``RunRecord.done``), and ``solved`` is
    False."""
    if strategy != "sampling" and strategy not in (1, 2, 3, 4):
        raise ValueError(f"strategy must be 'sampling' or 1-4 predefined poses, got {strategy!r}")
    check_objects(scene, attachments, objects)
    sim = Simulation(scene, attachments, objects, seed=seed, camera_link=camera_link)
    attachments.reset(seed)
    planner = Planner(attachments, sampling=strategy == "sampling", budget=budget)
    task, unsearched = _task(scene, attachments, strategy, goal)
    planner.check(task)
    n = _Figures()
    while True:
        try:
            result = planner.plan(task)
        except PlannerTimeout as e:  # not known to be unsolvable: the run stops and says so
            n.message = str(e)
            break
        except Unsolvable as e:
            n.add(e.figures)
            if task.give_up(e.item, e.surface, e.reason):
                continue  # plan the rest without it
            n.message = str(e)
            break
        n.add(result)
        if not result.plan:
            break
        if any(sim.execute(action, task) for action in result.plan):  # stops at the first surprise
            n.replans += 1
            if n.replans > max_replans:
                n.message = f"gave up after {max_replans} re-plans"
                break
    return _record(strategy, objects, seed, task, sim, n, {**unsearched, **task.unsearchable})


@dataclass
class _Figures:
    """What the planner calls of one run added up, and why the run stopped early ('' when it did not)."""

    t_p: float = 0.0
    calls: int = 0
    sampled: int = 0
    replans: int = 0
    message: str = ""
    call_seconds: list = field(default_factory=list)

    def add(self, result) -> None:
        if result is not None:
            self.t_p += result.seconds
            self.calls += result.calls
            self.sampled += result.sampled
            self.call_seconds += result.call_seconds


def _record(strategy, objects: dict, seed: int, task: Task, sim: Simulation, n: _Figures, unsearched: dict) -> RunRecord:
    """The RunRecord of a finished run: solved when every object was found, inspected and put back and every surface
    of the goal searched; message the first reason it was not."""
    missed = sum(1 for o in objects if o not in task.items)
    notes = [f"object {o} {why}" for o, why in task.unreachable.items()]
    notes += [f"surface {s} {why}" for s, why in task.unsearchable.items()]
    if missed:
        notes.append(f"{missed} object(s) never seen")
    message = n.message or "; ".join(notes)
    solved = not message and task.done()
    moves = sum(1 for e in sim.log if e.action[0] == "move-robot")
    label = "sampling" if strategy == "sampling" else f"{strategy} predefined"
    held = set(task.held.values())
    done = [o for o in task.goal_items() if (not task.goal.inspect or o in task.inspected)
            and (not task.goal.put_back or o not in held)]
    return RunRecord(strategy=label, objects=len(objects), seed=seed, solved=solved, message=message,
                     T=sim.clock + n.t_p, t_p=n.t_p, execution=sim.clock, replans=n.replans, calls=n.calls, moves=moves,
                     other=len(sim.log) - moves, sampled=n.sampled, failures=sim.failures, missed=missed,
                     unreachable=dict(task.unreachable), unsearched=unsearched, done=done,
                     searched=[s for s in task.surfaces if s in task.searched], call_seconds=n.call_seconds,
                     log=sim.log)
