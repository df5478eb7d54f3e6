"""The task planner with its attachments: the domain of ``domain.py`` solved by Fast Downward, with the
condition and reachability attachments writing the geometric facts, and the grounding attachment adding
poses when the planner finds no plan (Section III-C of the surface-map paper).

``Planner.plan(task)``: writes the facts of every pose (R_S > 0 per surface, then IK only for those), plans;
with no plan and sampling on, asks the grounding attachment for one new pose for each surface where one is
missing (a known object no pose reaches, or a surface not searched with no pose left to look from; if neither
explains the failure, every surface with work left), adds them to the task as objects and plans again, until
a plan is found or a surface has used up its budget of sampled poses. Then the task is unsolvable and
``Unsolvable`` says why: "unsolvable: object X is out of reach from every pose with R_S > 0".
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .attachments import Attachments
from .domain import SEARCH, Task, solve
from .durations import expected_pickup_duration

__all__ = ["Planner", "Unsolvable", "PlannerTimeout", "PlanResult"]


class Unsolvable(RuntimeError):
    """No plan, and no more poses to try (the message names the object or surface left out). item / surface: the
    object no pose reaches or the surface no pose sees (None when the failure names neither); reason: why, without
    the name; figures: the failed plan()'s PlanResult (its planner calls, seconds and sampled poses count too)."""

    def __init__(self, message: str, item: str | None = None, surface: str | None = None, reason: str = "",
                 figures: "PlanResult | None" = None):
        super().__init__(message)
        self.item, self.surface, self.reason, self.figures = item, surface, reason, figures


class PlannerTimeout(RuntimeError):
    """Fast Downward ran out of its time budget (or memory) before it found a plan or proved there is none: the
    task is not known to be unsolvable (the message gives the budget and the size of the task)."""


@dataclass
class PlanResult:
    """A plan, the seconds spent (attachments + planner calls), the planner calls and poses sampled."""

    plan: list
    seconds: float
    calls: int
    sampled: int
    call_seconds: list


class Planner:
    """`attachments`: an ``Attachments``; `sampling`: whether the grounding attachment may add poses; `budget`:
    sampled poses allowed per surface and task (``reset()`` starts a task)."""

    def __init__(self, attachments: Attachments, sampling: bool = True, budget: int = 8, search: str = SEARCH,
                 timeout: float = 30.0):
        if budget < 0:
            raise ValueError(f"budget must be at least 0, got {budget!r}")
        if not timeout > 0:
            raise ValueError(f"timeout must be positive (seconds per planner call), got {timeout!r}")
        self.att, self.sampling, self.budget, self.search = attachments, sampling, int(budget), search
        self.timeout = float(timeout)
        self.used: dict = {}

    def reset(self) -> None:
        self.used = {}

    # ------------------------------------------------------------------ facts
    def write_facts(self, task: Task) -> None:
        """usable (condition attachment) for every pose and surface, reach (reachability attachment, asked
        only where the condition holds) for every pose, known object and arm, and the expected pickup duration
        of each reach (cost attachment)."""
        task.usable = {(p, s) for p, pose in task.poses.items() for s in task.surfaces
                       if self.att.condition(pose, s) > 0.0}
        task.reach, task.pick_costs = set(), {}
        for o, s in task.items.items():
            point = np.asarray(task.positions[o], float)
            try:
                self.att.check_position(point, s)
            except ValueError as e:
                raise ValueError(f"{o}: {e}") from None
            for p, pose in task.poses.items():
                if (p, s) not in task.usable:
                    continue
                for arm, rp in self.att.reach(pose, point, s).items():
                    task.reach.add((p, o, arm))
                    distance = float(np.hypot(point[0] - pose[0], point[1] - pose[1]))
                    task.pick_costs[(p, o, arm)] = expected_pickup_duration(rp, distance)

    def _missing(self, task: Task) -> tuple[list, dict]:
        """Surfaces that need a new pose, and {surface: object} of the objects no pose reaches."""
        unreached = {}
        for o in task.goal_items():
            if o in task.inspected and o not in task.held.values():
                continue
            if not any(r[1] == o for r in task.reach):
                unreached.setdefault(task.items[o], o)
        blind = [s for s in task.goal_surfaces() if s not in task.searched
                 and not any((p, s) in task.usable and (p, s) not in task.viewed for p in task.poses)]
        need = list(dict.fromkeys(list(unreached) + blind))
        if not need:
            busy = set(unreached) | {s for s in task.goal_surfaces() if s not in task.searched}
            busy |= {task.items[o] for o in task.goal_items() if o not in task.inspected}
            need = [s for s in task.surfaces if s in busy] or list(task.surfaces)
        return need, unreached

    # ------------------------------------------------------------------ planning
    def check(self, task: Task) -> None:
        """ValueError naming what does not fit before anything is planned: Task.check, every surface among the
        attachments' surfaces, every item's position on its surface (Attachments.check_position)."""
        task.check()
        for s in task.surfaces:
            if s not in self.att.maps:
                raise ValueError(f"surface {s!r} of the task has no surface map (surfaces: {', '.join(self.att.maps)})")
        for o, s in task.items.items():
            try:
                self.att.check_position(task.positions[o], s)
            except ValueError as e:
                raise ValueError(f"item {o!r}: {e}") from None

    def plan(self, task: Task) -> PlanResult:
        """A plan for `task` (Planner.check first), sampling poses where none serves; Unsolvable when the budget
        is spent."""
        self.check(task)
        t0 = time.perf_counter()
        calls, sampled, call_seconds = 0, 0, []
        while True:
            t_call = time.perf_counter()
            self.write_facts(task)
            solution = solve(task, search=self.search, timeout=self.timeout)
            calls += 1
            call_seconds.append(time.perf_counter() - t_call)  # the attachments' facts and the planner
            if solution.plan is not None:
                return PlanResult(solution.plan, time.perf_counter() - t0, calls, sampled, call_seconds)
            if solution.status in ("TIMEOUT", "MEMOUT"):  # out of budget: not a proof that there is no plan
                raise PlannerTimeout(
                    f"the planner (Fast Downward) gave no answer within its budget of {self.timeout:g} s per call "
                    f"(status {solution.status}) for {len(task.items)} objects, {len(task.surfaces)} surfaces and "
                    f"{len(task.poses)} poses: the task is not known to be unsolvable (give more time: "
                    "Planner(timeout=...))")
            if not solution.status.startswith("UNSOLVABLE"):
                raise RuntimeError(f"the planner (Fast Downward) failed: status {solution.status}")
            need, unreached = self._missing(task)
            added = 0
            if self.sampling:
                for s in need:
                    if self.used.get(s, 0) >= self.budget:
                        continue
                    self.used[s] = self.used.get(s, 0) + 1
                    for pose in self.att.ground(s, 1):
                        task.poses[f"{s}/sample_{self.used[s]}"] = np.asarray(pose, float)
                        added += 1
            sampled += added
            if added == 0 and not any(self.sampling and self.used.get(s, 0) < self.budget for s in need):
                figures = PlanResult([], time.perf_counter() - t0, calls, sampled, call_seconds)
                raise self._why(task, need, unreached, figures)

    def _tried(self, task: Task, surface: str) -> str:
        """How many poses were tried for `surface`: those of the task with R_S > 0 there, and how many of them
        the grounding attachment sampled for it (the budget counts per surface)."""
        usable = sum(1 for p in task.poses if (p, surface) in task.usable)
        text = f"{usable} pose{'' if usable == 1 else 's'} with R_S > 0 at {surface}"
        if self.sampling:
            text += f", {self.used.get(surface, 0)} of them sampled for it (budget {self.budget} per surface)"
        return text

    def _why(self, task: Task, need: list, unreached: dict, figures: PlanResult) -> Unsolvable:
        if unreached:
            s, o = next(iter(unreached.items()))
            reason = f"out of reach from every pose with R_S > 0 ({self._tried(task, s)})"
            return Unsolvable(f"unsolvable: object {o} is {reason}", item=o, reason=reason, figures=figures)
        blind = [s for s in need if s not in task.searched]
        if blind:
            reason = f"cannot be searched from any pose with R_S > 0 ({self._tried(task, blind[0])})"
            return Unsolvable(f"unsolvable: surface {blind[0]} {reason}", surface=blind[0], reason=reason,
                              figures=figures)
        tried = "; ".join(self._tried(task, s) for s in need)
        return Unsolvable(f"unsolvable: no plan for the surfaces {', '.join(need)} ({tried})", figures=figures)
