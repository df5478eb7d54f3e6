"""Coverage figures of an exploration: the share of a region the map knows."""
from __future__ import annotations

import numpy as np

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


def observed_share(emap: ExplorationMap, scene: Scene, regions=None) -> float:
    """Share (0-1) of the non-solid cells of `regions` ((lo, hi) pairs; default scene_region(scene))
    that the map knows (free or occupied). Everything is unknown at the start."""
    res = emap.resolution
    if regions is None:
        regions = [tuple(scene_region(scene))]
    known = total = 0
    for lo, hi in regions:
        pts = _grid(np.asarray(lo, float), np.asarray(hi, float), res)
        if len(pts) == 0:
            continue
        pts = pts[~scene.solid(pts)]
        total += len(pts)
        known += int(np.count_nonzero(emap.state(pts)))
    return known / total if total else 0.0
