"""How explore() picks the next view: frontier-void (ours, next_best_view) and three baselines in the
same harness (same robot, camera, reach checks, safe-view rule, budget and stopping rule).

- "frontier_void": next_best_view (Algorithm 1 + frustum scoring), ranked by expected void cells.
- "random": random reachable views: the first valid pose of a seeded random sample.
- "frontiers": the valid sampled pose with the most (expected) frontier cells in view.
- "unknown": the valid sampled pose with the most (expected) unknown cells in view (nbvplanner's gain).

The baselines sample camera poses uniformly in the arm's reach sphere (or the workspace box) above
the floor, each looking at a uniform random point of the search space, and score them all with
score_views (IK, arm collisions, camera clearance and the safe-view rule of next_best_view). The
scores and their order are the C++ ones (ViewCandidate.expected_gain, ranks_before: best_by); this
module chooses among the candidate sets, with the settings of ExploreOptions.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .. import _core
from .candidate_poses import aimed_poses, capability_test, sample_poses

STRATEGIES = ("frontier_void", "random", "frontiers", "unknown")
# The field each strategy's stopping rule looks at ("random" ranks by nothing, it stops on the void gain).
GAIN_OF = {"frontier_void": "expected_void", "random": "expected_void", "frontiers": "expected_frontier",
           "unknown": "expected_unknown"}
# The NbvOptions gain each strategy scores with: with "frontier_void" the rays end at the box of the void
# cells (NbvOptions::gain), so the frontiers / unknown baselines score with their own gain, whole rays.
SCORE_GAIN = {"frontier_void": "frontier_void", "random": "frontier_void", "frontiers": "frontiers",
              "unknown": "unknown"}
# The baselines count every void cell alike: NbvOptions' defaults (the paper's count), not the loop's weights.
_PLAIN = _core.NbvOptions()


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
    details: dict = field(default_factory=dict)  # how it was found: aimed, harder (frontier_void), status_counts
    rank_gain: float = 0.0  # frontier_void: the gain views are ranked by (expected_gain: enclosure-weighted void cells)
    search: Optional[_core.NbvResult] = None  # frontier_void: next_best_view's answer from the chosen base

    def info(self) -> dict:
        """What on_view gets: best_pose plus the figures above (and next_best_view's fields for frontier_void)."""
        d = {} if self.search is None else self.search.to_dict()
        d.update(self.details)
        d.update(best_pose=self.pose, expected_void=self.expected_void, expected_unknown=self.expected_unknown,
                 expected_frontier=self.expected_frontier, utility=self.utility, q=self.q)
        return d


def _choice_of(view, base: int, utility: float, utility_dm3: float, candidates: int, valid: int, **kw) -> Choice:
    """The Choice of a scored view (ViewCandidate or ScoredView) from base index `base`."""
    return Choice(pose=np.asarray(view.pose), void_cells=int(view.void_cells), expected_void=view.expected_void,
                  expected_unknown=view.expected_unknown, expected_frontier=view.expected_frontier, utility=utility,
                  utility_dm3=utility_dm3, q=view.q, base=base, candidates=candidates, valid=valid,
                  rank_gain=view.expected_gain, **kw)


def _base_order(bases, current) -> list:
    """Indices of `bases`, the current one first (so ties keep it)."""
    return [current] + [j for j in range(len(bases)) if j != current]


def _score(emap, camera, poses, search, base, sphere, seed, gain, **extra):
    """score_views of `poses` with the NbvOptions `search` from chain base `base` (its sphere), gains of the
    valid poses only; None when there are no poses."""
    if len(poses) == 0:
        return None
    return _core.score_views(emap, camera, poses, search, score_invalid=False, chain_base=base,
                             workspace_sphere=sphere, seed=seed, gain=gain,
                             capability_base=None if search.capability_map is None else base, **extra)


def _aimed_choice(emap, camera, base, i, sphere, settings, seed, n: int, by: str, unexposed_share: float,
                  distance, directions: int = 1, search_space=None, every_cell: bool = False) -> Optional[Choice]:
    """The best valid of `n` poses aimed at void cells (aimed_poses with `directions`; frontier_void's gain)
    by `by` ("expected_gain", the ranking gain, or "expected_void"), or None."""
    rng = np.random.default_rng(seed)
    search = settings.search
    poses = aimed_poses(rng, emap, sphere=sphere, box=search.workspace_box, n=n, floor=settings.min_camera_height,
                        distance=distance, unexposed_share=unexposed_share, directions=directions,
                        reachable=capability_test(search, base) if directions > 1 else None,
                        search_space=search_space, every_cell=every_cell, clearance=search.unknown_margin,
                        max_cells=settings.max_ray_cells)
    views = _score(emap, camera, poses, search, base, sphere, seed, "frontier_void")
    v = None if views is None else views.best_by(by)
    if v is None:
        return None
    return _choice_of(v, i, v.expected_void, v.utility_dm3, len(poses), int(np.count_nonzero(views.valid)),
                      details={"aimed": True})


def _nbv_choice(emap, camera, bases, current, sphere_of, settings, seed, region, last_chance: bool) -> Choice:
    """next_best_view over all bases (the current one first, so ties keep it); with settings.second_look,
    every view gets a second look (aimed_poses poses per base) and the better view is taken: by the ranking
    gain, or by expected void cells when the search's best expects at most min_utility of them; when the
    better still expects at most min_utility, low_aimed_poses more aimed poses per base (any void cell),
    and with `last_chance` (the low view would end the loop) last_poses poses whose eyes lie along rays out
    of every void cell (aimed_poses' `directions`)."""
    widen_below = settings.min_utility if settings.second_look else None
    best = None
    for i in _base_order(bases, current):
        bp = bases[i]
        search = settings.search
        r = _core.next_best_view(emap, camera, search, seed=seed, workspace_sphere=sphere_of(bp), chain_base=bp,
                                 capability_base=None if search.capability_map is None else bp, gain="frontier_void")
        top = r.best
        if widen_below is not None and top is not None and top.expected_void <= widen_below:
            # the best by the ranking gain is a low view: a view is low only when none on offer expects more
            top = r.best_by("expected_void")
        if top is None:
            c = Choice(pose=None, base=i, candidates=r.poses_scored, search=r)
        else:  # (utility_dm3: of the search's best by its ranking)
            c = _choice_of(top, i, top.expected_void, r.utility_dm3, r.poses_scored, len(r.ranked), search=r)
        if best is None or c.utility > best.utility:
            best = c
    if widen_below is None:
        return best
    # the second look; when the search's best is low, the better view is the one the stopping rule would
    # take (more expected void cells), else the one the search would rank first (its ranking gain)
    low = best.utility <= widen_below
    most = best  # the view on offer with the most expected void cells
    for i in _base_order(bases, current):
        a = _aimed_choice(emap, camera, bases[i], i, sphere_of(bases[i]), settings, seed, settings.aimed_poses,
                          "expected_void" if low else "expected_gain", settings.unexposed_share,
                          settings.aimed_distance)
        if a is not None and (a.utility > best.utility if low else a.rank_gain > best.rank_gain):
            a.search, a.details = best.search, dict(best.details, aimed=True)
            best = a
        most = best if best.utility > most.utility else most
    if best.utility > widen_below:
        return best
    best = most
    # about to take a low view: low_aimed_poses more aimed at any void cell, by expected void cells; when
    # it would end the loop, also last_poses from eyes found along rays out of every void cell
    looks = [(1, settings.low_aimed_poses, settings.aimed_distance)]
    if last_chance:
        looks.append((settings.last_directions, settings.last_poses, settings.last_distance))
    for i in _base_order(bases, current):
        for k, n, distance in looks:  # (a random stream per look)
            a = _aimed_choice(emap, camera, bases[i], i, sphere_of(bases[i]), settings, seed + 7919 + k, n,
                              "expected_void", 1.0, distance, directions=k, search_space=region, every_cell=k > 1)
            if a is not None and a.utility > best.utility:
                a.search, a.details = best.search, dict(best.details, aimed=True, harder=True)
                best = a
    return best


def _sampled_choice(strategy, emap, camera, bases, current, sphere_of, settings, seed, region) -> Choice:
    """The baselines: sample poses per base, score them, take the best valid (random: the first valid)."""
    rng = np.random.default_rng(seed)
    search = settings.search
    best, statuses, pooled, valid, most_void = None, {}, 0, 0, 0.0
    for i in _base_order(bases, current):
        bp = bases[i]
        sphere = sphere_of(bp)
        poses = sample_poses(rng, region, sphere=sphere, box=search.workspace_box, n=settings.sampled_poses,
                             floor=settings.min_camera_height)
        views = _score(emap, camera, poses, search, bp, sphere, seed, SCORE_GAIN[strategy],
                       enclosure_power=_PLAIN.enclosure_power, unexposed_weight=_PLAIN.unexposed_weight)
        if views is None:
            continue
        pooled += len(views)
        for s in views.status:
            statuses[s] = statuses.get(s, 0) + 1
        ok = np.flatnonzero(views.valid)
        valid += len(ok)
        if len(ok) == 0:
            continue
        if strategy == "random":  # the first valid view; it stops on the best void gain on offer
            most_void = max(most_void, float(np.max(views.expected_void[ok])))
            best = best or (i, views[int(ok[0])])
            continue
        v = views.best_by("expected_gain")
        if best is None or _core.ranks_before(v, best[1]):
            best = (i, v)
    if best is None:
        return Choice(pose=None, candidates=pooled, details={"status_counts": statuses})
    i, v = best
    utility = most_void if strategy == "random" else float(getattr(v, GAIN_OF[strategy]))
    return _choice_of(v, i, utility, v.utility_dm3, pooled, valid, details={"status_counts": statuses})


def choose_view(strategy, emap, camera, bases, current, sphere_of, settings, seed, region,
                last_chance: bool = False) -> Choice:
    """The next view of `strategy` (see the module) from any of `bases` (chain base poses; the current
    one first). `sphere_of(base)` is the reach sphere around a base (or the fixed workspace sphere),
    `settings` the ExploreOptions (its search: next_best_view's options; seed, chain_base and the
    workspace sphere are set per base), `seed` this view's."""
    check_strategy(strategy)
    if strategy == "frontier_void":
        return _nbv_choice(emap, camera, bases, current, sphere_of, settings, seed, region, last_chance)
    return _sampled_choice(strategy, emap, camera, bases, current, sphere_of, settings, seed, region)
