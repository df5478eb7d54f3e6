"""The `octoreach` command line."""
from __future__ import annotations

import argparse
import sys

import numpy as np


def _load_robot(args):
    from . import robots

    how = getattr(args, "allowed_collisions", "auto")
    if args.urdf:
        return robots.from_urdf(args.urdf, args.package_dir or [], args.srdf, allowed_collisions=how)
    return robots.load(getattr(args, "name", None) or args.robot, allowed_collisions=how)


def _cmd_robot(args) -> int:
    from ._core import find_arms

    robot = _load_robot(args)
    print(f"{robot.name}: {len(robot.link_names)} links ({len(robot.collision_links)} with collision geometry), "
          f"{robot.dof} dof, root {robot.root_link}, {len(robot.allowed_collisions)} allowed-collision pairs")
    print("links:")
    for name in robot.link_names:
        print(f"  {name}")
    print("joints (configuration order, limits in rad or m):")
    for name, lo, hi in zip(robot.joint_names, robot.lower, robot.upper):
        print(f"  {name}: [{lo:.4g}, {hi:.4g}]")
    for name in robot.mimic_joints:
        print(f"  {name}: mimic")
    if robot.srdf_groups:
        print("SRDF groups:")
    for name, g in robot.srdf_groups.items():
        parts = [f"chain {b} -> {t}" for b, t in g["chains"]]
        parts += [f"joints {', '.join(g['joints'])}"] if g["joints"] else []
        parts += [f"links {', '.join(g['links'])}"] if g["links"] else []
        parts += [f"subgroups {', '.join(g['subgroups'])}"] if g["subgroups"] else []
        print(f"  {name}: {'; '.join(parts) or 'empty'}")
    for e in robot.end_effectors:
        print(f"end effector {e['name']}: parent link {e['parent_link']}, group {e['group'] or '-'}"
              f"{', parent group ' + e['parent_group'] if e['parent_group'] else ''}")
    arms = find_arms(robot)
    print("arms (what --arm NAME uses; tool frame, approach axis and why):" if arms else
          "arms: none found (give one by its links: --base LINK --tip LINK --approach-axis X Y Z)")
    for a in arms:
        print(f"  {a.name}: {a.base_link} -> {a.tip_link}, approach axis {tuple(round(float(v), 3) for v in a.approach_axis)}"
              f" ({a.reason}); from {a.source}")
    poses = robot.link_poses(robot.home()) if arms else {}
    for a in arms:  # where the tool frame's axes point at home, in the arm's base frame
        R = (np.linalg.inv(poses[a.base_link]) @ poses[a.tip_link])[:3, :3]
        axes = ", ".join(f"{n} -> {tuple(round(float(v), 2) for v in R[:, k])}" for k, n in enumerate("xyz"))
        print(f"tool frame {a.tip_link} (arm {a.name}) at home, axes in {a.base_link}: {axes}")
    if args.write_srdf:
        robot.write_srdf(args.write_srdf)
        print(f"wrote {args.write_srdf}")
    return 0


def _cmd_ik(args) -> int:
    robot = _load_robot(args)
    chain = robot.chain(args.base, args.tip)
    T = np.eye(4)
    T[:3, 3] = args.xyz
    q = chain.ik(T, mode=args.mode, rng_seed=args.seed, approach_axis=np.array(args.approach_axis, float))
    if q is None:
        print("no solution")
        return 1
    print(" ".join(f"{v:.6f}" for v in q))
    return 0


def _arm_arg(args, robot):
    """The Arm of --arm NAME or --base/--tip, with --approach-axis overriding the inferred axis."""
    from ._core import Arm

    axis = None if args.approach_axis is None else tuple(args.approach_axis)
    if args.arm is None:
        if args.base or args.tip:
            if not (args.base and args.tip):
                raise ValueError("give both --base LINK and --tip LINK (or --arm NAME)")
            return Arm.resolve(robot, (args.base, args.tip), approach_axis=axis)
        from .arms import default_arm

        return Arm.resolve(robot, default_arm(robot), approach_axis=axis)
    return Arm.resolve(robot, args.arm, approach_axis=axis)


def _named_arm(args, robot, name):
    from ._core import Arm

    return Arm.resolve(robot, name, approach_axis=None if args.approach_axis is None else tuple(args.approach_axis))


def _angle(text: str) -> float:
    """An angle on the command line: radians, or degrees with an explicit suffix ("90deg")."""
    t = str(text).strip().lower()
    try:
        return float(np.radians(float(t[:-3]))) if t.endswith("deg") else float(t)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an angle: {text!r} (radians, or degrees as e.g. 90deg)") from None


def _surfaces(args):
    """{name: (surface, obstacles of the rest of the room or None)} from --scene, --polygon or --table."""
    from . import rooms
    from ._core import Surface

    if args.scene:
        room = rooms.Room.load(args.scene)
        if not room.surfaces:
            raise ValueError(f"scene file {args.scene!r} holds no surface")
        return {name: (surface, room.obstacles(without=name)) for name, surface in room.surfaces.items()}
    if args.polygon:
        surface, obstacles = rooms.surface_from_file(args.polygon)
        return {"surface": (surface, obstacles if len(obstacles) else None)}
    sx, sy, h = args.table
    return {"table": (Surface.rectangle(sx, sy, h, args.table_x, args.table_y, args.table_yaw), None)}


def _cmd_capability(args) -> int:
    from . import arms

    robot = _load_robot(args)
    arm = _arm_arg(args, robot)
    if not args.quiet:
        print(f"arm {arm.base_link} -> {arm.tip_link}: approach axis {arm.reason}", file=sys.stderr)
    import time

    t0 = time.perf_counter()
    cache = None if args.no_cache else (args.cache_dir or True)
    if args.cluster:  # blocks of voxels on a cluster's workers, merged (the bytes of the one-process block build)
        from . import cluster

        cap = cluster.build_capability_split(robot, arm, cluster=args.cluster, block_size=args.block_size or 16,
                                             cache=cache, progress=not args.quiet, robot_spec=_robot_spec(args),
                                             resolution=args.resolution, directions=args.directions, seed=args.seed)
    else:
        cap = arms.capability_map(robot, arm, resolution=args.resolution, directions=args.directions, seed=args.seed,
                                  block_size=args.block_size, progress=not args.quiet, cache=cache)
    cap.save(args.out, with_solutions=args.with_solutions)
    if args.octovis:
        cap.export_octovis(args.octovis)
    print(f"{cap!r}: {cap.stats['reachable_cells']} reachable cells in {time.perf_counter() - t0:.1f} s -> {args.out}")
    return 0


def _robot_spec(args) -> dict:
    """How a cluster's workers load the robot of --robot/--urdf (they check its model hash)."""
    import os

    if args.urdf:
        return {"urdf": os.path.abspath(args.urdf), "srdf": os.path.abspath(args.srdf) if args.srdf else None,
                "package_dirs": [os.path.abspath(p) for p in args.package_dir or []],
                "allowed_collisions": args.allowed_collisions}
    return {"name": getattr(args, "name", None) or args.robot, "allowed_collisions": args.allowed_collisions}


def _cmd_cache(args) -> int:
    from .cache import MapCache

    store = MapCache(args.cache_dir)
    if args.action == "clear":
        print(f"deleted {store.clear()} maps from {store.directory}")
        return 0
    entries = store.entries()
    print(f"{store.directory}: {len(entries)} maps, {sum(e['bytes'] for e in entries) / 1e6:.1f} MB")
    for e in entries:
        f = e["fields"]
        arm = f.get("arm") or f.get("capability", {}).get("arm", {})
        what = f"{f.get('robot') or f.get('capability', {}).get('robot', '?')} {arm.get('base_link', '?')} -> " \
               f"{arm.get('tip_link', '?')}"
        res = (f.get("options") or {}).get("resolution") or f.get("capability", {}).get("options", {}).get("resolution")
        extra = f" surface {f['surface']} z {f['height']:g}" if e["kind"] == "surface" else ""
        print(f"  {e['kind']:10s} {e['key'][:12]}  {what} at {res} m{extra}  {e['bytes'] / 1e3:.0f} KB  {e['created']}")
    return 0


def _cmd_build_many(args) -> int:
    from . import cluster

    report = cluster.build_many(args.job, cluster=args.cluster, out=args.out,
                                cache=None if args.no_cache else (args.cache_dir or True), progress=not args.quiet,
                                task_cpus=args.task_cpus)
    built = len(report.files) - report.cache_hits
    print(f"{len(report.files)} maps ({built} built, {report.cache_hits} from the cache) in {report.seconds:.1f} s")
    for name, path in report.files.items():
        print(f"  {name} -> {path}")
    return 0


def _cmd_surface(args) -> int:
    import os

    from ._core import CapabilityMap, SurfaceMap

    robot = _load_robot(args)
    surfaces = _surfaces(args)
    sources = []
    if not args.arms:
        from .arms import default_arm

        args.arms = [default_arm(robot)]
    for arm in args.arms:
        source = CapabilityMap.load(arm) if arm.endswith(".orcm") else _named_arm(args, robot, arm)
        if isinstance(source, CapabilityMap) and not source.has_solutions:
            raise ValueError(f"{arm}: the capability map was saved without joint solutions (--with-solutions)")
        sources.append(source)
    if args.scene:  # one map per surface: build each arm's capability map once
        from . import arms

        sources = [s if isinstance(s, CapabilityMap) else
                   arms.capability_map(robot, s, resolution=args.resolution, directions=args.directions, seed=args.seed,
                                       progress=not args.quiet) for s in sources]
        for folder in (args.out, args.plot, args.octovis):
            if folder:
                os.makedirs(folder, exist_ok=True)
    for name, (surface, obstacles) in surfaces.items():
        maps = [SurfaceMap.build(robot, source, surface, resolution=args.resolution, theta_bins=args.theta_bins,
                                 z_range=(args.z, args.z), obstacles=obstacles, directions=args.directions,
                                 seed=args.seed, progress=not args.quiet) for source in sources]
        smap = maps[0] if len(maps) == 1 else SurfaceMap.combine(maps, args.combine)
        if smap.voxel_count == 0:
            print(f"octoreach: warning: empty surface map of {name!r}: {smap.empty_reason}", file=sys.stderr)
        stem = name.replace("/", "_")
        out = os.path.join(args.out, stem + ".orsm") if args.scene else args.out
        smap.save(out)
        if args.octovis:
            smap.export_octovis(os.path.join(args.octovis, stem + ".ot") if args.scene else args.octovis)
        if args.plot:
            from . import plots

            plots.surface_slices(smap, os.path.join(args.plot, stem + ".png") if args.scene else args.plot)
        print(f"{name}: {smap!r}: best R_S {smap.max_reachability:.3f} -> {out}")
    return 0


def _cmd_info(args) -> int:
    from . import map_files

    m = map_files.load(args.map)
    print(repr(m))
    for k, v in sorted(m.parameters.items()):
        print(f"  {k}: {v}")
    centres, values = m.voxels()
    values = np.asarray(values)
    if values.size:
        print(f"  values: min {values[values > 0].min():.4f}, max {values.max():.4f}, voxels {len(centres)}")
    lo, hi = m.bounds
    print(f"  bounds: {np.round(lo, 3).tolist()} .. {np.round(hi, 3).tolist()}")
    return 0


def _cmd_export(args) -> int:
    from . import map_files

    m = map_files.load(args.map)
    m.export_octovis(args.out)
    print(f"wrote {args.out} (open with octovis)")
    return 0


def _cmd_query(args) -> int:
    from ._core import SurfaceMap

    smap = SurfaceMap.load(args.map)
    try:
        poses = np.array([[float(x), float(y), float(z), _angle(t)] for x, y, z, t in args.pose], dtype=float)
    except argparse.ArgumentTypeError as e:
        raise ValueError(f"--pose: {e}") from None
    for pose, r in zip(poses, smap.reachability(poses)):
        print(f"x={pose[0]:+.3f} y={pose[1]:+.3f} z={pose[2]:+.3f} theta={pose[3]:+.4f}  R_S={r:.4f}")
    return 0


def _cmd_sample(args) -> int:
    from ._core import PoseSampler, SurfaceMap

    smap = SurfaceMap.load(args.map)
    sampler = PoseSampler(smap, candidates=args.candidates, seed=args.seed)
    poses = sampler.sample(args.count)
    for pose, r in zip(poses, smap.reachability(poses)):
        print(f"x={pose[0]:+.3f} y={pose[1]:+.3f} z={pose[2]:+.3f} theta={pose[3]:+.4f}  R_S={r:.4f}")
    return 0


def _cmd_view(args) -> int:
    from .viewer import view

    joints = {}
    for item in args.joint or []:
        name, _, value = item.partition("=")
        try:
            joints[name] = float(value)
        except ValueError:
            raise ValueError(f"--joint {item!r}: expected NAME=VALUE (radians or metres)") from None
    view(*args.files, robot=args.robot, joints=joints, samples=args.samples, seed=args.seed, port=args.port,
         host=args.host, html=args.html, png=args.png, block=not args.no_serve)
    return 0


def _cmd_experiment(args) -> int:
    from . import experiments

    if args.name == "tidy-up":
        from .planning import SCENES, require_planner

        for flag in ("runs", "runs_table2", "budget"):
            if getattr(args, flag) < (0 if flag == "budget" else 1):
                raise ValueError(f"--{flag.replace('_', '-')} must be at least {0 if flag == 'budget' else 1}, "
                                 f"got {getattr(args, flag)}")
        scenes = tuple(args.scenes or SCENES)
        unknown = [s for s in scenes if s not in SCENES]
        if unknown:
            raise ValueError(f"--scenes: unknown scene {unknown[0]!r} (scenes: {', '.join(SCENES)})")
        try:
            require_planner()
        except ImportError as e:  # PlannerMissing: says which extra to install
            raise RuntimeError(str(e)) from None
        experiments.tidy_up(runs=args.runs, runs_table_two=args.runs_table2, objects=tuple(args.objects),
                            scenes=scenes, seed=args.seed, resolution=args.resolution, directions=args.directions,
                            budget=args.budget,
                            plot_path=args.plot, progress=not args.quiet)
        if args.plot:
            print(f"plot: {args.plot}")
        return 0
    if args.scene not in (1, 2):
        raise ValueError(f"--scene must be 1 or 2, got {args.scene}")
    if args.views < 1:
        raise ValueError(f"--views must be at least 1, got {args.views}")
    experiments.exploration_tables(scenes=(args.scene,), max_views=args.views, seed=args.seed,
                                   strategy=args.strategy)
    return 0


def _robot_args(sp):
    """--robot/--urdf/--srdf/--package-dir/--allowed-collisions: which robot, and its collision set-up."""
    sp.add_argument("--robot", default="pr2", help="robot of example-robot-data by name (default: pr2)")
    sp.add_argument("--urdf", help="URDF file of your own robot (overrides --robot)")
    sp.add_argument("--srdf", help="SRDF file for --urdf (groups and disabled collision pairs)")
    sp.add_argument("--package-dir", action="append", help="folder to resolve package:// URIs (repeatable)")
    sp.add_argument("--allowed-collisions", choices=["auto", "sample", "srdf"], default="auto",
                    help="auto (default): sample the allowed-collision matrix (cached) when the SRDF is missing or "
                         "incomplete; sample: always; srdf: only what the URDF/SRDF say")


def _arm_args(sp, many=False):
    """Which arm(s) and the capability-map build options; defaults from CapabilityMapOptions (C++)."""
    from ._core import CapabilityMapOptions

    defaults = CapabilityMapOptions()  # the build defaults, defined once in C++
    if many:
        sp.add_argument("--arms", nargs="+",
                        help="arm names (SRDF groups, e.g. right_arm left_arm) or saved capability maps (.orcm "
                             "with solutions); several are combined (default: right_arm, or the robot's only arm)")
    else:
        sp.add_argument("--arm", help="arm name (see `octoreach robot NAME`, e.g. right_arm; default: right_arm, or "
                                      "the robot's only arm)")
        sp.add_argument("--base", help="chain base link (instead of --arm)")
        sp.add_argument("--tip", help="chain tip (tool) link (instead of --arm)")
    sp.add_argument("--approach-axis", type=float, nargs=3, metavar=("X", "Y", "Z"),
                    help="tool axis that approaches the object, tip frame (default: inferred from the gripper)")
    sp.add_argument("--resolution", type=float, default=defaults.resolution,
                    help=f"voxel edge in m (default {defaults.resolution})")
    sp.add_argument("--directions", type=int, default=defaults.directions,
                    help=f"approach directions (default {defaults.directions})")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.add_argument("--quiet", action="store_true", help="no progress bar")
    sp.add_argument("--octovis", help="also write a colour octree (.ot) for octovis")


def _add_robot_commands(sub):
    """robot, ik."""
    sp = sub.add_parser("robot", help="print a robot's links, joints with limits, SRDF groups, end effectors and arms")
    sp.add_argument("name", nargs="?", help="robot of example-robot-data by name (same as --robot)")
    _robot_args(sp)
    sp.add_argument("--write-srdf", metavar="PATH", help="write the robot's SRDF (groups, allowed-collision pairs) to PATH")
    sp.set_defaults(func=_cmd_robot)

    sp = sub.add_parser("ik", help="solve inverse kinematics for a position")
    _robot_args(sp)
    sp.add_argument("--base", required=True, help="base link of the chain")
    sp.add_argument("--tip", required=True, help="tip link of the chain")
    sp.add_argument("--xyz", type=float, nargs=3, required=True, help="target position in the base frame (m)")
    sp.add_argument("--mode", choices=["full", "position", "approach"], default="position", help="IK mode")
    sp.add_argument("--approach-axis", type=float, nargs=3, default=[0, 0, 1],
                    help="tool axis that approaches the target, tip frame (unit vector; default 0 0 1)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.set_defaults(func=_cmd_ik)


def _add_build_commands(sub):
    """capability, surface: the map builds."""
    sp = sub.add_parser("capability", help="build an arm's capability map")
    _robot_args(sp)
    _arm_args(sp)
    sp.add_argument("--with-solutions", action="store_true", help="store joint solutions (needed for surface maps)")
    sp.add_argument("--out", required=True, help="output map file (.orcm)")
    sp.add_argument("--block-size", type=int, default=0,
                    help="build in blocks of this many voxels per edge (0: one flood over the whole box; part of the map)")
    sp.add_argument("--cluster", help="build the blocks on a Ray cluster: local, auto or HOST:PORT (needs the cluster "
                                      "extra); the same bytes as --block-size in one process (default size 16)")
    _cache_args(sp)
    sp.set_defaults(func=_cmd_capability)

    sp = sub.add_parser("surface", help="build a surface map for a table or shelf polygon")
    _robot_args(sp)
    _arm_args(sp, many=True)
    sp.add_argument("--table", type=float, nargs=3, default=[1.4, 0.65, 0.72], metavar=("SX", "SY", "HEIGHT"),
                    help="rectangular table: sizes and top height in m (default 1.4 0.65 0.72)")
    sp.add_argument("--table-x", type=float, default=0.0, help="table centre x (m)")
    sp.add_argument("--table-y", type=float, default=0.0, help="table centre y (m)")
    sp.add_argument("--table-yaw", type=_angle, default=0.0, help="table yaw (rad, or degrees as e.g. 90deg)")
    sp.add_argument("--polygon", help="JSON (or YAML) file: a list of [x, y, z] vertices (m), or {\"vertices\": [...], "
                                      "\"thickness\": 0.03, \"legs\": 0.05, \"boxes\": [...], \"meshes\": [...]}; "
                                      "replaces --table")
    sp.add_argument("--scene", help="room file (JSON or YAML: surfaces, shelves, boxes, meshes, octomaps; m and rad): "
                                    "one map per surface, each with every obstacle of the room; --out (and --plot, "
                                    "--octovis) are then folders")
    sp.add_argument("--theta-bins", type=int, default=16, help="orientation bins over 2 pi rad (default 16)")
    sp.add_argument("--z", type=float, default=0.0, help="height of the robot's reference frame (m; default 0: floor)")
    sp.add_argument("--combine", choices=["max", "min"], default="max",
                    help="several arms: max = any arm reaches, min = both reach (default max)")
    sp.add_argument("--plot", help="also write a PNG of the map's slices")
    sp.add_argument("--out", required=True, help="output map file (.orsm); with --scene a folder (one NAME.orsm per "
                                                 "surface, '/' in names written as '_')")
    sp.set_defaults(func=_cmd_surface)


def _cache_args(sp):
    sp.add_argument("--cache-dir", help="map cache folder (default $OCTOREACH_CACHE_DIR or ~/.cache/octoreach/maps)")
    sp.add_argument("--no-cache", action="store_true", help="neither look maps up in the cache nor store them")


def _add_scale_commands(sub):
    """cache, build-many: the map cache and many maps on a cluster."""
    sp = sub.add_parser("cache", help="list or clear the map cache")
    sp.add_argument("action", choices=["list", "clear"], help="list the cached maps, or delete them all")
    sp.add_argument("--cache-dir", help="map cache folder (default $OCTOREACH_CACHE_DIR or ~/.cache/octoreach/maps)")
    sp.set_defaults(func=_cmd_cache)

    sp = sub.add_parser("build-many", help="build many maps (robots x arms x surfaces x resolutions) as tasks on a "
                                           "Ray cluster (the cluster extra); see octoreach.jobs for the job file")
    sp.add_argument("job", help="job file (YAML or JSON): robots, arms, resolutions, capability, surfaces, surface, "
                                "base_heights, out")
    sp.add_argument("--cluster", default="local",
                    help="local (default: Ray on this machine), none (in this process, no Ray), auto (the cluster "
                         "this machine joined) or HOST:PORT of a Ray head")
    sp.add_argument("--out", help="output folder (default: the job file's 'out', else build_many_out)")
    sp.add_argument("--task-cpus", type=int, default=1, help="CPUs (and threads) per task (default 1)")
    sp.add_argument("--quiet", action="store_true", help="no progress line")
    _cache_args(sp)
    sp.set_defaults(func=_cmd_build_many)


def _add_file_commands(sub):
    """info, export, query, sample: commands on saved maps."""
    sp = sub.add_parser("info", help="print a map file's parameters, robot, size and value range")
    sp.add_argument("map", help="a capability (.orcm), point (.orpm) or surface (.orsm) map file")
    sp.set_defaults(func=_cmd_info)

    sp = sub.add_parser("export", help="write a map as a colour octree (.ot) for octovis")
    sp.add_argument("map", help="a map file")
    sp.add_argument("--out", required=True, help="output .ot file")
    sp.set_defaults(func=_cmd_export)

    sp = sub.add_parser("query", help="R_S of base poses in a surface map (the condition attachment)")
    sp.add_argument("map", help="a surface map file")
    sp.add_argument("--pose", nargs=4, action="append", required=True, metavar=("X", "Y", "Z", "THETA"),
                    help="a base pose: x y z in m, theta in rad (or degrees as e.g. 90deg); repeatable")
    sp.set_defaults(func=_cmd_query)

    sp = sub.add_parser("sample", help="sample well spread base poses from a surface map (the grounding attachment); "
                                       "prints x y z in m and theta in rad")
    sp.add_argument("map", help="a surface map file")
    sp.add_argument("--count", type=int, default=5, help="poses to sample (default 5)")
    sp.add_argument("--candidates", type=int, default=40, help="valid candidates per pose (default 40)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.set_defaults(func=_cmd_sample)


def _add_view_and_experiment_commands(sub):
    """view (3D in the browser), experiment (the papers' experiments)."""
    sp = sub.add_parser("view", help="show maps, samples and explorations in 3D in the browser (needs the viewer extra)")
    sp.add_argument("files", nargs="+", help="surface (.orsm) or capability (.orcm) map files, OctoMap .bt files")
    sp.add_argument("--robot", help="robot by name (default: the one a surface map was built for)")
    sp.add_argument("--joint", action="append", metavar="NAME=VALUE",
                    help="set a joint of the shown configuration (repeatable; default: the map's reference posture)")
    sp.add_argument("--samples", type=int, default=5, help="base poses to sample and show (default 5)")
    sp.add_argument("--seed", type=int, default=1, help="sampler seed (default 1)")
    sp.add_argument("--port", type=int, default=8080, help="port (default 8080; the next free one if taken)")
    sp.add_argument("--host", default="127.0.0.1", help="address to serve on (default 127.0.0.1)")
    sp.add_argument("--html", help="also write the scene as a static HTML page")
    sp.add_argument("--png", help="also write a screenshot (headless Chromium)")
    sp.add_argument("--no-serve", action="store_true", help="write --html/--png and exit instead of serving")
    sp.set_defaults(func=_cmd_view)

    sp = sub.add_parser("experiment", help="paper experiments: tidy-up (surface maps) or exploration (frontier voids)")
    sp.add_argument("name", choices=["tidy-up", "exploration"], help="which experiment")
    sp.add_argument("--runs", type=int, default=2, help="tidy-up: runs per Table I cell and per scene (default 2)")
    sp.add_argument("--runs-table2", type=int, default=7, help="tidy-up: runs per strategy in Table II (default 7)")
    sp.add_argument("--objects", type=int, nargs="+", default=[1, 2, 3, 4], help="tidy-up: Table I object counts (default 1 2 3 4)")
    sp.add_argument("--scenes", nargs="+", help="tidy-up: scenes of the scene table (default all: paper chairs corners "
                    "shelf l_table narrow)")
    sp.add_argument("--resolution", type=float, default=0.1, help="tidy-up: map resolution in m (default 0.1)")
    sp.add_argument("--directions", type=int, help="tidy-up: capability-map directions (default 100, the experiment's)")
    sp.add_argument("--budget", type=int, default=8, help="tidy-up: sampled poses per surface and task (default 8)")
    sp.add_argument("--plot", default="tidy_up.png", help="tidy-up: PNG to write (default tidy_up.png)")
    sp.add_argument("--scene", type=int, default=1, help="exploration: paper scene 1 or 2 (default 1)")
    sp.add_argument("--views", type=int, default=10, help="exploration: view budget (default 10)")
    from .exploration.strategies import STRATEGIES

    sp.add_argument("--strategy", default="frontier_void", choices=STRATEGIES,
                    help="exploration: how views are chosen (default frontier_void, the paper's)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.add_argument("--quiet", action="store_true", help="no progress line")
    sp.set_defaults(func=_cmd_experiment)


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="octoreach", description="Where a robot should stand and where it should look.")
    sub = p.add_subparsers(dest="command", required=True)
    _add_robot_commands(sub)
    _add_build_commands(sub)
    _add_file_commands(sub)
    _add_view_and_experiment_commands(sub)
    _add_scale_commands(sub)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, OSError, RuntimeError, ImportError) as e:  # ConnectionError is an OSError
        print(f"octoreach: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    raise SystemExit(main())
