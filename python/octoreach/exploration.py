"""Frontier-void exploration (Dornhege & Kleiner, SSRR 2011): scenes, the explore loop, plots, demo.

The compiled core does the work (``ExplorationMap``, ``DepthCamera``, ``next_best_view``); this
module strings it together as the paper's loop: sense, integrate, frontiers, voids, next best view,
move, until the best view's utility is 0 or the view budget runs out.

Poses are 4x4 numpy arrays (camera -> world). The camera looks along its +z axis (+x right,
+y down in the image). Units: metres, radians.

Demo: ``python -m octoreach.exploration --scene 2 --out exploration_out`` writes the table
(``table.txt``, ``table.json``), one PNG per view and the final map as ``map.bt`` (octovis).
"""
from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from . import _core
from ._core import DepthCamera, ExplorationMap, Scene, next_best_view

__all__ = [
    "ExplorationResult",
    "ViewRow",
    "closed_box_scene",
    "cluttered_scene",
    "explore",
    "base_ring",
    "explorer_capability_map",
    "explorer_robot",
    "look_at",
    "observed_share",
    "paper_scene",
    "plot_map",
    "scene_region",
]


def look_at(eye, target, roll: float = 0.0) -> np.ndarray:
    """Camera pose (4x4 camera -> world) at `eye` looking at `target`, image +y pointing down."""
    return _core.look_at(np.asarray(eye, float), np.asarray(target, float), float(roll))


# ----------------------------------------------------------------------------------- scenes


def _floor(s: Scene, half: float = 2.0) -> None:
    s.add_box((-half, -half, -0.05), (half, half, 0.0))


def paper_scene(which: int = 1) -> Scene:
    """The paper's settings, from its figures: 1 = a computer, two open-topped crates and two-by-fours;
    2 = two larger closed boxes and smaller boxes with small openings. Objects stand 0.5-1.3 m in
    front (+x) of a robot at the origin."""
    s = Scene()
    _floor(s)
    if which == 1:
        s.add_box((0.95, -0.15, 0.0), (1.15, 0.15, 0.45))  # computer tower
        s.add_crate((0.55, -0.6, 0.0), (0.9, -0.25, 0.3), 0.02)
        s.add_crate((0.55, 0.25, 0.0), (0.95, 0.6, 0.25), 0.02)
        s.add_board((0.45, -0.1, 0.0), (0.85, -0.05, 0.1))  # two-by-fours lying on the floor
        s.add_board((0.45, 0.05, 0.0), (0.85, 0.1, 0.1))
    elif which == 2:
        s.add_closed_box((0.7, -0.7, 0.0), (1.1, -0.25, 0.4), 0.02, "-x", 0.12, 0.12)
        s.add_closed_box((0.7, 0.25, 0.0), (1.15, 0.7, 0.4), 0.02, "+z", 0.14, 0.14)
        s.add_closed_box((0.5, -0.12, 0.0), (0.75, 0.12, 0.25), 0.02, "-x", 0.08, 0.08)
        s.add_closed_box((1.0, -0.15, 0.0), (1.25, 0.15, 0.2), 0.02, "+z", 0.1, 0.1)
    else:
        raise ValueError(f"paper scene must be 1 or 2, got {which!r}")
    return s


def closed_box_scene(face: str = "-x", opening: float = 0.12) -> Scene:
    """One closed box (0.4 m cube) with one square opening in `face`, 0.6-1.0 m in front of the origin."""
    s = Scene()
    _floor(s)
    s.add_closed_box((0.6, -0.2, 0.0), (1.0, 0.2, 0.4), 0.02, face, opening, opening)
    return s


def cluttered_scene() -> Scene:
    """A room corner with twelve crates and closed boxes (benchmark scene)."""
    s = Scene()
    _floor(s, 3.0)
    s.add_box((-3, 3, 0), (3, 3.05, 2.0))
    s.add_box((3, -3, 0), (3.05, 3, 2.0))
    for i in range(4):
        for j in range(3):
            x, y = 0.5 + 0.6 * i, -1.2 + 0.8 * j
            if (i + j) % 2:
                s.add_crate((x, y, 0), (x + 0.4, y + 0.4, 0.3), 0.02)
            else:
                s.add_closed_box((x, y, 0), (x + 0.45, y + 0.4, 0.35), 0.02, "-x", 0.12, 0.1)
    s.add_board((0.3, 1.2, 0.0), (1.5, 1.25, 0.5))
    return s


def scene_region(scene: Scene, margin: float = 0.05) -> np.ndarray:
    """The search space S (2, 3) (lo, hi rows): the bounds of the scene's objects (boxes no wider
    than 2 m, so floors and walls are left out), grown by `margin`, from the floor (z = 0) up."""
    objs = [(np.asarray(lo), np.asarray(hi)) for lo, hi in scene.boxes
            if np.max((np.asarray(hi) - np.asarray(lo))[:2]) < 2.0]
    if not objs:
        lo, hi = scene.bounds()
        return np.array([lo, hi], float)
    lo = np.min([o[0] for o in objs], axis=0) - margin
    hi = np.max([o[1] for o in objs], axis=0) + margin
    lo[2] = 0.0
    return np.array([lo, hi])


def explorer_robot():
    """The project's explorer (mobile base + 5-DOF arm + camera, urdf/explorer.urdf) and its camera chain."""
    from . import robots
    from ._core import Robot

    robot = Robot.from_urdf(str(robots.project_urdf("explorer")))
    return robot, robot.chain("arm_base_link", "camera_optical_frame")


def base_ring(region, standoff: float = 0.45) -> list:
    """Four base_footprint poses (4x4, world) around a search region ((2, 3) lo, hi), each
    `standoff` metres outside one of its vertical faces and facing the region's centre."""
    lo, hi = np.asarray(region, float)
    c = (lo + hi) / 2
    out = []
    for x, y in ((lo[0] - standoff, c[1]), (c[0], lo[1] - standoff), (c[0], hi[1] + standoff), (hi[0] + standoff, c[1])):
        yaw = np.arctan2(c[1] - y, c[0] - x)
        T = np.eye(4)
        T[:2, :2] = [[np.cos(yaw), -np.sin(yaw)], [np.sin(yaw), np.cos(yaw)]]
        T[:2, 3] = (x, y)
        out.append(T)
    return out


def explorer_capability_map(chain, resolution: float = 0.1, directions: int = 100, seed: int = 0):
    """A coarse capability map of `chain` (camera +z as the approach axis; positions in the chain's
    base link frame) for pruning next-best-view cells and poses: about 5-10 s on two cores."""
    from ._core import CapabilityMap

    return CapabilityMap.build(chain, resolution=resolution, directions=directions, approach_axis=(0.0, 0.0, 1.0),
                               seed=seed, progress=False)


# ---------------------------------------------------------------------------------- metrics


def _grid(lo, hi, res):
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


# ------------------------------------------------------------------------------ exploration


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


@dataclass
class ExplorationResult:
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


def explore(scene: Scene, camera: DepthCamera, start_pose, *, chain=None, base_pose=None, robot=None,
            workspace_box=None, workspace_sphere=None, workspace: Optional[Callable] = None,
            max_views: int = 10, resolution: float = 0.025, max_valid_poses: int = 50,
            orientations_per_cell: int = 8, max_candidate_cells: int = 400, min_distance: float = 0.05,
            score_size=(48, 36), void_fit_threshold: float = 0.6, seed: int = 0, search_space=None,
            capability_map=None, min_reachability: float = 0.0, capability_orientations: bool = True,
            base_moves=None,
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
    Stops when the best view expects 0 void cells or after `max_views` views.
    `on_view(row, emap, nbv)` is called after each view (plots, progress)."""
    if robot is True or (robot is not None and chain is None):
        rob, chain = explorer_robot() if robot is True else (robot, None)
        if chain is None:
            raise ValueError("pass chain= with a robot other than the explorer")
        footprint = np.eye(4) if base_pose is None else np.asarray(base_pose, float)
        base_pose = footprint @ rob.link_poses(rob.home())[chain.base_link]
    if chain is not None and base_pose is None:
        base_pose = np.eye(4)
    auto_sphere = chain is not None and workspace_sphere is None and workspace_box is None and workspace is None
    reach = 0.0
    if auto_sphere:
        # a cheap first prune: the arm's reach around its first joint, estimated by sampling FK
        rng = np.random.default_rng(seed)
        lo = np.where(np.isfinite(chain.lower), chain.lower, -np.pi)
        hi = np.where(np.isfinite(chain.upper), chain.upper, np.pi)
        Q = rng.uniform(lo, hi, size=(2000, chain.dof))
        tips = chain.fk_batch(Q)[:, :3, 3]
        centre = np.zeros(3)  # the chain's base frame origin
        reach = float(np.max(np.linalg.norm(tips - centre, axis=1)))
    bases = [np.asarray(base_pose, float)] if chain is not None else [None]
    if base_moves is not None:
        if chain is None:
            raise ValueError("base_moves needs a chain (or robot=True)")
        bases += [np.asarray(b, float) for b in base_moves]
        if any(b.shape != (4, 4) for b in bases):
            raise ValueError("base_moves must be 4x4 poses (chain base -> world)")
    current = 0
    if isinstance(capability_map, str):
        if capability_map != "auto" or chain is None:
            raise ValueError(f"capability_map must be a CapabilityMap, None or 'auto' (with a chain), got {capability_map!r}")
        capability_map = explorer_capability_map(chain)
    region = scene_region(scene) if search_space is None else np.asarray(search_space, float)
    emap = ExplorationMap(resolution=resolution, void_fit_threshold=void_fit_threshold, seed=seed,
                          search_space=region)
    interiors = scene.interiors
    pose = np.asarray(start_pose, float)
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
        nbv = None
        for i in [current] + [j for j in range(len(bases)) if j != current]:
            bp = bases[i]
            sphere = ((bp[:3, 3]).copy(), reach) if auto_sphere else workspace_sphere
            r = next_best_view(emap, camera, max_valid_poses=max_valid_poses,
                               orientations_per_cell=orientations_per_cell,
                               max_candidate_cells=max_candidate_cells, score_width=score_size[0],
                               score_height=score_size[1], min_distance=min_distance, seed=seed + view,
                               workspace_box=workspace_box, workspace_sphere=sphere,
                               workspace=workspace, chain=chain, chain_base=bp,
                               capability_map=capability_map,
                               capability_base=None if capability_map is None else bp,
                               min_reachability=min_reachability,
                               capability_orientations=capability_orientations)
            if nbv is None or r["void_cells"] > nbv["void_cells"]:
                nbv, best_base = r, i
        t_search = time.perf_counter() - t0
        row = ViewRow(view=view, integration_s=t_int, search_s=t_search, void_cells=int(nbv["void_cells"]),
                      utility_dm3=float(nbv["utility_dm3"]), observed_share=observed_share(emap, scene, [tuple(region)]),
                      interior_share=observed_share(emap, scene, interiors) if interiors else 0.0,
                      points=int(stats["points"]), frontier_cells=int(emap.frontier_cell_count),
                      void_total=int(emap.void_cell_count), void_clusters=len(clusters),
                      pose=pose.tolist(), base=current, void_seen=int(stats["void_removed"]))
        rows.append(row)
        if on_view is not None:
            on_view(row, emap, nbv)
        if nbv["best_pose"] is None or nbv["void_cells"] == 0:
            break
        pose = nbv["best_pose"]
        current = best_base
    return ExplorationResult(rows=rows, map=emap, poses=poses, total_s=time.perf_counter() - t_all)


# ------------------------------------------------------------------------------------ plots


def _ellipsoid_wire(ax, cluster, color="purple"):
    u = np.linspace(0, 2 * np.pi, 16)
    v = np.linspace(0, np.pi, 9)
    sphere = np.stack([np.outer(np.cos(u), np.sin(v)), np.outer(np.sin(u), np.sin(v)),
                       np.outer(np.ones_like(u), np.cos(v))], -1)
    pts = sphere @ (np.asarray(cluster.axes) * np.asarray(cluster.semi_axes)).T + np.asarray(cluster.centroid)
    ax.plot_wireframe(pts[..., 0], pts[..., 1], pts[..., 2], color=color, linewidth=0.4, alpha=0.6)


def plot_map(emap: ExplorationMap, path, poses=(), next_pose=None, title: str = "",
             max_points: int = 20000, ellipsoids: int = 8) -> Path:
    """PNG of the map: occupied cells grey, frontiers red, voids violet, the largest void
    ellipsoids, the views so far (blue arrows) and the next view (green arrow)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rng = np.random.default_rng(0)

    def sub(p):
        return p[rng.choice(len(p), max_points, replace=False)] if len(p) > max_points else p

    fig = plt.figure(figsize=(8, 7))
    ax = fig.add_subplot(111, projection="3d")
    occ = sub(emap.cells("occupied"))
    fr = sub(emap.cells("frontier"))
    vo = sub(emap.cells("void"))
    if len(occ):
        ax.scatter(occ[:, 0], occ[:, 1], occ[:, 2], s=0.5, c="0.55", alpha=0.3, label="occupied")
    if len(fr):
        ax.scatter(fr[:, 0], fr[:, 1], fr[:, 2], s=1.0, c="red", alpha=0.6, label="frontier")
    if len(vo):
        ax.scatter(vo[:, 0], vo[:, 1], vo[:, 2], s=1.0, c="darkviolet", alpha=0.5, label="void")
    clusters = sorted(emap.void_clusters(), key=lambda c: -c.size)[:ellipsoids]
    for c in clusters:
        _ellipsoid_wire(ax, c)
    for i, T in enumerate(poses):
        T = np.asarray(T)
        p, d = T[:3, 3], T[:3, 2] * 0.25
        ax.quiver(p[0], p[1], p[2], d[0], d[1], d[2], color="blue")
        ax.text(p[0], p[1], p[2], str(i + 1), color="blue", fontsize=8)
    if next_pose is not None:
        T = np.asarray(next_pose)
        p, d = T[:3, 3], T[:3, 2] * 0.3
        ax.quiver(p[0], p[1], p[2], d[0], d[1], d[2], color="green", linewidth=2)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    allp = [a for a in (occ, fr, vo) if len(a)]
    if allp:
        allp = np.concatenate(allp)
        c = (allp.min(0) + allp.max(0)) / 2
        r = float((allp.max(0) - allp.min(0)).max()) / 2 + 0.05
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(max(c[2] - r, -0.1), c[2] + r)
    ax.view_init(elev=35, azim=-140)
    ax.legend(loc="upper left", markerscale=6)
    ax.set_title(title)
    path = Path(path)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


# ------------------------------------------------------------------------------------- demo


def run_demo(scene_id: int = 2, out="exploration_out", max_views: int = 10, resolution: float = 0.025,
             width: int = 640, height: int = 480, seed: int = 0, plots: bool = True, quiet: bool = False,
             export: bool = True, capability_map="auto", move_base: bool = False):
    """One exploration of a paper scene with the explorer robot; writes table.txt, table.json,
    view_NN.png and map.bt into `out`. `capability_map`: a CapabilityMap of the arm, "auto" (build a
    coarse one) or None (IK only). `move_base`: the base may also drive to the four poses of
    base_ring(scene_region(scene)) between views. Returns the ExplorationResult."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    scene = paper_scene(scene_id)
    camera = DepthCamera(width, height, np.deg2rad(58.0), 4.0, noise=0.0, seed=seed)
    robot, chain = explorer_robot()
    base_link = robot.link_poses(robot.home())[chain.base_link]
    start = look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    poses_so_far = []

    def on_view(row, emap, nbv):
        poses_so_far.append(np.array(row.pose))
        if not quiet:
            print(f"view {row.view}: integration {row.integration_s:.3f} s, search {row.search_s:.3f} s, "
                  f"next view expects {row.void_cells} void cells ({row.utility_dm3:.2f} dm^3), "
                  f"observed {row.observed_share:.1%}, interiors {row.interior_share:.1%}", flush=True)
        if plots:
            plot_map(emap, out / f"view_{row.view:02d}.png", poses=poses_so_far, next_pose=nbv["best_pose"],
                     title=f"scene {scene_id}, after view {row.view}: {row.void_total} void cells")

    if isinstance(capability_map, str) and capability_map == "auto":
        capability_map = explorer_capability_map(chain, seed=seed)
    moves = [F @ base_link for F in base_ring(scene_region(scene))] if move_base else None
    result = explore(scene, camera, start, chain=chain, base_pose=base_link, max_views=max_views,
                     resolution=resolution, seed=seed, capability_map=capability_map, base_moves=moves,
                     on_view=on_view)
    (out / "table.txt").write_text(result.table() + "\n")
    (out / "table.json").write_text(json.dumps({"scene": scene_id, "resolution": resolution,
                                                "total_s": result.total_s, "rows": result.to_dicts()},
                                               indent=1))
    if export:
        result.map.write_bt(str(out / "map.bt"))  # OctoMap prints a progress line to stdout
    if not quiet:
        print(result.table())
        print(f"whole exploration {result.total_s:.1f} s; wrote {out}/table.txt, table.json, "
              f"view_*.png, map.bt (open with octovis)")
    return result


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="Frontier-void exploration demo (Dornhege & Kleiner)")
    ap.add_argument("--scene", type=int, default=2, choices=(1, 2), help="paper experiment 1 or 2")
    ap.add_argument("--out", default="exploration_out", help="output folder")
    ap.add_argument("--views", type=int, default=10, help="view budget")
    ap.add_argument("--resolution", type=float, default=0.025)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--no-capability-map", action="store_true", help="prune view cells by IK only")
    ap.add_argument("--move-base", action="store_true", help="let the base drive to 4 poses around the scene")
    a = ap.parse_args(argv)
    run_demo(a.scene, a.out, a.views, a.resolution, seed=a.seed, plots=not a.no_plots,
             capability_map=None if a.no_capability_map else "auto", move_base=a.move_base)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
