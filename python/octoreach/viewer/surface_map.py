"""A surface map in the scene: coloured cells for one theta bin (slider) or the best theta, clickable.

Every number comes from the compiled map: cells and their R_S per theta bin from ``SurfaceMap.voxels()``,
the R_S of a clicked cell from ``SurfaceMap.reachability``; theta bin k is centred on 2 pi k / theta_bins
(pose_map.hpp).

All cells are one batched mesh sent once; the colours and visibilities of every theta selection are computed
when the layer is made, so a slider move sends one node's colours (3 bytes a cell) and visibilities (a scale of
0 or 1, 4 bytes a cell) and nothing else.
"""
from __future__ import annotations

import numpy as np

from . import cells, colours

BEST = -1  # theta selection: the best theta of each cell


class SurfaceMapLayer:
    """Cells of a SurfaceMap under `name`; `show(theta_bin)` recolours them, `pick(ray)` finds a cell. Cell
    indices (clicks, `shown`, `cell_pose`) index `centres`, the map's voxels, whatever theta is shown."""

    def __init__(self, scene, smap, name: str = "/surface_map"):
        self.scene, self.smap, self.name = scene, smap, name
        centres, values = smap.voxels()
        self.centres = np.asarray(centres, dtype=float).reshape(-1, 3)
        self.values = np.asarray(values, dtype=float).reshape(len(self.centres), smap.theta_bins)
        self.vmax = float(smap.max_reachability) or 1.0
        self.edge = float(smap.resolution)
        self.tile_height = self.edge * 0.2
        n, bins = self.values.shape
        self.best_bins = self.values.argmax(axis=1) if n else np.zeros(0, dtype=int)
        # Row k: R_S at theta bin k; the last row (index BEST = -1): each cell's best R_S.
        rs = np.vstack([self.values.T, self.values.max(axis=1, initial=0.0)[None, :]])
        self._colours = colours.scale(rs.reshape(-1), self.vmax).reshape(bins + 1, n, 3)
        self._scales = (rs > 0).astype(np.float32)
        self.theta_bin = BEST
        self.shown = np.flatnonzero(self._scales[BEST])
        # Flat tiles (a fifth of the edge high) keep the robot's footprint and the floor visible.
        self.handle = cells.add_cells(scene, name, self.centres, self._colours[BEST], self.edge * 0.92,
                                      self.tile_height, scales=self._scales[BEST])

    def colours_at(self, theta_bin: int) -> np.ndarray:
        """(N, 3) uint8 colours of the cells at theta bin `theta_bin` (BEST: each cell's best R_S)."""
        return self._colours[int(theta_bin)]

    def theta_of_bin(self, k: int) -> float:
        return 2.0 * np.pi * k / self.smap.theta_bins

    def show(self, theta_bin: int) -> None:
        """Shows the cells with R_S > 0 at theta bin `theta_bin` (BEST: each cell's best theta): updates the
        node's colours and visibilities only."""
        k = int(theta_bin)
        if k != BEST and not 0 <= k < self.smap.theta_bins:
            raise ValueError(f"theta bin {k} out of range 0..{self.smap.theta_bins - 1} (or BEST = -1)")
        self.theta_bin = k
        self.shown = np.flatnonzero(self._scales[k])
        self.handle.batched_colors = self._colours[k]
        self.handle.batched_scales = self._scales[k]

    def cell_bin(self, index: int) -> int:
        """Theta bin of cell `index` in the current selection (its best bin under BEST)."""
        return int(self.best_bins[index]) if self.theta_bin == BEST else self.theta_bin

    def cell_pose(self, index: int) -> np.ndarray:
        """Base pose (x, y, z, theta) of cell `index` at the selected (or its best) theta."""
        x, y, z = self.centres[index]
        return np.array([x, y, z, self.theta_of_bin(self.cell_bin(index))])

    def reachability(self, index: int) -> float:
        """R_S of cell `index` at the selected (or its best) theta, looked up by the compiled map."""
        return float(self.smap.reachability(self.cell_pose(index)[None, :])[0])

    def pick(self, origin, direction) -> int | None:
        """Shown cell hit first by a ray (world frame), or None."""
        hit = cells.first_hit(origin, direction, self.centres[self.shown], self.edge * 0.92, self.tile_height)
        return None if hit is None else int(self.shown[hit])
