"""Scene families made of containers and furniture: open crates, closed boxes with openings on any face,
shelves and bookcases, cluttered table tops. Each builder takes a numpy Generator and returns
(scene, target (2, 3), parts); see scene_families for the families' contract.

Everything stands 0.5-1.3 m in front (+x) of the explorer at the origin, inside its arm's reach
(about 1.1 m from its arm base at (0.2, 0, 0.3)).
"""
from __future__ import annotations

import numpy as np

from .._core import Scene
from .scene_parts import add_box_with_opening, add_floor, add_open_box
from .usar_scenes import _place

WALL = 0.02  # m: boards of crates, boxes and shelves


def _cube_at(lo_xy, z, edge) -> np.ndarray:
    """A target cube (2, 3) of `edge` with its lower corner at (lo_xy, z)."""
    lo = np.array([lo_xy[0], lo_xy[1], z], float)
    return np.array([lo, lo + edge])


def _corner_target(rng, inner_lo, inner_hi, edge, near_x: bool) -> np.ndarray:
    """A cube on the floor of the inner box in a corner: against its -x wall (hidden from the robot's side
    by that wall) when `near_x`, else against its +x wall; against its -y or +y wall at random."""
    x = inner_lo[0] if near_x else inner_hi[0] - edge
    y = inner_lo[1] if rng.random() < 0.5 else inner_hi[1] - edge
    return _cube_at((x, y), inner_lo[2], edge)


def open_crates(rng):
    """1-3 open crates (footprints 0.22-0.45 m, 0.12-0.4 m high), some on solid blocks, some with a
    divider; the target in a corner of one crate's floor."""
    s = Scene()
    add_floor(s)
    taken, inners, parts = [], [], []
    for _ in range(int(rng.integers(1, 4))):
        size, h = rng.uniform(0.22, 0.45, size=2), rng.uniform(0.12, 0.4)
        raised = rng.uniform(0.05, 0.2) if rng.random() < 0.3 else 0.0
        spot = _place(rng, size, taken, gap=0.1)
        if spot is None:
            continue
        taken.append(spot)
        if raised:
            s.add_box((*spot[0], 0.0), (*spot[1], raised))
            parts.append(("block", (*spot[0], 0.0), (*spot[1], raised)))
        lo, hi = np.array([*spot[0], raised]), np.array([*spot[1], raised + h])
        add_open_box(s, lo, hi, WALL, ("+z",))
        inner_lo, inner_hi = lo + WALL, hi - np.array([WALL, WALL, 0.0])
        if rng.random() < 0.5:  # a divider across the longer side, not quite as high as the walls
            a = 0 if size[0] > size[1] else 1
            d_lo, d_hi = inner_lo.copy(), inner_hi.copy()
            d_lo[a] = inner_lo[a] + rng.uniform(0.35, 0.65) * (inner_hi[a] - inner_lo[a])
            d_hi[a] = d_lo[a] + WALL
            d_hi[2] = inner_lo[2] + rng.uniform(0.6, 1.0) * (inner_hi[2] - inner_lo[2])
            s.add_box(d_lo, d_hi)
        s.add_interior(inner_lo, inner_hi)
        inners.append((inner_lo, inner_hi))
        parts.append(("crate", lo, hi))
    k = int(rng.integers(len(inners)))
    target = _corner_target(rng, *inners[k], rng.uniform(0.04, 0.07), near_x=rng.random() < 0.5)
    return s, target, parts


def _opening(rng, lo, hi, face):
    """(width, height, offset) of a random opening in `face` of the box [lo, hi]: 6 cm up to 60 % of the
    face, anywhere inside its walls."""
    a = "xyz".index(face[1])
    u, v = [k for k in range(3) if k != a]
    room = [hi[u] - lo[u] - 2 * WALL, hi[v] - lo[v] - 2 * WALL]
    w = rng.uniform(0.06, max(0.061, 0.6 * room[0]))
    h = rng.uniform(0.06, max(0.061, 0.6 * room[1]))
    off = [rng.uniform(-1, 1) * max(0.0, (room[0] - w) / 2), rng.uniform(-1, 1) * max(0.0, (room[1] - h) / 2)]
    return w, h, off


def closed_boxes(rng):
    """1-3 closed boxes (footprints 0.22-0.45 m, 0.18-0.42 m high) with one opening of 6 cm up to 60 % of a
    random face (+x, -x, +y, -y or +z) anywhere on it; some on solid blocks, some with a smaller box on top;
    the target on one box's floor."""
    s = Scene()
    add_floor(s)
    taken, inners, parts = [], [], []
    for _ in range(int(rng.integers(1, 4))):
        size, h = rng.uniform(0.22, 0.45, size=2), rng.uniform(0.18, 0.42)
        spot = _place(rng, size, taken, gap=0.1)
        if spot is None:
            continue
        taken.append(spot)
        z0 = rng.uniform(0.05, 0.2) if rng.random() < 0.3 else 0.0
        if z0:
            s.add_box((*spot[0], 0.0), (*spot[1], z0))
            parts.append(("block", (*spot[0], 0.0), (*spot[1], z0)))
        stack = [(np.array([*spot[0], z0]), np.array([*spot[1], z0 + h]))]
        if rng.random() < 0.25 and z0 + h < 0.45:  # a smaller box on top
            shrink = rng.uniform(0.03, 0.06, size=2)
            top = stack[0][1][2]
            stack.append((np.array([spot[0][0] + shrink[0], spot[0][1] + shrink[1], top]),
                          np.array([spot[1][0] - shrink[0], spot[1][1] - shrink[1], top + rng.uniform(0.15, 0.25)])))
        for lo, hi in stack:
            face = ("+z", "-x", "+y", "-y", "+x")[int(rng.integers(5))]
            w, oh, off = _opening(rng, lo, hi, face)
            add_box_with_opening(s, lo, hi, WALL, face, w, oh, off)
            s.add_interior(lo + WALL, hi - WALL)
            inners.append((lo + WALL, hi - WALL))
            parts.append((f"closed_box {face} {w:.2f}x{oh:.2f}", lo, hi))
    inner_lo, inner_hi = inners[int(rng.integers(len(inners)))]
    edge = rng.uniform(0.04, 0.07)
    xy = inner_lo[:2] + rng.uniform(0, 1, size=2) * np.maximum(inner_hi[:2] - inner_lo[:2] - edge, 0.0)
    target = _cube_at(xy, inner_lo[2], edge)
    return s, target, parts


def _shelf_frame(rng):
    """The local frame of a bookcase: (to_world, facing), to_world((d0, d1), (w0, w1), (z0, z1)) -> (lo, hi)
    with d the depth from the open front (0) inwards and w across it; the front faces the robot (-x) or the
    centre line (+y / -y, standing to the side)."""
    facing = ("-x", "-x", "-x", "+y", "-y")[int(rng.integers(5))]
    if facing == "-x":
        xf, yc = rng.uniform(0.55, 0.8), rng.uniform(-0.25, 0.25)

        def to_world(d, w, z, W):
            return (np.array([xf + d[0], yc - W / 2 + w[0], z[0]]), np.array([xf + d[1], yc - W / 2 + w[1], z[1]]))
    else:
        sign = 1.0 if facing == "+y" else -1.0  # +y: stands at y < 0, its front towards +y
        yf, xc = -sign * rng.uniform(0.25, 0.4), rng.uniform(0.7, 0.95)

        def to_world(d, w, z, W):
            ys = sorted((yf - sign * d[0], yf - sign * d[1]))
            return (np.array([xc - W / 2 + w[0], ys[0], z[0]]), np.array([xc - W / 2 + w[1], ys[1], z[1]]))
    return to_world, facing


def shelves(rng):
    """A bookcase of 1-3 x 1-3 open cubbies (0.16-0.3 m wide, 0.15-0.28 m high, 0.22-0.35 m deep) facing the
    robot or standing to its side, on a solid plinth or on legs, with or without a back, sometimes a door
    standing ajar in front of one cubby; the target in a back corner of one cubby."""
    s = Scene()
    add_floor(s)
    to_world, facing = _shelf_frame(rng)
    cw, ch, depth = rng.uniform(0.16, 0.3), rng.uniform(0.15, 0.28), rng.uniform(0.22, 0.35)
    cols = min(int(rng.integers(1, 4)), int((0.95 - WALL) // (cw + WALL)))
    rows = min(int(rng.integers(1, 4)), int((0.75 - WALL) // (ch + WALL)))
    W, H = cols * (cw + WALL) + WALL, rows * (ch + WALL) + WALL
    plinth, back = rng.random() < 0.5, rng.random() < 0.7
    hb = rng.uniform(0.05, 0.15)
    D = depth + (WALL if back else 0.0)
    box = lambda d, w, z: s.add_box(*to_world(d, w, z, W))  # noqa: E731
    parts = [(f"bookcase {rows}x{cols} facing {facing}", *to_world((0, D), (0, W), (0, hb + H), W))]
    if plinth:
        box((0, D), (0, W), (0, hb))
        parts.append(("plinth", *to_world((0, D), (0, W), (0, hb), W)))
    else:
        for d in ((0, 0.04), (D - 0.04, D)):
            for w in ((0, 0.04), (W - 0.04, W)):
                box(d, w, (0, hb))
    for c in range(cols + 1):  # sides and dividers
        box((0, depth), (c * (cw + WALL), c * (cw + WALL) + WALL), (hb, hb + H))
    for r in range(rows + 1):  # bottom, shelves, top
        box((0, depth), (0, W), (hb + r * (ch + WALL), hb + r * (ch + WALL) + WALL))
    if back:
        box((depth, D), (0, W), (hb, hb + H))
    cubbies = [((0, depth), (c * (cw + WALL) + WALL, (c + 1) * (cw + WALL)),
                (hb + r * (ch + WALL) + WALL, hb + (r + 1) * (ch + WALL))) for r in range(rows) for c in range(cols)]
    for d, w, z in cubbies:
        s.add_interior(*to_world(d, w, z, W))
    if rng.random() < 0.4:  # a door ajar: a board standing a few cm in front of one cubby, covering part of it
        d, w, z = cubbies[int(rng.integers(len(cubbies)))]
        gap, share = rng.uniform(0.02, 0.08), rng.uniform(0.5, 0.85)
        cover = (w[0], w[0] + share * (w[1] - w[0])) if rng.random() < 0.5 else (w[1] - share * (w[1] - w[0]), w[1])
        box((-gap - WALL, -gap), cover, z)
        parts.append(("door", *to_world((-gap - WALL, -gap), cover, z, W)))
    d, w, z = cubbies[int(rng.integers(len(cubbies)))]
    edge = min(rng.uniform(0.04, 0.07), 0.8 * (z[1] - z[0]))
    wt = (w[0], w[0] + edge) if rng.random() < 0.5 else (w[1] - edge, w[1])
    target = np.array(to_world((depth - edge, depth), wt, (z[0], z[0] + edge), W))
    return s, target, parts


def _table_object(rng, s, lo_xy, hi_xy, z, kind):
    """One object on a table top at footprint [lo_xy, hi_xy] standing on z; returns (kind, lo, hi, inner or
    None): the inner box of a container (cup, bowl, box with an opening)."""
    h = {"block": rng.uniform(0.04, 0.2), "book": rng.uniform(0.15, 0.25), "cup": rng.uniform(0.08, 0.14),
         "bowl": rng.uniform(0.05, 0.08), "box": rng.uniform(0.1, 0.18)}[kind]
    lo, hi = np.array([*lo_xy, z]), np.array([*hi_xy, z + h])
    wall = 0.01
    if kind in ("block", "book"):
        s.add_box(lo, hi)
        return kind, lo, hi, None
    if kind in ("cup", "bowl"):
        add_open_box(s, lo, hi, wall, ("+z",))
        return kind, lo, hi, (lo + wall, hi - np.array([wall, wall, 0.0]))
    face = ("+z", "-x", "+y", "-y", "+x")[int(rng.integers(5))]
    a = "xyz".index(face[1])
    u, v = [k for k in range(3) if k != a]
    size = hi - lo - 2 * wall
    add_box_with_opening(s, lo, hi, wall, face, rng.uniform(0.4, 0.8) * size[u], rng.uniform(0.4, 0.8) * size[v])
    return kind, lo, hi, (lo + wall, hi - wall)


def table_tops(rng):
    """A table (0.5-0.75 x 0.6-1.0 m, 0.3-0.5 m high) with 4-7 objects on it: blocks, standing books, cups,
    bowls and small boxes with an opening; the interior is the layer of clutter above the top, the target
    inside a container or behind a tall object. The search space is that layer (a "search_space" part): the
    robot searches the table, not the floor under it."""
    s = Scene()
    add_floor(s)
    size = np.array([rng.uniform(0.5, 0.75), rng.uniform(0.6, 1.0)])
    x0, yc, ht = rng.uniform(0.5, 0.6), rng.uniform(-0.2, 0.2), rng.uniform(0.3, 0.5)
    t_lo, t_hi = np.array([x0, yc - size[1] / 2]), np.array([x0 + size[0], yc + size[1] / 2])
    s.add_box((*t_lo, ht - 0.03), (*t_hi, ht))
    for x in ((t_lo[0], t_lo[0] + 0.04), (t_hi[0] - 0.04, t_hi[0])):
        for y in ((t_lo[1], t_lo[1] + 0.04), (t_hi[1] - 0.04, t_hi[1])):
            s.add_box((x[0], y[0], 0.0), (x[1], y[1], ht - 0.03))
    objects, taken = [], []
    for _ in range(int(rng.integers(4, 8))):
        kind = ("block", "book", "cup", "bowl", "box")[int(rng.integers(5))]
        fp = {"block": rng.uniform(0.04, 0.15, 2), "book": np.array([rng.uniform(0.02, 0.04), rng.uniform(0.12, 0.2)]),
              "cup": rng.uniform(0.06, 0.1, 2), "bowl": rng.uniform(0.12, 0.2, 2), "box": rng.uniform(0.12, 0.22, 2)}[kind]
        if kind == "book" and rng.random() < 0.5:
            fp = fp[::-1]
        spot = _place_in(rng, fp, taken, t_lo + 0.03, t_hi - 0.03)
        if spot is not None:
            taken.append(spot)
            objects.append(_table_object(rng, s, spot[0], spot[1], ht, kind))
    top = max([o[2][2] for o in objects] + [ht + 0.1])
    s.add_interior((*t_lo, ht), (*t_hi, top))
    edge = rng.uniform(0.03, 0.05)
    inners = [o[3] for o in objects if o[3] is not None and np.all(o[3][1][:2] - o[3][0][:2] > edge)]
    if inners and rng.random() < 0.6:
        lo, hi = inners[int(rng.integers(len(inners)))]
        target = _cube_at(lo[:2] + rng.uniform(0, 1, 2) * (hi[:2] - lo[:2] - edge), lo[2], edge)
    else:  # behind the tallest object, on its far (+x) side
        _, lo, hi, _ = max(objects, key=lambda o: o[2][2]) if objects else ("", (*t_lo, ht), (*t_lo, ht), None)
        x = min(hi[0] + 0.005, t_hi[0] - edge)
        target = _cube_at((x, (lo[1] + hi[1]) / 2 - edge / 2), ht, edge)
    # the robot searches the table top: the layer above it, 5 cm around (scene_region's margin), not the floor under it
    search = ("search_space", (*(t_lo - 0.05), ht - 0.03), (*(t_hi + 0.05), top + 0.05))
    return s, target, [(o[0], o[1], o[2]) for o in objects] + [("table", (*t_lo, 0.0), (*t_hi, ht)), search]


def _place_in(rng, size_xy, taken, lo, hi, gap: float = 0.03, tries: int = 100):
    """A random spot (lo, hi in x, y) of `size_xy` inside [lo, hi] keeping `gap` from `taken`, or None."""
    for _ in range(tries):
        p = rng.uniform(lo, np.maximum(lo, hi - size_xy))
        q = p + size_xy
        if np.all(q <= hi) and all(p[0] >= b[1][0] + gap or q[0] <= b[0][0] - gap or p[1] >= b[1][1] + gap
                                   or q[1] <= b[0][1] - gap for b in taken):
            return p, q
    return None
