"""How explore() picks the next view: frontier-void (ours, next_best_view) and three baselines in the
same harness (same robot, camera, reach checks, safe-view rule, budget and stopping rule).

- "frontier_void": next_best_view (Algorithm 1 + frustum scoring), ranked by expected void cells.
- "random": random reachable views: the first valid pose of a seeded random sample.
- "frontiers": the valid sampled pose with the most (expected) frontier cells in view.
- "unknown": the valid sampled pose with the most (expected) unknown cells in view (nbvplanner's gain).

The baselines sample camera poses uniformly in the arm's reach sphere (or the workspace box) above
the floor, each looking at a uniform random point of the search space, and score them all with
score_views (IK, arm collisions, camera clearance and the safe-view rule of next_best_view).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .. import _core
from .camera import look_at

STRATEGIES = ("frontier_void", "random", "frontiers", "unknown")
# The gain each strategy ranks by, and stops on ("random" ranks by nothing, it stops on the void gain).
GAIN_OF = {"frontier_void": "expected_void", "random": "expected_void", "frontiers": "expected_frontier",
           "unknown": "expected_unknown"}
# The NbvOptions gain each strategy scores with: with "frontier_void" the rays end at the box of the void
# cells (NbvOptions::gain), so the frontiers / unknown baselines score with their own gain, whole rays.
SCORE_GAIN = {"frontier_void": "frontier_void", "random": "frontier_void", "frontiers": "frontiers",
              "unknown": "unknown"}
CANDIDATES = 200  # sampled poses per view and base for the baselines
# frontier_void's second look: on every view, this many camera poses aimed at random void cells (from
# 0.3-1.0 m, inside the arm's reach) are scored too, and the better view is taken (by the ranking gain; by
# expected void cells when next_best_view's best expects at most the stopping threshold). The paper's
# candidate cells come from utility vectors through frontier cells; the last voids of a box (its corners,
# seen only through a small opening) have few vectors that leave the box, and valid views that expect
# 70-100 void cells were missed while the loop stopped with "utility 0" (round 10, then only at low
# views); the views straight down into open crates are missed the same way (round 11: every view).
AIMED_POSES = 400
# ... and when the better of the two expects at most the stopping threshold (the loop is about to count a
# low view), this many more, aimed at any void cell (exposed or not), before the low view is taken: the
# last voids of a closed box lie deep behind its small opening (round 12: a cheaper search pays for it).
LOW_AIMED_POSES = 1200
# ... and when that low view would end the loop (the patience's last one), also up to LAST_POSES poses
# whose eyes are found along LAST_DIRECTIONS random rays out of every void cell (aimed_poses with
# `directions`: the eye observed-free, clear and reachable, the ray past no surface and no unseen wall),
# LAST_DISTANCE (m) from the cell (nearer than the aimed poses' 0.3 m: a small box's low opening is looked
# into from a few centimetres in front of it). Round 13: with one random direction per cell, 91 % of the
# rays from paper scene 2's last void cells met a surface and the others' eyes mostly lay inside the box;
# round 12's seed 3 stopped at 88.5 % with a valid view expecting 219 void cells never drawn (down through
# the +z opening from 9 cm above the lid; others look up into the -x openings from 12 cm above the floor).
LAST_DIRECTIONS = 128
LAST_POSES = 4000
LAST_DISTANCE = (0.15, 1.0)
MAX_RAY_CELLS = 4096  # aimed_poses(every_cell=True) walks rays out of at most this many void cells
# next_best_view's search breadth: score_views, which scores given poses, has no search of its own
SEARCH_ONLY_OPTIONS = ("max_valid_poses", "orientations_per_cell", "max_candidate_cells")


def check_strategy(strategy) -> str:
    """`strategy` itself, or ValueError naming the choices."""
    if strategy not in STRATEGIES:
        raise ValueError(f"unknown strategy {strategy!r}; choose one of {', '.join(STRATEGIES)}")
    return strategy


@dataclass
class Choice:
    """The view a strategy picked (pose None: no valid view) with its expected gains."""

    pose: Optional[np.ndarray]
    void_cells: int = 0  # raw distinct void cells in view (unknown space transparent up to the first occupied cell)
    expected_void: float = 0.0
    expected_unknown: float = 0.0
    expected_frontier: float = 0.0
    utility: float = 0.0  # the gain the stopping rule looks at (GAIN_OF[strategy]) of the best valid view
    utility_dm3: float = 0.0
    q: Optional[np.ndarray] = None
    base: int = 0
    candidates: int = 0  # poses scored
    valid: int = 0  # of them valid
    details: dict = field(default_factory=dict)  # next_best_view's result (frontier_void) or counts by status
    rank_gain: float = 0.0  # frontier_void: the gain views are ranked by (expected_gain: enclosure-weighted void cells)

    def info(self) -> dict:
        """What on_view gets: best_pose plus the figures above (and next_best_view's keys for frontier_void)."""
        d = dict(self.details)
        d.update(best_pose=self.pose, expected_void=self.expected_void, expected_unknown=self.expected_unknown,
                 expected_frontier=self.expected_frontier, utility=self.utility, q=self.q)
        return d


def sample_poses(rng, region, sphere=None, box=None, n: int = CANDIDATES, floor: float = 0.05) -> np.ndarray:
    """`n` camera poses (n, 4, 4): positions uniform in the sphere (centre, radius) and/or box ((2, 3))
    above `floor` (neither: the search space grown by 0.5 m), each looking at a uniform random point of `region` ((2, 3) lo, hi) at least 0.1 m away."""
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


def _score(emap, camera, poses, options):
    """score_views as a list of dicts (pose, valid, status, void_cells, expected_* gains, q)."""
    if len(poses) == 0:
        return []
    r = _core.score_views(emap, camera, poses, score_invalid=False, **options)  # gains of valid poses only
    q = r["q"]
    out = []
    for i in range(len(poses)):
        out.append({"pose": r["pose"][i], "valid": bool(r["valid"][i]), "status": r["status"][i],
                    "void_cells": int(r["void_cells"][i]), "expected_void": float(r["expected_void"][i]),
                    "expected_unknown": float(r["expected_unknown"][i]),
                    "expected_frontier": float(r["expected_frontier"][i]),
                    "expected_gain": float(r["expected_gain"][i]),
                    "q": None if q is None or not r["valid"][i] else np.asarray(q[i])})
    return out


def _base_order(bases, current) -> list:
    """Indices of `bases`, the current one first (so ties keep it)."""
    return [current] + [j for j in range(len(bases)) if j != current]


def _score_options(options, base, sphere, seed, **extra) -> dict:
    """score_views' keywords for one base: `options` without the search's breadth, the base, its sphere."""
    opts = {k: v for k, v in options.items() if k not in SEARCH_ONLY_OPTIONS}
    opts.update(chain_base=base, workspace_sphere=sphere, seed=seed,
                capability_base=None if options.get("capability_map") is None else base, **extra)
    return opts


def _view_choice(v, base, utility, emap, candidates, valid, details) -> Choice:
    """The Choice of a scored view `v` (a _score dict) from base index `base`."""
    return Choice(pose=np.asarray(v["pose"]), void_cells=v["void_cells"], expected_void=float(v["expected_void"]),
                  expected_unknown=float(v["expected_unknown"]), expected_frontier=float(v["expected_frontier"]),
                  utility=utility, utility_dm3=float(v["expected_void"]) * emap.resolution ** 3 * 1000, q=v.get("q"),
                  base=base, candidates=candidates, valid=valid, details=details)


# The aimed poses' targets: void cells with an observed free cell among their 26 neighbours
# (_core.exposed_cells: the face of a void that observed space shows, which a view can see at once: 83 % of
# the void cells left in paper scene 1's open crates after the first view, 16 % of the unknown inside of its
# solid computer tower), and this share of the others.
UNEXPOSED_SHARE = 0.25


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


def aimed_poses(rng, emap, sphere=None, box=None, n: int = AIMED_POSES, floor: float = 0.05,
                distance=(0.3, 1.0), unexposed_share: Optional[float] = None, directions: int = 1,
                reachable=None, search_space=None, every_cell: bool = False) -> np.ndarray:
    """Up to `n` camera poses (n, 4, 4), each looking at a random void cell of `emap` from a random direction
    (not from below) at a distance drawn from `distance` (m), kept inside the sphere (centre, radius)
    and/or box ((2, 3)), above `floor`, and in line of sight of the cell (no occupied cell of the map
    between them: in_line_of_sight). Round 12: without that test most poses aimed at the last slivers of
    an open crate looked at them through the crate's own wall. The cells are drawn among the exposed
    ones (_core.exposed_cells) and `unexposed_share` (default UNEXPOSED_SHARE) of the others.

    `directions` > 1: the eyes are found along that many random rays (any direction) out of each cell
    (_poses_out_of_voids: observed free past the cell's unknown space, before any surface or unseen wall,
    clear, `reachable` ((N, 4, 4) camera poses -> bools, e.g. the capability map's); unknown cells outside
    `search_space` ((2, 3)) count as free, as in the search's camera clearance), from `n` cells drawn as
    above or from every void cell (`every_cell`), and `n` of the rays that find one are kept at random: the
    last voids of a closed box are seen only through its opening, which few random directions pass (round
    13: 9 % of the directions from paper scene 2's last void cells leave without meeting a surface)."""
    keys = np.asarray(emap.void_keys())
    if len(keys) == 0 or n <= 0:
        return np.zeros((0, 4, 4))
    k = int(directions)
    drawn = keys[rng.integers(len(keys), size=8 * n)]
    targets = np.asarray(emap.centers(drawn), float).reshape(-1, 3)
    share = UNEXPOSED_SHARE if unexposed_share is None else unexposed_share
    keep = np.asarray(_core.exposed_cells(emap, drawn), bool) | (rng.random(len(targets)) < share)
    if k > 1:
        if every_cell:  # (at most MAX_RAY_CELLS of them, at random: the rays' cost grows with the cells)
            every = keys if len(keys) <= MAX_RAY_CELLS else rng.choice(keys, MAX_RAY_CELLS, replace=False)
            cells = np.asarray(emap.centers(every), float).reshape(-1, 3)
        else:
            cells = targets[keep][:n]
        return _poses_out_of_voids(rng, emap, cells, k, sphere, box, floor, distance, reachable, search_space, n=n)
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


def _poses_out_of_voids(rng, emap, targets, k, sphere, box, floor, distance, reachable, search_space=None,
                        clearance: float = 0.05, n: Optional[int] = None, chunk: int = 8192) -> np.ndarray:
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


def _capability_test(options, base):
    """(N, 4, 4) camera poses (world) -> bools: the capability map's position and axis test of score_views
    (NbvOptions min_reachability, capability_orientations), or None without a capability map."""
    cmap = options.get("capability_map")
    if cmap is None:
        return None
    to_arm = np.linalg.inv(np.asarray(base, float))
    floor = options.get("min_reachability") or 0.0
    axes = options.get("capability_orientations", True)

    def test(T):
        Tb = np.einsum("ij,njk->nik", to_arm, T)
        ok = np.asarray(cmap.reachability(Tb[:, :3, 3]), float) > floor
        return ok & np.asarray(cmap.reachable(Tb), bool) if axes else ok

    return test


def _aimed_choice(emap, camera, base, i, sphere, options, seed, n: int = AIMED_POSES,
                  unexposed_share: Optional[float] = None, by: str = "expected_gain",
                  directions: int = 1, search_space=None, distance=(0.3, 1.0),
                  every_cell: bool = False) -> Optional[Choice]:
    """The best valid of `n` poses aimed at void cells (aimed_poses with `directions`; frontier_void's gain)
    by `by` (the ranking gain, or "expected_void"), or None."""
    rng = np.random.default_rng(seed)
    poses = aimed_poses(rng, emap, sphere=sphere, box=options.get("workspace_box"), n=n,
                        unexposed_share=unexposed_share, directions=directions,
                        reachable=_capability_test(options, base) if directions > 1 else None,
                        search_space=search_space, distance=distance, every_cell=every_cell)
    opts = _score_options(options, base, sphere, seed, gain="frontier_void")
    valid = [v for v in _score(emap, camera, poses, opts) if v["valid"]]
    if not valid:
        return None
    v = max(valid, key=lambda w: (w[by], w["expected_unknown"]))
    c = _view_choice(v, i, float(v["expected_void"]), emap, len(poses), len(valid), {"aimed": True})
    c.rank_gain = float(v["expected_gain"])
    return c


def _nbv_choice(emap, camera, bases, current, sphere_of, options, seed, widen_below=None, region=None,
                last_chance: bool = False) -> Choice:
    """next_best_view over all bases (the current one first, so ties keep it); with `widen_below`, every
    view gets a second look (AIMED_POSES aimed poses per base) and the better view is taken: by the ranking
    gain, or by expected void cells when the search's best expects at most `widen_below` of them; when the
    better still expects at most `widen_below`, LOW_AIMED_POSES more aimed poses per base (any void cell),
    and with `last_chance` (the low view would end the loop) LAST_POSES poses whose eyes lie along rays out
    of every void cell (aimed_poses' `directions`)."""
    best = None
    for i in _base_order(bases, current):
        bp = bases[i]
        cap_base = None if options.get("capability_map") is None else bp
        r = _core.next_best_view(emap, camera, seed=seed, workspace_sphere=sphere_of(bp), chain_base=bp,
                                 capability_base=cap_base, gain="frontier_void", **options)
        top = r["ranked"][0] if r["ranked"] else {}
        if widen_below is not None and r["ranked"] and top["expected_void"] <= widen_below:
            # the best by the ranking gain is a low view: a view is low only when none on offer expects more
            top = max(r["ranked"], key=lambda v: v["expected_void"])
        c = Choice(pose=None if top.get("pose") is None else np.asarray(top["pose"]), void_cells=int(top.get("void_cells", 0)),
                   expected_void=float(top.get("expected_void", 0.0)),
                   expected_unknown=float(top.get("expected_unknown", 0.0)),
                   expected_frontier=float(top.get("expected_frontier", 0.0)),
                   utility=float(top.get("expected_void", 0.0)), utility_dm3=float(r["utility_dm3"]),
                   q=top.get("q"), base=i, candidates=int(r["poses_scored"]), valid=len(r["ranked"]), details=r)
        c.rank_gain = float(top.get("expected_enclosed_void", 0.0))
        if best is None or c.utility > best.utility:
            best = c
    if widen_below is None:
        return best
    # the second look; when the search's best is low, the better view is the one the stopping rule would
    # take (more expected void cells), else the one the search would rank first (its ranking gain)
    low = best.utility <= widen_below
    most = best  # the view on offer with the most expected void cells
    for i in _base_order(bases, current):
        a = _aimed_choice(emap, camera, bases[i], i, sphere_of(bases[i]), options, seed,
                          by="expected_void" if low else "expected_gain")
        if a is not None and (a.utility > best.utility if low else a.rank_gain > best.rank_gain):
            a.details = dict(best.details, aimed=True)
            best = a
        most = best if best.utility > most.utility else most
    if best.utility > widen_below:
        return best
    best = most
    # about to take a low view: LOW_AIMED_POSES more aimed at any void cell, by expected void cells; when
    # it would end the loop, also LAST_POSES from eyes found along rays out of every void cell
    for i in _base_order(bases, current):
        looks = [(1, LOW_AIMED_POSES, (0.3, 1.0))]
        if last_chance:
            looks.append((LAST_DIRECTIONS, LAST_POSES, LAST_DISTANCE))
        for k, n, distance in looks:  # (a random stream per look)
            a = _aimed_choice(emap, camera, bases[i], i, sphere_of(bases[i]), options, seed + 7919 + k, n=n,
                              unexposed_share=1.0, by="expected_void", directions=k, search_space=region,
                              distance=distance, every_cell=k > 1)
            if a is not None and a.utility > best.utility:
                a.details = dict(best.details, aimed=True, harder=True)
                best = a
    return best


def _sampled_choice(strategy, emap, camera, bases, current, sphere_of, options, seed, region, candidates) -> Choice:
    """The baselines: sample poses per base, score them, take the best valid (random: the first valid)."""
    rng = np.random.default_rng(seed)
    gain = GAIN_OF[strategy]
    best, pool = None, []
    for i in _base_order(bases, current):
        bp = bases[i]
        sphere = sphere_of(bp)
        poses = sample_poses(rng, region, sphere=sphere, box=options.get("workspace_box"), n=candidates)
        views = _score(emap, camera, poses, _score_options(options, bp, sphere, seed, gain=SCORE_GAIN[strategy]))
        pool += [(i, v) for v in views]
    valid = [(i, v) for i, v in pool if v["valid"]]
    statuses = {}
    for _, v in pool:
        statuses[v["status"]] = statuses.get(v["status"], 0) + 1
    if not valid:
        return Choice(pose=None, candidates=len(pool), details={"status_counts": statuses})
    if strategy == "random":
        i, v = valid[0]
    else:
        i, v = max(valid, key=lambda iv: (iv[1][gain], iv[1]["expected_unknown"]))
    # the stopping rule: the strategy's gain of the best valid view (random: the best void gain on offer)
    utility = max(float(w["expected_void"]) for _, w in valid) if strategy == "random" else float(v[gain])
    return _view_choice(v, i, utility, emap, len(pool), len(valid), {"status_counts": statuses})


def choose_view(strategy, emap, camera, bases, current, sphere_of, options, seed, region,
                candidates: int = CANDIDATES, widen_below=None, last_chance: bool = False) -> Choice:
    """The next view of `strategy` (see the module) from any of `bases` (chain base poses; the current
    one first). `sphere_of(base)` is the reach sphere around a base (or the fixed workspace sphere),
    `options` next_best_view's keywords without seed, chain_base and the workspace sphere."""
    check_strategy(strategy)
    if strategy == "frontier_void":
        return _nbv_choice(emap, camera, bases, current, sphere_of, options, seed, widen_below, region, last_chance)
    return _sampled_choice(strategy, emap, camera, bases, current, sphere_of, options, seed, region, candidates)
