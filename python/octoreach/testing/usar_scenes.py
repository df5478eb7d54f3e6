"""Seeded USAR-like scenes: crates and closed boxes with openings of different sizes, faces and
heights, debris on the floor, and one small target object hidden in one of the containers.

The robot stands at the origin (as in the paper's scenes) and the containers stand 0.5-1.3 m in
front of it (+x), inside the explorer arm's reach from above or from the side. Everything is drawn
from ``numpy.random.default_rng(seed)``: the same seed gives the same scene.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._core import Scene
from ..exploration.metrics import points_on

FACES = ("+z", "-x", "+y", "-y", "+x")  # opening faces of closed boxes (+z: a lid with a hole)
WALL = 0.02  # wall thickness of crates and closed boxes (m)
# Where containers and debris stand (x, y in metres, in front of a robot at the origin).
AREA = ((0.5, -0.75), (1.3, 0.75))


@dataclass
class UsarScene:
    """A generated scene: the Scene, its containers (kind, lo, hi, face, opening), the hidden target
    ((2, 3) lo, hi rows) and the index of the container that holds it."""

    scene: Scene
    containers: list
    target: np.ndarray
    target_container: int
    seed: int
    debris: list = field(default_factory=list)

    def target_points(self, points, margin: float = 0.015) -> int:
        """How many of `points` (N, 3) lie on the target (points_on)."""
        return points_on(self.target, points, margin)


def _free(xy_lo, xy_hi, taken, gap) -> bool:
    """True when the rectangle [xy_lo, xy_hi] keeps `gap` from every rectangle in `taken`."""
    for lo, hi in taken:
        if xy_lo[0] < hi[0] + gap and xy_hi[0] > lo[0] - gap and xy_lo[1] < hi[1] + gap and xy_hi[1] > lo[1] - gap:
            return False
    return True


def _place(rng, size_xy, taken, gap, tries=200):
    """A random spot (lo, hi in x, y) for a footprint of `size_xy` inside AREA, clear of `taken`; None if none."""
    (ax0, ay0), (ax1, ay1) = AREA
    for _ in range(tries):
        x = rng.uniform(ax0, ax1 - size_xy[0])
        y = rng.uniform(ay0, ay1 - size_xy[1])
        lo, hi = np.array([x, y]), np.array([x + size_xy[0], y + size_xy[1]])
        if _free(lo, hi, taken, gap):
            return lo, hi
    return None


def _container(rng, s: Scene, lo_xy, hi_xy, height, kind):
    """Adds a crate or a closed box with a random opening; returns its description."""
    lo = np.array([lo_xy[0], lo_xy[1], 0.0])
    hi = np.array([hi_xy[0], hi_xy[1], height])
    if kind == "crate":
        s.add_crate(lo, hi, WALL)
        return {"kind": "crate", "lo": lo, "hi": hi, "face": "+z", "opening": (hi - lo)[:2] - 2 * WALL}
    face = FACES[int(rng.integers(len(FACES)))]
    size = hi - lo
    # the opening fits the face with a wall margin; its size is drawn between 7 cm and 80 % of the face
    axes = {"+z": (0, 1), "-x": (1, 2), "+x": (1, 2), "+y": (0, 2), "-y": (0, 2)}[face]
    limit = [0.8 * size[a] - 2 * WALL for a in axes]
    w = rng.uniform(min(0.07, limit[0]), max(0.07, limit[0]))
    h = rng.uniform(min(0.07, limit[1]), max(0.07, limit[1]))
    s.add_closed_box(lo, hi, WALL, face, w, h)
    return {"kind": "closed_box", "lo": lo, "hi": hi, "face": face, "opening": np.array([w, h])}


def usar_scene(seed: int = 0, containers: int = 3, debris: int = 3, closed_share: float = 0.7) -> UsarScene:
    """A seeded USAR-like scene: `containers` crates and closed boxes (each closed with probability
    `closed_share`; footprints 0.25-0.45 m, heights 0.18-0.45 m, openings of 7 cm up to 80 % of the
    face on a random face), `debris` small boxes and boards on the floor between them, and a target
    (a 5-8 cm cube) on the floor inside one container (a closed box when there is one). ValueError for counts that do not fit."""
    if not 1 <= containers <= 6:
        raise ValueError(f"containers must be 1..6 (the area holds at most 6), got {containers!r}")
    if not 0 <= debris <= 10:
        raise ValueError(f"debris must be 0..10, got {debris!r}")
    if not 0.0 <= closed_share <= 1.0:
        raise ValueError(f"closed_share must be in [0, 1], got {closed_share!r}")
    rng = np.random.default_rng(seed)
    s = Scene()
    s.add_box((-2.0, -2.0, -0.05), (2.0, 2.0, 0.0))  # floor
    taken, boxes = [], []
    for _ in range(containers):
        size = rng.uniform(0.25, 0.45, size=2)
        spot = _place(rng, size, taken, gap=0.12)
        if spot is None:
            continue
        taken.append(spot)
        kind = "closed_box" if rng.random() < closed_share else "crate"
        boxes.append(_container(rng, s, spot[0], spot[1], rng.uniform(0.18, 0.45), kind))
    if not boxes:
        raise ValueError(f"no container fits (seed {seed})")
    pieces = []
    for _ in range(debris):
        if rng.random() < 0.5:  # a lump
            size = rng.uniform(0.05, 0.15, size=3)
        else:  # a board lying on the floor
            size = np.array([rng.uniform(0.2, 0.4), rng.uniform(0.04, 0.08), rng.uniform(0.03, 0.06)])
            if rng.random() < 0.5:
                size = size[[1, 0, 2]]
        spot = _place(rng, size[:2], taken, gap=0.03)
        if spot is None:
            continue
        taken.append(spot)
        lo, hi = np.array([*spot[0], 0.0]), np.array([*spot[1], size[2]])
        s.add_box(lo, hi)
        pieces.append((lo, hi))
    # the target hides in a closed box when there is one (a crate's inside is seen from the start view)
    closed = [i for i, b in enumerate(boxes) if b["kind"] == "closed_box"] or list(range(len(boxes)))
    k = closed[int(rng.integers(len(closed)))]
    c = boxes[k]
    inner_lo, inner_hi = c["lo"] + WALL, c["hi"] - WALL
    edge = rng.uniform(0.05, 0.08)
    room = inner_hi[:2] - inner_lo[:2] - edge
    xy = inner_lo[:2] + rng.uniform(0.0, 1.0, size=2) * np.maximum(room, 0.0)
    t_lo = np.array([xy[0], xy[1], inner_lo[2]])
    t_hi = np.minimum(t_lo + edge, inner_hi)
    s.add_box(t_lo, t_hi)
    return UsarScene(scene=s, containers=boxes, target=np.array([t_lo, t_hi]), target_container=k, seed=seed,
                     debris=pieces)
