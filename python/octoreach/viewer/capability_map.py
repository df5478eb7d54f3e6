"""A capability map in the scene: its voxels coloured by reachability index (or by the quality of their cells),
cut by a horizontal slice plane.

Voxel centres and values come from the compiled ``CapabilityMap.voxels()``; the viewer only selects the
voxels below the plane and, of those, draws the outer shell (voxels with a face neighbour missing, the slice
face included): the inner ones cannot be seen, and leaving them out makes the node a fraction of the size
(a 0.05 m PR2 arm: about a quarter of its 18,000 voxels).
"""
from __future__ import annotations

import numpy as np

from . import cells, colours


COLOUR_BY = ("reachability", "quality")


def voxel_colour_values(cap, colour_by: str) -> np.ndarray:
    """Per voxel of cap.voxels(), in [0, 1]: the reachability index D, or (colour_by "quality") the mean quality
    (manipulability x joint-limit penalty) of its reachable cells relative to the map's best cell. A map without
    quality raises ValueError saying how to rebuild it."""
    if colour_by == "reachability":
        return np.asarray(cap.voxels()[1], dtype=float).reshape(-1)
    if colour_by == "quality":
        return np.asarray(cap.voxel_quality("mean", relative=True), dtype=float)
    raise ValueError(f"colour_by must be one of {', '.join(COLOUR_BY)}, got {colour_by!r}")


def _colours(cap, colour_by: str) -> np.ndarray:
    """Red (low) to blue (high): D over [0, 1]; quality over [0, the largest voxel's] (few come near the best cell)."""
    return colours.scale(voxel_colour_values(cap, colour_by), 1.0 if colour_by == "reachability" else None)


class CapabilityMapLayer:
    """Voxels under `name` (arm base frame placed at `base_pose`); `cut(z)` shows those with centre z <= z.
    `shown`: indices (into `centres`) of the voxels below the cut; `drawn`: those of the drawn shell, in the
    order of the node's instances (a click's instance index i is voxel drawn[i]). colour_by: "reachability"
    (D) or "quality" (voxel_colour_values)."""

    def __init__(self, scene, cap, name: str = "/capability_map", base_pose=None, colour_by: str = "reachability"):
        self.scene, self.cap, self.name = scene, cap, name
        centres, values = cap.voxels()
        self.centres = np.asarray(centres, dtype=float).reshape(-1, 3)
        self.values = np.asarray(values, dtype=float).reshape(-1)
        self.edge = float(cap.resolution)
        self.keys = cells.grid_keys(self.centres, self.edge)
        self.colour_by = colour_by
        self.colours = _colours(cap, colour_by)
        self.frame = scene.add_frame(name, show_axes=False)
        if base_pose is not None:
            self.place(base_pose)
        lo = self.centres.min(axis=0) if len(self.centres) else np.zeros(3)
        hi = self.centres.max(axis=0) if len(self.centres) else np.zeros(3)
        self.z_range = (float(lo[2]), float(hi[2]))
        size = (hi - lo)[:2] + self.edge
        self.plane = scene.add_box(f"{name}/slice_plane", color=colours.SLICE_PLANE,
                                   dimensions=(float(size[0]), float(size[1]), 0.002), opacity=0.35,
                                   position=(float((lo[0] + hi[0]) / 2), float((lo[1] + hi[1]) / 2), 0.0))
        self.handle = None
        self.shown = self.drawn = np.zeros(0, dtype=int)
        # First cut at the arm base's height (clipped into the map): shows the map's inside at once.
        self.cut(min(max(0.0, self.z_range[0]), self.z_range[1]))

    def place(self, base_pose) -> None:
        """Puts the map's frame (the arm's base link) at the 4x4 world pose `base_pose`."""
        import viser.transforms as tf

        T = np.asarray(base_pose, float)
        self.frame.wxyz = tf.SO3.from_matrix(T[:3, :3]).wxyz
        self.frame.position = T[:3, 3]

    def cut(self, z: float) -> None:
        """Shows the voxels with centre z <= `z` (their outer shell) and moves the slice plane there (arm
        base frame)."""
        self.z = float(z)
        self.shown = np.flatnonzero(self.centres[:, 2] <= self.z + 1e-9)
        self.drawn = self.shown[cells.shell(self.keys[self.shown])]
        self.handle = cells.add_cells(self.scene, f"{self.name}/voxels", self.centres[self.drawn],
                                      self.colours[self.drawn], self.edge * 0.9)
        p = self.plane.position
        self.plane.position = (p[0], p[1], self.z + self.edge / 2)

    def recolour(self, colour_by: str) -> None:
        """Colours the voxels by "reachability" or "quality" and redraws the current cut."""
        self.colours = _colours(self.cap, colour_by)
        self.colour_by = colour_by
        self.cut(self.z)

    def voxel(self, instance: int) -> int:
        """Voxel index (into `centres`) of the drawn instance `instance`."""
        return int(self.drawn[instance])

    def value(self, index: int) -> float:
        """Reachability index of voxel `index` (the compiled map's lookup at its centre)."""
        return float(self.cap.reachability(self.centres[index][None, :])[0])
