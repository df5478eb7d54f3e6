"""An exploration in the scene: occupied cells, frontiers, voids, void ellipsoids and the views' frusta.

Takes an ``ExplorationMap`` (for example from a .bt file) or what ``explore()`` returns (its final map,
camera poses and per-view rows). Cells, clusters and ellipsoids come from the compiled map
(``cells``, ``void_clusters``); a slider steps through the views (frusta up to the chosen view, its row).
"""
from __future__ import annotations

import numpy as np

from . import cells, colours


def _wxyz(R):
    import viser.transforms as tf

    return tf.SO3.from_matrix(np.asarray(R, float)).wxyz


class ExplorationLayer:
    def __init__(self, scene, source, name: str = "/exploration", fov: float = np.radians(60), aspect: float = 4 / 3):
        emap = getattr(source, "map", source)
        self.scene, self.map, self.name = scene, emap, name
        self.poses = [np.asarray(p, float) for p in getattr(source, "poses", [])]
        self.rows = list(getattr(source, "rows", []))
        r = float(emap.resolution)
        occupied = np.asarray(emap.cells("occupied"), float).reshape(-1, 3)
        shade = np.tile(np.array(colours.OCCUPIED, np.uint8), (len(occupied), 1))
        # Occupied cells as lit boxes so the geometry reads; frontier and void cells as small points (the
        # voids start hidden: they fill the hull and would bury the geometry; the controls toggle layers).
        self.occupied = cells.add_cells(scene, f"{name}/occupied", occupied, shade, r * 0.95)
        frontier = np.asarray(emap.cells("frontier"), float).reshape(-1, 3)
        self.frontier = scene.add_point_cloud(f"{name}/frontiers", frontier.astype(np.float32), colours.FRONTIER,
                                              point_size=r * 0.3)
        void = np.asarray(emap.cells("void"), float).reshape(-1, 3)
        self.void = scene.add_point_cloud(f"{name}/voids", void.astype(np.float32), colours.VOID, point_size=r * 0.3,
                                          visible=False)
        self.ellipsoids = []
        for i, c in enumerate(emap.void_clusters()):
            axes = np.asarray(c.axes, float)
            if np.linalg.det(axes) < 0:
                axes = axes * np.array([1.0, 1.0, -1.0])
            h = scene.add_icosphere(f"{name}/ellipsoids/{i}", radius=1.0, color=colours.ELLIPSOID, opacity=0.3,
                                    scale=tuple(float(max(s, r / 2)) for s in c.semi_axes),
                                    wxyz=_wxyz(axes), position=np.asarray(c.centroid, float), cast_shadow=False)
            self.ellipsoids.append(h)
        self.frusta = []
        for i, T in enumerate(self.poses):
            self.frusta.append(scene.add_camera_frustum(f"{name}/views/{i}", fov=fov, aspect=aspect, scale=0.12,
                                                        thickness=0.006, color=colours.FRUSTUM, wxyz=_wxyz(T[:3, :3]),
                                                        position=T[:3, 3]))
        if self.frusta:
            self.step(len(self.frusta) - 1)
        self.layers = {"occupied": [self.occupied], "frontiers": [self.frontier], "voids": [self.void],
                       "ellipsoids": self.ellipsoids, "views": self.frusta}
        self.counts = {"occupied": len(occupied), "frontier": len(frontier), "void": len(void),
                       "ellipsoids": len(self.ellipsoids), "views": len(self.poses)}

    def set_visible(self, layer: str, visible: bool) -> None:
        """Shows or hides one of `layers` (occupied, frontiers, voids, ellipsoids, views)."""
        for h in self.layers[layer]:
            h.visible = visible

    def step(self, view: int) -> str:
        """Shows the frusta of views 0..view (the latest one highlighted) and returns that view's row as text."""
        for i, f in enumerate(self.frusta):
            f.visible = i <= view
            f.color = colours.FRUSTUM if i == view else (120, 120, 120)
        if 0 <= view < len(self.rows):
            r = self.rows[view]
            return (f"view {r.view}: {r.points} points, {r.frontier_cells} frontier cells, {r.void_total} void "
                    f"cells in {r.void_clusters} clusters, observed {r.observed_share:.1%}")
        return f"view {view}"
