"""The work surface in the scene: the map's table or shelf polygon as a slab (triangulated as the C++ Surface does:
any simple polygon), and a Surface's obstacle boxes (table legs, walls) when the Surface itself is given."""
from __future__ import annotations

import numpy as np

from . import colours


def slab(vertices, thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of the polygon (K, 3) extruded `thickness` below its top face (along its normal),
    every face wound outwards. The top and bottom are the polygon's own triangles (``Surface.triangles``: ear
    clipping in C++), right for any simple polygon, an L-shaped counter as well as a convex table."""
    from .._core import Surface

    surface = Surface(np.asarray(vertices, dtype=float).reshape(-1, 3), thickness)
    top = np.asarray(surface.vertices, dtype=float)
    n = np.asarray(surface.normal, dtype=float)
    k = len(top)
    tri = np.array(surface.triangles, dtype=np.int64).reshape(-1, 3)
    a, b, c = top[tri[:, 0]], top[tri[:, 1]], top[tri[:, 2]]
    flip = np.cross(b - a, c - a) @ n < 0  # each triangle counter-clockwise seen from the normal
    tri[flip] = tri[flip][:, ::-1]
    loop = np.arange(k)
    if np.cross(top, np.roll(top, -1, axis=0)).sum(axis=0) @ n < 0:  # the outline clockwise seen from the normal
        loop = loop[::-1]
    v = np.vstack([top, top - thickness * n]).astype(np.float32)
    nxt = np.roll(loop, -1)
    sides = np.vstack([np.column_stack([loop, k + loop, k + nxt]), np.column_stack([loop, k + nxt, nxt])])
    faces = np.vstack([tri, tri[:, ::-1] + k, sides])
    return v, faces.astype(np.uint32)


def top_area(vertices, faces) -> float:
    """Area of the slab's top faces (those facing up): the surface drawn, to compare with the polygon's."""
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    up = cross[:, 2] > 1e-12
    return float(np.linalg.norm(cross[up], axis=1).sum() / 2.0)


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
