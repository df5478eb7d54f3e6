"""A surface map in the scene: coloured cells for one theta bin (slider) or the best theta, clickable.

Every number comes from the compiled map: cells and their R_S per theta bin from ``SurfaceMap.voxels()``,
the R_S of a clicked cell from ``SurfaceMap.reachability``; theta bin k is centred on 2 pi k / theta_bins
(pose_map.hpp).
"""
from __future__ import annotations

import numpy as np

from . import cells, colours

BEST = -1  # theta selection: the best theta of each cell


class SurfaceMapLayer:
    """Cells of a SurfaceMap under `name`; `show(theta_bin)` recolours them, `pick(ray)` finds a cell."""

    def __init__(self, scene, smap, name: str = "/surface_map"):
        self.scene, self.smap, self.name = scene, smap, name
        centres, values = smap.voxels()
        self.centres = np.asarray(centres, dtype=float).reshape(-1, 3)
        self.values = np.asarray(values, dtype=float).reshape(len(self.centres), smap.theta_bins)
        self.vmax = float(smap.max_reachability) or 1.0
        self.edge = float(smap.resolution)
        self.tile_height = self.edge * 0.2
        self.theta_bin = BEST
        self.handle = None
        self.shown = np.zeros(0, dtype=int)
        self.show(BEST)

    def theta_of_bin(self, k: int) -> float:
        return 2.0 * np.pi * k / self.smap.theta_bins

    def _bins(self) -> np.ndarray:
        """Theta bin of each cell in the current selection."""
        if self.theta_bin == BEST:
            return self.values.argmax(axis=1) if self.values.size else np.zeros(0, dtype=int)
        return np.full(len(self.centres), self.theta_bin)

    def show(self, theta_bin: int) -> None:
        """Shows the cells with R_S > 0 at theta bin `theta_bin` (BEST: each cell's best theta)."""
        self.theta_bin = int(theta_bin)
        rs = self.values[np.arange(len(self.centres)), self._bins()] if len(self.centres) else np.zeros(0)
        self.shown = np.flatnonzero(rs > 0)
        # Flat tiles (a fifth of the edge high) keep the robot's footprint and the floor visible.
        self.handle = cells.add_cells(self.scene, self.name, self.centres[self.shown],
                                      colours.scale(rs[self.shown], self.vmax), self.edge * 0.92, self.tile_height)

    def cell_pose(self, index: int) -> np.ndarray:
        """Base pose (x, y, z, theta) of shown cell `index` at the selected (or its best) theta."""
        i = self.shown[index]
        k = self._bins()[i]
        x, y, z = self.centres[i]
        return np.array([x, y, z, self.theta_of_bin(k)])

    def reachability(self, index: int) -> float:
        """R_S of shown cell `index`, looked up by the compiled map."""
        return float(self.smap.reachability(self.cell_pose(index)[None, :])[0])

    def pick(self, origin, direction) -> int | None:
        """Shown cell hit first by a ray (world frame), or None."""
        return cells.first_hit(origin, direction, self.centres[self.shown], self.edge * 0.92, self.tile_height)
