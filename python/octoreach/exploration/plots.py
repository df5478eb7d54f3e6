"""Pictures of an exploration map: occupied cells, frontiers, voids, void ellipsoids and the views
(matplotlib, Agg canvas like octoreach.plots: no display, no pyplot state, the caller's backend untouched)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .._core import ExplorationMap


def _ellipsoid_wire(ax, cluster, color="purple"):
    u = np.linspace(0, 2 * np.pi, 16)
    v = np.linspace(0, np.pi, 9)
    sphere = np.stack([np.outer(np.cos(u), np.sin(v)), np.outer(np.sin(u), np.sin(v)),
                       np.outer(np.ones_like(u), np.cos(v))], -1)
    pts = sphere @ (np.asarray(cluster.axes) * np.asarray(cluster.semi_axes)).T + np.asarray(cluster.centroid)
    ax.plot_wireframe(pts[..., 0], pts[..., 1], pts[..., 2], color=color, linewidth=0.4, alpha=0.6)


def _scatter_cells(ax, emap, max_points):
    """Occupied, frontier and void cells (each subsampled to `max_points`); returns the drawn centres."""
    rng = np.random.default_rng(0)

    def sub(p):
        return p[rng.choice(len(p), max_points, replace=False)] if len(p) > max_points else p

    occ = sub(emap.cells("occupied"))
    fr = sub(emap.cells("frontier"))
    vo = sub(emap.cells("void"))
    if len(occ):
        ax.scatter(occ[:, 0], occ[:, 1], occ[:, 2], s=0.5, c="0.55", alpha=0.3, label="occupied")
    if len(fr):
        ax.scatter(fr[:, 0], fr[:, 1], fr[:, 2], s=1.0, c="red", alpha=0.6, label="frontier")
    if len(vo):
        ax.scatter(vo[:, 0], vo[:, 1], vo[:, 2], s=1.0, c="darkviolet", alpha=0.5, label="void")
    return [a for a in (occ, fr, vo) if len(a)]


def _draw_views(ax, poses, next_pose):
    """The views so far as numbered blue arrows, the next view as a green one (camera +z)."""
    for i, T in enumerate(poses):
        T = np.asarray(T)
        p, d = T[:3, 3], T[:3, 2] * 0.25
        ax.quiver(p[0], p[1], p[2], d[0], d[1], d[2], color="blue")
        ax.text(p[0], p[1], p[2], str(i + 1), color="blue", fontsize=8)
    if next_pose is not None:
        T = np.asarray(next_pose)
        p, d = T[:3, 3], T[:3, 2] * 0.3
        ax.quiver(p[0], p[1], p[2], d[0], d[1], d[2], color="green", linewidth=2)


def _frame_cells(ax, drawn):
    """Equal-scale axes around the drawn cells (floor at most 0.1 m below)."""
    if not drawn:
        return
    allp = np.concatenate(drawn)
    c = (allp.min(0) + allp.max(0)) / 2
    r = float((allp.max(0) - allp.min(0)).max()) / 2 + 0.05
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(max(c[2] - r, -0.1), c[2] + r)


def plot_map(emap: ExplorationMap, path, poses=(), next_pose=None, title: str = "",
             max_points: int = 20000, ellipsoids: int = 8) -> Path:
    """PNG of the map: occupied cells grey, frontiers red, voids violet, the largest void
    ellipsoids, the views so far (blue arrows) and the next view (green arrow)."""
    fig = Figure(figsize=(8, 7))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111, projection="3d")
    drawn = _scatter_cells(ax, emap, max_points)
    clusters = sorted(emap.void_clusters(), key=lambda c: -c.size)[:ellipsoids]
    for c in clusters:
        _ellipsoid_wire(ax, c)
    _draw_views(ax, poses, next_pose)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    _frame_cells(ax, drawn)
    ax.view_init(elev=35, azim=-140)
    ax.legend(loc="upper left", markerscale=6)
    ax.set_title(title)
    path = Path(path)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    return path
