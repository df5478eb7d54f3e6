"""`octoreach view`: maps, samples, explorations, a robot and a room in 3D in the browser (the viewer extra)."""
from __future__ import annotations


def _robot(args):
    """The robot of --urdf (with --package-dir, --srdf: drawn as its URDF says, nothing sampled) or --robot NAME."""
    if args.urdf:
        from .. import robots

        return robots.from_urdf(args.urdf, args.package_dir or [], args.srdf, allowed_collisions="srdf")
    if args.srdf or args.package_dir:
        raise ValueError("--srdf and --package-dir go with --urdf FILE")
    return args.robot


def _cmd_view(args) -> int:
    from ..viewer import view

    joints = {}
    for item in args.joint or []:
        name, _, value = item.partition("=")
        try:
            joints[name] = float(value)
        except ValueError:
            raise ValueError(f"--joint {item!r}: expected NAME=VALUE (radians or metres)") from None
    robot = _robot(args)
    if not args.files and robot is None and args.scene is None:
        raise ValueError("nothing to view: give map files, --urdf FILE (or --robot NAME) or --scene ROOM")
    view(*args.files, robot=robot, joints=joints, samples=args.samples, seed=args.seed, port=args.port,
         host=args.host, html=args.html, png=args.png, room=args.scene, colour_by=args.colour_by,
         serve=not args.no_serve)
    return 0


def add_commands(sub):
    """view: maps, samples, explorations, a robot and a room in 3D in the browser."""
    sp = sub.add_parser("view", help="show maps, samples, explorations, a robot and a room in 3D in the browser "
                                     "(needs the viewer extra)")
    sp.add_argument("files", nargs="*", help="surface (.orsm) or capability (.orcm) map files, OctoMap .bt files")
    sp.add_argument("--robot", help="robot by name (default: the one a surface map was built for)")
    sp.add_argument("--urdf", help="URDF file of your own robot (drawn from its visuals, meshes resolved as the loader "
                                   "does); alone, the robot at home")
    sp.add_argument("--package-dir", action="append", help="folder to resolve package:// URIs of --urdf (repeatable)")
    sp.add_argument("--srdf", help="SRDF file for --urdf (its tuck postures give a map's reference posture)")
    sp.add_argument("--scene", help="room file (JSON or YAML) to draw; with a surface map, its samples are checked "
                                    "against it instead of the room the map was built with (a surface map shows "
                                    "that room by itself)")
    sp.add_argument("--joint", action="append", metavar="NAME=VALUE",
                    help="set a joint of the shown configuration (repeatable; default: the map's reference posture)")
    sp.add_argument("--samples", type=int, default=5, help="base poses to sample and show (default 5)")
    sp.add_argument("--seed", type=int, default=1, help="sampler seed (default 1)")
    sp.add_argument("--port", type=int, default=8080, help="port (default 8080; the next free one if taken)")
    sp.add_argument("--host", default="127.0.0.1", help="address to serve on (default 127.0.0.1)")
    sp.add_argument("--html", help="also write the scene as a static HTML page")
    sp.add_argument("--png", help="also write a screenshot (headless Chromium)")
    sp.add_argument("--no-serve", action="store_true", help="write --html/--png and exit instead of serving")
    sp.add_argument("--colour-by", choices=("reachability", "quality"), default="reachability",
                    help="colour a capability map's voxels by reachability index D (default) or by the quality of "
                         "their cells' joint solutions (manipulability x joint-limit penalty)")
    sp.set_defaults(func=_cmd_view)
