"""The paper's loop: sense, integrate, frontiers, voids, next best view, move; and its per-view table."""
from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Callable, Optional

import numpy as np

from .. import _core
from .._core import DepthCamera, ExplorationMap, Scene
from ._options import given
from .metrics import observed_share, points_on
from .physics import PhysicalCheck
from .robot import arm_base_pose, arm_reach, explorer_capability_map, explorer_robot
from .scenes import scene_region
from .strategies import CANDIDATES, SEARCH_ONLY_OPTIONS, Choice, check_strategy, choose_view

VIEW_BUDGET = 10  # views of one exploration unless told otherwise (explore, run_demo, the demo's --views)


# The stated stopping threshold of the benchmark (explore's own default is the paper's utility 0): a
# chosen view expecting at most this many void cells (visibility- and seeability-weighted, 2.5 cm cells:
# 10 cells = 0.16 dm^3) is not worth taking. Round 13: 20 until then; paper scene 2's runs ended at 85-97 %
# of the observable interior, 3-4 of 20 seeds under 90 %, with views expecting 10-20 cells still adding
# about a point each (the model under-expects the last views of a box 1.6x); at 10: 20 of 20 seeds at
# 93-97 % after 47-61 views (docs/exploration.md, round 13).
STOP_UTILITY = 10.0
# ... for this many chosen views in a row (the search samples orientations at random: one or two poor
# searches should not end the exploration; the low view is taken, and the next search starts from its
# map). Round 8: 2 ended paper scene 1 at 94 % after 18 views on one of two seeds (3: 99.8 % after 31).
STOP_PATIENCE = 3

# The loop's search breadth for frontier_void (round 8), wider than next_best_view's defaults (the
# paper's N = 50 valid poses from the best 400 cells): in paper scene 2 the views that see into the
# boxes' last corners and into the small box with the low opening are valid and expected to see a lot,
# but their cells rank below the first 50 valid poses, and the loop stopped with 81-84 % seen. About
# 1.3x the search's CPU time (docs/exploration.md, round 8; 150 / 1200 did no better at 1.8x).
LOOP_VALID_POSES = 100
LOOP_CANDIDATE_CELLS = 800

# The loop's ranking of frontier_void views: each void cell also counts with its enclosure^power (NbvOptions::
# enclosure_power; next_best_view's default 0 is the paper's plain count). Voids inside boxes first, the
# shadows behind objects later (docs/exploration.md, round 10). The stopping rule still looks at the plain
# expected void cells.
LOOP_ENCLOSURE_POWER = 2.0

# ... and a void cell with no observed free neighbour counts with this factor (NbvOptions::unexposed_weight;
# next_best_view's default 1 is the paper's count): the faces of voids that observed space shows first,
# the unknown insides of solids later (round 12: paper scene 1's computer tower drew views 2-4 from the crates).
LOOP_UNEXPOSED_WEIGHT = 0.2

# A view not taken because its arm would touch the scene's true geometry (physical_check) is a motion
# that failed: the loop does not choose views within this distance (m) of its camera again, as a robot
# whose motion to a view failed would not try the same view again (else a search on an unchanged map
# picks it again and again until the budget).
FAILED_VIEW_RADIUS = 0.1

STOP_REASONS = ("utility 0", "utility below min_utility", "view budget", "nothing to explore", "no valid view")


@dataclass
class ViewRow:
    """One view of the loop, like a row of the paper's Tables I and II: the view taken, the map after
    it, and the next view chosen from that map with what it is expected to see."""

    view: int
    integration_s: float  # insert + incremental frontiers/voids + void clustering
    search_s: float  # choosing the next view
    void_cells: int  # void cells in the chosen next view (raw: unknown space transparent up to the first occupied cell)
    expected_void: float  # void cells the chosen next view is expected to see (visibility-weighted)
    utility_dm3: float  # the same as a volume
    observed_share: float  # of the scene's initially unknown volume, after this view
    interior_share: float  # of the box interiors, after this view
    points: int
    frontier_cells: int
    void_total: int  # void cells in the map
    void_clusters: int
    pose: list = field(default_factory=list)  # camera pose of this view (4x4 as nested lists)
    # void cells (of this row's map) that the next view's insert turned known; None until it is taken
    void_seen: Optional[int] = None
    base: int = 0  # index of the base the view was taken from (0: base_pose, i: base_moves[i - 1])
    utility: float = 0.0  # the strategy's gain of the chosen next view (what the stopping rule looks at)
    expected_unknown: float = 0.0
    expected_frontier: float = 0.0
    candidates: int = 0  # poses scored for the next view
    valid_candidates: int = 0  # of them valid (reachable, collision-free, safe)
    physically_valid: bool = True  # this view's arm pose is clear of the scene's true geometry (else not taken)
    target_points: int = 0  # points of this view's cloud on the target (explore(target=...))


@dataclass
class ExplorationResult:
    """What explore() returns: the per-view rows, the final map, the camera poses, the wall time, the
    strategy and why the loop stopped (one of STOP_REASONS)."""

    rows: list
    map: ExplorationMap
    poses: list
    total_s: float
    strategy: str = "frontier_void"
    stop_reason: str = ""

    def table(self) -> str:
        """The table as text (paper's columns plus coverage and the seen void cells)."""
        head = f"{'view':>4} {'integr. s':>9} {'search s':>9} {'exp. void':>10} {'seen void':>9} {'utility dm3':>11} " \
               f"{'observed':>8} {'interiors':>9}"
        lines = [head]
        for r in self.rows:
            seen = "-" if r.void_seen is None else str(r.void_seen)
            lines.append(f"{r.view:>4} {r.integration_s:>9.3f} {r.search_s:>9.3f} {r.expected_void:>10.1f} {seen:>9} "
                         f"{r.utility_dm3:>11.2f} {r.observed_share:>8.1%} {r.interior_share:>9.1%}")
        lines.append(f"stopped: {self.stop_reason} ({self.strategy})")
        return "\n".join(lines)

    def to_dicts(self) -> list:
        return [asdict(r) for r in self.rows]

    @property
    def observed_share(self) -> float:
        return self.rows[-1].observed_share if self.rows else 0.0

    @property
    def interior_share(self) -> float:
        return self.rows[-1].interior_share if self.rows else 0.0

    def target_seen_view(self, min_points: int = 5):
        """The first view whose cloud had at least `min_points` points on the target, or None."""
        for r in self.rows:
            if r.target_points >= min_points:
                return r.view
        return None


def _carrier(robot, chain, base_pose):
    """(robot, chain, base_pose) of the arm that carries the camera: `robot=True` is the explorer, another
    robot needs `chain`; a chain without a base pose stands at the origin; robot None when not given."""
    rob = None
    if robot is True or (robot is not None and chain is None):
        rob, chain = explorer_robot() if robot is True else (robot, None)
        if chain is None:
            raise ValueError("pass chain= with a robot other than the explorer")
        base_pose = arm_base_pose(rob, chain, base_pose)
    elif robot is not None:
        rob = robot
    if chain is not None and base_pose is None:
        base_pose = np.eye(4)
    return rob, chain, base_pose


def _bases(chain, base_pose, base_moves) -> list:
    """The chain base poses the search may use: the current one first, then `base_moves`."""
    bases = [np.asarray(base_pose, float)] if chain is not None else [None]
    if base_moves is not None:
        if chain is None:
            raise ValueError("base_moves needs a chain (or robot=True)")
        bases += [np.asarray(b, float) for b in base_moves]
        if any(b.shape != (4, 4) for b in bases):
            raise ValueError("base_moves must be 4x4 poses (chain base -> world)")
    return bases


def _capability(capability_map, chain):
    """`capability_map` itself, or the coarse explorer map for "auto"."""
    if isinstance(capability_map, str):
        if capability_map != "auto" or chain is None:
            raise ValueError(f"capability_map must be a CapabilityMap, None or 'auto' (with a chain), got {capability_map!r}")
        capability_map = explorer_capability_map(chain)
    return capability_map


def _check_loop_args(strategy, max_views, min_utility, candidates, start_pose):
    check_strategy(strategy)
    if not isinstance(max_views, (int, np.integer)) or isinstance(max_views, bool) or max_views < 1:
        raise ValueError(f"max_views must be an integer >= 1, got {max_views!r}")
    if not np.isfinite(min_utility) or min_utility < 0:
        raise ValueError(f"min_utility must be a finite number >= 0, got {min_utility!r}")
    if not isinstance(candidates, (int, np.integer)) or candidates < 1:
        raise ValueError(f"candidates must be an integer >= 1, got {candidates!r}")
    pose = np.asarray(start_pose, float)
    if pose.shape != (4, 4) or not np.all(np.isfinite(pose)):
        raise ValueError(f"start_pose must be a finite 4x4 pose, got shape {pose.shape}")
    return pose


def _row(view, emap, scene, region, stats, clusters, choice, t_int, t_search, pose, base, valid, target,
         pts) -> ViewRow:
    interiors = scene.interiors
    return ViewRow(view=view, integration_s=t_int, search_s=t_search, void_cells=choice.void_cells,
                   expected_void=choice.expected_void,
                   utility_dm3=choice.utility_dm3, observed_share=observed_share(emap, scene, [tuple(region)]),
                   interior_share=observed_share(emap, scene, interiors) if interiors else 0.0,
                   points=int(stats.get("points", 0)), frontier_cells=int(emap.frontier_cell_count),
                   void_total=int(emap.void_cell_count), void_clusters=len(clusters),
                   pose=pose.tolist(), base=base, utility=choice.utility, expected_unknown=choice.expected_unknown,
                   expected_frontier=choice.expected_frontier, candidates=choice.candidates,
                   valid_candidates=choice.valid, physically_valid=valid,
                   target_points=points_on(target, pts) if target is not None and pts is not None else 0)


def away_from(failed, workspace=None, radius: float = FAILED_VIEW_RADIUS) -> Callable:
    """A workspace callable ((N, 3) positions -> (N,) bools) that keeps what `workspace` keeps (all when
    None) farther than `radius` from every position in `failed` (a list the loop appends to)."""
    def keep(P):
        P = np.asarray(P, float).reshape(-1, 3)
        ok = np.ones(len(P), bool) if workspace is None else np.asarray(workspace(P), bool)
        for f in failed:
            ok &= np.sum((P - f) ** 2, axis=1) > radius ** 2
        return ok

    return keep


def _seen(emap, void_before) -> int:
    """How many of the cells at `void_before` (centres) the map now knows."""
    return int(np.count_nonzero(emap.state(void_before) != 0)) if len(void_before) else 0


def explore(scene: Scene, camera: DepthCamera, start_pose, *, chain=None, base_pose=None, robot=None,
            strategy: str = "frontier_void", min_utility: float = 0.0, patience: int = 1,
            candidates: int = CANDIDATES,
            workspace_box=None, workspace_sphere=None, workspace: Optional[Callable] = None,
            max_views: int = VIEW_BUDGET, resolution: Optional[float] = None, max_valid_poses: Optional[int] = None,
            orientations_per_cell: Optional[int] = None, max_candidate_cells: Optional[int] = None,
            min_distance: float = 0.05, score_size=None, void_fit_threshold: Optional[float] = None, seed: int = 0,
            search_space=None, capability_map=None, min_reachability: Optional[float] = None,
            capability_orientations: Optional[bool] = None, base_moves=None, target=None,
            physical_check: bool = True, learn_misses: bool = True, enclosure_power: Optional[float] = None,
            unexposed_weight: Optional[float] = None, second_look: bool = True, ground_is_obstacle: bool = False,
            on_view: Optional[Callable] = None) -> ExplorationResult:
    """Runs the paper's loop from `start_pose` (4x4 camera -> world) and returns the per-view table.

    `strategy` picks the views (strategies.STRATEGIES): "frontier_void" (ours, next_best_view),
    "random" (the first valid of `candidates` random reachable poses), "frontiers" / "unknown" (the
    valid sampled pose with the most expected frontier / unknown cells in view). All use the same robot,
    camera, reach checks, safe-view rule, budget and stopping rule.
    The loop stops (ExplorationResult.stop_reason) when the map has no void after the first view
    ("nothing to explore"), when no valid view is left ("no valid view"), when the chosen view's
    utility (its strategy's gain: expected void cells for frontier_void and random, frontier or
    unknown cells for the others) is 0 ("utility 0", the paper's criterion) or has been <= `min_utility`
    for `patience` chosen views in a row ("utility below min_utility"; the low views are taken), or after
    `max_views` views ("view budget"). STOP_UTILITY and STOP_PATIENCE are the benchmark's stated rule.

    The camera is carried by `chain` (tip = camera frame, +z forward) whose base sits at `base_pose`
    (4x4 chain base -> world), or moves freely inside the workspace (box (2, 3), sphere (centre,
    radius), callable on (N, 3) positions). `robot=True` uses urdf/explorer.urdf standing at the
    origin (or at `base_pose`, the pose of its base_footprint); pass `robot=` with `chain=` for another
    robot. The base does not move unless
    `base_moves` lists other poses of the chain's base (4x4 chain base -> world, like `base_pose`
    with a chain): then each view searches from the current base and from each of them, and the
    robot drives to the base of the best view (ties keep the current base; driving is free).
    Voids are looked for in `search_space` ((2, 3) lo, hi; default scene_region(scene)), and the
    observed share is measured over the same box.
    `capability_map` (a CapabilityMap of `chain`, positions in its base link frame, which sits at
    `base_pose`) prunes candidate cells whose voxel has reachability index <= `min_reachability`;
    with `capability_orientations` it also rules out sampled poses whose (voxel, optical axis) cell
    is unreachable before any IK. IK stays the final check of each pose. `capability_map="auto"` builds a coarse one
    (explorer_capability_map).
    `resolution`, `void_fit_threshold` go to ExplorationMap; `max_valid_poses`, `orientations_per_cell`,
    `max_candidate_cells`, `score_size` ((width, height)), `min_reachability` and `capability_orientations`
    to next_best_view / score_views; None keeps their defaults (but max_valid_poses and max_candidate_cells
    default to the loop's LOOP_VALID_POSES and LOOP_CANDIDATE_CELLS). `enclosure_power` (frontier_void):
    enclosed voids first (NbvOptions.enclosure_power; None: LOOP_ENCLOSURE_POWER, 0: the paper's plain
    count). `unexposed_weight` (frontier_void): void cells with no observed free neighbour count with this
    factor (NbvOptions.unexposed_weight; None: LOOP_UNEXPOSED_WEIGHT, 1: the paper's count).
    `second_look` (frontier_void): on every view, AIMED_POSES poses aimed along lines of sight at void
    cells are scored too and the better view is taken (strategies.aimed_poses; by the ranking gain). A view
    counts as low only when no view on offer expects more than `min_utility` void cells: then the one
    expecting the most is taken, after LOW_AIMED_POSES more aimed poses (any void cell), so the loop stops
    only when none of them finds a view worth taking.
    `ground_is_obstacle` (all strategies, with a chain): the ground below the search space is an obstacle
    for the links the arm moves (NbvOptions.ground_is_obstacle; off until the benchmark's record is run
    with it).
    View k searches with seed `seed + k`.
    `physical_check` (with a robot): a chosen view whose arm touches the scene's true geometry is not
    taken (counted as a view, `physically_valid` False, nothing integrated), and no later view within
    FAILED_VIEW_RADIUS of its camera is chosen. `target` ((2, 3) lo, hi):
    each row counts the points of its cloud on it (metrics.points_on).
    `learn_misses`: before each insert the loop announces the view to the map (next_best_view.expect_view),
    so the void (and unknown) cells that view was expected to see and did not lose seeability; views
    aimed at voids nobody can see stop scoring, and the loop can end (all strategies alike).
    `on_view(row, emap, info)` is called after each view (plots, progress); `info` holds best_pose and
    the chosen view's gains (and next_best_view's result for frontier_void)."""
    pose = _check_loop_args(strategy, max_views, min_utility, candidates, start_pose)
    if not isinstance(patience, (int, np.integer)) or isinstance(patience, bool) or patience < 1:
        raise ValueError(f"patience must be an integer >= 1, got {patience!r}")
    if target is not None:
        points_on(target, np.zeros((0, 3)))  # ValueError for a wrong shape, before any work
    rob, chain, base_pose = _carrier(robot, chain, base_pose)
    auto_sphere = chain is not None and workspace_sphere is None and workspace_box is None and workspace is None
    # a cheap first prune: the arm's reach around its first joint, estimated by sampling FK
    reach = arm_reach(chain, seed) if auto_sphere else 0.0
    bases = _bases(chain, base_pose, base_moves)
    capability_map = _capability(capability_map, chain)
    region = scene_region(scene) if search_space is None else np.asarray(search_space, float)
    emap = ExplorationMap(seed=seed, search_space=region,
                          **given(resolution=resolution, void_fit_threshold=void_fit_threshold))
    width, height = (None, None) if score_size is None else score_size
    # min_distance: 0.05 m rather than next_best_view's 0 on purpose: the loop's camera keeps clear of surfaces
    options = dict(workspace_box=workspace_box, workspace=workspace, chain=chain, capability_map=capability_map,
                   min_distance=min_distance,
                   max_valid_poses=LOOP_VALID_POSES if max_valid_poses is None else max_valid_poses,
                   max_candidate_cells=LOOP_CANDIDATE_CELLS if max_candidate_cells is None else max_candidate_cells,
                   **given(orientations_per_cell=orientations_per_cell, score_width=width, score_height=height,
                           min_reachability=min_reachability, capability_orientations=capability_orientations))
    if ground_is_obstacle:
        options["ground_is_obstacle"] = True
    if strategy == "frontier_void":
        options["enclosure_power"] = LOOP_ENCLOSURE_POWER if enclosure_power is None else enclosure_power
        options["unexposed_weight"] = LOOP_UNEXPOSED_WEIGHT if unexposed_weight is None else unexposed_weight
    else:  # score_views has no search of its own; the baselines rank by their own gains
        for k in SEARCH_ONLY_OPTIONS:
            options.pop(k, None)
    physics = PhysicalCheck(rob, chain, scene, physical_check)

    def sphere_of(bp):
        return (bp[:3, 3].copy(), reach) if auto_sphere else workspace_sphere

    failed = []  # camera positions of the views not taken

    current, q, valid, low = 0, None, True, 0
    rows, poses, stop = [], [], "view budget"
    void_before = np.zeros((0, 3))
    t_all = time.perf_counter()
    for view in range(1, max_views + 1):
        poses.append(pose)
        valid = physics.valid(q, bases[current]) if view > 1 else True
        if not valid:
            failed.append(pose[:3, 3].copy())
            options["workspace"] = away_from(failed, workspace)
        t0 = time.perf_counter()
        pts, stats = None, {}
        if valid:
            pts = camera.capture(scene, pose)
            if learn_misses and emap.void_cell_count:  # the cells this view is expected to see (see expect_view)
                _core.expect_view(emap, camera, pose, **given(score_width=width, score_height=height))
            stats = emap.insert(pts, pose[:3, 3], camera.max_range)
        clusters = emap.void_clusters()
        t_int = time.perf_counter() - t0
        if rows:
            rows[-1].void_seen = _seen(emap, void_before) if valid else None
        if view == 1 and emap.void_cell_count == 0:
            rows.append(_row(view, emap, scene, region, stats, clusters, Choice(pose=None), t_int, 0.0, pose,
                             current, valid, target, pts))
            stop = "nothing to explore"
            if on_view is not None:
                on_view(rows[-1], emap, Choice(pose=None).info())
            break
        void_before = emap.centers(emap.void_keys())
        t0 = time.perf_counter()
        choice = choose_view(strategy, emap, camera, bases, current, sphere_of, options, seed + view, region,
                             candidates, widen_below=min_utility if second_look else None,
                             last_chance=low + 1 >= patience)
        t_search = time.perf_counter() - t0
        rows.append(_row(view, emap, scene, region, stats, clusters, choice, t_int, t_search, pose, current, valid,
                         target, pts))
        if on_view is not None:
            on_view(rows[-1], emap, choice.info())
        if choice.pose is None:
            stop = "no valid view"
            break
        low = low + 1 if choice.utility <= min_utility else 0
        if low >= patience or choice.utility <= 0:
            stop = "utility 0" if choice.utility <= 0 else "utility below min_utility"
            break
        pose, q, current = np.asarray(choice.pose, float), choice.q, choice.base
    return ExplorationResult(rows=rows, map=emap, poses=poses, total_s=time.perf_counter() - t_all,
                             strategy=strategy, stop_reason=stop)
