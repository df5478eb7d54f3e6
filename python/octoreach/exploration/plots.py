"""Pictures of an exploration: the map after a view (occupied geometry as shaded voxel faces,
frontiers and voids lightly on top, void ellipsoids, the views so far and the chosen view's frustum)
and coverage-versus-views curves of several strategies. matplotlib on an Agg canvas like
octoreach.plots: no display, no pyplot state, the caller's backend untouched."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .._core import ExplorationMap
from ..atomic_write import save_figure

LIGHT = np.array([-0.35, -0.55, 0.76])  # towards the light (from the viewer's side, above)
VIEW = dict(elev=35, azim=-140)
STRATEGY_COLOURS = {"frontier_void": "tab:green", "random": "tab:gray", "frontiers": "tab:red",
                    "unknown": "tab:blue"}


def _ellipsoid_wire(ax, cluster, color="purple"):
    u = np.linspace(0, 2 * np.pi, 16)
    v = np.linspace(0, np.pi, 9)
    sphere = np.stack([np.outer(np.cos(u), np.sin(v)), np.outer(np.sin(u), np.sin(v)),
                       np.outer(np.ones_like(u), np.cos(v))], -1)
    pts = sphere @ (np.asarray(cluster.axes) * np.asarray(cluster.semi_axes)).T + np.asarray(cluster.centroid)
    ax.plot_wireframe(pts[..., 0], pts[..., 1], pts[..., 2], color=color, linewidth=0.25, alpha=0.25, zorder=3)


def voxel_faces(centres, res: float):
    """The exposed faces of the cubes of edge `res` at `centres` (N, 3): (quads (F, 4, 3), normals (F, 3)).
    A face is exposed when the cell next to it is not one of the cubes."""
    centres = np.asarray(centres, float).reshape(-1, 3)
    if len(centres) == 0:
        return np.zeros((0, 4, 3)), np.zeros((0, 3))
    origin = centres.min(0)
    idx = np.rint((centres - origin) / res).astype(np.int64) + 1
    dims = idx.max(0) + 2
    code = (idx[:, 0] * dims[1] + idx[:, 1]) * dims[2] + idx[:, 2]
    occupied = np.sort(code)
    quads, normals = [], []
    for axis in range(3):
        u, v = [a for a in range(3) if a != axis]
        for sign in (-1, 1):
            step = np.zeros(3, np.int64)
            step[axis] = sign
            nb = idx + step
            nb_code = (nb[:, 0] * dims[1] + nb[:, 1]) * dims[2] + nb[:, 2]
            pos = np.searchsorted(occupied, nb_code).clip(0, len(occupied) - 1)
            exposed = occupied[pos] != nb_code
            c = centres[exposed]
            if len(c) == 0:
                continue
            h = res / 2
            corners = np.zeros((4, 3))
            corners[:, axis] = sign * h
            corners[:, u] = [-h, h, h, -h]
            corners[:, v] = [-h, -h, h, h]
            quads.append(c[:, None, :] + corners[None])
            n = np.zeros(3)
            n[axis] = sign
            normals.append(np.repeat(n[None], len(c), 0))
    if not quads:
        return np.zeros((0, 4, 3)), np.zeros((0, 3))
    return np.concatenate(quads), np.concatenate(normals)


def _crop(cells, region, margin=0.3):
    """The cells within `region` ((2, 3)) grown by `margin` (floor at most 0.1 m below); all without a region."""
    if region is None or len(cells) == 0:
        return cells
    lo, hi = np.asarray(region, float) + [[-margin] * 3, [margin] * 3]
    lo[2] = max(lo[2], -0.1)
    return cells[np.all((cells >= lo) & (cells <= hi), axis=1)]


def _shaded_geometry(ax, emap, region, max_faces):
    """Occupied cells as lit voxel faces coloured by height (cropped to `region` grown by 0.3 m)."""
    from matplotlib import colormaps
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    occ = _crop(emap.cells("occupied"), region)
    quads, normals = voxel_faces(occ, emap.resolution)
    if len(quads) > max_faces:  # keep the picture cheap: the upward faces last to go
        keep = np.argsort(-normals[:, 2], kind="stable")[:max_faces]
        quads, normals = quads[keep], normals[keep]
    if len(quads) == 0:
        return occ
    light = LIGHT / np.linalg.norm(LIGHT)
    shade = 0.35 + 0.65 * np.clip(normals @ light, 0.0, 1.0)
    z = quads[:, :, 2].mean(1)
    zn = (z - z.min()) / max(float(np.ptp(z)), 1e-9)
    base = colormaps["YlOrBr"](0.25 + 0.5 * zn)[:, :3]
    colours = np.clip(base * shade[:, None], 0, 1)
    ax.add_collection3d(Poly3DCollection(quads, facecolors=colours, edgecolors="none", linewidths=0, zorder=1))
    return occ


def _light_cells(ax, emap, max_points, region):
    """Frontiers and voids as small, light points on top of the geometry (each cropped like the geometry
    and subsampled to `max_points`)."""
    rng = np.random.default_rng(0)

    def sub(p):
        p = _crop(p, region)
        return p[rng.choice(len(p), max_points, replace=False)] if len(p) > max_points else p

    fr, vo = sub(emap.cells("frontier")), sub(emap.cells("void"))
    if len(vo):
        ax.scatter(vo[:, 0], vo[:, 1], vo[:, 2], s=0.5, c="mediumpurple", alpha=0.12, depthshade=False,
                   label="void", zorder=2)
    if len(fr):
        ax.scatter(fr[:, 0], fr[:, 1], fr[:, 2], s=0.3, c="crimson", alpha=0.15, depthshade=False,
                   label="frontier", zorder=2)
    return [a for a in (fr, vo) if len(a)]


def frustum_lines(pose, fov: float, aspect: float, depth: float) -> list:
    """Line segments ((2, 3) each) of a camera frustum: apex to the 4 corners at `depth`, and the far rectangle."""
    T = np.asarray(pose, float)
    hx = np.tan(fov / 2) * depth
    hy = hx / aspect
    corners = np.array([[-hx, -hy, depth], [hx, -hy, depth], [hx, hy, depth], [-hx, hy, depth]])
    world = corners @ T[:3, :3].T + T[:3, 3]
    apex = T[:3, 3]
    return [np.array([apex, c]) for c in world] + [np.array([world[i], world[(i + 1) % 4]]) for i in range(4)]


def _draw_views(ax, poses, next_pose, fov, aspect, depth):
    """The views so far as numbered blue arrows, the chosen next view as a green frustum."""
    for i, T in enumerate(poses):
        T = np.asarray(T)
        p, d = T[:3, 3], T[:3, 2] * 0.15
        ax.quiver(p[0], p[1], p[2], d[0], d[1], d[2], color="royalblue", linewidth=1, zorder=4)
        ax.text(p[0], p[1], p[2], str(i + 1), color="royalblue", fontsize=8, zorder=4)
    if next_pose is not None:
        for seg in frustum_lines(next_pose, fov, aspect, depth):
            ax.plot(seg[:, 0], seg[:, 1], seg[:, 2], color="green", linewidth=1.6, zorder=5)


def _frame(ax, drawn):
    """Equal-scale axes around the drawn cells (floor at most 0.1 m below)."""
    if not drawn:
        return
    allp = np.concatenate(drawn)
    c = (allp.min(0) + allp.max(0)) / 2
    r = float((allp.max(0) - allp.min(0)).max()) / 2 + 0.05
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(max(c[2] - r, -0.1), c[2] + r)


def plot_map(emap: ExplorationMap, path, poses=(), next_pose=None, title: str = "", max_points: int = 6000,
             ellipsoids: int = 4, camera=None, region=None, frustum_depth: float = 0.35,
             max_faces: int = 60000) -> Path:
    """PNG of the map: occupied cells as voxel faces shaded by a light and coloured by height, voids
    (violet) and frontiers (red) as small light points on top, the largest void ellipsoids (thin), the
    views so far (blue arrows) and the chosen next view as a green frustum (`camera`: a DepthCamera or
    CameraIntrinsics for its field of view, default 58 degrees at 4:3). `region` ((2, 3)) crops the
    geometry, frontiers and voids to the search space grown by 0.3 m (the floor and the frontiers far away
    would hide the boxes)."""
    fov = float(getattr(camera, "fov", np.deg2rad(58.0)))
    aspect = float(camera.width) / float(camera.height) if camera is not None else 4.0 / 3.0
    fig = Figure(figsize=(8, 7))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111, projection="3d", computed_zorder=False)
    occ = _shaded_geometry(ax, emap, region, max_faces)
    drawn = _light_cells(ax, emap, max_points, region)
    if len(occ):
        drawn.append(occ)
    for c in sorted(emap.void_clusters(), key=lambda c: -c.size)[:ellipsoids]:
        _ellipsoid_wire(ax, c)
    _draw_views(ax, poses, next_pose, fov, aspect, frustum_depth)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    _frame(ax, drawn)
    ax.view_init(**VIEW)
    if drawn:
        ax.legend(loc="upper left", markerscale=8)
    ax.set_title(title)
    path = Path(path)
    save_figure(fig, path, dpi=110, bbox_inches="tight")
    return path


def _coverage_axes(ax, curves: dict, level: float, title: str, ylabel: str) -> None:
    for name, runs in curves.items():
        runs = [list(r) for r in runs if len(r)]
        if not runs:
            continue
        n = max(len(r) for r in runs)
        a = np.array([r + [r[-1]] * (n - len(r)) for r in runs], float)
        x = np.arange(1, n + 1)
        colour = STRATEGY_COLOURS.get(name)
        ax.plot(x, a.mean(0), label=f"{name} ({len(runs)} runs)", color=colour, linewidth=2)
        ax.fill_between(x, a.min(0), a.max(0), color=colour, alpha=0.15, linewidth=0)
    ax.axhline(level, color="k", linestyle="--", linewidth=0.8)
    ax.set_xlabel("views")
    ax.set_ylabel(ylabel)
    ax.set_ylim(0, 1.02)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=7)
    ax.set_title(title, fontsize=9)


def plot_coverage(curves: dict, path, level: float = 0.9, title: str = "", ylabel: str = "observable interior seen") -> Path:
    """Coverage against views for several strategies: `curves` maps a strategy name to a list of runs,
    each a sequence of coverages (0-1) after view 1, 2, ...; a run that stopped early keeps its last
    figure. Draws the mean per strategy with the range over runs as a band, and `level` dashed.
    `curves` may also map panel titles (scenes) to such dicts: one panel each."""
    panels = curves if curves and all(isinstance(v, dict) for v in curves.values()) else {title: curves}
    cols = min(3, len(panels))
    rows = (len(panels) + cols - 1) // cols
    fig = Figure(figsize=(4.6 * cols, 3.6 * rows))
    FigureCanvasAgg(fig)
    for i, (name, c) in enumerate(panels.items()):
        _coverage_axes(fig.add_subplot(rows, cols, i + 1), c, level, name, ylabel)
    fig.tight_layout()
    path = Path(path)
    save_figure(fig, path, dpi=110, bbox_inches="tight")
    return path
