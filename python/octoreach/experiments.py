"""Paper experiments in kinematic simulation, written as examples a planner author can copy.

``tidy_up`` is the task of Section V of "Identifying Good Poses When Doing Your Household Chores" (Hertle &
Nebel): objects lie on one or two tables and the PR2 must reach every one of them with
either arm. Two ways to choose where the robot stands are compared:

* **A, predefined poses**: 1-4 hand-placed base poses per table (the middle of each long side,
  facing the table, then the two ends), visited in order;
* **B, sampling**: poses drawn on demand from the table's surface map (the *grounding attachment*,
  ``PoseSampler``, eq. 3 discounting against the poses already drawn), accepted by the
  *condition attachment* (``SurfaceMap.reachability(pose) > 0``), until every object is reached
  or a budget of poses runs out.

"Reaching" an object is checked like a planner's cost attachment would: inverse kinematics of the
arm for a top grasp (approach directions of the upper hemisphere) 5 cm above the table, free of
self-collision and with no arm link touching the table. The three building blocks are small
functions so that they can be lifted into a planner::

    condition(smap, pose)            -> bool     # is this base pose worth standing at?
    ground(sampler)                  -> (4,)     # propose a new base pose
    reachable(robot, arm, pose, obj) -> bool     # can `arm` grasp `obj` from `pose`?

``exploration_tables`` prints the per-view tables of the frontier-void exploration paper
(Dornhege & Kleiner) for its two scenes by running ``octoreach.exploration.run_demo``.

Simplifications (this is a kinematic simulation, not the paper's Gazebo runs): no navigation,
perception or execution failures; the robot knows where the objects are; time is the wall time
of pose selection plus IK checks (maps are built once, offline); tables stand far enough apart
(3 m) that each pose is checked against the table it serves only.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from . import arms as _arms
from . import robots as _robots
from ._core import OrientationSet, PoseSampler, Robot, Surface, SurfaceMap, grasp_orientations, link_roles
from ._core import base_pose as _base_pose

__all__ = ["World", "build_world", "condition", "ground", "reachable", "predefined_poses", "place_objects",
           "tidy_up", "format_tidy_up", "exploration_tables"]

ARMS = ("right_arm", "left_arm")
TABLE_SIZE = (1.4, 0.65, 0.72)  # the paper's table: 1.4 x 0.65 m, 0.72 m high
TABLE_POSES = ((0.0, 0.0, 0.0), (0.0, 3.0, np.pi / 2))  # (x, y, yaw) of table 1 and table 2
OBJECT_HEIGHT = 0.05  # grasp point above the table top (the tool holds an object standing on it)
EDGE_MARGIN = 0.05  # objects are placed at least this far from a table edge
STANDOFF = 0.5  # predefined poses: base centre this far from the table edge


def base_transform(pose) -> np.ndarray:
    """4x4 pose of the robot's root link (base_footprint) from (x, y, z, theta)."""
    return _base_pose(np.asarray(pose, float))


# ------------------------------------------------------------------------------------ the world


@dataclass
class Table:
    """One table: its surface, collision objects and the combined (either arm) surface map."""

    surface: Surface
    pose: tuple  # (x, y, yaw) of its centre
    obstacles: object
    smap: SurfaceMap


@dataclass
class World:
    """Everything built once and reused by every trial: robot, per-arm IK data, tables with maps."""

    robot: Robot
    tables: list
    resolution: float
    arm_data: dict = field(default_factory=dict)


@dataclass
class _Arm:
    chain: object
    axis: np.ndarray
    reference: np.ndarray
    root_to_armbase: np.ndarray  # arm base link in the root frame (reference posture)
    arm_links: list
    body_links: list
    grasps: np.ndarray  # (G, 3, 3) tool orientations of top grasps, in the world frame


def _arm_data(robot: Robot, arm: str, orientations: OrientationSet) -> _Arm:
    base, tip, axis = _arms.resolve(robot, arm)
    chain = robot.chain(base, tip)
    reference = _arms.default_reference(robot, arm)
    roles = link_roles(robot, chain)
    ids = grasp_orientations(orientations, orientations.subset("upper_hemisphere"))
    grasps = np.array([orientations.rotation(i, axis) for i in ids])
    return _Arm(chain=chain, axis=axis, reference=reference,
                root_to_armbase=robot.link_poses(reference)[base], arm_links=roles["arm"],
                body_links=roles["body"], grasps=grasps)


def build_world(tables: int = 1, resolution: float = 0.1, directions: int = 100, robot: Robot = None,
                seed: int = 0) -> World:
    """The PR2, capability maps of both arms and one combined ('max': either arm) surface map per table.

    This is the offline part (a few seconds at 0.1 m and 100 directions); trials only query it."""
    if tables not in (1, 2):
        raise ValueError(f"tables must be 1 or 2, got {tables!r}")
    robot = _robots.pr2() if robot is None else robot
    caps = {arm: _arms.capability_map(robot, arm, resolution=resolution, directions=directions, seed=seed,
                                      progress=False) for arm in ARMS}
    world = World(robot=robot, tables=[], resolution=resolution,
                  arm_data={arm: _arm_data(robot, arm, caps[arm].orientations) for arm in ARMS})
    sx, sy, h = TABLE_SIZE
    for x, y, yaw in TABLE_POSES[:tables]:
        surface = Surface.rectangle(sx, sy, h, x, y, yaw)
        surface.add_legs()
        maps = [SurfaceMap.build(robot, caps[arm], surface, resolution=resolution, z_range=(0, 0),
                                 grasp_height=OBJECT_HEIGHT, progress=False) for arm in ARMS]
        world.tables.append(Table(surface=surface, pose=(x, y, yaw), obstacles=surface.obstacles(),
                                  smap=SurfaceMap.combine(maps, "max")))
    return world


# ----------------------------------------------------------------- the three planner building blocks


def condition(smap: SurfaceMap, pose) -> bool:
    """Condition attachment: may the robot work at the surface from base pose (x, y, z, theta)?
    True when the surface map's R_S of the pose is above 0 (one O(log n) lookup)."""
    return bool(smap.reachability(np.asarray(pose, float).reshape(1, 4))[0] > 0.0)


def ground(sampler: PoseSampler) -> np.ndarray:
    """Grounding attachment: a new base pose (x, y, z, theta) for the planning state, drawn from the
    surface map and discounted against the sampler's earlier poses (eq. 3) so that each call offers
    an alternative. ``sampler.reset()`` starts a new task."""
    return np.asarray(sampler.sample(), float)


def reachable(robot: Robot, arm: str, pose, obj, obstacles=None, world: World = None, attempts: int = 10) -> bool:
    """Can `arm` grasp the object at `obj` (x, y, z of the grasp point, world frame) from base pose
    `pose` (x, y, z, theta of base_footprint)? IK in approach mode for each top grasp (the tool's
    approach axis from the upper hemisphere), with self-collision and arm-vs-`obstacles` checks;
    the body (links the arm does not move) must not touch `obstacles` either.

    `world` supplies precomputed arm data (built once by build_world); without it the data are
    derived here (a capability map's orientation set is not needed: grasps come from a small one)."""
    data = world.arm_data[arm] if world is not None else _arm_data_standalone(robot, arm)
    B = base_transform(pose)
    if obstacles is not None and robot.in_collision(data.reference, obstacles, base_pose=B, links=data.body_links):
        return False
    world_to_arm = np.linalg.inv(B @ data.root_to_armbase)
    Ts = np.repeat(np.eye(4)[None], len(data.grasps), axis=0)
    Ts[:, :3, :3] = data.grasps
    Ts[:, :3, 3] = np.asarray(obj, float)
    Ts = world_to_arm[None] @ Ts
    _, ok = data.chain.ik_batch(Ts, mode="approach", approach_axis=data.axis, self_collision=True,
                                reference=data.reference, obstacles=obstacles, base_pose=B,
                                obstacle_links=data.arm_links, attempts=attempts,
                                position_tolerance=1e-3, orientation_tolerance=1e-2)
    return bool(np.any(ok))


_STANDALONE: dict = {}


def _arm_data_standalone(robot: Robot, arm: str) -> _Arm:
    key = (id(robot), arm)
    if key not in _STANDALONE:
        # the orientation set of a 100-direction capability map (its default rolls and symmetry)
        _STANDALONE[key] = _arm_data(robot, arm, OrientationSet.sphere(100))
    return _STANDALONE[key]


# --------------------------------------------------------------------------------- the task


def predefined_poses(table: Table, count: int = 4) -> np.ndarray:
    """Strategy A's hand-placed poses (count, 4): the middle of the -y long side, then of the +y
    long side (both facing the table), then the +x and -x ends (table frame), STANDOFF m from the edge."""
    if not 1 <= count <= 4:
        raise ValueError(f"count must be 1-4, got {count!r}")
    sx, sy, _ = TABLE_SIZE
    x, y, yaw = table.pose
    local = [(0.0, -(sy / 2 + STANDOFF), np.pi / 2), (0.0, sy / 2 + STANDOFF, -np.pi / 2),
             (sx / 2 + STANDOFF, 0.0, np.pi), (-(sx / 2 + STANDOFF), 0.0, 0.0)]
    c, s = np.cos(yaw), np.sin(yaw)
    out = [(x + c * lx - s * ly, y + s * lx + c * ly, 0.0, (yaw + lt + np.pi) % (2 * np.pi) - np.pi)
           for lx, ly, lt in local[:count]]
    return np.array(out)


def place_objects(world: World, count: int, rng: np.random.Generator) -> list:
    """`count` objects at random on random tables: list of (table index, grasp point (3,))."""
    sx, sy, h = TABLE_SIZE
    objs = []
    for _ in range(count):
        k = int(rng.integers(len(world.tables)))
        lx = rng.uniform(-sx / 2 + EDGE_MARGIN, sx / 2 - EDGE_MARGIN)
        ly = rng.uniform(-sy / 2 + EDGE_MARGIN, sy / 2 - EDGE_MARGIN)
        x, y, yaw = world.tables[k].pose
        c, s = np.cos(yaw), np.sin(yaw)
        objs.append((k, np.array([x + c * lx - s * ly, y + s * lx + c * ly, h + OBJECT_HEIGHT])))
    return objs


def _work_at(world: World, table: Table, pose, objs, todo: set) -> int:
    """Tries every unreached object of this table with both arms from `pose`; returns how many were reached."""
    got = 0
    for i in sorted(todo):
        if world.tables[objs[i][0]] is not table:
            continue
        if any(reachable(world.robot, arm, pose, objs[i][1], table.obstacles, world=world) for arm in ARMS):
            todo.discard(i)
            got += 1
    return got


def run_predefined(world: World, objs, count: int) -> dict:
    """Strategy A: visit the first `count` predefined poses of each table holding objects, in order."""
    todo, visited, useful = set(range(len(objs))), 0, 0
    t0 = time.perf_counter()
    for k, table in enumerate(world.tables):
        for pose in predefined_poses(table, count):
            if not any(objs[i][0] == k for i in todo):
                break
            visited += 1
            useful += _work_at(world, table, pose, objs, todo) > 0
    return {"solved": not todo, "visited": visited, "useful": useful, "seconds": time.perf_counter() - t0}


def run_sampling(world: World, objs, seed: int, budget: int = 10) -> dict:
    """Strategy B: per table holding objects, ground poses from its surface map (at most `budget`),
    keep those the condition attachment accepts, and try the unreached objects there."""
    todo, visited, useful = set(range(len(objs))), 0, 0
    t0 = time.perf_counter()
    for k, table in enumerate(world.tables):
        if not any(objs[i][0] == k for i in todo):
            continue
        ref = world.arm_data[ARMS[0]].reference
        sampler = PoseSampler(table.smap, seed=seed * 1009 + k,
                              in_collision=(world.robot, table.obstacles, ref))
        for _ in range(budget):
            if not any(objs[i][0] == k for i in todo):
                break
            pose = ground(sampler)
            if not condition(table.smap, pose):
                continue
            visited += 1
            useful += _work_at(world, table, pose, objs, todo) > 0
    return {"solved": not todo, "visited": visited, "useful": useful, "seconds": time.perf_counter() - t0}


def tidy_up(trials: int = 100, objects=(1, 2, 3, 4), tables: int = 1, resolution: float = 0.1, seed: int = 0,
            progress: bool = False, budget: int = 10, world: World = None, verbose: bool = False) -> list:
    """The paper's inspect-objects task (Section V-B, Table I) in kinematic simulation.

    For each object count n in `objects`, `trials` tasks place n objects at random (seeded) on 1 or 2
    tables; each task is solved by strategy A with 1, 2, 3 and 4 predefined poses per table and by
    strategy B (sampling, at most `budget` poses per table). Returns one dict per (strategy, n):
    strategy, poses ('1'..'4' or 'sampled'), objects, trials, solved (share in [0, 1]), poses_visited
    (mean base poses moved to), useful_poses (mean poses from which something was reached), time_s
    (mean planning time: pose selection + IK checks). `world` reuses maps from build_world; with
    `verbose` the tables are printed (format_tidy_up)."""
    if tables not in (1, 2):
        raise ValueError(f"tables must be 1 or 2, got {tables!r}")
    if trials < 1:
        raise ValueError(f"trials must be at least 1, got {trials!r}")
    objects = tuple(int(n) for n in objects)
    if not objects or min(objects) < 1:
        raise ValueError(f"objects must be positive counts, got {objects!r}")
    if world is None:
        world = build_world(tables, resolution, seed=seed)
    elif len(world.tables) != tables:
        raise ValueError(f"world has {len(world.tables)} tables, tables={tables}")
    strategies = [("A", str(c)) for c in (1, 2, 3, 4)] + [("B", "sampled")]
    results = {(s, p, n): [] for s, p in strategies for n in objects}
    total = len(objects) * trials
    done = 0
    for n in objects:
        for t in range(trials):
            rng = np.random.default_rng([seed, n, t])
            objs = place_objects(world, n, rng)
            for s, p in strategies:
                r = run_predefined(world, objs, int(p)) if s == "A" else run_sampling(world, objs, seed * 7919 + t, budget)
                results[(s, p, n)].append(r)
            done += 1
            if progress:
                print(f"\rtidy-up: {done}/{total} tasks", end="", flush=True)
    if progress:
        print()
    rows = []
    for s, p in strategies:
        for n in objects:
            rs = results[(s, p, n)]
            rows.append({"strategy": s, "poses": p, "objects": n, "tables": tables, "trials": len(rs),
                         "solved": float(np.mean([r["solved"] for r in rs])),
                         "poses_visited": float(np.mean([r["visited"] for r in rs])),
                         "useful_poses": float(np.mean([r["useful"] for r in rs])),
                         "time_s": float(np.mean([r["seconds"] for r in rs]))})
    if verbose:
        print(format_tidy_up(rows))
    return rows


def format_tidy_up(rows: list) -> str:
    """Tables like the paper's Table I: one per measure (solved share, poses visited, planning time),
    a row per strategy, a column per object count."""
    counts = sorted({r["objects"] for r in rows})
    labels = []
    for r in rows:
        label = f"{r['poses']} pose{'s' if r['poses'] != '1' else ''}" if r["strategy"] == "A" else "sampling"
        if label not in labels:
            labels.append(label)
    cell = {}
    for r in rows:
        label = f"{r['poses']} pose{'s' if r['poses'] != '1' else ''}" if r["strategy"] == "A" else "sampling"
        cell[(label, r["objects"])] = r
    out = []
    meta = rows[0] if rows else {"tables": "?", "trials": "?"}
    for key, title, fmt in (("solved", "share of tasks solved", "{:.2f}"),
                            ("poses_visited", "mean base poses visited", "{:.2f}"),
                            ("useful_poses", "mean base poses from which an object was reached", "{:.2f}"),
                            ("time_s", "mean planning time [s] (pose choice + IK checks)", "{:.3f}")):
        out.append(f"{title} ({meta['tables']} table(s), {meta['trials']} trials per column)")
        out.append(f"{'':<10}" + "".join(f"{str(n) + ' object' + ('s' if n > 1 else ''):>12}" for n in counts))
        for label in labels:
            out.append(f"{label:<10}" + "".join(f"{fmt.format(cell[(label, n)][key]):>12}" for n in counts))
        out.append("")
    return "\n".join(out).rstrip()


# ---------------------------------------------------------------------------- exploration


def exploration_tables(scenes=(1, 2), out=None, verbose: bool = True, **kwargs) -> dict:
    """Per-view tables of the frontier-void paper (Tables I and II: view, integration time, search
    time, void cells, utility dm^3) for its scenes, by octoreach.exploration.run_demo (no plots, no
    octree export; keyword arguments go to run_demo, e.g. max_views, resolution, width, height).
    Returns {scene: ExplorationResult}; prints the tables when `verbose`."""
    import tempfile
    from pathlib import Path

    from . import exploration

    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            folder = Path(out) / f"scene_{scene}" if out is not None else Path(tmp) / f"scene_{scene}"
            kwargs.setdefault("plots", False)
            kwargs.setdefault("export", False)
            res = exploration.run_demo(scene, out=folder, quiet=True, **kwargs)
            results[scene] = res
            if verbose:
                print(f"Table {'I' if scene == 1 else 'II'}: exploration of paper scene {scene} "
                      f"({res.total_s:.1f} s in total)")
                print(res.table())
                print()
    return results
