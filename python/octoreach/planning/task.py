"""What the planner is told (``Task``) and what it must achieve (``Goal``).

The goal of the tidy-up task of the surface-map paper is the default: every surface searched, every item found
inspected and put back on the surface it belongs to, both hands free. A ``Goal`` says which parts a task wants
(``Goal(put_back=False)``: inspect and keep holding; ``Goal(search=["table"])``: search one surface only). Items
and surfaces the task has given up on (``Task.give_up``: an object out of reach of every pose, a surface no pose
sees) leave the goal, so the rest of the task is still planned and done.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["Goal", "Task"]


@dataclass
class Goal:
    """The planner's goal. search: True (every surface of the task), False (none) or a list of surface names;
    inspect: every known item inspected; put_back: every known item back on its surface and no arm holding one."""

    search: bool | list = True
    inspect: bool = True
    put_back: bool = True


@dataclass
class Task:
    """What the planner is told: poses by name (x, y, z, theta), where the robot is, the surfaces, the known
    items with their surfaces and the facts the attachments established.

    usable: {(pose, surface)} with R_S > 0; reach: {(pose, item, arm)} where the arm grasps the item;
    viewed: {(pose, surface)} already inspected from there; searched: surfaces believed searched; held:
    {arm: item}; inspected: items inspected; items: {item: surface it lies on / belongs to}; positions:
    {item: (3,) point on its surface}; goal: what the task must achieve (``Goal``); unreachable {item: reason}
    and unsearchable {surface: reason}: what the task gave up on (left out of the goal)."""

    poses: dict
    at: str
    surfaces: list
    arms: list
    items: dict = field(default_factory=dict)
    usable: set = field(default_factory=set)
    reach: set = field(default_factory=set)
    viewed: set = field(default_factory=set)
    searched: set = field(default_factory=set)
    held: dict = field(default_factory=dict)
    inspected: set = field(default_factory=set)
    positions: dict = field(default_factory=dict)  # item -> (3,) where it lies (the continuous state)
    pick_costs: dict = field(default_factory=dict)  # (pose, item, arm) -> expected pickup seconds (cost attachment)
    goal: Goal = field(default_factory=Goal)
    unreachable: dict = field(default_factory=dict)
    unsearchable: dict = field(default_factory=dict)

    def goal_surfaces(self) -> list:
        """The surfaces the goal wants searched, in task order, without those given up on."""
        wanted = self.goal.search
        return [s for s in self.surfaces if (wanted is True or (wanted is not False and s in wanted))
                and s not in self.unsearchable]

    def goal_items(self) -> list:
        """The known items the goal wants inspected or put back, without those given up on."""
        return [o for o in self.items if o not in self.unreachable] if self.goal.inspect or self.goal.put_back else []

    def done(self) -> bool:
        """True when the goal holds."""
        items = set(self.goal_items())
        return (set(self.goal_surfaces()) <= self.searched and (not self.goal.inspect or items <= self.inspected)
                and (not self.goal.put_back or not any(self.held.get(a) in items for a in self.held)))

    def give_up(self, item: str | None = None, surface: str | None = None, reason: str = "") -> bool:
        """Leaves an item (into unreachable) or a surface (into unsearchable) out of the goal with the reason;
        False when there was nothing new to give up (the caller stops then)."""
        if item is not None and item in self.items and item not in self.unreachable:
            self.unreachable[item] = reason
            return True
        if surface is not None and surface in self.surfaces and surface not in self.unsearchable:
            self.unsearchable[surface] = reason
            return True
        return False

    def check(self) -> None:
        """ValueError naming what does not fit: a pose that is not 4 finite numbers, the robot's pose, an item's
        surface, position or holder, a goal surface or a held item the task does not have."""
        for name, pose in self.poses.items():
            try:
                values = [float(v) for v in pose]
            except (TypeError, ValueError):
                values = []
            if len(values) != 4 or not all(map(math.isfinite, values)):
                raise ValueError(f"pose {name!r} must be 4 finite numbers (x, y, z, theta), got {pose!r}")
        if self.at not in self.poses:
            raise ValueError(f"the robot's pose {self.at!r} is not one of the task's poses ({', '.join(self.poses)})")
        for item, surface in self.items.items():
            if surface not in self.surfaces:
                raise ValueError(f"item {item!r}: its surface {surface!r} is not one of the task's surfaces "
                                 f"({', '.join(map(str, self.surfaces)) or 'none'})")
            if item not in self.positions:
                raise ValueError(f"item {item!r} has no position (Task.positions)")
        for arm, item in self.held.items():
            if arm not in self.arms:
                raise ValueError(f"held: {arm!r} is not one of the task's arms ({', '.join(self.arms)})")
            if item is not None and item not in self.items:
                raise ValueError(f"held: arm {arm!r} holds {item!r}, which is not one of the task's items")
        if self.goal.search not in (True, False):
            unknown = [s for s in self.goal.search if s not in self.surfaces]
            if unknown:
                raise ValueError(f"goal: surface {unknown[0]!r} is not one of the task's surfaces "
                                 f"({', '.join(map(str, self.surfaces))})")
