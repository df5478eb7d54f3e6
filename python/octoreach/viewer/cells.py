"""Coloured cubes for voxels: one batched mesh per layer (one draw call), and ray picking of its cells."""
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


def add_cells(scene, name: str, centres: np.ndarray, colours: np.ndarray, edge: float, height=None, opacity=None):
    """A batched mesh of boxes (edge x edge x height, default cubes) at `centres` with per-box `colours`;
    click events carry the box's index as `instance_index`."""
    v, f = cube(edge, height)
    centres = np.asarray(centres, dtype=np.float32).reshape(-1, 3)
    n = len(centres)
    wxyz = np.tile(np.array([1.0, 0.0, 0.0, 0.0], dtype=np.float32), (n, 1))
    return scene.add_batched_meshes_simple(name, v, f, batched_wxyzs=wxyz, batched_positions=centres,
                                           batched_colors=np.asarray(colours, dtype=np.uint8).reshape(-1, 3),
                                           lod="off", opacity=opacity, cast_shadow=False,
                                           receive_shadow=False)


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
