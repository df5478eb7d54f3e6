"""Frontier-void exploration (Dornhege & Kleiner, SSRR 2011): scenes, the explore loop, plots, demo.

The compiled core does the work (``ExplorationMap``, ``DepthCamera``, ``next_best_view``); this
package strings it together as the paper's loop: sense, integrate, frontiers, voids, next best view,
move, until the best view's utility is 0 or the view budget runs out.

One concept per module: ``camera`` (look_at), ``scenes`` (paper scenes, the search space),
``robot`` (the explorer robot, its arm and capability map, base poses), ``metrics`` (observed
shares), ``loop`` (explore and its table), ``plots`` (map pictures), ``demo`` (run_demo, the
command line).

Poses are 4x4 numpy arrays (camera -> world). The camera looks along its +z axis (+x right,
+y down in the image). Units: metres, radians.

Demo: ``python -m octoreach.exploration --scene 2 --out exploration_out`` writes the table
(``table.txt``, ``table.json``), one PNG per view and the final map as ``map.bt`` (octovis).
"""
from __future__ import annotations

from .._core import DepthCamera, ExplorationMap, Scene, next_best_view  # noqa: F401  (as before the split)
from .camera import look_at
from .demo import main, run_demo
from .loop import ExplorationResult, ViewRow, explore
from .metrics import observed_share
from .plots import plot_map
from .robot import arm_base_pose, arm_reach, base_ring, explorer_capability_map, explorer_robot
from .scenes import closed_box_scene, cluttered_scene, paper_scene, scene_region

__all__ = [
    "ExplorationResult",
    "ViewRow",
    "arm_base_pose",
    "arm_reach",
    "base_ring",
    "closed_box_scene",
    "cluttered_scene",
    "explore",
    "explorer_capability_map",
    "explorer_robot",
    "look_at",
    "main",
    "observed_share",
    "paper_scene",
    "plot_map",
    "run_demo",
    "scene_region",
]
