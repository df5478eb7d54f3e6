"""Building blocks of the generated scene families, made of the Scene's axis-aligned boxes only (so the
simulator's physical check, the oracle and the camera all see the same solids): boards, open boxes,
boxes with an opening, tilted plates and turned blocks as staircases of thin boxes, round pipes as
rings of thin boxes. None of them records an interior: each family states its own interiors.

Staircases and rings use steps of STEP (1 cm), finer than the exploration's cells (2.5 cm and up), so the
map cannot tell them from the smooth shape.
"""
from __future__ import annotations

import numpy as np

from .._core import Scene

STEP = 0.01  # m: the step of staircases and rings
FACES = ("-x", "+x", "-y", "+y", "-z", "+z")


def add_floor(s: Scene, half: float = 2.0) -> None:
    """The floor every family stands on: a 5 cm slab whose top is z = 0."""
    s.add_box((-half, -half, -0.05), (half, half, 0.0))


def _face_box(lo, hi, wall, face):
    """The board of `face` ("+x", ...) of the box [lo, hi] with walls `wall` thick, as (lo, hi)."""
    a, sign = "xyz".index(face[1]), face[0]
    blo, bhi = np.array(lo, float), np.array(hi, float)
    if sign == "-":
        bhi[a] = lo[a] + wall
    else:
        blo[a] = hi[a] - wall
    return blo, bhi


def add_open_box(s: Scene, lo, hi, wall: float, open_faces=()) -> None:
    """A box of boards `wall` thick inside [lo, hi] with the faces in `open_faces` left out (a crate:
    ("+z",); a square pipe: ("-x", "+x"))."""
    for f in FACES:
        if f not in open_faces:
            s.add_box(*_face_box(lo, hi, wall, f))


def add_box_with_opening(s: Scene, lo, hi, wall: float, face: str, width: float, height: float,
                         offset=(0.0, 0.0)) -> None:
    """A closed box of boards with one rectangular opening (`width` along the face's first free axis,
    `height` along the second, x before y before z) in `face`, centred on the face plus `offset` (m)."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    if face not in FACES:
        raise ValueError(f"face must be one of {FACES}, got {face!r}")
    for f in FACES:
        if f != face:
            s.add_box(*_face_box(lo, hi, wall, f))
    blo, bhi = _face_box(lo, hi, wall, face)
    a = "xyz".index(face[1])
    u, v = [k for k in range(3) if k != a]
    c = (lo + hi) / 2
    h_lo = [c[u] + offset[0] - width / 2, c[v] + offset[1] - height / 2]
    h_hi = [c[u] + offset[0] + width / 2, c[v] + offset[1] + height / 2]
    if h_lo[0] < lo[u] + wall or h_hi[0] > hi[u] - wall or h_lo[1] < lo[v] + wall or h_hi[1] > hi[v] - wall:
        raise ValueError("the opening does not fit inside the face's walls")
    # four boards around the hole: below and above it along v (full width), left and right of it along u
    for (ulo, uhi, vlo, vhi) in ((lo[u], hi[u], lo[v], h_lo[1]), (lo[u], hi[u], h_hi[1], hi[v]),
                                 (lo[u], h_lo[0], h_lo[1], h_hi[1]), (h_hi[0], hi[u], h_lo[1], h_hi[1])):
        if uhi - ulo <= 1e-9 or vhi - vlo <= 1e-9:
            continue
        p, q = blo.copy(), bhi.copy()
        p[u], q[u], p[v], q[v] = ulo, uhi, vlo, vhi
        s.add_box(p, q)


def add_tilted_plate(s: Scene, axis: int, a0: float, a1: float, b0: float, b1: float, z0: float, z1: float,
                     thickness: float) -> None:
    """A plate tilted about a horizontal axis: along world axis `axis` (0: x, 1: y) from a0 to a1 its
    underside rises linearly from z0 to z1; across (the other horizontal axis) it spans b0..b1; `thickness`
    measured vertically. Built as steps of STEP along `axis`, each box reaching from the lower underside of
    its step to the higher top, so no gap opens between steps."""
    n = max(1, int(np.ceil(abs(a1 - a0) / STEP)))
    edges = np.linspace(a0, a1, n + 1)
    under = np.linspace(z0, z1, n + 1)
    other = 1 - axis
    for i in range(n):
        lo, hi = np.zeros(3), np.zeros(3)
        lo[axis], hi[axis] = min(edges[i], edges[i + 1]), max(edges[i], edges[i + 1])
        lo[other], hi[other] = b0, b1
        lo[2], hi[2] = min(under[i], under[i + 1]), max(under[i], under[i + 1]) + thickness
        s.add_box(lo, hi)


def wedge_interiors(axis: int, a0: float, a1: float, b0: float, b1: float, z0: float, z1: float,
                    floor: float = 0.0, strips: int = 8) -> list:
    """(lo, hi) boxes filling the space between `floor` and the underside of add_tilted_plate's plate (same
    arguments): `strips` strips along `axis`, each up to the underside's lowest point over the strip."""
    out = []
    edges = np.linspace(a0, a1, strips + 1)
    under = np.linspace(z0, z1, strips + 1)
    for i in range(strips):
        top = min(under[i], under[i + 1])
        if top - floor <= 1e-6:
            continue
        lo, hi = np.zeros(3), np.zeros(3)
        lo[axis], hi[axis] = min(edges[i], edges[i + 1]), max(edges[i], edges[i + 1])
        lo[1 - axis], hi[1 - axis] = b0, b1
        lo[2], hi[2] = floor, top
        out.append((lo, hi))
    return out


def add_turned_block(s: Scene, center, size, yaw: float, z0: float, z1: float) -> None:
    """A block of footprint `size` (2,) turned by `yaw` (rad) about the vertical through `center` (x, y),
    from z0 to z1: strips of STEP along x, each covering the footprint's extent in y over the strip."""
    c = np.asarray(center, float)
    half = np.asarray(size, float) / 2
    R = np.array([[np.cos(yaw), -np.sin(yaw)], [np.sin(yaw), np.cos(yaw)]])
    corners = np.array([[sx * half[0], sy * half[1]] for sx in (-1, 1) for sy in (-1, 1)]) @ R.T + c
    x_lo, x_hi = corners[:, 0].min(), corners[:, 0].max()
    n = max(1, int(np.ceil((x_hi - x_lo) / STEP)))
    edges = np.linspace(x_lo, x_hi, n + 1)
    for i in range(n):
        ys = _footprint_y(corners, edges[i], edges[i + 1])
        if ys is not None:
            s.add_box((edges[i], ys[0], z0), (edges[i + 1], ys[1], z1))


def _footprint_y(corners, x0: float, x1: float):
    """The y extent of the convex quadrilateral `corners` (4, 2) over the strip x0..x1, or None: its
    corners inside the strip and its edges' crossings of the strip's two sides."""
    ys = [p[1] for p in corners if x0 <= p[0] <= x1]
    ring = corners[[0, 1, 3, 2]]  # around the rectangle
    for p, q in zip(ring, np.roll(ring, -1, axis=0)):
        if abs(q[0] - p[0]) < 1e-12:
            continue
        for x in (x0, x1):
            if min(p[0], q[0]) <= x <= max(p[0], q[0]):
                ys.append(p[1] + (x - p[0]) / (q[0] - p[0]) * (q[1] - p[1]))
    return (min(ys), max(ys)) if ys else None


def add_round_pipe(s: Scene, axis: int, a0: float, a1: float, center, r_in: float, r_out: float) -> None:
    """A round pipe along world axis `axis` (0: x, 1: y) from a0 to a1, its axis through `center`
    ((other horizontal coordinate, z)), inner radius r_in, outer r_out: the ring's cross-section as columns
    of STEP-wide boxes (each column's run(s) between the two circles)."""
    cu, cz = float(center[0]), float(center[1])
    other = 1 - axis
    n = int(np.ceil(2 * r_out / STEP))
    edges = cu - r_out + STEP * np.arange(n + 1)
    for i in range(n):
        u0, u1 = edges[i], min(edges[i + 1], cu + r_out)
        near = min(abs(u0 - cu), abs(u1 - cu)) if (u0 - cu) * (u1 - cu) > 0 else 0.0
        far = max(abs(u0 - cu), abs(u1 - cu))
        if near >= r_out:
            continue
        h_out = np.sqrt(r_out ** 2 - near ** 2)  # the column covers the outer circle over its width
        runs = [(cz - h_out, cz + h_out)]
        if far < r_in:  # the inner circle cuts the column in two
            h_in = np.sqrt(r_in ** 2 - far ** 2)
            runs = [(cz - h_out, cz - h_in), (cz + h_in, cz + h_out)]
        for z0, z1 in runs:
            lo, hi = np.zeros(3), np.zeros(3)
            lo[axis], hi[axis] = a0, a1
            lo[other], hi[other] = u0, u1
            lo[2], hi[2] = max(z0, 0.0), z1
            if hi[2] > lo[2]:
                s.add_box(lo, hi)


def disk_interiors(axis: int, a0: float, a1: float, center, r: float, slabs: int = 6) -> list:
    """(lo, hi) boxes inside a round pipe's bore (add_round_pipe's axis, ends, centre; r its inner radius):
    `slabs` horizontal slabs, each as wide as the bore's narrowest chord over its height."""
    cu, cz = float(center[0]), float(center[1])
    out = []
    zs = np.linspace(cz - r, cz + r, slabs + 1)
    for i in range(slabs):
        far = max(abs(zs[i] - cz), abs(zs[i + 1] - cz))
        half = np.sqrt(max(r ** 2 - far ** 2, 0.0))
        if half <= 1e-6:
            continue
        lo, hi = np.zeros(3), np.zeros(3)
        lo[axis], hi[axis] = a0, a1
        lo[1 - axis], hi[1 - axis] = cu - half, cu + half
        lo[2], hi[2] = max(zs[i], 0.0), zs[i + 1]
        out.append((lo, hi))
    return out
