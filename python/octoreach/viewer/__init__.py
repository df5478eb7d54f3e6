"""octoreach's 3D viewer in the browser (viser): robots, surface and capability maps, samples, explorations.

    octoreach.view("demo_out/table_either_arm.orsm")       # or: octoreach view FILE... on the command line

One concept per file: robot_meshes (a Robot's visuals at link poses), surfaces (the work surface),
surface_map (cells per theta), capability_map (voxels and slice plane), samples (footprints and arrows),
exploration (cells, frontiers, voids, ellipsoids, frusta), cells (batched boxes, outer shells, picking),
mesh_files (STL with numpy; boxes, cylinders, spheres), colours,
room (a room's obstacles from their shapes), files (what can be opened), app (the server and its controls), view
(view(): everything in one call), export (static HTML), browser (headless Chromium screenshots and clicks).
"""
from .app import Viewer  # noqa: F401
from .view import view  # noqa: F401
from .exploration import ExplorationRecorder  # noqa: F401

__all__ = ["ExplorationRecorder", "Viewer", "view"]
