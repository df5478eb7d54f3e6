"""PNG figures of reachability maps (matplotlib, Agg canvas: no display and no pyplot state).

``slices`` is the generic helper: horizontal slices of any voxel map (a capability map, later an
inverse point map or a surface map) coloured red (low) to blue (high) as in Fig. 2 of Hertle and
Nebel, with an optional surface polygon drawn on every slice. ``capability_slices`` and
``reachability_histogram`` are the capability-map front ends. Every function returns the path
it wrote.
"""
from __future__ import annotations

import math
import os
from typing import Callable, Optional, Sequence, Union

import numpy as np
from matplotlib import colormaps
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from .atomic_write import save_figure

#: Red (low) to blue (high), the colouring of the paper's figures.
COLORMAP = "jet_r"

VoxelData = Union[tuple, Callable[[np.ndarray], np.ndarray]]


def _check_heights(heights) -> np.ndarray:
    try:
        h = np.asarray(heights, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"heights must be a sequence of numbers (m), got {heights!r}") from None
    if h.ndim == 0:
        h = h.reshape(1)
    if h.ndim != 1 or h.size == 0:
        raise ValueError(f"heights must be a non-empty 1-D sequence of z values (m), got shape {h.shape}")
    if not np.isfinite(h).all():
        raise ValueError(f"heights must be finite, got {h.tolist()}")
    if h.size > 64:
        raise ValueError(f"at most 64 slices per figure, got {h.size}")
    return h


def _check_polygon(polygon) -> Optional[np.ndarray]:
    if polygon is None:
        return None
    p = np.asarray(polygon, dtype=float)
    if p.ndim != 2 or p.shape[1] not in (2, 3) or p.shape[0] < 2:
        raise ValueError(f"polygon must have shape (N, 2) or (N, 3) with N >= 2, got {p.shape}")
    if not np.isfinite(p).all():
        raise ValueError("polygon vertices must be finite")
    p = p[:, :2]
    return np.vstack([p, p[:1]])  # closed outline


def _infer_resolution(centres: np.ndarray) -> float:
    steps = []
    for k in range(3):
        u = np.unique(np.round(centres[:, k], 9))
        if u.size > 1:
            steps.append(np.diff(u).min())
    if not steps:
        raise ValueError("cannot infer the voxel size from a single voxel: pass resolution=")
    return float(min(steps))


def _voxel_data(data, resolution, extent, heights):
    """(centres (M, 3), values (M,), resolution) from a map, a (centres, values) pair or a callable."""
    if hasattr(data, "voxels") and hasattr(data, "resolution"):
        centres, values = data.voxels()
        return np.asarray(centres, float), np.asarray(values, float), float(data.resolution)
    if callable(data):
        if resolution is None or extent is None:
            raise ValueError("a callable needs resolution= and extent=((xmin, xmax), (ymin, ymax))")
        (x0, x1), (y0, y1) = extent
        r = float(resolution)
        xs = np.arange(x0 + r / 2, x1, r)
        ys = np.arange(y0 + r / 2, y1, r)
        X, Y = np.meshgrid(xs, ys, indexing="ij")
        pts = [np.stack([X.ravel(), Y.ravel(), np.full(X.size, z)], 1) for z in heights]
        centres = np.vstack(pts)
        values = np.asarray(data(centres), dtype=float).reshape(-1)
        if values.shape != (len(centres),):
            raise ValueError(f"the callable returned {values.shape} values for {len(centres)} points")
        return centres, values, r
    try:
        centres, values = data
    except (TypeError, ValueError):
        raise ValueError("data must be a map with voxels(), a (centres (M, 3), values (M,)) pair, "
                         "or a callable points (N, 3) -> values (N,)") from None
    centres = np.asarray(centres, dtype=float)
    values = np.asarray(values, dtype=float)
    if centres.ndim != 2 or centres.shape[1] != 3:
        raise ValueError(f"centres must have shape (M, 3), got {centres.shape}")
    if values.shape != (centres.shape[0],):
        raise ValueError(f"values must have shape ({centres.shape[0]},), got {values.shape}")
    if resolution is None:
        resolution = _infer_resolution(centres)
    if not (resolution > 0 and math.isfinite(resolution)):
        raise ValueError(f"resolution must be a positive number of metres, got {resolution}")
    return centres, values, float(resolution)


def _slice_grid(centres, r, extent, poly):
    """(x0, y0, nx, ny, r): the xy grid of cells of edge r that every slice shares (so panels share their
    axes), over `extent`, else the voxels, widened to hold the polygon."""
    if extent is not None:
        (x0, x1), (y0, y1) = extent
    elif len(centres):
        x0, y0 = centres[:, :2].min(axis=0) - r / 2
        x1, y1 = centres[:, :2].max(axis=0) + r / 2
    else:
        x0 = y0 = -r
        x1 = y1 = r
    if poly is not None:
        x0, y0 = min(x0, poly[:, 0].min() - r), min(y0, poly[:, 1].min() - r)
        x1, y1 = max(x1, poly[:, 0].max() + r), max(y1, poly[:, 1].max() + r)
    nx = max(1, int(round((x1 - x0) / r)))
    ny = max(1, int(round((y1 - y0) / r)))
    return x0, y0, nx, ny, r


def _draw_slice(ax, centres, values, z, grid, poly, colours):
    """Draws the voxel layer holding height z on `ax` over the shared grid; returns the image."""
    x0, y0, nx, ny, r = grid
    cells = np.full((ny, nx), np.nan)
    # the voxel layer holding z; a height on a boundary belongs to the layer above, as in the octree lookup
    sel = (z >= centres[:, 2] - r / 2 - 1e-9) & (z < centres[:, 2] + r / 2 - 1e-9)
    layer = centres[sel]
    if len(layer):
        ix = np.floor((layer[:, 0] - x0) / r).astype(int)
        iy = np.floor((layer[:, 1] - y0) / r).astype(int)
        inside = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
        cells[iy[inside], ix[inside]] = values[sel][inside]
    image = ax.imshow(np.ma.masked_invalid(cells), origin="lower", extent=(x0, x0 + nx * r, y0, y0 + ny * r),
                      interpolation="nearest", **colours)
    if poly is not None:
        ax.plot(poly[:, 0], poly[:, 1], color="black", linewidth=1.5)
    ax.set_title(f"z = {z:.3f} m", fontsize=9)
    ax.set_aspect("equal")
    ax.grid(True, color="0.85", linewidth=0.5)
    ax.set_axisbelow(True)
    if not len(layer):
        ax.text(0.5, 0.5, "no voxels", transform=ax.transAxes, ha="center", va="center", color="0.5")
    return image


def slices(
    data: VoxelData,
    heights: Sequence[float],
    path: Union[str, os.PathLike],
    *,
    resolution: Optional[float] = None,
    extent=None,
    polygon=None,
    title: Optional[str] = None,
    value_label: str = "reachability",
    vmin: float = 0.0,
    vmax: float = 1.0,
    colormap: str = COLORMAP,
    columns: Optional[int] = None,
    panel_size: float = 3.2,
    dpi: int = 110,
) -> str:
    """Writes a PNG of horizontal slices at z = `heights` (m, in the data's frame); returns `path`.

    data: a map with ``voxels()`` and ``resolution`` (capability map, point map ...), a pair
    (centres (M, 3), values (M,)) of voxel centres and values, or a callable points (N, 3) -> values (N,)
    evaluated on a grid of `resolution` over `extent` ((xmin, xmax), (ymin, ymax)).
    A slice shows the voxels whose z range holds the height; empty cells stay white.
    polygon: an outline (N, 2) or (N, 3) (x, y used) drawn on every slice, e.g. a table top.
    """
    h = _check_heights(heights)
    poly = _check_polygon(polygon)
    if not (math.isfinite(vmin) and math.isfinite(vmax) and vmax > vmin):
        raise ValueError(f"need finite vmin < vmax, got {vmin}, {vmax}")
    centres, values, r = _voxel_data(data, resolution, extent, h)
    grid = _slice_grid(centres, r, extent, poly)

    n = len(h)
    cols = columns or min(n, 4)
    rows = math.ceil(n / cols)
    fig = Figure(figsize=(panel_size * cols + 1.2, panel_size * rows + (0.6 if title else 0.2)), dpi=dpi,
                 constrained_layout=True)
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, cols, squeeze=False, sharex=True, sharey=True)
    image = None
    for k, z in enumerate(h):
        image = _draw_slice(axes[k // cols][k % cols], centres, values, z, grid, poly,
                            dict(cmap=colormap, vmin=vmin, vmax=vmax))
    for k in range(n, rows * cols):
        axes[k // cols][k % cols].set_visible(False)
    for row in axes:
        row[0].set_ylabel("y (m)")
    for ax in axes[-1]:
        ax.set_xlabel("x (m)")
    fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.85, label=value_label)
    if title:
        fig.suptitle(title, fontsize=10)
    path = os.fspath(path)
    save_figure(fig, path, format="png")
    return path


def _map_title(cmap) -> str:
    return (f"{cmap.robot_name}: {cmap.base_link} -> {cmap.tip_link}, {cmap.resolution:g} m voxels, "
            f"{len(cmap.orientations)} orientations")


def capability_slices(cmap, heights: Sequence[float], path: Union[str, os.PathLike], *,
                      title: Optional[str] = None, polygon=None, colour_by: str = "reachability", **kwargs) -> str:
    """Writes horizontal slices of capability map `cmap` at z = `heights` (m, chain base link frame), coloured red
    (low) to blue (high) by the reachability index D, or (colour_by="quality") by the mean quality of each voxel's
    reachable cells (manipulability x joint-limit penalty of their stored solutions) relative to the map's best
    cell; returns `path`. A map without quality raises ValueError saying how to rebuild it."""
    if colour_by == "reachability":
        return slices(cmap, heights, path, polygon=polygon, title=title or _map_title(cmap),
                      value_label="reachability index D", **kwargs)
    if colour_by != "quality":
        raise ValueError(f"colour_by must be 'reachability' or 'quality', got {colour_by!r}")
    values = np.asarray(cmap.voxel_quality("mean", relative=True), float)
    kwargs.setdefault("vmax", float(values.max()) if len(values) and values.max() > 0 else 1.0)  # the colours span the map
    centres = np.asarray(cmap.voxels()[0], float).reshape(-1, 3)
    return slices((centres, values), heights, path, resolution=cmap.resolution, polygon=polygon,
                  title=title or _map_title(cmap), value_label="quality (relative to the map's best cell)", **kwargs)


def default_heights(cmap, count: int = 4) -> list[float]:
    """`count` evenly spaced voxel-centre heights (m, base link frame) through the map's bounds."""
    lo, hi = cmap.bounds
    r = cmap.resolution
    zs = np.arange(lo[2] + r / 2, hi[2], r)
    if zs.size == 0:
        return [float(lo[2])]
    idx = np.unique(np.linspace(0, zs.size - 1, min(count, zs.size) + 2)[1:-1].round().astype(int))
    return [round(float(zs[i]), 9) for i in idx]


def reachability_histogram(data, path: Union[str, os.PathLike], *, bins: int = 20, title: Optional[str] = None,
                           dpi: int = 110) -> str:
    """Writes a histogram of the reachability index of the voxels with D > 0; returns `path`.

    data: a map with ``voxels()`` or an array of values.
    """
    if not isinstance(bins, (int, np.integer)) or bins < 1:
        raise ValueError(f"bins must be a positive integer, got {bins!r}")
    if hasattr(data, "voxels"):
        values = np.asarray(data.voxels()[1], dtype=float)
        title = title or _map_title(data)
    else:
        values = np.asarray(data, dtype=float).reshape(-1)
    if not np.isfinite(values).all():
        raise ValueError("values must be finite")
    fig = Figure(figsize=(5.5, 3.6), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    edges = np.linspace(0.0, 1.0, bins + 1)
    counts, _, patches = ax.hist(values, bins=edges, edgecolor="white", linewidth=0.5)
    # bars coloured like the slices
    colours = colormaps[COLORMAP]((edges[:-1] + edges[1:]) / 2)
    for patch, colour in zip(patches, colours):
        patch.set_facecolor(colour)
    ax.set_xlabel("reachability index D")
    ax.set_ylabel("voxels")
    ax.set_xlim(0, 1)
    ax.text(0.98, 0.95, f"{values.size} voxels, mean D {values.mean() if values.size else 0:.3f}",
            transform=ax.transAxes, ha="right", va="top", fontsize=8)
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    path = os.fspath(path)
    save_figure(fig, path, format="png")
    return path


def _pose_map_layer(smap, z: Optional[float]):
    """(centres (M, 3), values (M, theta_bins), z) of the voxel layer of a pose map holding height z
    (default: the lowest layer, where a robot on the floor stands)."""
    centres, values = smap.voxels()
    centres = np.asarray(centres, float)
    values = np.asarray(values, float)
    if len(centres) == 0:
        raise ValueError("the map is empty: nothing to plot")
    r = smap.resolution
    if z is None:
        z = float(centres[:, 2].min())
    if not math.isfinite(z):
        raise ValueError(f"z must be finite, got {z}")
    sel = (z >= centres[:, 2] - r / 2 - 1e-9) & (z < centres[:, 2] + r / 2 - 1e-9)
    return centres[sel], values[sel], z


def surface_slices(smap, path: Union[str, os.PathLike], *, z: Optional[float] = None,
                   thetas=(0.0, math.pi / 2, math.pi, 3 * math.pi / 2),
                   title: Optional[str] = None, dpi: int = 110) -> str:
    """Writes the surface map's layer at height `z` (default: its floor layer) as PNG panels: R_S of the best
    orientation per position, then R_S for the given orientations (rad), red (low) to blue (high), with
    the surface outline drawn (the paper's Fig. 2b); returns `path`."""
    centres, values, z = _pose_map_layer(smap, z)
    r = smap.resolution
    bins = values.shape[1]
    poly = np.asarray(smap.polygon, float) if hasattr(smap, "polygon") and len(smap.polygon) else None
    panels = [("best orientation", values.max(axis=1))]
    for theta in thetas:
        k = int(round(theta / (2 * math.pi / bins))) % bins
        panels.append((f"theta = {math.degrees(2 * math.pi * k / bins):.1f} deg", values[:, k]))
    x0, y0 = centres[:, :2].min(axis=0) - r / 2
    x1, y1 = centres[:, :2].max(axis=0) + r / 2
    if poly is not None:
        x0, y0 = min(x0, poly[:, 0].min() - r), min(y0, poly[:, 1].min() - r)
        x1, y1 = max(x1, poly[:, 0].max() + r), max(y1, poly[:, 1].max() + r)
    # Snap the frame to the voxel grid (voxel edges at multiples of r), so cells sit where they belong
    # relative to the outline.
    x0, y0 = math.floor(x0 / r + 1e-9) * r, math.floor(y0 / r + 1e-9) * r
    x1, y1 = math.ceil(x1 / r - 1e-9) * r, math.ceil(y1 / r - 1e-9) * r
    nx, ny = max(1, int(round((x1 - x0) / r))), max(1, int(round((y1 - y0) / r)))
    ix = np.floor((centres[:, 0] - x0) / r + 1e-9).astype(int).clip(0, nx - 1)
    iy = np.floor((centres[:, 1] - y0) / r + 1e-9).astype(int).clip(0, ny - 1)
    cols = min(len(panels), 3)
    rows = math.ceil(len(panels) / cols)
    fig = Figure(figsize=(3.6 * cols + 1.2, 3.2 * rows + 0.6), dpi=dpi, constrained_layout=True)
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, cols, squeeze=False, sharex=True, sharey=True)
    vmax = max(1e-9, float(values.max()))
    image = None
    for k, (label, v) in enumerate(panels):
        ax = axes[k // cols][k % cols]
        grid = np.full((ny, nx), np.nan)
        grid[iy, ix] = np.where(v > 0, v, np.nan)
        image = ax.imshow(np.ma.masked_invalid(grid), origin="lower", extent=(x0, x0 + nx * r, y0, y0 + ny * r),
                          cmap=COLORMAP, vmin=0, vmax=vmax, interpolation="nearest")
        if poly is not None:
            closed = np.vstack([poly[:, :2], poly[:1, :2]])
            ax.plot(closed[:, 0], closed[:, 1], color="black", linewidth=1.5)
        ax.set_title(label, fontsize=9)
        ax.set_aspect("equal")
    for k in range(len(panels), rows * cols):
        axes[k // cols][k % cols].set_visible(False)
    for row in axes:
        row[0].set_ylabel("y (m)")
    for ax in axes[-1]:
        ax.set_xlabel("x (m)")
    fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.85, label="surface reachability R_S")
    z_label = z
    zr = getattr(smap, "z_range", None)
    if zr is not None and zr[0] == zr[1] and abs(zr[0] - z) <= r:
        z_label = zr[0]  # a single evaluated height (a robot on the floor)
    fig.suptitle(title or f"{smap.robot_name} surface map ({getattr(smap, 'arms', '')}), z = {z_label:.2f} m, "
                 f"{r:g} m, {bins} orientations", fontsize=9)
    path = os.fspath(path)
    save_figure(fig, path, format="png")
    return path


def sample_comparison(smap, path: Union[str, os.PathLike], *, count: int = 500, seed: int = 0,
                      candidates: int = 40, dpi: int = 110) -> str:
    """Writes `count` consecutive samples of a PoseSampler without and with the reachability discount of
    eq. (3), side by side (the paper's Fig. 3): positions coloured by R_S, arrows for the orientation, the
    surface outline in black; returns `path`."""
    from ._core import PoseSampler

    if not isinstance(count, (int, np.integer)) or count < 1:
        raise ValueError(f"count must be a positive integer, got {count!r}")
    runs = [("without discount", PoseSampler(smap, candidates=candidates, seed=seed,
                                             discount_sigma=(1e-9, 1e-9, 1e-9, 1e-9))),
            ("with discount (eq. 3)", PoseSampler(smap, candidates=candidates, seed=seed))]
    poly = np.asarray(smap.polygon, float) if len(smap.polygon) else None
    fig = Figure(figsize=(11, 4.8), dpi=dpi, constrained_layout=True)
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, 2, sharex=True, sharey=True)
    scatter = None
    for ax, (label, sampler) in zip(axes, runs):
        poses = sampler.sample(count)
        rs = smap.reachability(poses)
        norm = Normalize(vmin=0.0, vmax=max(1e-9, float(smap.max_reachability)))  # one scale for both panels
        scatter = ax.scatter(poses[:, 0], poses[:, 1], c=rs, cmap=COLORMAP, norm=norm, s=10)
        ax.quiver(poses[:, 0], poses[:, 1], np.cos(poses[:, 3]), np.sin(poses[:, 3]), rs, cmap=COLORMAP, norm=norm,
                  angles="xy", scale_units="xy", scale=12, width=0.003)
        if poly is not None:
            closed = np.vstack([poly[:, :2], poly[:1, :2]])
            ax.plot(closed[:, 0], closed[:, 1], color="black", linewidth=1.5)
        gaps = [np.linalg.norm(poses[i + 1:, :2] - poses[i, :2], axis=1) for i in range(count - 1)]
        gap = f"mean gap {np.concatenate(gaps).mean():.2f} m" if count > 1 else "one sample"
        ax.set_title(f"{count} samples {label}: {len(np.unique(poses.round(6), axis=0))} distinct, {gap}",
                     fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
    axes[0].set_ylabel("y (m)")
    fig.colorbar(scatter, ax=list(axes), shrink=0.85, label="R_S")
    path = os.fspath(path)
    save_figure(fig, path, format="png")
    return path
