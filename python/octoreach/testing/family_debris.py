"""Scene families of collapsed structure: pipes and tunnels, collapsed slabs and wedges, USAR-like rubble
piles. Each builder takes a numpy Generator and returns (scene, target (2, 3), parts); see scene_families
for the families' contract. Tilted plates and turned blocks are staircases of thin boxes (scene_parts).
"""
from __future__ import annotations

import numpy as np

from .._core import Scene
from .scene_parts import (add_floor, add_open_box, add_round_pipe, add_tilted_plate, add_turned_block,
                          disk_interiors, wedge_interiors)

WALL = 0.02


def _along(axis, a, u, z):
    """(lo, hi) of a box given its extent `a` along world `axis` (0: x, 1: y), `u` along the other
    horizontal axis and `z`."""
    lo, hi = np.zeros(3), np.zeros(3)
    lo[axis], hi[axis] = a
    lo[1 - axis], hi[1 - axis] = u
    lo[2], hi[2] = z
    return lo, hi


def _pipe_span(rng, length):
    """(axis, (a0, a1), u): a pipe of `length` along x (in front of the robot, off its centre line) or along
    y (across its view), inside the arm's reach."""
    axis = int(rng.integers(2))
    if axis == 0:
        a0 = rng.uniform(0.5, 1.2 - length)
        return axis, (a0, a0 + length), rng.uniform(-0.45, 0.45)
    a0 = rng.uniform(-0.55, 0.55 - length)
    return axis, (a0, a0 + length), rng.uniform(0.6, 1.0)


def pipes(rng):
    """A round pipe (bore 12-24 cm), a square duct (10-20 cm) or a tunnel (walls and a roof on the floor),
    0.4-0.7 m long, along x or y, on the floor or on two blocks, open at both ends or capped at one; the
    target inside, 30-70 % along it."""
    s = Scene()
    add_floor(s)
    kind = ("round", "square", "tunnel")[int(rng.integers(3))]
    length = rng.uniform(0.4, 0.7)
    axis, (a0, a1), u = _pipe_span(rng, length)
    lift = rng.uniform(0.05, 0.15) if kind != "tunnel" and rng.random() < 0.3 else 0.0
    if kind == "round":
        r_in = rng.uniform(0.06, 0.12)
        r_out = r_in + 0.015
        cz = lift + r_out
        add_round_pipe(s, axis, a0, a1, (u, cz), r_in, r_out)
        interiors = disk_interiors(axis, a0, a1, (u, cz), r_in)
        bore = _along(axis, (a0, a1), (u - r_in, u + r_in), (cz - r_in, cz + r_in))
        floor_z, half_w = cz - 0.8 * r_in, 0.55 * r_in  # the target sits low in the bore, clear of the ring
    else:
        w, h = rng.uniform(0.1, 0.2), rng.uniform(0.1, 0.2)
        lo, hi = _along(axis, (a0, a1), (u - w / 2 - WALL, u + w / 2 + WALL), (lift, lift + h + 2 * WALL))
        open_faces = ("-" + "xy"[axis], "+" + "xy"[axis]) + (("-z",) if kind == "tunnel" else ())
        if kind == "tunnel":
            hi[2] -= WALL  # the floor is the tunnel's fourth side
        add_open_box(s, lo, hi, WALL, open_faces)
        bore = _along(axis, (a0, a1), (u - w / 2, u + w / 2), (lo[2] + (0 if kind == "tunnel" else WALL), hi[2] - WALL))
        interiors = [bore]
        floor_z, half_w = bore[0][2], w / 2
    if lift:
        for a in ((a0 + 0.03, a0 + 0.09), (a1 - 0.09, a1 - 0.03)):
            s.add_box(*_along(axis, a, (bore[0][1 - axis] - 0.02, bore[1][1 - axis] + 0.02), (0.0, lift)))
    if rng.random() < 0.3:  # a cap on one end
        end = (a0, a0 + WALL) if rng.random() < 0.5 else (a1 - WALL, a1)
        cap_lo, cap_hi = _along(axis, end, (bore[0][1 - axis], bore[1][1 - axis]), (bore[0][2], bore[1][2]))
        s.add_box(cap_lo, cap_hi)
    for lo, hi in interiors:
        s.add_interior(lo, hi)
    edge = min(rng.uniform(0.04, 0.06), 1.6 * half_w)
    at = a0 + rng.uniform(0.3, 0.7) * length
    target = np.array(_along(axis, (at - edge / 2, at + edge / 2), (u - edge / 2, u + edge / 2),
                             (floor_z, floor_z + edge)))
    return s, target, [(f"{kind} pipe along {'xy'[axis]}", *bore)]


def _slab_span(rng, length, width):
    """(axis, (a0, a1), (b0, b1)) of a slab `length` along x or y and `width` across, in reach."""
    axis = int(rng.integers(2))
    if axis == 0:
        a0, b0 = rng.uniform(0.5, 1.25 - length), rng.uniform(-0.45, 0.45 - width)
    else:
        a0, b0 = rng.uniform(-0.6, 0.6 - length), rng.uniform(0.55, 1.2 - width)
    return axis, (a0, a0 + length), (b0, b0 + width)


def collapsed_slabs(rng):
    """A plate (0.4-0.7 x 0.3-0.55 m, 2-4 cm thick) fallen with one end on the floor and the other on a
    support 0.1-0.25 m high (a block, sometimes turned), its high side facing any way; one long side
    sometimes closed by debris; turned blocks around; the target in the wedge under it."""
    s = Scene()
    add_floor(s)
    length, width = rng.uniform(0.4, 0.7), rng.uniform(0.3, 0.55)
    axis, (a0, a1), (b0, b1) = _slab_span(rng, length, width)
    hs, t = rng.uniform(0.1, 0.25), rng.uniform(0.02, 0.04)
    high_at_start = rng.random() < 0.5
    z0, z1 = (hs, 0.0) if high_at_start else (0.0, hs)
    depth = rng.uniform(0.05, 0.1)  # of the support, along the slab
    sup = (a0, a0 + depth) if high_at_start else (a1 - depth, a1)
    if rng.random() < 0.4:  # a turned block
        center, size = np.zeros(2), np.zeros(2)
        center[axis], center[1 - axis] = sum(sup) / 2, (b0 + b1) / 2
        size[axis], size[1 - axis] = depth, width
        add_turned_block(s, center, size, rng.uniform(-0.3, 0.3), 0.0, hs)
    else:
        s.add_box(*_along(axis, sup, (b0, b1), (0.0, hs)))
    add_tilted_plate(s, axis, a0, a1, b0, b1, z0, z1, t)
    if rng.random() < 0.5:  # one long side closed by blocks, each as high as the underside over it
        side = (b0, b0 + 0.04) if rng.random() < 0.5 else (b1 - 0.04, b1)
        edges = np.linspace(a0, a1, 5)
        for e0, e1 in zip(edges[:-1], edges[1:]):
            h = min(np.interp(e0, (a0, a1), (z0, z1)), np.interp(e1, (a0, a1), (z0, z1)))
            if h > 0.02:
                s.add_box(*_along(axis, (e0, e1), side, (0.0, h)))
    for lo, hi in wedge_interiors(axis, a0, a1, b0, b1, z0, z1):
        s.add_interior(lo, hi)
    _turned_debris(rng, s, int(rng.integers(1, 4)), avoid=_along(axis, (a0, a1), (b0, b1), (0, hs + t)))
    edge = rng.uniform(0.04, 0.06)
    frac = rng.uniform(0.35, 0.65)  # from the high end
    at = (a0 + frac * length) if high_at_start else (a1 - frac * length)
    under = np.interp(at, (a0, a1), (z0, z1))
    edge = min(edge, 0.8 * under)
    bt = rng.uniform(b0 + 0.05, b1 - 0.05 - edge)
    target = np.array(_along(axis, (at - edge / 2, at + edge / 2), (bt, bt + edge), (0.0, edge)))
    return s, target, [(f"slab along {'xy'[axis]}, high end {'first' if high_at_start else 'last'}",
                        *_along(axis, (a0, a1), (b0, b1), (0.0, hs + t)))]


def _turned_debris(rng, s, n, avoid, area=((0.5, -0.7), (1.25, 0.7))):
    """`n` blocks (8-20 cm, 5-15 cm high) turned about the vertical, on the floor clear of the box `avoid`
    (their circumscribed circle 3 cm away from it); fewer when no spot is found."""
    for _ in range(n):
        for _ in range(50):
            size = rng.uniform(0.08, 0.2, size=2)
            c = rng.uniform(area[0], area[1])
            r = np.hypot(*size) / 2 + 0.03
            if np.any(c + r < avoid[0][:2]) or np.any(c - r > avoid[1][:2]):
                add_turned_block(s, c, size, rng.uniform(0, np.pi), 0.0, rng.uniform(0.05, 0.15))
                break


def rubble(rng):
    """A USAR-like pile (0.45-0.7 m across): 2-4 pillars, 1-2 slabs laid across pairs of them (flat or
    tilted), 4-8 turned lumps and boards around; the interior is the pile's box, the target on the floor
    under a slab."""
    s = Scene()
    add_floor(s)
    span = rng.uniform(0.45, 0.7)
    lo_xy = np.array([rng.uniform(0.5, 1.25 - span), rng.uniform(-0.4, 0.4 - span)])
    hi_xy = lo_xy + span
    pillars = []
    for _ in range(int(rng.integers(2, 5))):
        p = rng.uniform(0.06, 0.12, size=2)
        c = rng.uniform(lo_xy + p / 2, hi_xy - p / 2)
        h = rng.uniform(0.08, 0.22)
        s.add_box((*(c - p / 2), 0.0), (*(c + p / 2), h))
        pillars.append((c, p, h))
    pillars.sort(key=lambda q: q[0][0])
    slabs, top = [], max(q[2] for q in pillars)
    for i in range(min(len(pillars) - 1, int(rng.integers(1, 3)))):
        (ca, pa, ha), (cb, pb, hb) = pillars[i], pillars[i + 1]
        a0, a1 = ca[0] - pa[0] / 2, cb[0] + pb[0] / 2
        b_mid, w = (ca[1] + cb[1]) / 2, rng.uniform(0.15, 0.3)
        t = rng.uniform(0.02, 0.035)
        if a1 - a0 < 0.12:
            continue
        if rng.random() < 0.5:
            add_tilted_plate(s, 0, a0, a1, b_mid - w / 2, b_mid + w / 2, ha, hb, t)
        else:
            s.add_box((a0, b_mid - w / 2, min(ha, hb)), (a1, b_mid + w / 2, min(ha, hb) + t))
        slabs.append((a0, a1, b_mid - w / 2, b_mid + w / 2, min(ha, hb)))
        top = max(top, max(ha, hb) + t)
    pile = (np.array([*lo_xy, 0.0]), np.array([*hi_xy, top]))
    for _ in range(int(rng.integers(4, 9))):  # lumps and boards around and between
        size = rng.uniform(0.04, 0.12, size=2) if rng.random() < 0.5 else np.array([rng.uniform(0.15, 0.3), 0.04])
        c = rng.uniform(lo_xy - 0.1, hi_xy + 0.1)
        if any(sl[0] - 0.08 < c[0] < sl[1] + 0.08 and sl[2] - 0.08 < c[1] < sl[3] + 0.08 for sl in slabs):
            continue  # keep the cavities under the slabs open
        add_turned_block(s, c, size, rng.uniform(0, np.pi), 0.0, rng.uniform(0.03, 0.1))
    s.add_interior(*pile)
    edge = rng.uniform(0.04, 0.06)
    if slabs:
        a0, a1, b0, b1, h = slabs[0]
        edge = min(edge, 0.8 * h)
        at, bt = (a0 + a1) / 2 - edge / 2, (b0 + b1) / 2 - edge / 2
    else:
        at, bt = lo_xy[0] + span / 2, lo_xy[1] + span / 2
    target = np.array([[at, bt, 0.0], [at + edge, bt + edge, edge]])
    return s, target, [("pile", *pile)] + [("slab", (sl[0], sl[2], sl[4]), (sl[1], sl[3], sl[4])) for sl in slabs]
