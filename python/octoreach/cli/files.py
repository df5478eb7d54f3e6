"""`octoreach info`, `export`, `query` and `sample`: commands on saved maps."""
from __future__ import annotations

import argparse
import sys

import numpy as np

from .args import angle


def _cmd_info(args) -> int:
    from .. import map_files

    m = map_files.load(args.map)
    print(repr(m))
    capability = m.kind == "capability"
    for k, v in sorted(m.parameters.items()):
        note = ""
        if capability and k == "voxels":  # records; the drawn voxels (D > 0) are counted on the values line
            note = " (voxel records: a reachable or a mixed cell)"
        elif k == "checks" and "(room: " in str(v):
            note = " (obstacles besides the surface's own; see room below)"
        print(f"  {k}: {v}{note}")
    print(_values_line(*m.voxels()))
    lo, hi = m.bounds
    print(f"  bounds: {np.round(lo, 3).tolist()} .. {np.round(hi, 3).tolist()}")
    room = getattr(m, "room", None)
    if room is not None:
        others = list(dict.fromkeys(list(room.obstacles.names)[room.surface_count:]))  # each name once
        count = len(room.obstacles)
        print("  room: none recorded (a file written before maps recorded their room)" if room.empty else
              f"  room: {count} obstacles: {room.surface_count} of the surface (slab, legs, boxes) and "
              f"{count - room.surface_count} others ({', '.join(others[:8]) or 'none'}"
              f"{' ...' if len(others) > 8 else ''}); body of {len(room.body)} shapes on {len(set(room.body_links))} "
              "links")
    return 0


def _values_line(centres, values) -> str:
    """min and max of a map's values and what they are counted over: voxels (capability: D > 0) or voxels x
    headings (surface and point maps)."""
    values = np.asarray(values)
    if not values.size:
        return "  values: none (no voxel holds a value > 0)"
    span = f"  values: min {values[values > 0].min():.4f}, max {values.max():.4f}"
    if values.ndim == 1:
        return f"{span} over {len(centres)} voxels with D > 0 (a reachable cell)"
    return (f"{span} over {len(centres)} voxels x {values.shape[1]} headings "
            f"({np.count_nonzero(values):,} poses with a value > 0)")


def _cmd_export(args) -> int:
    from .. import map_files

    m = map_files.load(args.map)
    m.export_octovis(args.out)
    print(f"wrote {args.out} (open with octovis)")
    return 0


def _cmd_query(args) -> int:
    from .._core import SurfaceMap

    smap = SurfaceMap.load(args.map)
    try:
        poses = np.array([[float(x), float(y), float(z), angle(t)] for x, y, z, t in args.pose], dtype=float)
    except argparse.ArgumentTypeError as e:
        raise ValueError(f"--pose: {e}") from None
    rs = smap.reachability(poses)  # checks the poses first
    for pose, r, hit in zip(poses, rs, _touched(smap, poses, args)):
        note = f"  in collision with {hit!r}" if hit else ""
        print(f"x={pose[0]:+.3f} y={pose[1]:+.3f} z={pose[2]:+.3f} theta={pose[3]:+.4f}  R_S={r:.4f}{note}")
    return 0


def _touched(smap, poses, args) -> list[str]:
    """Per pose, the obstacle of the room (the map's own, or --scene's) its body touches ('' when none or unchecked)."""
    from .. import room_checks

    if args.no_room_check or not smap.room.body:
        if not args.no_room_check:
            print("octoreach: note: the surface map records no room (a file written before maps recorded theirs): "
                  "poses are not checked for collisions", file=sys.stderr)
        return [""] * len(poses)
    obstacles = smap.room.obstacles
    if args.scene:
        obstacles = room_checks.scene_obstacles(args.scene)
        room_checks.warn_differences(smap, obstacles, args.scene)
    return list(smap.room.touched(poses, obstacles))


def _cmd_sample(args) -> int:
    from .. import room_checks
    from .._core import SurfaceMap

    smap = SurfaceMap.load(args.map)
    sampler = room_checks.sampler(smap, scene=args.scene, room_check=not args.no_room_check,
                                  candidates=args.candidates, seed=args.seed)
    poses = sampler.sample(args.count)
    for pose, r in zip(poses, smap.reachability(poses)):
        print(f"x={pose[0]:+.3f} y={pose[1]:+.3f} z={pose[2]:+.3f} theta={pose[3]:+.4f}  R_S={r:.4f}")
    return 0


def _room_arguments(sp, what: str) -> None:
    sp.add_argument("--scene", help=f"room file (JSON or YAML) to check {what} against instead of the room the map was "
                                    "built with (a room that differs from it is said)")
    sp.add_argument("--no-room-check", action="store_true",
                    help=f"do not check {what} against the room (by default the body is kept out of the room the "
                         "map was built with)")


def add_commands(sub):
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
    _room_arguments(sp, "the poses")
    sp.set_defaults(func=_cmd_query)

    sp = sub.add_parser("sample", help="sample well spread base poses from a surface map (the grounding attachment); "
                                       "prints x y z in m and theta in rad")
    sp.add_argument("map", help="a surface map file")
    sp.add_argument("--count", type=int, default=5, help="poses to sample (default 5)")
    sp.add_argument("--candidates", type=int, default=40, help="valid candidates per pose (default 40)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    _room_arguments(sp, "the sampled poses")
    sp.set_defaults(func=_cmd_sample)
