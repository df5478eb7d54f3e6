"""Test and benchmark utilities, not the planner's API: the exploration oracle (the observable interior by brute
force), seeded generated scenes with a hidden target (USAR-like scenes and the scene families), and brute-force
references of the maps, and the saturated IK truth the maps are checked against (reach_truth).

    from octoreach.testing import observable_cells, usar_scene, family_scene, direct_reachability, reach_truth
"""
from __future__ import annotations

from . import reach_truth
from .brute_force import direct_reachability
from .oracle import Observable, observable_cells
from .scene_families import FAMILIES, FamilyScene, family_instances, family_scene
from .usar_scenes import UsarScene, usar_scene

__all__ = ["FAMILIES", "FamilyScene", "Observable", "UsarScene", "direct_reachability", "family_instances",
           "family_scene", "observable_cells", "reach_truth", "usar_scene"]
