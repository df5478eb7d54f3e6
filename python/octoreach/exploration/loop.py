"""The paper's loop: sense, integrate, frontiers, voids, next best view, move; and its per-view table."""
from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Callable, Optional

import numpy as np

from .._core import DepthCamera, ExplorationMap, Scene, next_best_view
from ._options import given
from .metrics import observed_share
from .robot import arm_base_pose, arm_reach, explorer_capability_map, explorer_robot
from .scenes import scene_region

VIEW_BUDGET = 10  # views of one exploration unless told otherwise (explore, run_demo, the demo's --views)


@dataclass
class ViewRow:
    """One view of the loop, like a row of the paper's Tables I and II."""

    view: int
    integration_s: float  # insert + incremental frontiers/voids + void clustering
    search_s: float  # next-best-view search
    void_cells: int  # expected void cells seen from the chosen next view
    utility_dm3: float  # the same as a volume
    observed_share: float  # of the scene's initially unknown volume, after this view
    interior_share: float  # of the box interiors, after this view
    points: int
    frontier_cells: int
    void_total: int  # void cells in the map
    void_clusters: int
    pose: list = field(default_factory=list)  # camera pose of this view (4x4 as nested lists)
    void_seen: int = 0  # void cells this view's insert turned known (compare with the previous row's void_cells)
    base: int = 0  # index of the base the view was taken from (0: base_pose, i: base_moves[i - 1])
    expected_void: float = 0.0  # void cells the chosen next view is expected to see (visibility-weighted)


@dataclass
class ExplorationResult:
    """What explore() returns: the per-view rows, the final map, the camera poses and the wall time."""

    rows: list
    map: ExplorationMap
    poses: list
    total_s: float

    def table(self) -> str:
        """The table as text (paper's columns plus coverage)."""
        head = f"{'view':>4} {'integr. s':>9} {'search s':>9} {'void cells':>10} {'utility dm3':>11} " \
               f"{'observed':>8} {'interiors':>9}"
        lines = [head]
        for r in self.rows:
            lines.append(f"{r.view:>4} {r.integration_s:>9.3f} {r.search_s:>9.3f} {r.void_cells:>10d} "
                         f"{r.utility_dm3:>11.2f} {r.observed_share:>8.1%} {r.interior_share:>9.1%}")
        return "\n".join(lines)

    def to_dicts(self) -> list:
        return [asdict(r) for r in self.rows]

    @property
    def observed_share(self) -> float:
        return self.rows[-1].observed_share if self.rows else 0.0

    @property
    def interior_share(self) -> float:
        return self.rows[-1].interior_share if self.rows else 0.0


def _carrier(robot, chain, base_pose):
    """(chain, base_pose) of the arm that carries the camera: `robot=True` is the explorer, another
    robot needs `chain`; a chain without a base pose stands at the origin."""
    if robot is True or (robot is not None and chain is None):
        rob, chain = explorer_robot() if robot is True else (robot, None)
        if chain is None:
            raise ValueError("pass chain= with a robot other than the explorer")
        base_pose = arm_base_pose(rob, chain, base_pose)
    if chain is not None and base_pose is None:
        base_pose = np.eye(4)
    return chain, base_pose


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


def _best_view(emap, camera, bases, current, sphere_of, options, seed):
    """The next best view over all bases (the current one first, so ties keep it): (result, base index)."""
    nbv = best_base = None
    for i in [current] + [j for j in range(len(bases)) if j != current]:
        bp = bases[i]
        capability_base = None if options.get("capability_map") is None else bp
        r = next_best_view(emap, camera, seed=seed, workspace_sphere=sphere_of(bp), chain_base=bp,
                           capability_base=capability_base, **options)
        if nbv is None or r["expected_gain"] > nbv["expected_gain"]:
            nbv, best_base = r, i
    return nbv, best_base


def _row(view, emap, scene, region, stats, clusters, nbv, t_int, t_search, pose, base) -> ViewRow:
    interiors = scene.interiors
    return ViewRow(view=view, integration_s=t_int, search_s=t_search, void_cells=int(nbv["void_cells"]),
                   utility_dm3=float(nbv["utility_dm3"]), observed_share=observed_share(emap, scene, [tuple(region)]),
                   interior_share=observed_share(emap, scene, interiors) if interiors else 0.0,
                   points=int(stats["points"]), frontier_cells=int(emap.frontier_cell_count),
                   void_total=int(emap.void_cell_count), void_clusters=len(clusters),
                   pose=pose.tolist(), base=base, void_seen=int(stats["void_removed"]),
                   expected_void=float(nbv["expected_void"]))


def explore(scene: Scene, camera: DepthCamera, start_pose, *, chain=None, base_pose=None, robot=None,
            workspace_box=None, workspace_sphere=None, workspace: Optional[Callable] = None,
            max_views: int = VIEW_BUDGET, resolution: Optional[float] = None, max_valid_poses: Optional[int] = None,
            orientations_per_cell: Optional[int] = None, max_candidate_cells: Optional[int] = None,
            min_distance: float = 0.05, score_size=None, void_fit_threshold: Optional[float] = None, seed: int = 0,
            search_space=None, capability_map=None, min_reachability: Optional[float] = None,
            capability_orientations: Optional[bool] = None, base_moves=None,
            on_view: Optional[Callable] = None) -> ExplorationResult:
    """Runs the paper's loop from `start_pose` (4x4 camera -> world) and returns the per-view table.

    The camera is carried by `chain` (tip = camera frame, +z forward) whose base sits at `base_pose`
    (4x4 chain base -> world), or moves freely inside the workspace (box (2, 3), sphere (centre,
    radius), callable on (N, 3) positions). `robot=True` uses urdf/explorer.urdf standing at the
    origin (or at `base_pose`, the pose of its base_footprint). The base does not move unless
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
    to next_best_view; None keeps their defaults. View k searches with seed `seed + k`.
    Stops when the best view expects 0 void cells or after `max_views` views.
    `on_view(row, emap, nbv)` is called after each view (plots, progress)."""
    chain, base_pose = _carrier(robot, chain, base_pose)
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
                   **given(max_valid_poses=max_valid_poses, orientations_per_cell=orientations_per_cell,
                           max_candidate_cells=max_candidate_cells, score_width=width, score_height=height,
                           min_reachability=min_reachability, capability_orientations=capability_orientations))

    def sphere_of(bp):
        return (bp[:3, 3].copy(), reach) if auto_sphere else workspace_sphere

    pose = np.asarray(start_pose, float)
    current = 0
    rows, poses = [], []
    t_all = time.perf_counter()
    for view in range(1, max_views + 1):
        poses.append(pose)
        pts = camera.capture(scene, pose)
        t0 = time.perf_counter()
        stats = emap.insert(pts, pose[:3, 3], camera.max_range)
        clusters = emap.void_clusters()
        t_int = time.perf_counter() - t0
        t0 = time.perf_counter()
        nbv, best_base = _best_view(emap, camera, bases, current, sphere_of, options, seed + view)
        t_search = time.perf_counter() - t0
        row = _row(view, emap, scene, region, stats, clusters, nbv, t_int, t_search, pose, current)
        rows.append(row)
        if on_view is not None:
            on_view(row, emap, nbv)
        if nbv["best_pose"] is None or nbv["void_cells"] == 0:
            break
        pose = nbv["best_pose"]
        current = best_base
    return ExplorationResult(rows=rows, map=emap, poses=poses, total_s=time.perf_counter() - t_all)
