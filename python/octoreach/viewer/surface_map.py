"""A surface map in the scene: coloured cells for one theta bin (slider) or the best theta, clickable.

Every number comes from the compiled map: cells and their R_S per theta bin from ``SurfaceMap.voxels()``,
the R_S of a clicked cell from ``SurfaceMap.reachability``; theta bin k is centred on 2 pi k / theta_bins
(pose_map.hpp).

Every theta selection (each bin, and the best theta) is its own batched mesh of the cells with R_S > 0 there,
coloured for it, all sent when the layer is made and all but the selected one hidden: a slider move flips two
nodes' visibility (one atomic message pair, a few bytes) and the browser draws one frame; nothing is re-sent or
recomputed in the page.
"""
from __future__ import annotations

import contextlib

import numpy as np

from . import cells, colours

BEST = -1  # theta selection: the best theta of each cell


class SurfaceMapLayer:
    """Cells of a SurfaceMap under `name`; `show(theta_bin)` shows another theta selection, `pick(ray)` finds a
    cell. Cell indices (clicks, `shown`, `cell_pose`) index `centres`, the map's voxels, whatever theta is shown;
    they are drawn at `drawn_centres` (on the floor: z lowered by `floor_offset`).
    `atomic`: the viser server's `atomic` (a move's two visibility changes reach the page together)."""

    def __init__(self, scene, smap, name: str = "/surface_map", atomic=None):
        self.scene, self.smap, self.name = scene, smap, name
        self._atomic = atomic or contextlib.nullcontext
        centres, values = smap.voxels()
        self.centres = np.asarray(centres, dtype=float).reshape(-1, 3)
        self.values = np.asarray(values, dtype=float).reshape(len(self.centres), smap.theta_bins)
        # Drawn on the floor: a cell's z is the height of the robot's reference frame (a PR2's base link: 0; a
        # robot whose frame is its torso: that height), so the lowest level is drawn at z = 0, where the robot
        # stands, and higher ones (a map over a z range) above it. Picks and poses use the map's own z.
        self.floor_offset = float(self.centres[:, 2].min()) if len(self.centres) else 0.0
        self.drawn_centres = self.centres - [0.0, 0.0, self.floor_offset]
        self.vmax = float(smap.max_reachability) or 1.0
        self.edge = float(smap.resolution)
        self.tile_height = self.edge * 0.2
        n, bins = self.values.shape
        self.best_bins = self.values.argmax(axis=1) if n else np.zeros(0, dtype=int)
        # Selection k (0 .. bins - 1, and BEST): the cells with R_S > 0 there and their R_S.
        self.cells: dict[int, np.ndarray] = {}
        self.rs: dict[int, np.ndarray] = {}
        for k in [BEST, *range(bins)]:
            rs = self.values.max(axis=1, initial=0.0) if k == BEST else self.values[:, k]
            self.cells[k] = np.flatnonzero(rs > 0)
            self.rs[k] = rs[self.cells[k]]
        self.theta_bin = BEST
        self.root = scene.add_frame(name, show_axes=False)
        self.handles: dict = {}
        self._add_nodes()

    def _add_nodes(self) -> None:
        """One node a selection, coloured for it; only the best theta's visible. Flat tiles (a fifth of the edge
        high) keep the robot's footprint and the floor visible."""
        for k, shown in self.cells.items():
            self.handles[k] = cells.add_cells(self.scene, self.node_name(k), self.drawn_centres[shown],
                                              colours.scale(self.rs[k], self.vmax), self.edge * 0.92,
                                              self.tile_height, visible=k == self.theta_bin, top_only=True)

    def node_name(self, theta_bin: int) -> str:
        return f"{self.name}/best" if theta_bin == BEST else f"{self.name}/theta_{theta_bin:02d}"

    @property
    def shown(self) -> np.ndarray:
        """Indices (into `centres`) of the cells shown: R_S > 0 at the selected theta."""
        return self.cells[self.theta_bin]

    @property
    def handle(self):
        """The node of the selected theta."""
        return self.handles[self.theta_bin]

    def colours_at(self, theta_bin: int) -> np.ndarray:
        """(N, 3) uint8 colours of all cells at theta bin `theta_bin` (BEST: each cell's best R_S)."""
        rs = self.values.max(axis=1, initial=0.0) if theta_bin == BEST else self.values[:, int(theta_bin)]
        return colours.scale(rs, self.vmax)

    def theta_of_bin(self, k: int) -> float:
        return 2.0 * np.pi * k / self.smap.theta_bins

    def show(self, theta_bin: int) -> None:
        """Shows the cells with R_S > 0 at theta bin `theta_bin` (BEST: each cell's best theta): hides the node
        shown and shows that selection's."""
        k = int(theta_bin)
        if k != BEST and not 0 <= k < self.smap.theta_bins:
            raise ValueError(f"theta bin {k} out of range 0..{self.smap.theta_bins - 1} (or BEST = -1)")
        if k == self.theta_bin:
            return
        with self._atomic():
            self.handles[self.theta_bin].visible = False
            self.handles[k].visible = True
        self.theta_bin = k

    def cell_of(self, theta_bin: int, instance: int) -> int:
        """Cell index (into `centres`) of instance `instance` of selection `theta_bin`'s node (a click's
        instance index)."""
        return int(self.cells[int(theta_bin)][instance])

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
        hit = cells.first_hit(origin, direction, self.drawn_centres[self.shown], self.edge * 0.92, self.tile_height)
        return None if hit is None else int(self.shown[hit])
