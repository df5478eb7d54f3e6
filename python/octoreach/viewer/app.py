"""The viewer: a viser server holding the scene (robot, surface, maps, samples, exploration) and its controls.

    v = Viewer()                      # serves http://127.0.0.1:8080 (the next free port if taken)
    v.add_surface_map(smap, robot=octoreach.robots.pr2())
    v.wait()                          # until Ctrl-C

``view(*items, ...)`` does the same for files and objects in one call (``octoreach view`` on the command line).
"""
from __future__ import annotations

import contextlib
import io
import sys
import threading
import time

import numpy as np

from . import files
from .capability_map import COLOUR_BY, CapabilityMapLayer
from .exploration import ExplorationLayer
from .robot_meshes import RobotLayer, RobotMeshes
from .samples import SamplesLayer, sample_poses
from .surface_map import BEST, SurfaceMapLayer
from .room import RoomLayer, draw_surroundings, room_obstacles


def _import_viser():
    try:
        import viser
    except ImportError:
        raise RuntimeError("the viewer needs viser: pip install 'octoreach[viewer]'") from None
    return viser


class Viewer:
    """A running viewer. Layers are added with the add_* methods; `selected` holds the last clicked cell."""

    def __init__(self, port: int = 8080, host: str = "127.0.0.1", verbose: bool = True, announce: bool = True):
        """verbose: print notes (and, with announce, the address as soon as the server runs)."""
        viser = _import_viser()
        with contextlib.redirect_stdout(io.StringIO()):  # viser's banner: the URL is printed below
            self.server = viser.ViserServer(host=host, port=port, verbose=False)
        self.server.gui.configure_theme(control_width="medium", show_share_button=False)
        self.scene = self.server.scene
        self.url = f"http://{host}:{self.server.get_port()}"
        self.verbose = verbose
        if verbose and announce:
            self.announce()
        self.notes: list[str] = []
        self.robot_layer = None
        self.room_layer = None
        self.surface_map = None
        self.capability_map = None
        self.exploration = None
        self.samples = None
        self.selected: dict | None = None
        self._clicked = threading.Event()
        self._info = self.server.gui.add_markdown("Click a cell to see its value.")
        self.scene.set_up_direction("+z")
        # No image-based light: building its environment map takes seconds on software WebGL (headless
        # browsers, machines without a GPU); viser's default lights shade the scene.
        self.scene.configure_environment_map(None)
        self.scene.add_light_hemisphere("/lights/sky", intensity=1.1)
        self.scene.configure_default_lights(cast_shadow=False)  # shadow maps streak the small cells

    # -- layers --------------------------------------------------------------------------------------
    def add_robot(self, robot, q=None, base_pose=None) -> RobotLayer:
        """Any Robot's visual meshes (Robot.visuals, else its collision shapes) at configuration q (default home)
        with its root link at base_pose (4x4)."""
        meshes = RobotMeshes(robot)
        if meshes.missing:
            self.note(f"{len(meshes.missing)} visual mesh file(s) of {robot.name!r} not found (e.g. "
                      f"{meshes.missing[0]!r}): those links are drawn with their collision shapes")
        self.robot_layer = RobotLayer(self.scene, meshes, q=q, base_pose=base_pose)
        return self.robot_layer

    def add_surface_map(self, smap, robot=None, samples: int = 5, seed: int = 1, q=None, surface=None,
                        surface_thickness=0.03, room=None):
        """A surface map: its surface and room, cells (theta slider), `samples` sampled poses and the robot standing
        at the first of them (robot: a Robot, a name, or None for the robot the map was built for). The room is the
        one the map was built with (SurfaceMap.room), or `room` (a room file, rooms.Room or Obstacles: drawn, and
        the samples checked against it; one that differs from the map's is said); `surface`: the Surface the map
        was built on, to draw its slab and boxes. A map file written before maps recorded their room shows its
        polygon as a slab `surface_thickness` thick, and the viewer says so."""
        frame, in_collision = draw_surroundings(self, smap, surface=surface, room=room, thickness=surface_thickness)
        self.surface_map = SurfaceMapLayer(self.scene, smap, atomic=self.server.atomic)
        self._watch_surface_clicks(self.surface_map)
        if isinstance(robot, str):
            robot = files.robot_by_name(robot)
        elif robot is None and smap.robot_name:  # the map's own robot, when it can be found
            try:
                robot = files.robot_by_name(smap.robot_name, smap.urdf_hash)
            except (ValueError, OSError):
                self.note(f"the map's robot {smap.robot_name!r} is neither the project's nor example-robot-data's: "
                          "drawn without it (give --urdf FILE or --robot NAME, or robot= in Python)")
        if robot is not None:
            if smap.urdf_hash and robot.urdf_hash != smap.urdf_hash:
                print(f"octoreach: warning: the map was built for another robot model ({smap.robot_name}) than "
                      f"{robot.name}'s URDF", file=sys.stderr)
            q = files.reference_posture(robot, smap) if q is None else q
            self.add_robot(robot, q=q)
        if smap.voxel_count == 0:
            print(f"octoreach: warning: empty surface map: {smap.empty_reason}", file=sys.stderr)
            samples = 0
        footprint = self.robot_layer.meshes.footprint(self.robot_layer.q) if self.robot_layer else \
            np.array([[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]])
        if in_collision is None and smap.room.empty:  # an old file: the robot against the surface, when known
            from .._core import Surface

            in_collision = (surface if surface is not None else Surface(smap.polygon, surface_thickness)).obstacles()
        if not smap.room.body and in_collision is not None:
            in_collision = (robot, in_collision, self.robot_layer.q) if self.robot_layer else None
        poses, rs = sample_poses(smap, samples, seed=seed, in_collision=in_collision)
        layer = self.surface_map
        # Outlines and arrows just above the tiles, which lie on the floor (below a pose's z when the robot's
        # reference frame is above its feet: lift < 0 then).
        top = float(layer.drawn_centres[:, 2].max() + layer.tile_height / 2) if len(layer.centres) else 0.0
        lift = top - (float(poses[:, 2].min()) if len(poses) else 0.0) + 0.02
        self.samples = SamplesLayer(self.scene, poses, rs, footprint, lift=lift)
        if len(poses):
            self.server.gui.add_markdown(self.samples.table())
        if self.robot_layer is not None and len(poses):
            self.stand(poses[0], smap.reference_frame)
        self._surface_controls(smap)
        drawn = self.surface_map.drawn_centres
        self.frame_camera(np.vstack([frame, drawn]) if len(frame) else drawn)
        return self.surface_map

    def add_room(self, room):
        """A room on its own (a room file, rooms.Room, Obstacles or a SurfaceMap's MapRoom): every obstacle drawn."""
        obstacles, count, _ = room_obstacles(room)
        self.room_layer = RoomLayer(self.scene, obstacles, count)
        if len(self.room_layer.points):
            self.frame_camera(self.room_layer.points)
        return self.room_layer

    def add_capability_map(self, cap, base_pose=None, colour_by: str = "reachability"):
        """A capability map's voxels (arm base frame at base_pose) with a slice-plane slider; coloured by
        "reachability" (D) or "quality" (of the cells' stored solutions), with a selector when the map has quality."""
        self.capability_map = layer = CapabilityMapLayer(self.scene, cap, base_pose=base_pose, colour_by=colour_by)
        lo, hi = layer.z_range
        step = float(cap.resolution)
        slider = self.server.gui.add_slider("slice z (m)", min=lo, max=max(hi, lo + step), step=step, initial_value=layer.z)

        @slider.on_update
        def _(_event) -> None:
            layer.cut(slider.value)
            self._watch_clicks(layer)  # cut() makes a new node

        if cap.has_quality:
            choice = self.server.gui.add_dropdown("colour by", options=COLOUR_BY, initial_value=colour_by)

            @choice.on_update
            def _(_event) -> None:
                layer.recolour(choice.value)
                self._watch_clicks(layer)

        self._watch_clicks(layer)
        self.frame_camera(layer.centres)
        return layer

    def add_exploration(self, source, steps=None):
        """An ExplorationMap (or an explore() result, or a .bt path) with a slider over its views; `steps`: an
        ExplorationRecorder passed to explore(on_view=...) for the map as it was after each view."""
        self.exploration = layer = ExplorationLayer(self.scene, files.exploration_map(source), steps=steps)
        for key, handles in layer.layers.items():
            if not handles:
                continue
            box = self.server.gui.add_checkbox(key, initial_value=bool(handles[0].visible))
            box.on_update(lambda _e, key=key, box=box: layer.set_visible(key, box.value))
        if layer.frusta:
            slider = self.server.gui.add_slider("view", min=0, max=max(len(layer.frusta) - 1, 1), step=1,
                                                initial_value=len(layer.frusta) - 1)

            self._view_slider = slider

            @slider.on_update
            def _(_event) -> None:
                self._info.content = layer.step(int(slider.value))

        occupied = np.asarray(layer.map.cells("occupied"), float).reshape(-1, 3)
        views = np.array([T[:3, 3] for T in layer.poses]).reshape(-1, 3)
        self.frame_camera(np.vstack([occupied, views, np.zeros((0 if len(occupied) else 1, 3))]), distance=1.3)
        return layer

    def note(self, text: str) -> None:
        """Says something about what the scene shows (or leaves out): in the control panel and on stderr."""
        self.notes.append(text)
        self.server.gui.add_markdown(f"*Note: {text}.*")
        if self.verbose:
            print(f"octoreach: note: {text}", file=sys.stderr, flush=True)

    # -- interaction ---------------------------------------------------------------------------------
    def show_view(self, view: int) -> None:
        """Steps the exploration to view `view` (as its slider does)."""
        if getattr(self, "_view_slider", None) is not None:
            self._view_slider.value = view
        self._info.content = self.exploration.step(int(view))

    def stand(self, pose4, reference_frame: str | None = None) -> None:
        """Moves the robot so that its reference frame (default: root link) is at base pose (x, y, z, theta)."""
        from .._core import base_pose

        layer = self.robot_layer
        T = base_pose(np.asarray(pose4, float))
        robot = layer.meshes.robot
        if reference_frame and reference_frame != robot.root_link:
            T = T @ np.linalg.inv(robot.link_poses(layer.q)[reference_frame])
        layer.set_base_pose(T)

    def select_cell(self, index: int) -> dict:
        """What a click on surface-map cell `index` (an index into the layer's centres, as the click's instance
        index) does: report its R_S and stand the robot there."""
        layer = self.surface_map
        pose = layer.cell_pose(index)
        rs = layer.reachability(index)
        self.selected = {"kind": "surface_map", "index": int(index), "pose": pose, "rs": rs}
        self._info.content = (f"**R_S = {rs:.3f}** at x = {pose[0]:+.2f} m, y = {pose[1]:+.2f} m, "
                              f"z = {pose[2]:.2f} m, theta = {np.degrees(pose[3]):.1f} deg")
        if self.robot_layer is not None:
            self.stand(pose, self.surface_map.smap.reference_frame)
        self._clicked.set()
        return self.selected

    def _select_voxel(self, instance: int) -> dict:
        layer = self.capability_map
        index = layer.voxel(instance)
        value = layer.value(index)
        c = layer.centres[index]
        self.selected = {"kind": "capability_map", "index": index, "centre": c, "value": value}
        self._info.content = f"**reachability index = {value:.3f}** at {np.round(c, 3).tolist()}"
        self._clicked.set()
        return self.selected

    def _watch_clicks(self, layer) -> None:
        @layer.handle.on_click
        def _(event) -> None:
            if event.instance_index is not None:
                self._select_voxel(int(event.instance_index))

    def _watch_surface_clicks(self, layer) -> None:
        for k, handle in layer.handles.items():
            @handle.on_click
            def _(event, k=k) -> None:
                if event.instance_index is not None:
                    index = layer.cell_of(k, int(event.instance_index))
                else:
                    index = layer.pick(event.ray_origin, event.ray_direction)
                if index is not None:
                    self.select_cell(int(index))

    def _surface_controls(self, smap) -> None:
        gui = self.server.gui
        best = gui.add_checkbox("best theta", initial_value=True)
        bins = smap.theta_bins
        theta = gui.add_slider("theta (deg)", min=0.0, max=360.0 * (bins - 1) / bins, step=360.0 / bins,
                               initial_value=0.0, disabled=True)

        def update(_event) -> None:
            theta.disabled = best.value
            self.show_theta(BEST if best.value else int(round(theta.value * bins / 360.0)) % bins)

        best.on_update(update)
        theta.on_update(update)
        self._theta_controls = (best, theta)

    def show_theta(self, theta_bin: int) -> float:
        """Shows the surface map at theta bin `theta_bin` (BEST = -1: best theta); returns the seconds taken."""
        t = time.perf_counter()
        self.surface_map.show(theta_bin)
        return time.perf_counter() - t

    def frame_camera(self, points, distance: float = 1.0) -> None:
        """Initial camera: looking at the points' box from the front left, `distance` times its diagonal."""
        pts = np.asarray(points, float).reshape(-1, 3)
        if not len(pts):
            return
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        centre = (lo + hi) / 2
        extent = float(max(np.linalg.norm(hi - lo), 1.0))
        cam = self.server.initial_camera
        cam.look_at = tuple(centre)
        cam.position = tuple(centre + np.array([-0.45, -0.65, 0.55]) * extent * distance)
        cam.up = (0.0, 0.0, 1.0)
        cam.fov = np.radians(50)

    # -- life ----------------------------------------------------------------------------------------
    def has_node(self, name: str) -> bool:
        """Whether the scene tree holds a node `name` (as the server holds it)."""
        return self.scene.get_handle_by_name(name) is not None

    def wait_for_click(self, timeout: float) -> dict | None:
        """Waits up to `timeout` s for the next cell click; returns `selected` (None on timeout)."""
        hit = self._clicked.wait(timeout)
        self._clicked.clear()
        return self.selected if hit else None

    def save_html(self, path) -> str:
        from .export import save_html

        return save_html(self, path)

    def screenshot(self, path, width: int = 1280, height: int = 800) -> str:
        from .browser import Browser

        with Browser(width, height) as b:
            b.open(self.url, self)
            return b.screenshot(path)

    def wait(self) -> None:
        """Serves until Ctrl-C."""
        try:
            while True:
                time.sleep(1.0)
        except KeyboardInterrupt:
            pass
        finally:
            self.close()

    def announce(self) -> None:
        """Prints the viewer's address."""
        print(f"octoreach: viewer at {self.url}", flush=True)

    def close(self) -> None:
        with contextlib.redirect_stdout(io.StringIO()):  # viser's "Server stopped"
            self.server.stop()
