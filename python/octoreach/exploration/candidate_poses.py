"""Candidate camera poses the strategies score (with score_views) besides next_best_view's own: sampled in
the arm's reach (the baselines), aimed along lines of sight at void cells (frontier_void's second look),
and found along rays out of every void cell (its last chance). The counts and distances come from
ExploreOptions (defaults: ExploreOptions(); docs/design/next_best_view.md says why)."""
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


def _axes_reachable(reachable, eyes, targets) -> np.ndarray:
    """(N,) bools of `reachable` ((N, 4, 4) camera poses -> bools) for cameras at `eyes` looking at `targets`
    (any roll: the capability map's axis test looks at the optical axis only)."""
    if reachable is None or len(eyes) == 0:
        return np.ones(len(eyes), bool)
    z = targets - eyes
    z /= np.maximum(np.linalg.norm(z, axis=1, keepdims=True), 1e-12)
    helper = np.where(np.abs(z[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x, axis=1, keepdims=True)
    T = np.zeros((len(eyes), 4, 4))
    T[:, :3, 0], T[:, :3, 1], T[:, :3, 2], T[:, :3, 3], T[:, 3, 3] = x, np.cross(z, x), z, eyes, 1.0
    return np.asarray(reachable(T), bool)


def aimed_poses(rng, emap, sphere=None, box=None, n: Optional[int] = None, floor: Optional[float] = None,
                distance=None, unexposed_share: Optional[float] = None, directions: int = 1,
                reachable=None, search_space=None, every_cell: bool = False, clearance: Optional[float] = None,
                max_cells: Optional[int] = None) -> np.ndarray:
    """Up to `n` camera poses (n, 4, 4), each looking at a random void cell of `emap` from a random direction
    (not from below) at a distance drawn from `distance` (m), kept inside the sphere (centre, radius)
    and/or box ((2, 3)), above `floor`, and in line of sight of the cell (no occupied cell of the map
    between them: in_line_of_sight, else cameras aimed at the last slivers of an open crate look at them
    through the crate's own wall). The cells are drawn among the exposed ones (_core.exposed_cells) and
    `unexposed_share` of the others. None takes ExploreOptions' second-look defaults (aimed_poses,
    min_camera_height, aimed_distance, unexposed_share; NbvOptions.unknown_margin, max_ray_cells).

    `directions` > 1: the eyes are found along that many random rays (any direction) out of each cell
    (_poses_out_of_voids: observed free past the cell's unknown space, before any surface or unseen wall,
    `clearance` clear, `reachable` ((N, 4, 4) camera poses -> bools, e.g. the capability map's); unknown
    cells outside `search_space` ((2, 3)) count as free, as in the search's camera clearance), from `n`
    cells drawn as above or from every void cell (`every_cell`; at most `max_cells`, at random), and `n` of
    the rays that find one are kept at random: the last voids of a closed box are seen only through its
    opening, which few random directions pass."""
    n = _DEFAULTS.aimed_poses if n is None else n
    floor = _DEFAULTS.min_camera_height if floor is None else floor
    distance = _DEFAULTS.aimed_distance if distance is None else distance
    share = _DEFAULTS.unexposed_share if unexposed_share is None else unexposed_share
    keys = np.asarray(emap.void_keys())
    if len(keys) == 0 or n <= 0:
        return np.zeros((0, 4, 4))
    k = int(directions)
    drawn = keys[rng.integers(len(keys), size=8 * n)]
    targets = np.asarray(emap.centers(drawn), float).reshape(-1, 3)
    keep = np.asarray(_core.exposed_cells(emap, drawn), bool) | (rng.random(len(targets)) < share)
    if k > 1:
        if every_cell:  # (at most max_cells of them, at random: the rays' cost grows with the cells)
            limit = _DEFAULTS.max_ray_cells if max_cells is None else max_cells
            every = keys if len(keys) <= limit else rng.choice(keys, limit, replace=False)
            cells = np.asarray(emap.centers(every), float).reshape(-1, 3)
        else:
            cells = targets[keep][:n]
        clearance = _DEFAULTS.search.unknown_margin if clearance is None else clearance
        return _poses_out_of_voids(rng, emap, cells, k, sphere, box, floor, distance, reachable, search_space,
                                   clearance=clearance, n=n)
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


def _free_states(emap, points, search_space=None) -> np.ndarray:
    """emap.state of `points` (..., 3) with unknown cells outside `search_space` ((2, 3)) as free (1), as the
    search's camera clearance counts them (the map need not have observed the space above the scene)."""
    points = np.asarray(points, float)
    states = np.asarray(emap.state(points.reshape(-1, 3))).reshape(points.shape[:-1])
    if search_space is not None:
        lo, hi = np.asarray(search_space, float)
        outside = np.any((points < lo) | (points > hi), axis=-1)
        states = np.where((states == 0) & outside, np.uint8(1), states)
    return states


def _observed_around(emap, points, clearance: float, search_space=None) -> np.ndarray:
    """(N,) bools: every cell within `clearance` (m, Chebyshev, in cells) of each point is free (_free_states:
    the search's camera clearance, checked on a cube of cell centres)."""
    m = int(np.ceil(clearance / emap.resolution - 1e-9))
    r = np.arange(-m, m + 1) * emap.resolution
    off = np.stack(np.meshgrid(r, r, r, indexing="ij"), axis=-1).reshape(-1, 3)
    if len(points) == 0:
        return np.zeros(0, bool)
    return np.all(_free_states(emap, points[:, None, :] + off[None, :, :], search_space) == 1, axis=1)


def _poses_out_of_voids(rng, emap, targets, k, sphere, box, floor, distance, reachable, search_space, *,
                        clearance: float, n: Optional[int] = None, chunk: int = 8192) -> np.ndarray:
    """Up to `n` (default len(targets)) poses looking at `targets` (void cell centres) from eyes found by
    walking `k` random rays out of each cell: an eye is an observed-free point of a ray that has left
    unknown space once, before the ray meets an occupied cell or unknown space again, `distance` (m) from
    the cell, allowed (_eyes_allowed, `reachable`) and with free space `clearance` (m) around it
    (_observed_around); one eye per ray, at random along it, and `n` of the rays with one, at random. The
    rays cross unknown space first: a void deep in a closed box is left only through its opening, and the
    camera must stand in observed-free space beyond it."""
    n = len(targets) if n is None else n
    if len(targets) == 0 or n <= 0:
        return np.zeros((0, 4, 4))
    step = 0.5 * emap.resolution
    s = emap.resolution + step * np.arange(int(np.ceil((distance[1] - emap.resolution) / step)) + 1)
    found_t, found_e = [], []
    T_all = np.repeat(targets, k, axis=0)
    for c in range(0, len(T_all), chunk):  # bounded memory: (chunk, samples) at a time
        T = T_all[c:c + chunk]
        d = rng.normal(size=T.shape)  # any direction: a low opening shows a box's upper inside from below
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        states = _free_states(emap, T[:, None, :] + s[None, :, None] * d[:, None, :], search_space)
        # before the first occupied sample, and before unknown space met again after observed-free space
        # (an unseen wall: the map's walls are unknown until a view has seen them)
        after_free = np.cumsum(states == 1, axis=1) > 0
        clear = np.cumsum((states == 2) | ((states == 0) & after_free), axis=1) == 0
        cand = clear & (states == 1) & (s >= distance[0])[None, :]
        pick = np.where(cand, rng.random(cand.shape), -1.0).argmax(axis=1)  # a random sample of each ray
        ray = np.flatnonzero(cand[np.arange(len(T)), pick])
        eyes = T[ray] + s[pick[ray], None] * d[ray]
        ok = _eyes_allowed(eyes, sphere, box, floor)
        ray, eyes = ray[ok], eyes[ok]
        ok = _axes_reachable(reachable, eyes, T[ray])
        ray, eyes = ray[ok], eyes[ok]
        ok = _observed_around(emap, eyes, clearance, search_space)
        found_t.append(T[ray[ok]])
        found_e.append(eyes[ok])
    targets, eyes = np.concatenate(found_t), np.concatenate(found_e)
    pick = rng.permutation(len(eyes))[:n]
    return np.array([look_at(eyes[i], targets[i]) for i in pick]).reshape(-1, 4, 4)


def capability_test(search, base):
    """(N, 4, 4) camera poses (world) -> bools: the capability map's position and axis test of score_views
    with the NbvOptions `search` (capability_map, min_reachability, capability_orientations) for the chain
    base pose `base`, or None without a capability map."""
    cmap = search.capability_map
    if cmap is None:
        return None
    to_arm = np.linalg.inv(np.asarray(base, float))
    floor = search.min_reachability
    axes = search.capability_orientations

    def test(T):
        Tb = np.einsum("ij,njk->nik", to_arm, T)
        ok = np.asarray(cmap.reachability(Tb[:, :3, 3]), float) > floor
        return ok & np.asarray(cmap.reachable(Tb), bool) if axes else ok

    return test
