"""Continual planning (Section V of the surface-map paper): plan, execute action by action, and plan again
after every surprise (objects found, a surface only partly seen, a failed grasp), until the task is done or
the planner proves it unsolvable.

``run_task(scene, attachments, objects, strategy, seed)`` runs one task in the simulation and returns its
``RunRecord`` with the figures of the paper's Table II: total time T (execution + planning), planning time
t_p, re-plans, moves and other actions.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .attachments import Attachments
from .domain import Task
from .planner import Planner, PlannerTimeout, Unsolvable
from .scenes import Scene
from .simulation import Simulation

__all__ = ["RunRecord", "run_task"]


@dataclass
class RunRecord:
    """One run. Times in seconds: T = execution + t_p (t_p: wall time of the attachments and planner calls on
    this machine). solved: every object found, inspected and put back; message: why not. replans: plans made
    after a surprise; calls: planner calls (grounding retries included); sampled: poses the grounding
    attachment added; missed: objects never seen."""

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
    call_seconds: list = field(default_factory=list)
    log: list = field(default_factory=list, repr=False)


def run_task(scene: Scene, attachments: Attachments, objects: dict, strategy="sampling", seed: int = 0,
             budget: int = 8, max_replans: int = 60) -> RunRecord:
    """One tidy-up task: `objects` {name: (surface, point)} (``scenes.place_objects``); `strategy` 'sampling'
    (no poses given, the grounding attachment adds them) or k in 1..4 (the first k predefined poses of each
    surface, nothing sampled)."""
    if strategy != "sampling" and strategy not in (1, 2, 3, 4):
        raise ValueError(f"strategy must be 'sampling' or 1-4 predefined poses, got {strategy!r}")
    attachments.reset(seed)
    sampling = strategy == "sampling"
    planner = Planner(attachments, sampling=sampling, budget=budget)
    poses = {"start": np.asarray(scene.start, float)}
    if not sampling:
        for s, rows in scene.predefined.items():
            for i, pose in enumerate(rows[:strategy]):
                poses[f"{s}/pose_{i + 1}"] = pose
    surfaces = [s for s in scene.room.surfaces if attachments.maps[s].max_reachability > 0.0]
    arms = list(attachments.caps)
    task = Task(poses=poses, at="start", surfaces=surfaces, arms=arms, held={a: None for a in arms})
    sim = Simulation(scene, attachments, objects, seed=seed)
    t_p, calls, replans, sampled, message, call_seconds = 0.0, 0, 0, 0, "", []
    while True:
        try:
            result = planner.plan(task)
        except (Unsolvable, PlannerTimeout) as e:
            message = str(e)
            break
        t_p += result.seconds
        calls += result.calls
        sampled += result.sampled
        call_seconds += result.call_seconds
        if not result.plan:
            break
        surprised = False
        for action in result.plan:
            if sim.execute(action, task):
                surprised = True
                break
        if surprised:
            replans += 1
            if replans > max_replans:
                message = f"gave up after {max_replans} re-plans"
                break
    missed = sum(1 for o in objects if o not in task.items)
    solved = not message and task.done() and missed == 0
    if not message and missed:
        message = f"{missed} object(s) never seen"
    moves = sum(1 for e in sim.log if e.action[0] == "move-robot")
    label = "sampling" if sampling else f"{strategy} predefined"
    return RunRecord(strategy=label, objects=len(objects), seed=seed, solved=solved, message=message,
                     T=sim.clock + t_p, t_p=t_p, execution=sim.clock, replans=replans, calls=calls, moves=moves,
                     other=len(sim.log) - moves, sampled=sampled, failures=sim.failures, missed=missed,
                     call_seconds=call_seconds, log=sim.log)
