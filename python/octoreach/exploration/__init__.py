"""Frontier-void exploration (Dornhege & Kleiner, SSRR 2011): the explore loop, paper scenes, plots, demo.

The compiled core does the work (``ExplorationMap``, ``DepthCamera``, ``next_best_view``); this
package strings it together as the paper's loop: sense, integrate, frontiers, voids, next best view,
move, until the best view's utility is 0 or the view budget runs out.

One concept per module: ``camera`` (look_at), ``scenes`` (paper scenes, the search space), ``robot``
(the explorer robot, its arm and capability map, base poses), ``metrics`` (observed shares, run
figures), ``physics`` (the simulator's check that an arm pose is clear of the scene), ``candidate_poses``
(sampled and aimed camera poses), ``strategies`` (frontier-void and the baselines), ``explorer`` (Explorer:
exploration in the user's own loop), ``loop`` (explore, a simulator driver over Explorer, its table and stop
reason), ``plots`` (map
pictures, coverage curves; matplotlib, loaded on first use), ``demo`` (run_demo, the command line).
The oracle and the generated scenes of the tests and benchmarks are in ``octoreach.testing``.

Poses are 4x4 numpy arrays (camera -> world). The camera looks along its +z axis (+x right,
+y down in the image). Units: metres, radians.

Demo: ``python -m octoreach.exploration --scene 2 --out exploration_out`` writes the table
(``table.txt``, ``table.json``), one PNG per view and the final map as ``map.bt`` (octovis).
"""
from __future__ import annotations

from .camera import look_at
from .._core import ExploreOptions
from .explorer import Explorer
from .loop import BEYOND_VOIDS, FAILED_VIEW_RADIUS, STOP_PATIENCE, STOP_REASONS, STOP_UTILITY, ExplorationResult, ViewRow, explore
from .metrics import coverage_after, observed_share, points_on, region_points, seen_expected_ratios, views_to_reach
from .robot import arm_base_pose, arm_reach, base_ring, explorer_capability_map, explorer_robot
from .scenes import closed_box_scene, cluttered_scene, paper_scene, scene_region
from .strategies import STRATEGIES, stop_message

_LAZY = {"plot_coverage": "plots", "plot_map": "plots", "run_demo": "demo", "main": "demo"}


def __getattr__(name):
    """Plots and the demo load on first use (they import matplotlib)."""
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "BEYOND_VOIDS", "FAILED_VIEW_RADIUS", "STOP_PATIENCE", "STOP_REASONS", "STOP_UTILITY", "STRATEGIES", "ExplorationResult",
    "ExploreOptions", "Explorer", "ViewRow",
    "arm_base_pose", "arm_reach", "base_ring", "closed_box_scene", "cluttered_scene", "coverage_after", "explore",
    "explorer_capability_map", "explorer_robot", "look_at", "main", "observed_share", "paper_scene",
    "plot_coverage", "plot_map", "points_on", "region_points", "run_demo", "scene_region", "seen_expected_ratios",
    "stop_message",
    "views_to_reach",
]
