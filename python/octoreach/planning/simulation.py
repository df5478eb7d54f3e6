"""A small discrete-event simulation of a robot (the paper's PR2 by default) executing the tidy-up domain in a scene: the world the
continual planner acts in. Seeded and deterministic: the same scene, objects and seed give the same events.

* **Time**: every action advances the clock by its duration (``durations.py``: one table with sources).
* **Perception**: ``inspect-surface`` reveals the objects of that surface the head camera sees from the pose
  (``head_camera.py``: range and line of sight past the room's obstacles), so objects are unknown until then;
  the surface counts as searched once SEEN_SHARE of its grid points (0.1 m) have been seen from the poses
  inspected so far. New objects, or a surface still partly unseen, are surprises.
* **Execution failures**: a grasp fails with ``durations.grasp_failure_probability`` (growing as R_P, the
  reachability attachment's share of grasps, falls and as the object lies farther from the base). A failed
  grasp leaves the object where it was and is a surprise. Moves and the other actions always succeed.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .attachments import Attachments
from .task import Task
from .durations import duration, grasp_failure_probability, move_duration
from .head_camera import HeadCamera
from .scenes import Scene

__all__ = ["Simulation"]

SEEN_SHARE = 0.9
SEEN_RESOLUTION = 0.1  # m, grid of the surface points the camera must see
OBJECT_TOP = 0.04  # m above the surface: the point of an object the camera must see


@dataclass
class Event:
    """One executed action: when it ended (s), the action tuple, its outcome ('ok' or the surprise)."""

    time: float
    action: tuple
    outcome: str


@dataclass
class Simulation:
    """The true world of one run: the scene, where the objects really are ({name: (surface, point)}), the
    clock, and the log; `camera_link` the robot's camera (None: found, see ``head_camera.HeadCamera``).
    ``execute(action, task)`` runs one planned action and updates the planner's task with what the robot
    observes; it returns the surprise (a string) or None."""

    scene: Scene
    attachments: Attachments
    objects: dict
    seed: int = 0
    clock: float = 0.0
    log: list = field(default_factory=list)
    failures: int = 0
    camera_link: str | None = None

    def __post_init__(self):
        self.rng = np.random.default_rng([self.seed, 7])
        robot = self.attachments.robot
        self.camera = HeadCamera(robot, self.attachments.posture(), self.camera_link)
        self.obstacles = self.scene.room.obstacles()
        self.points, self.seen = {}, {}
        for name, surface in self.scene.room.surfaces.items():
            self.points[name] = surface.points(SEEN_RESOLUTION) + 0.02 * np.asarray(surface.normal)
            self.seen[name] = np.zeros(len(self.points[name]), bool)

    def execute(self, action: tuple, task: Task) -> str | None:
        kind = action[0]
        surprise = getattr(self, "_" + kind.replace("-", "_"))(task, *action[1:])
        self.log.append(Event(self.clock, action, surprise or "ok"))
        return surprise

    def _move_robot(self, task: Task, start: str, goal: str):
        self.clock += move_duration(task.poses[start], task.poses[goal])
        task.at = goal
        return None

    def _inspect_surface(self, task: Task, pose: str, surface: str):
        self.clock += duration("inspect-surface")
        task.viewed.add((pose, surface))
        at = task.poses[pose]
        self.seen[surface] |= self.camera.visible(at, self.points[surface], self.obstacles)
        found = []
        for name, (where, point) in self.objects.items():
            if where != surface or name in task.items:
                continue
            if self.camera.visible(at, point + np.array([0.0, 0.0, OBJECT_TOP]), self.obstacles)[0]:
                task.items[name] = surface
                task.positions[name] = np.asarray(point, float)
                found.append(name)
        share = float(self.seen[surface].mean()) if len(self.seen[surface]) else 1.0
        if share >= SEEN_SHARE:
            task.searched.add(surface)
        else:
            task.searched.discard(surface)
        notes = []
        if found:
            notes.append(f"found {', '.join(found)}")
        if share < SEEN_SHARE:
            notes.append(f"{surface} only {100 * share:.0f} % seen")
        return "; ".join(notes) or None

    def _pickup_object(self, task: Task, pose: str, item: str, surface: str, arm: str):
        self.clock += duration("pickup-object")
        at, point = task.poses[pose], task.positions[item]
        rp = self.attachments.reach(at, point, surface).get(arm, 0.0)
        p = grasp_failure_probability(rp, float(np.hypot(point[0] - at[0], point[1] - at[1])))
        if self.rng.random() < p:
            self.failures += 1
            return f"grasp of {item} with {arm} failed (p = {p:.2f})"
        task.held[arm] = item
        return None

    def _inspect_object(self, task: Task, item: str, arm: str):
        self.clock += duration("inspect-object")
        task.inspected.add(item)
        return None

    def _putdown_object(self, task: Task, pose: str, item: str, surface: str, arm: str):
        self.clock += duration("putdown-object")
        task.held[arm] = None
        return None
