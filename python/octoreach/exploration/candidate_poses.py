"""Candidate camera poses the strategies score (with score_views) besides next_best_view's own: sampled in
the arm's reach (the baselines) and aimed along lines of sight at void cells (as frontier_void's second
look aims them). The counts and distances come from ExploreOptions (defaults: ExploreOptions();
docs/design/next_best_view.md says why)."""
from __future__ import annotations

from typing import Optional

import numpy as np

from .. import _core
from .camera import look_at

_DEFAULTS = _core.ExploreOptions()


def sample_poses(rng, region, sphere=None, box=None, n: Optional[int] = None, floor: Optional[float] = None) -> np.ndarray:
    """`n` camera poses (n, 4, 4; default ExploreOptions.sampled_poses): positions uniform in the sphere
    (centre, radius) and/or box ((2, 3)) above `floor` (default min_camera_height; neither: the search
    space grown by 0.5 m), each looking at a uniform random point of `region` ((2, 3) lo, hi) at least
    0.1 m away."""
    n = _DEFAULTS.sampled_poses if n is None else n
    floor = _DEFAULTS.min_camera_height if floor is None else floor
    region = np.asarray(region, float)
    if sphere is not None:
        c, r = np.asarray(sphere[0], float), float(sphere[1])
        lo, hi = c - r, c + r
    elif box is not None:
        lo, hi = np.asarray(box, float)
    else:  # a free camera with only a callable workspace: around the search space
        lo, hi = region[0] - 0.5, region[1] + 0.5
    if box is not None:
        lo, hi = np.maximum(lo, np.asarray(box, float)[0]), np.minimum(hi, np.asarray(box, float)[1])
    lo = lo.copy()
    lo[2] = max(lo[2], floor)
    out = []
    for _ in range(200 * n):
        if len(out) == n or np.any(hi <= lo):
            break
        p = rng.uniform(lo, hi)
        if sphere is not None and np.linalg.norm(p - c) > r:
            continue
        t = rng.uniform(region[0], region[1])
        if np.linalg.norm(t - p) < 0.1:
            continue
        out.append(look_at(p, t))
    return np.array(out).reshape(-1, 4, 4)


def in_line_of_sight(emap, targets, eyes) -> np.ndarray:
    """(N,) bools: the segment from each target (N, 3) to its eye (N, 3) meets no occupied cell of `emap`
    past the target's own cell (unknown cells may lie on it: they may be seen through)."""
    targets, eyes = np.asarray(targets, float).reshape(-1, 3), np.asarray(eyes, float).reshape(-1, 3)
    if len(targets) == 0:
        return np.zeros(0, bool)
    length = np.linalg.norm(eyes - targets, axis=1)
    steps = int(np.ceil(length.max() / (0.5 * emap.resolution))) + 1
    # samples every half cell from one cell past the target to the eye (shorter segments repeat their eye)
    s = np.minimum(emap.resolution + 0.5 * emap.resolution * np.arange(steps)[None, :], length[:, None])
    u = (eyes - targets) / np.maximum(length, 1e-12)[:, None]
    points = targets[:, None, :] + s[:, :, None] * u[:, None, :]
    occupied = np.asarray(emap.state(points.reshape(-1, 3))).reshape(len(targets), steps) == 2
    return ~occupied.any(axis=1)


def aimed_poses(rng, emap, sphere=None, box=None, n: Optional[int] = None, floor: Optional[float] = None,
                distance=None, unexposed_share: Optional[float] = None) -> np.ndarray:
    """Up to `n` camera poses (n, 4, 4), each looking at a random void cell of `emap` from a random direction
    (not from below) at a distance drawn from `distance` (m), kept inside the sphere (centre, radius)
    and/or box ((2, 3)), above `floor`, and in line of sight of the cell (no occupied cell of the map
    between them: in_line_of_sight, else cameras aimed at the last slivers of an open crate look at them
    through the crate's own wall). The cells are drawn among the exposed ones (_core.exposed_cells) and
    `unexposed_share` of the others. None takes ExploreOptions' second-look defaults (aimed_poses,
    min_camera_height, aimed_distance, unexposed_share). The loop's own looks (these and the last chance
    along rays out of every void cell) are C++: _core.choose_view."""
    n = _DEFAULTS.aimed_poses if n is None else n
    floor = _DEFAULTS.min_camera_height if floor is None else floor
    distance = _DEFAULTS.aimed_distance if distance is None else distance
    share = _DEFAULTS.unexposed_share if unexposed_share is None else unexposed_share
    keys = np.asarray(emap.void_keys())
    if len(keys) == 0 or n <= 0:
        return np.zeros((0, 4, 4))
    drawn = keys[rng.integers(len(keys), size=8 * n)]
    targets = np.asarray(emap.centers(drawn), float).reshape(-1, 3)
    keep = np.asarray(_core.exposed_cells(emap, drawn), bool) | (rng.random(len(targets)) < share)
    targets = targets[keep][:4 * n]
    d = rng.normal(size=targets.shape)
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    eyes = targets + d * rng.uniform(distance[0], distance[1], size=(len(targets), 1))
    idx = np.flatnonzero(_eyes_allowed(eyes, sphere, box, floor))
    idx = idx[in_line_of_sight(emap, targets[idx], eyes[idx])][:n]
    return np.array([look_at(eyes[i], targets[i]) for i in idx]).reshape(-1, 4, 4)


def _eyes_allowed(eyes, sphere, box, floor) -> np.ndarray:
    """(N,) bools: `eyes` above `floor`, inside the sphere (centre, radius) and the box ((2, 3)) when given."""
    ok = eyes[:, 2] >= floor
    if sphere is not None:
        ok &= np.linalg.norm(eyes - np.asarray(sphere[0], float), axis=1) <= float(sphere[1])
    if box is not None:
        lo, hi = np.asarray(box, float)
        ok &= np.all((eyes >= lo) & (eyes <= hi), axis=1)
    return ok
