"""``view(*items, ...)``: maps, explorations, a robot and a room shown in one call (``octoreach view`` on the command
line), its arguments checked before the server starts."""
from __future__ import annotations

import threading

from . import files
from .app import Viewer


def check_arguments(port=8080, host: str = "127.0.0.1", samples: int = 5, html=None, png=None,
                    resolve_timeout: float = 10.0) -> None:
    """ValueError (OSError for an output) naming the first bad argument of view(), before anything is loaded or
    served: a port outside 0-65535, a host that does not resolve within `resolve_timeout` s, a sample count
    outside 0-limits.MAX_VIEW_SAMPLES, an --html/--png target that may not be replaced (a device, a link)."""
    import socket

    from ..atomic_write import check_target
    from ..limits import MAX_VIEW_SAMPLES

    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ValueError(f"port must be an integer in 0-65535 (0: any free port), got {port!r}")
    if isinstance(samples, bool) or not isinstance(samples, int) or not 0 <= samples <= MAX_VIEW_SAMPLES:
        raise ValueError(f"samples must be an integer in 0-{MAX_VIEW_SAMPLES:,} (octoreach.limits.MAX_VIEW_SAMPLES), "
                         f"got {samples!r}")
    if not isinstance(host, str) or not host or "\x00" in host:
        raise ValueError(f"host must be a host name or address, got {host!r}")
    answer: dict = {}

    def resolve():
        try:
            answer["ok"] = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
        except (OSError, UnicodeError) as e:
            answer["error"] = getattr(e, "strerror", None) or str(e)

    thread = threading.Thread(target=resolve, daemon=True)
    thread.start()
    thread.join(resolve_timeout)
    if "ok" not in answer:
        why = answer.get("error", f"no answer within {resolve_timeout:g} s")
        raise ValueError(f"host {host[:200]!r} does not resolve ({why})")
    for path, what in ((html, "HTML page"), (png, "screenshot")):
        if path is not None:
            check_target(path, what)


def view(*items, robot=None, q=None, joints: dict | None = None, samples: int = 5, seed: int = 1, port: int = 8080,
         host: str = "127.0.0.1", block: bool = True, html: str | None = None, png: str | None = None,
         steps=None, surface=None, room=None, verbose: bool = True, colour_by: str = "reachability",
         serve: bool = True) -> Viewer:
    """Shows maps, explorations, a robot and a room in the browser: each item is a file path (.orsm, .orcm, .bt), a
    SurfaceMap, CapabilityMap, ExplorationMap or an explore() result. `robot`: a Robot (any: from a URDF file,
    example-robot-data, ...) or a name; it defaults to the one a surface map records; its configuration is `q`,
    else the map's reference posture (other arm tucked) or home, with `joints` ({name: value}) set on top.
    `room`: a room file, rooms.Room or Obstacles, drawn (a surface map's samples are checked against it); a
    surface map shows the room it was built with by itself. `steps`: an ExplorationRecorder for an explore()
    result (the map after each view on the view slider). `surface`: the Surface a surface map was built on (its
    slab and boxes are drawn). `colour_by`: a capability map's voxels by "reachability" (D) or "quality" (of their
    cells' stored solutions). `html`/`png` also write the scene as a static page / a screenshot. With no item,
    the robot and the room alone. block=True serves until Ctrl-C; otherwise the running Viewer is returned.
    serve=False writes `html`/`png` and stops the server (its address is not printed); the Viewer is returned
    closed. Bad items and `joints` (an unknown name, a value outside the joint's limits) raise ValueError before
    the address is printed."""
    check_arguments(port, host, samples, html, png)
    loaded = [files.load(item) for item in items]
    if not loaded and robot is None and room is None:
        raise ValueError("nothing to view: give a map file (.orsm, .orcm), a .bt file, a map object, a robot or a room")
    v = Viewer(port=port, host=host, verbose=verbose, announce=False)  # the address once the scene is up
    try:
        _show(v, loaded, robot, q, joints, samples, seed, steps, surface, room, colour_by)
        if html:
            print(f"octoreach: wrote {v.save_html(html)}", flush=True)
        if png:
            print(f"octoreach: wrote {v.screenshot(png)}", flush=True)
    except BaseException:
        v.close()
        raise
    if not serve:
        v.close()
        return v
    if verbose:
        v.announce()
    if block:
        v.wait()
    return v


def _show(v: Viewer, loaded, robot, q, joints, samples, seed, steps, surface, room, colour_by) -> None:
    for kind, obj in loaded:
        if kind == "surface_map":
            v.add_surface_map(obj, robot=robot, samples=samples, seed=seed, q=q, surface=surface, room=room)
        elif kind == "capability_map":
            v.add_capability_map(obj, colour_by=colour_by)
        else:
            v.add_exploration(obj, steps=steps)
    if room is not None and v.room_layer is None:
        v.add_room(room)
    if robot is not None and v.robot_layer is None:
        r = files.robot_by_name(robot) if isinstance(robot, str) else robot
        v.add_robot(r, q=q)
        if not loaded and v.room_layer is None:  # the robot alone: framed
            v.frame_camera(v.robot_layer.points(), distance=1.4)
    if joints and v.robot_layer is not None:
        v.robot_layer.set_configuration(files.with_joints(v.robot_layer.meshes.robot, v.robot_layer.q, joints))
    layer, rl = v.capability_map, v.robot_layer
    other = layer is not None and rl is not None and bool(layer.cap.urdf_hash) and \
        rl.meshes.robot.urdf_hash != layer.cap.urdf_hash
    if other:
        v.note(f"the capability map was built for another robot model ({layer.cap.robot_name!r}) than this "
               f"{rl.meshes.robot.name!r}: its voxels are drawn at this robot's {layer.cap.base_link!r} if it has one, "
               "and say nothing about this robot's reach")
    if layer is not None and rl is not None and rl.meshes.robot.has_link(layer.cap.base_link):
        T = rl.base_pose @ rl.meshes.robot.link_poses(rl.q)[layer.cap.base_link]
        layer.place(T)  # on the robot's arm
        v.frame_camera(layer.centres @ T[:3, :3].T + T[:3, 3])
