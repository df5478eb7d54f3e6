"""The paper's loop: sense, integrate, frontiers, voids, next best view, move; and its per-view table."""
from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Callable, Optional

import numpy as np

from .._checks import finite_pose
from .._core import DepthCamera, ExplorationMap, ExploreOptions, Scene
from .explorer import Explorer
from .metrics import observed_share, points_on
from .physics import PhysicalCheck
from .scenes import scene_region
from .strategies import check_strategy, stop_message

# The loop's settings are ExploreOptions (C++; docs/design/next_best_view.md says why each value); these
# names read them for the callers that want one figure.
VIEW_BUDGET = ExploreOptions().max_views  # views of one exploration unless told otherwise
FAILED_VIEW_RADIUS = ExploreOptions().failed_view_radius  # m around the camera of a view not taken
# The stopping rule of every entry point: min_utility None is ExploreOptions.stop_threshold(camera,
# resolution), from the sensor and the cell size; ExploreOptions.paper_stop() is the paper's utility 0.
STOP_UTILITY = ExploreOptions().min_utility
STOP_PATIENCE = ExploreOptions().patience
BEYOND_VOIDS = ExploreOptions().beyond_voids  # frontier-void also looks beyond the voids

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
    beyond: bool = False  # the chosen next view is one beyond the voids (its utility: expected_unknown)
    # unknown cells of the search space that the next view's insert turned known; None until it is taken
    space_seen: Optional[int] = None


@dataclass
class ExplorationResult:
    """What explore() returns: the per-view rows, the final map, the camera poses, the wall time, the
    strategy and why the loop stopped: stop_reason, one of STOP_REASONS; stop_message, the same with the
    search's counts per rejection status for "no valid view" (strategies.stop_message)."""

    rows: list
    map: ExplorationMap
    poses: list
    total_s: float
    strategy: str = "frontier_void"
    stop_reason: str = ""
    stop_message: str = ""

    def table(self) -> str:
        """The table as text (paper's columns plus coverage and the seen void cells)."""
        head = f"{'view':>4} {'integr. s':>9} {'search s':>9} {'exp. void':>10} {'seen void':>9} {'utility dm3':>11} " \
               f"{'observed':>8} {'interiors':>9}"
        lines = [head]
        for r in self.rows:
            seen = "-" if r.void_seen is None else str(r.void_seen)
            lines.append(f"{r.view:>4} {r.integration_s:>9.3f} {r.search_s:>9.3f} {r.expected_void:>10.1f} {seen:>9} "
                         f"{r.utility_dm3:>11.2f} {r.observed_share:>8.1%} {r.interior_share:>9.1%}")
        lines.append(f"stopped: {self.stop_message or self.stop_reason} ({self.strategy})")
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


def _check_args(strategy, start_pose, target) -> np.ndarray:
    """The start pose as a finite 4x4 array; ValueError for a bad strategy, start pose or target."""
    check_strategy(strategy)
    pose = finite_pose(start_pose, "start_pose")
    if target is not None:
        points_on(target, np.zeros((0, 3)))  # ValueError for a wrong shape, before any work
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
                   target_points=points_on(target, pts) if target is not None and pts is not None else 0,
                   beyond=bool(choice.details.get("beyond")))


def _seen(emap, void_before) -> int:
    """How many of the cells at `void_before` (centres) the map now knows."""
    return int(np.count_nonzero(emap.state(void_before) != 0)) if len(void_before) else 0


def explore(scene: Scene, camera: DepthCamera, start_pose, options: Optional[ExploreOptions] = None, *,
            robot=None, chain=None, base_pose=None, base_moves=None, capability_map=None, search_space=None,
            strategy: str = "frontier_void", resolution: Optional[float] = None,
            void_fit_threshold: Optional[float] = None, target=None, on_view: Optional[Callable] = None,
            **settings) -> ExplorationResult:
    """Runs the paper's loop from `start_pose` (4x4 camera -> world) and returns the per-view table.

    `options` (ExploreOptions, default ExploreOptions()) holds the loop's settings: its search (NbvOptions,
    default NbvOptions.exploration_loop(); its seed is the run's, view k searches with seed + k), budget,
    stopping rule, second look and baselines. Each keyword in `settings` sets the ExploreOptions field of
    that name, else the field of its search (`seed`, `max_valid_poses`, `workspace_box`, ...; `candidates`:
    sampled_poses; `score_size`: (width, height) of the score grid); None keeps the default.
    `strategy` picks the views (strategies.STRATEGIES): "frontier_void" (ours, next_best_view) or a
    baseline ("random", "frontiers", "unknown"); all use the same robot, camera, checks and stopping rule.
    The loop stops (ExplorationResult.stop_reason, one of STOP_REASONS) when the map has no void cell, when no
    valid view is left, when the chosen view's utility (its strategy's gain) is 0 or has been <= min_utility
    for `patience` views in a row (the low views are taken), or after max_views views. By default it stops
    by itself: min_utility None is ExploreOptions.stop_threshold (score rays x cell / sensor range expected
    void cells) for 3 views; min_utility=0, patience=1 (ExploreOptions.paper_stop()) is the paper's rule.
    The camera is carried by `chain` (tip = camera frame, +z forward; a Chain, or with `robot` a (base link, camera
    link) pair or the camera link's name) whose base sits at `base_pose`
    (4x4 chain base -> world), or moves freely inside the search's workspace. `robot=True` uses
    urdf/explorer.urdf (standing at `base_pose`, the pose of its base_footprint); pass `robot=` with
    `chain=` for another robot. `base_moves` (4x4 chain base poses): each view also searches from them and
    the robot drives to the base of the best view (ties keep the current base).
    Voids are looked for in `search_space` ((2, 3) lo, hi; default scene_region(scene)), where the observed
    share is measured too. `capability_map` (a CapabilityMap of `chain`, or "auto": explorer_capability_map)
    prunes the search's cells and poses. `resolution`, `void_fit_threshold` go to ExplorationMap.
    `target` ((2, 3) lo, hi): each row counts the points of its cloud on it (metrics.points_on).
    `on_view(row, emap, info)` is called after each view; `info` holds best_pose and the chosen view's
    gains (and next_best_view's fields for frontier_void)."""
    pose = _check_args(strategy, start_pose, target)
    region = scene_region(scene) if search_space is None else np.asarray(search_space, float)
    explorer = Explorer(camera, region, options, robot=robot, chain=chain, base_pose=base_pose,
                        base_moves=base_moves, capability_map=capability_map, strategy=strategy,
                        resolution=resolution, void_fit_threshold=void_fit_threshold, **settings)
    physics = PhysicalCheck(explorer.robot, explorer.chain, scene, explorer.options.physical_check,
                            explorer.options.search.reference)
    return _Loop(scene, camera, explorer, region, physics, target, on_view).run(pose)


class _Loop:
    """One run of explore(): the simulator around an Explorer (capture, physical check, the per-view table)."""

    def __init__(self, scene, camera, explorer, region, physics, target, on_view):
        self.scene, self.camera, self.explorer, self.region = scene, camera, explorer, region
        self.emap, self.physics, self.target, self.on_view = explorer.map, physics, target, on_view

    def run(self, pose) -> ExplorationResult:
        ex, emap = self.explorer, self.emap
        current, q = 0, None
        rows, poses, stop, message = [], [], "view budget", ""
        void_before = np.zeros((0, 3))
        t_all = time.perf_counter()
        while True:
            poses.append(pose)
            view = len(poses)
            valid = self.physics.valid(q, ex.bases[current]) if view > 1 else True
            t0 = time.perf_counter()
            pts, stats = self._sense(pose, valid)
            clusters = emap.void_clusters()
            t_int = time.perf_counter() - t0
            if rows:
                rows[-1].void_seen = _seen(emap, void_before) if valid else None
                rows[-1].space_seen = int(stats.get("space_known", 0)) if valid else None
            void_before = emap.centers(emap.void_keys())
            t0 = time.perf_counter()
            nv = ex.next_view()
            choice = ex.choice(nv)
            rows.append(_row(view, emap, self.scene, self.region, stats, clusters, choice, t_int,
                             time.perf_counter() - t0, pose, current, valid, self.target, pts))
            if self.on_view is not None:
                self.on_view(rows[-1], emap, choice.info())
            if nv.stop:
                stop, message = nv.stop_reason, stop_message(nv)
                break
            pose, q, current = np.asarray(nv.camera_pose, float), nv.q, nv.base
        return ExplorationResult(rows=rows, map=emap, poses=poses, total_s=time.perf_counter() - t_all,
                                 strategy=ex.strategy, stop_reason=stop, stop_message=message)

    def _sense(self, pose, valid):
        """The cloud of a view taken and its insert's statistics (the Explorer announces it first); a view not
        taken (its arm touches the scene) integrates nothing and keeps later views away from its camera."""
        if not valid:
            self.explorer.view_failed()
            return None, {}
        pts = self.camera.capture(self.scene, pose)
        return pts, self.explorer.integrate(pts, pose)
