"""The work surface in the scene: the map's table or shelf polygon as a slab, and a Surface's obstacle boxes
(table legs, walls) when the Surface itself is given (map files record the polygon only)."""
from __future__ import annotations

import numpy as np

from . import colours


def slab(vertices, thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of the polygon (K, 3) extruded `thickness` downwards, every face wound outwards
    (fan triangulation: exact for convex polygons, which is what surfaces are in practice)."""
    top = np.asarray(vertices, dtype=float).reshape(-1, 3)
    x, y = top[:, 0], top[:, 1]
    if np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)) < 0:  # clockwise seen from above: turn it round
        top = top[::-1]
    k = len(top)
    bottom = top - np.array([0.0, 0.0, thickness])
    v = np.vstack([top, bottom]).astype(np.float32)
    faces = []
    for i in range(1, k - 1):
        faces.append([0, i, i + 1])
        faces.append([k, k + i + 1, k + i])
    for i in range(k):
        j = (i + 1) % k
        faces.append([i, k + i, k + j])
        faces.append([i, k + j, j])
    return v, np.array(faces, dtype=np.uint32)


def add_surface(scene, vertices, thickness: float = 0.03, name: str = "/surface"):
    """Adds the surface polygon as a slab; returns the handle. Its faces are wound outwards, so it needs no
    double-sided material (and shares the robot meshes' shader program: one compile less for the browser)."""
    v, f = slab(vertices, thickness)
    return scene.add_mesh_simple(name, v, f, color=colours.SURFACE, cast_shadow=False)


def add_boxes(scene, boxes, name: str = "/surface/boxes") -> list:
    """Adds a Surface's obstacle boxes ((size (3,), pose (4, 4)) pairs, ``Surface.boxes``); returns the handles."""
    import viser.transforms as tf

    handles = []
    for i, (size, pose) in enumerate(boxes):
        T = np.asarray(pose, float)
        handles.append(scene.add_box(f"{name}/{i}", color=colours.SURFACE, dimensions=tuple(map(float, size)),
                                     wxyz=tf.SO3.from_matrix(T[:3, :3]).wxyz, position=T[:3, 3],
                                     cast_shadow=False))
    return handles
