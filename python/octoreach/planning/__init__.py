"""Task planning with surface maps: the condition, grounding and reachability attachments, a PDDL planner
(Unified Planning + Fast Downward, the ``planning`` extra) that adds sampled poses while it plans, continual
planning in a small simulation of any robot with an arm and a camera (the paper's PR2 by default), the scenes of the
tidy-up task and the paper's tables.

Files, one concept each: ``task`` (what the planner is told and the goal), ``attachments`` (the three
attachments), ``domain`` (the PDDL domain and one planner call), ``planner`` (planning with the grounding loop),
``durations`` (action durations and their sources), ``head_camera`` (what inspect-surface sees), ``simulation`` (the simulated world), ``continual`` (plan,
execute, re-plan), ``scenes`` (rooms, predefined poses, objects), ``tidy_up`` (Tables I and II).
"""
from .attachments import Attachments
from .continual import RunRecord, check_objects, run_task
from .domain import PlannerMissing, require_planner, solve
from .planner import Planner, PlannerTimeout, Unsolvable
from .scenes import SCENES, Scene, place_objects, predefined_poses, scene
from .simulation import Simulation
from .task import Goal, Task

__all__ = ["Attachments", "Goal", "Planner", "PlannerMissing", "PlannerTimeout", "RunRecord", "SCENES", "Scene",
           "Simulation", "Task", "Unsolvable", "check_objects", "place_objects", "predefined_poses", "require_planner",
           "run_task", "scene", "solve"]
