"""Coverage figures of an exploration: the share of a region the map knows, and the figures of a
run (views to reach a coverage, coverage after k views, seen/expected ratios)."""
from __future__ import annotations

import numpy as np

from .._checks import check_type
from .._core import ExplorationMap, Scene
from .scenes import scene_region


def _grid(lo, hi, res):
    # Sample points every `res` from lo + res/2: not the map's own cell centres (those sit on the
    # OctoMap key grid), so ExplorationMap.count_known would give other figures; kept for the tables.
    axes = [np.arange(l + res / 2, h, res) for l, h in zip(lo, hi)]
    if any(len(a) == 0 for a in axes):
        return np.zeros((0, 3))
    g = np.stack(np.meshgrid(*axes, indexing="ij"), -1)
    return g.reshape(-1, 3)


def region_points(scene: Scene, regions, res: float) -> np.ndarray:
    """Sample points (N, 3) every `res` in `regions` ((lo, hi) pairs), those inside solid boxes left out."""
    parts = []
    for lo, hi in regions:
        pts = _grid(np.asarray(lo, float), np.asarray(hi, float), res)
        if len(pts):
            parts.append(pts[~scene.solid(pts)])
    return np.concatenate(parts) if parts else np.zeros((0, 3))


def observed_share(emap: ExplorationMap, scene: Scene, regions=None) -> float:
    """Share (0-1) of the non-solid cells of `regions` ((lo, hi) pairs; default scene_region(scene))
    that the map knows (free or occupied). Everything is unknown at the start."""
    check_type(emap, ExplorationMap, "emap", "an ExplorationMap")
    check_type(scene, Scene, "scene", "a Scene (the regions are the third argument)")
    if regions is None:
        regions = [tuple(scene_region(scene))]
    pts = region_points(scene, regions, emap.resolution)
    if len(pts) == 0:
        return 0.0
    return int(np.count_nonzero(emap.state(pts))) / len(pts)


def views_to_reach(coverage, level: float):
    """The first view (1-based) whose coverage reaches `level`, or None."""
    for i, c in enumerate(coverage):
        if c >= level:
            return i + 1
    return None


def coverage_after(coverage, views: int) -> float:
    """Coverage after `views` views; a run that stopped earlier keeps its last figure (0 for none)."""
    if not len(coverage):
        return 0.0
    return float(coverage[min(views, len(coverage)) - 1])


def seen_expected_ratios(rows, min_expected: float = 1.0) -> list:
    """seen / expected cells of every view that expected at least `min_expected` cells (rows of explore(); the
    last row's view was never taken, nor was a physically invalid one: no seen figure): void cells, or for a view
    beyond the voids (`row.beyond`) the search space's unknown cells it was chosen for (`space_seen` /
    `expected_unknown`). A random view that expects 0.01 cells and sees 300 would say nothing about the model."""
    out = []
    for r in rows:
        beyond = getattr(r, "beyond", False)
        seen, expected = (r.space_seen, r.expected_unknown) if beyond else (r.void_seen, r.expected_void)
        if expected >= min_expected and seen is not None:
            out.append(seen / expected)
    return out


def points_on(box, points, margin: float = 0.015) -> int:
    """How many of `points` (N, 3) lie on the object `box` ((2, 3) lo, hi): within `margin` of it and more
    than `margin` above its bottom (so the floor it stands on does not count)."""
    box = np.asarray(box, float)
    if box.shape != (2, 3):
        raise ValueError(f"target must be a (2, 3) box (lo, hi rows), got shape {box.shape}")
    if not np.all(np.isfinite(box)) or np.any(box[0] > box[1]):
        raise ValueError(f"target must be a finite box with lo <= hi in every axis, got lo {box[0].tolist()}, "
                         f"hi {box[1].tolist()}")
    p = np.asarray(points, float).reshape(-1, 3)
    lo, hi = box[0] - margin, box[1] + margin
    lo[2] = box[0][2] + margin
    return int(np.count_nonzero(np.all((p >= lo) & (p <= hi), axis=1)))
