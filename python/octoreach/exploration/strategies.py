"""How explore() picks the next view: frontier-void (ours, next_best_view) and three baselines in the
same harness (same robot, camera, reach checks, safe-view rule, budget and stopping rule).

- "frontier_void": next_best_view (Algorithm 1 + frustum scoring), ranked by expected void cells.
- "random": random reachable views: the first valid pose of a seeded random sample.
- "frontiers": the valid sampled pose with the most (expected) frontier cells in view.
- "unknown": the valid sampled pose with the most (expected) unknown cells in view (nbvplanner's gain).

The baselines sample camera poses uniformly in the arm's reach sphere (or the workspace box) above
the floor, each looking at a uniform random point of the search space, and score them all with
score_views (IK, arm collisions, camera clearance and the safe-view rule of next_best_view). The whole
choice (search, second looks, last chance, stop decision) is C++ (_core.choose_view, view_choice.hpp);
this module maps it onto the loop's Choice, with the settings of ExploreOptions.
"""
from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .. import _core

STRATEGIES = ("frontier_void", "random", "frontiers", "unknown")


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
    details: dict = field(default_factory=dict)  # how it was found: aimed, harder, beyond (frontier_void)
    rank_gain: float = 0.0  # frontier_void: the gain views are ranked by (expected_gain: enclosure-weighted void cells)
    search: Optional[_core.NbvResult] = None  # frontier_void: next_best_view's answer from the chosen base
    stop: bool = False  # the loop ends here (choose_view's stop decision)
    stop_reason: str = ""

    def info(self) -> dict:
        """What on_view gets: best_pose plus the figures above (and next_best_view's fields for frontier_void)."""
        d = {} if self.search is None else self.search.to_dict()
        d.update(self.details)
        d.update(best_pose=self.pose, expected_void=self.expected_void, expected_unknown=self.expected_unknown,
                 expected_frontier=self.expected_frontier, utility=self.utility, q=self.q)
        return d


# The search's rejection counts (NbvResult field) by the status name of score_views, with what each means.
REJECTIONS = (
    ("not_reachable", "capability_rejected", "the capability map rules the pose out"),
    ("camera_not_clear", "camera_not_clear",
     "the camera stands within min_distance of an occupied cell or unknown_margin of an unknown cell of the "
     "search space"),
    ("no_ik", "ik_failures", "no joint solution reaches (or aims at) the pose"),
    ("arm_collision", "arm_collisions",
     "a link the chain moves touches an occupied cell, an unknown cell of the search space or the ground"),
)


def stop_message(view) -> str:
    """The stop reason of a NextView (or ViewChoice) with, for "no valid view", the search's counts per
    rejection status and what the largest one means, e.g. "no valid view (412 candidate cells; rejected:
    300 camera_not_clear, 112 no_ik: ...)"; "" when the view does not stop."""
    c = getattr(view, "choice", view)
    if not view.stop:
        return ""
    if view.stop_reason != "no valid view":
        return view.stop_reason
    r = c.search
    counts = [(name, int(getattr(r, field)), why) for name, field, why in REJECTIONS if getattr(r, field)]
    if not counts and int(c.candidates) == 0:
        return ("no valid view (no pose to score: none lies in the search's workspace, the arm's reach, and "
                "farther than failed_view_radius from the camera of every view not taken)")
    if not counts:
        return f"no valid view ({int(c.candidates)} poses scored, none valid)"
    counts.sort(key=lambda t: -t[1])
    listed = ", ".join(f"{n} {name}" for name, n, _ in counts)
    top, _, why = counts[0]
    return f"no valid view ({int(r.candidate_cells)} candidate cells; rejected: {listed}; {top}: {why})"


def _choice_of(c) -> Choice:
    """The Choice of a C++ ViewChoice."""
    details = {"aimed": True} if c.aimed else {}
    if c.harder:
        details["harder"] = True
    if c.beyond:
        details["beyond"] = True
    if not c.found:
        return Choice(pose=None, base=c.base, candidates=int(c.candidates), details=details,
                      search=c.search if c.search.poses_scored else None, stop=c.stop, stop_reason=c.stop_reason)
    v = c.view
    return Choice(pose=np.asarray(v.pose), void_cells=int(v.void_cells), expected_void=v.expected_void,
                  expected_unknown=v.expected_unknown, expected_frontier=v.expected_frontier, utility=c.utility,
                  utility_dm3=v.utility_dm3, q=v.q, base=int(c.base), candidates=int(c.candidates), valid=int(c.valid),
                  rank_gain=v.expected_gain, details=details, search=c.search if c.search.poses_scored else None,
                  stop=c.stop, stop_reason=c.stop_reason)


def choose_view(strategy, emap, camera, bases, current, sphere_of, settings, seed, region=None,
                last_chance: bool = False, memory: Optional[_core.ChoiceMemory] = None) -> Choice:
    """The next view of `strategy` (see the module) from any of `bases` (chain base poses, or [None] for a
    free camera; the current one first): _core.choose_view, the C++ choice (search, second looks, last chance,
    stop decision) with `settings` (ExploreOptions) and this view's `seed`. `sphere_of(base)` is the reach
    sphere around a base (its radius bounds the camera around every base) or the fixed workspace sphere.
    `memory` (a ChoiceMemory, updated) carries the low views and failed views between choices; without one,
    `last_chance` says whether a low view would end the loop. The search space is the map's (`region` is
    not used: the map holds it)."""
    check_strategy(strategy)
    o = copy.copy(settings)
    o.search.seed = int(seed)
    chain = o.search.chain is not None and bases[current] is not None
    sphere = sphere_of(bases[current]) if sphere_of is not None else None
    reach = 0.0
    if sphere is not None and o.search.workspace_sphere is None:
        if chain and np.allclose(np.asarray(sphere[0], float), np.asarray(bases[current], float)[:3, 3]):
            reach = float(sphere[1])
        else:
            o.search.workspace_sphere = sphere
    if memory is None:
        memory = _core.ChoiceMemory()
        memory.low_views = max(o.patience - 1, 0) if last_chance else 0
    poses = np.array([np.eye(4) if b is None else np.asarray(b, float) for b in bases])
    return _choice_of(_core.choose_view(emap, camera, poses, int(current), o, memory, strategy, reach))
