"""An exploration in the scene: occupied cells, frontiers, voids, void ellipsoids and the views' frusta.

Takes an ``ExplorationMap`` (for example from a .bt file) or what ``explore()`` returns (its final map,
camera poses and per-view rows). Cells, clusters and ellipsoids come from the compiled map
(``cells``, ``void_clusters``). A slider steps through the views: the frusta up to the chosen view and its
row; with the states an ``ExplorationRecorder`` kept during ``explore(on_view=recorder)``, also the map as
it was after that view.
"""
from __future__ import annotations

import numpy as np

from . import cells, colours


def _wxyz(R):
    import viser.transforms as tf

    return tf.SO3.from_matrix(np.asarray(R, float)).wxyz


def map_state(emap) -> dict:
    """What the layer draws of a map: cell centres by class and the void clusters' ellipsoids."""
    def centres(which):
        return np.asarray(emap.cells(which), float).reshape(-1, 3)

    clusters = [(np.asarray(c.centroid, float), np.asarray(c.axes, float), np.asarray(c.semi_axes, float))
                for c in emap.void_clusters()]
    return {"occupied": centres("occupied"), "frontier": centres("frontier"), "void": centres("void"),
            "clusters": clusters}


class ExplorationRecorder:
    """An ``on_view`` callback for ``explore()`` that keeps the map's state after each view (then passes the
    call on to `then`, if given): ``view(result, steps=recorder)`` steps through them."""

    def __init__(self, then=None):
        self.then = then
        self.states: list[dict] = []

    def __call__(self, row, emap, nbv) -> None:
        self.states.append(map_state(emap))
        if self.then is not None:
            self.then(row, emap, nbv)


class ExplorationLayer:
    def __init__(self, scene, source, name: str = "/exploration", steps=None, fov: float = np.radians(60),
                 aspect: float = 4 / 3):
        emap = getattr(source, "map", source)
        self.scene, self.map, self.name = scene, emap, name
        self.resolution = float(emap.resolution)
        self.poses = [np.asarray(p, float) for p in getattr(source, "poses", [])]
        self.rows = list(getattr(source, "rows", []))
        self.states = list(getattr(steps, "states", steps or []))
        self.visible = {"occupied": True, "frontiers": True, "voids": False, "ellipsoids": True, "views": True}
        self.final = map_state(emap)
        self.frusta = []
        for i, T in enumerate(self.poses):
            self.frusta.append(scene.add_camera_frustum(f"{name}/views/{i}", fov=fov, aspect=aspect, scale=0.12,
                                                        thickness=0.006, color=colours.FRUSTUM,
                                                        wxyz=_wxyz(T[:3, :3]), position=T[:3, 3]))
        self.ellipsoids = []
        self.draw(self.final)
        if self.frusta:
            self.step(len(self.frusta) - 1)

    def draw(self, state: dict) -> None:
        """(Re)draws the cells and ellipsoids of a map state."""
        r, name, scene = self.resolution, self.name, self.scene
        occ = state["occupied"]
        self.occupied = cells.add_cells(scene, f"{name}/occupied", occ,
                                        np.tile(np.array(colours.OCCUPIED, np.uint8), (len(occ), 1)), r * 0.95)
        # Frontier and void cells as small points; the voids start hidden: they fill the hull and would bury
        # the geometry (the controls toggle every layer).
        self.frontier = scene.add_point_cloud(f"{name}/frontiers", state["frontier"].astype(np.float32),
                                              colours.FRONTIER, point_size=r * 0.3)
        self.void = scene.add_point_cloud(f"{name}/voids", state["void"].astype(np.float32), colours.VOID,
                                          point_size=r * 0.3)
        for h in self.ellipsoids:
            h.remove()
        self.ellipsoids = []
        for i, (centroid, axes, semi) in enumerate(state["clusters"]):
            if np.linalg.det(axes) < 0:
                axes = axes * np.array([1.0, 1.0, -1.0])
            self.ellipsoids.append(scene.add_icosphere(
                f"{name}/ellipsoids/{i}", radius=1.0, color=colours.ELLIPSOID, opacity=0.3,
                scale=tuple(float(max(s, r / 2)) for s in semi), wxyz=_wxyz(axes), position=centroid,
                cast_shadow=False))
        self.counts = {"occupied": len(occ), "frontier": len(state["frontier"]), "void": len(state["void"]),
                       "ellipsoids": len(self.ellipsoids), "views": len(self.poses)}
        for layer, on in self.visible.items():
            self.set_visible(layer, on)

    @property
    def layers(self) -> dict:
        return {"occupied": [self.occupied], "frontiers": [self.frontier], "voids": [self.void],
                "ellipsoids": self.ellipsoids, "views": self.frusta}

    def set_visible(self, layer: str, visible: bool) -> None:
        """Shows or hides one of `layers` (occupied, frontiers, voids, ellipsoids, views)."""
        self.visible[layer] = bool(visible)
        for h in self.layers[layer]:
            h.visible = bool(visible)

    def step(self, view: int) -> str:
        """Shows the frusta of views 0..view (the latest one highlighted) and, with recorded states, the map
        after that view; returns that view's row as text."""
        for i, f in enumerate(self.frusta):
            f.visible = self.visible["views"] and i <= view
            f.color = colours.FRUSTUM if i == view else (120, 120, 120)
        if 0 <= view < len(self.states):
            self.draw(self.states[view])
            for i, f in enumerate(self.frusta):
                f.visible = self.visible["views"] and i <= view
        if 0 <= view < len(self.rows):
            r = self.rows[view]
            return (f"view {r.view}: {r.points} points, {r.frontier_cells} frontier cells, {r.void_total} void "
                    f"cells in {r.void_clusters} clusters, observed {r.observed_share:.1%}")
        return f"view {view}"
