"""`octoreach capability` and `octoreach surface`: the map builds."""
from __future__ import annotations

import sys

from .args import angle, arm_arg, arm_args, cache_args, load_robot, named_arm, robot_args, robot_spec


def _surfaces(args) -> list:
    """[(name, file stem, surface, obstacles())] from --scene, --polygon or --table: obstacles() gives the rest of
    the room (or None), built when that surface's turn comes (one room's worth at a time, not one per surface)."""
    from .. import rooms
    from .._core import Surface

    if args.scene:
        room = rooms.Room.load(args.scene)
        if not room.surfaces:
            raise ValueError(f"scene file {args.scene!r} holds no surface")
        stems = output_stems(list(room.surfaces), f"scene file {args.scene!r}")
        return [(name, stems[name], surface, lambda name=name: room.obstacles(without=name))
                for name, surface in room.surfaces.items()]
    if args.polygon:
        surface, obstacles = rooms.surface_from_file(args.polygon)
        return [("surface", "surface", surface, lambda: obstacles if len(obstacles) else None)]
    sx, sy, h = args.table
    return [("table", "table", Surface.rectangle(sx, sy, h, args.table_x, args.table_y, args.table_yaw), lambda: None)]


def output_stems(names, where: str) -> dict:
    """{name: file stem}: '/' (shelf boards are "<shelf>/<i>") written as '_'; ValueError naming both surfaces
    when two stems meet (also in letter case only, which some file systems ignore)."""
    stems, seen = {}, {}
    for name in names:
        stem = name.replace("/", "_")
        if stem.casefold() in seen:
            raise ValueError(f"{where}: the surfaces {seen[stem.casefold()]!r} and {name!r} would both be written to "
                             f"{stem}.orsm: rename one")
        seen[stem.casefold()] = name
        stems[name] = stem
    return stems


def _cmd_capability(args) -> int:
    from .. import arms

    robot = load_robot(args)
    arm = arm_arg(args, robot)
    if not args.quiet:
        print(f"arm {arm.base_link} -> {arm.tip_link}: approach axis {arm.reason}", file=sys.stderr)
    import time

    t0 = time.perf_counter()
    cache = None if args.no_cache else (args.cache_dir or True)
    if args.cluster:  # blocks of voxels on a cluster's workers, merged (the bytes of the one-process block build)
        from .. import cluster

        cap = cluster.build_capability_split(robot, arm, cluster=args.cluster, block_size=args.block_size or 16,
                                             cache=cache, progress=not args.quiet, robot_spec=robot_spec(args),
                                             resolution=args.resolution, directions=args.directions, poles=args.poles,
                                             seed=args.seed)
    else:
        cap = arms.capability_map(robot, arm, resolution=args.resolution, directions=args.directions, poles=args.poles,
                                  seed=args.seed, block_size=args.block_size, progress=not args.quiet, cache=cache)
    cap.save(args.out, with_solutions=args.with_solutions)
    if args.octovis:
        cap.export_octovis(args.octovis)
    print(f"{cap!r}: {cap.stats['reachable_cells']} reachable cells in {time.perf_counter() - t0:.1f} s -> {args.out}")
    return 0


def _capability_keywords(args, source) -> dict:
    """The capability-map keywords of SurfaceMap.build: an arm's map is built with them; a map file fixes its own
    directions and seed, and --poles against one built without them is an error."""
    from .._core import CapabilityMap

    if isinstance(source, CapabilityMap):
        return {"poles": True} if args.poles else {}
    return {"directions": args.directions, "poles": args.poles, "seed": args.seed}


def _cmd_surface(args) -> int:
    import os

    from .._core import CapabilityMap, SurfaceMap

    robot = load_robot(args)
    surfaces = _surfaces(args)
    sources = []
    if not args.arms:
        from ..arms import default_arm

        args.arms = [default_arm(robot)]
    for arm in args.arms:
        source = CapabilityMap.load(arm) if arm.endswith(".orcm") else named_arm(args, robot, arm)
        if isinstance(source, CapabilityMap) and not source.has_solutions:
            raise ValueError(f"{arm}: the capability map was saved without joint solutions, which the surface map "
                             "needs: rebuild it with octoreach capability ... --with-solutions")
        sources.append(source)
    # No --resolution: the (first) capability map's, SurfaceMap.build's default, so the maps of several arms
    # share one grid; with arm names only, CapabilityMapOptions' resolution.
    first = next((s for s in sources if isinstance(s, CapabilityMap)), None)
    resolution = first.resolution if args.resolution is None and first is not None else args.resolution
    grid = {} if resolution is None else {"resolution": resolution}
    if args.scene:  # one map per surface: build each arm's capability map once
        from .. import arms

        sources = [s if isinstance(s, CapabilityMap) else
                   arms.capability_map(robot, s, directions=args.directions, poles=args.poles, seed=args.seed,
                                       progress=not args.quiet, **grid) for s in sources]
        for folder in (args.out, args.plot, args.octovis):
            if folder:
                os.makedirs(folder, exist_ok=True)
    for name, stem, surface, obstacles_of in surfaces:
        obstacles = obstacles_of()
        maps = [SurfaceMap.build(robot, source, surface, theta_bins=args.theta_bins, **grid,
                                 z_range=(args.z, args.z), obstacles=obstacles, progress=not args.quiet,
                                 **_capability_keywords(args, source))
                for source in sources]
        del obstacles
        smap = maps[0] if len(maps) == 1 else SurfaceMap.combine(maps, args.combine)
        if smap.voxel_count == 0:
            print(f"octoreach: warning: empty surface map of {name!r}: {smap.empty_reason}", file=sys.stderr)
        out = os.path.join(args.out, stem + ".orsm") if args.scene else args.out
        smap.save(out)
        if args.octovis:
            smap.export_octovis(os.path.join(args.octovis, stem + ".ot") if args.scene else args.octovis)
        if args.plot:
            from .. import plots

            plots.surface_slices(smap, os.path.join(args.plot, stem + ".png") if args.scene else args.plot)
        print(f"{name}: {smap!r}: best R_S {smap.max_reachability:.3f} -> {out}")
    return 0


def add_commands(sub):
    """capability, surface: the map builds."""
    sp = sub.add_parser("capability", help="build an arm's capability map")
    robot_args(sp)
    arm_args(sp)
    sp.add_argument("--with-solutions", action="store_true", help="store joint solutions (needed for surface maps)")
    sp.add_argument("--out", required=True, help="output map file (.orcm)")
    sp.add_argument("--block-size", type=int, default=0,
                    help="build in blocks of this many voxels per edge (0: one flood over the whole box; part of the map)")
    sp.add_argument("--cluster", help="build the blocks on a Ray cluster: local, auto or HOST:PORT (needs the cluster "
                                      "extra); the same bytes as --block-size in one process (default size 16)")
    cache_args(sp)
    sp.set_defaults(func=_cmd_capability)

    sp = sub.add_parser("surface", help="build a surface map for a table or shelf polygon")
    robot_args(sp)
    arm_args(sp, many=True)
    sp.add_argument("--table", type=float, nargs=3, default=[1.4, 0.65, 0.72], metavar=("SX", "SY", "HEIGHT"),
                    help="rectangular table: sizes and top height in m (default 1.4 0.65 0.72)")
    sp.add_argument("--table-x", type=float, default=0.0, help="table centre x (m)")
    sp.add_argument("--table-y", type=float, default=0.0, help="table centre y (m)")
    sp.add_argument("--table-yaw", type=angle, default=0.0, help="table yaw (rad, or degrees as e.g. 90deg)")
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
