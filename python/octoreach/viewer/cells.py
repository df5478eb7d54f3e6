"""Coloured cubes for voxels: one batched mesh per layer (one draw call), the outer shell of a voxel set (what
can be seen of it), and ray picking of its cells."""
from __future__ import annotations

import numpy as np


def cube(edge: float, height: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (8, 3) and triangles (12, 3) of an axis-aligned box edge x edge x height (default: a cube),
    centred at 0."""
    h, hz = edge / 2.0, (edge if height is None else height) / 2.0
    v = np.array([[x, y, z] for x in (-h, h) for y in (-h, h) for z in (-hz, hz)], dtype=np.float32)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]], dtype=np.uint32)
    return v, f


def tile(edge: float, height: float) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (4, 3) and triangles (2, 3, facing +z) of the top face of a box edge x edge x height centred at
    0: a cell seen from above in a sixth of a box's triangles (a software-rendered frame's cost grows with
    them)."""
    h = edge / 2.0
    v = np.array([[-h, -h, 0], [h, -h, 0], [h, h, 0], [-h, h, 0]], dtype=np.float32)
    v[:, 2] = height / 2.0
    return v, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)


def add_cells(scene, name: str, centres: np.ndarray, colours: np.ndarray, edge: float, height=None, opacity=None,
              scales=None, visible: bool = True, top_only: bool = False):
    """A batched mesh of boxes (edge x edge x height, default cubes; `top_only`: their top faces alone) at
    `centres` with per-box `colours` and optional per-box `scales` (N,) (0 hides a box without re-sending the
    others); click events carry the box's index as `instance_index`."""
    v, f = tile(edge, edge if height is None else height) if top_only else cube(edge, height)
    centres = np.asarray(centres, dtype=np.float32).reshape(-1, 3)
    n = len(centres)
    wxyz = np.tile(np.array([1.0, 0.0, 0.0, 0.0], dtype=np.float32), (n, 1))
    return scene.add_batched_meshes_simple(name, v, f, batched_wxyzs=wxyz, batched_positions=centres,
                                           batched_scales=None if scales is None else np.asarray(scales, np.float32),
                                           batched_colors=np.asarray(colours, dtype=np.uint8).reshape(-1, 3),
                                           lod="off", opacity=opacity, cast_shadow=False,
                                           receive_shadow=False, visible=visible)


def grid_keys(centres: np.ndarray, edge: float) -> np.ndarray:
    """Integer grid coordinates (N, 3) of voxel centres on a grid of `edge` (from their minimum)."""
    c = np.asarray(centres, dtype=float).reshape(-1, 3)
    if not len(c):
        return np.zeros((0, 3), dtype=np.int64)
    return np.round((c - c.min(axis=0)) / edge).astype(np.int64)


def shell(keys: np.ndarray) -> np.ndarray:
    """Mask of the voxels (integer grid keys (N, 3), distinct) with at least one of their six face neighbours
    missing from the set: the only ones that can be seen from outside it."""
    keys = np.asarray(keys, dtype=np.int64).reshape(-1, 3)
    if not len(keys):
        return np.zeros(0, dtype=bool)
    k = keys - keys.min(axis=0) + 1  # a free layer around the set
    grid = np.zeros(tuple(k.max(axis=0) + 2), dtype=bool)
    grid[k[:, 0], k[:, 1], k[:, 2]] = True
    inner = np.ones(len(k), dtype=bool)
    for axis in range(3):
        for step in (-1, 1):
            n = k.copy()
            n[:, axis] += step
            inner &= grid[n[:, 0], n[:, 1], n[:, 2]]
    return ~inner


def first_hit(origin, direction, centres: np.ndarray, edge: float, height=None) -> int | None:
    """Index of the first box (centre, edge x edge x height) hit by the ray, or None (slab test on every box)."""
    if len(centres) == 0:
        return None
    o = np.asarray(origin, dtype=float)
    d = np.asarray(direction, dtype=float)
    d = np.where(np.abs(d) < 1e-12, 1e-12, d)
    half = np.array([edge, edge, edge if height is None else height]) / 2.0
    lo = (centres - half - o) / d
    hi = (centres + half - o) / d
    t_near = np.minimum(lo, hi).max(axis=1)
    t_far = np.maximum(lo, hi).min(axis=1)
    hit = (t_near <= t_far) & (t_far >= 0)
    if not hit.any():
        return None
    t = np.where(hit, t_near, np.inf)
    return int(np.argmin(t))
