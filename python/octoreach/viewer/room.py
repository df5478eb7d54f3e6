"""The room in the scene: every obstacle of a room drawn from its Shape (boxes with their pose, cylinders, spheres,
meshes from their triangles, OctoMaps as cells), whether it comes from a surface map (``SurfaceMap.room``, the room
the map was built with), a room file, a ``rooms.Room`` or an ``Obstacles``.

One mesh node per colour (the map's own surface, the rest of the room) keeps the draw calls few; OctoMaps are one
batched node of cells each.
"""
from __future__ import annotations

import os

import numpy as np

from . import cells, colours, mesh_files

#: Opacity of the room's obstacles other than the map's surface: walls and cabinets between the camera and the
#: robot leave it visible.
ROOM_OPACITY = 0.8


def room_obstacles(room):
    """(Obstacles, surface_count, label) of a room given as a MapRoom (its first surface_count obstacles are its
    map's surface), a rooms.Room or a room file path (its working surfaces first), or an Obstacles."""
    from .._core import MapRoom, Obstacles

    if isinstance(room, MapRoom):
        return room.obstacles, room.surface_count, "the room the map was built with"
    if isinstance(room, Obstacles):
        return room, 0, "the given room"
    from .. import room_checks

    from ..rooms import Room

    label = os.fspath(room) if isinstance(room, (str, os.PathLike)) else "the given room"
    if isinstance(room, (str, os.PathLike)):
        room = Room.load(room)
    if isinstance(room, Room):  # its working surfaces (boards, tops, their legs and boxes) come first
        return room.obstacles(), sum(len(s.obstacles()) for s in room.surfaces.values()), label
    return room_checks.scene_obstacles(room), 0, label


class RoomLayer:
    """A room's obstacles under a frame node `name`: `surface` (the first `surface_count` obstacles: the map's own
    surface, or a room's working surfaces, with their legs and boxes) and `obstacles` (the rest) as meshes,
    `octomap_<i>` as cells."""

    def __init__(self, scene, obstacles, surface_count: int = 0, name: str = "/room"):
        self.scene, self.name = scene, name
        self.root = scene.add_frame(name, show_axes=False)
        self.names = list(obstacles.names)
        parts: dict[str, list] = {"surface": [], "obstacles": []}
        self.handles: dict[str, object] = {}
        points = []
        for i, shape in enumerate(obstacles.shapes):
            if shape.kind == "octree":
                points.append(self._octree(shape, f"{name}/octomap_{len(self.handles)}"))
                continue
            mesh = mesh_files.shape_mesh(shape)
            if mesh is not None and len(mesh.faces):
                parts["surface" if i < surface_count else "obstacles"].append(mesh)
        for key, meshes in parts.items():
            if not meshes:
                continue
            mesh = mesh_files.concatenate(meshes)
            points.append(mesh.vertices)
            self.handles[key] = scene.add_mesh_simple(
                f"{name}/{key}", np.asarray(mesh.vertices, np.float32), np.asarray(mesh.faces, np.uint32),
                color=colours.SURFACE if key == "surface" else colours.ROOM, side="double", flat_shading=True,
                cast_shadow=False, opacity=None if key == "surface" else ROOM_OPACITY)
        self.points = np.vstack(points) if points else np.zeros((0, 3))

    def _octree(self, shape, node: str) -> np.ndarray:
        centres, edges = shape.octree_cells()
        T = np.asarray(shape.pose, float)
        world = np.asarray(centres, float) @ T[:3, :3].T + T[:3, 3]  # cells drawn upright at their centres
        if not len(world):
            return world
        edge = float(np.min(edges))
        colour = np.tile(np.array(colours.OCCUPIED, np.uint8), (len(world), 1))
        self.handles[node.rsplit("/", 1)[1]] = cells.add_cells(self.scene, node, world, colour, edge,
                                                              scales=np.asarray(edges, float) / edge)
        return world

    @property
    def visible(self) -> bool:
        return bool(self.root.visible)

    @visible.setter
    def visible(self, value: bool) -> None:
        self.root.visible = bool(value)


def draw_surroundings(viewer, smap, surface=None, room=None, thickness: float = 0.03):
    """What stands around a surface map's cells: its surface and room, drawn in `viewer`. `surface`: the Surface
    the map was built on (its slab and boxes); `room`: a room (file, Room, Obstacles) to draw instead of the
    one the map records (a room that differs from it is said); else the map's own room; a map that records
    none (a file written before maps recorded their room): its polygon as a slab, and a note.
    Returns (points to frame the camera on, the sampler's in_collision or None for the map's own room check)."""
    from .surfaces import add_boxes, add_surface

    polygon = np.asarray(smap.polygon if surface is None else surface.vertices, float)
    if surface is not None:
        add_surface(viewer.scene, polygon, float(surface.thickness))
        add_boxes(viewer.scene, surface.boxes)
    if room is not None:
        obstacles, count, label = room_obstacles(room)
        viewer.room_layer = RoomLayer(viewer.scene, obstacles, count)
        found = [] if smap.room.empty else list(smap.room.differences(obstacles))
        if found:
            viewer.note(f"{label} differs from the room the map was built with ({len(found)} difference"
                        f"{'s' if len(found) > 1 else ''}, e.g. {found[0]}): drawn and sampled against {label}")
        if surface is None and len(polygon) >= 3:  # the map's surface among the room's: its top, lifted a little
            add_surface(viewer.scene, polygon + [0.0, 0.0, 0.002], 0.002)
        return np.vstack([polygon, viewer.room_layer.points]), obstacles
    if surface is None and not smap.room.empty:
        viewer.room_layer = RoomLayer(viewer.scene, smap.room.obstacles, smap.room.surface_count)
        return np.vstack([polygon, viewer.room_layer.points]), None
    if surface is None and len(polygon) >= 3:
        add_surface(viewer.scene, polygon, thickness)
        viewer.note("the surface map records no room (a file written before maps recorded theirs): its surface is "
                    f"drawn as a {thickness * 100:.0f} cm slab, without the obstacles it was built with; give the room "
                    "(--scene ROOM, or view(..., room=...)) to draw them")
    return polygon, None
