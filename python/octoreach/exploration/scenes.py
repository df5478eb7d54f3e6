"""The exploration's worlds: the paper's scenes, a closed box, a cluttered room, and the search space S."""
from __future__ import annotations

import numpy as np

from .._core import Scene


def _floor(s: Scene, half: float = 2.0) -> None:
    s.add_box((-half, -half, -0.05), (half, half, 0.0))


def paper_scene(which: int = 1) -> Scene:
    """The paper's settings, from its figures: 1 = a computer, two open-topped crates and two-by-fours;
    2 = two larger closed boxes and smaller boxes with small openings. Objects stand 0.5-1.3 m in
    front (+x) of a robot at the origin."""
    s = Scene()
    _floor(s)
    if which == 1:
        s.add_box((0.95, -0.15, 0.0), (1.15, 0.15, 0.45))  # computer tower
        s.add_crate((0.55, -0.6, 0.0), (0.9, -0.25, 0.3), 0.02)
        s.add_crate((0.55, 0.25, 0.0), (0.95, 0.6, 0.25), 0.02)
        s.add_board((0.45, -0.1, 0.0), (0.85, -0.05, 0.1))  # two-by-fours lying on the floor
        s.add_board((0.45, 0.05, 0.0), (0.85, 0.1, 0.1))
    elif which == 2:
        s.add_closed_box((0.7, -0.7, 0.0), (1.1, -0.25, 0.4), 0.02, "-x", 0.12, 0.12)
        s.add_closed_box((0.7, 0.25, 0.0), (1.15, 0.7, 0.4), 0.02, "+z", 0.14, 0.14)
        s.add_closed_box((0.5, -0.12, 0.0), (0.75, 0.12, 0.25), 0.02, "-x", 0.08, 0.08)
        s.add_closed_box((1.0, -0.15, 0.0), (1.25, 0.15, 0.2), 0.02, "+z", 0.1, 0.1)
    else:
        raise ValueError(f"paper scene must be 1 or 2, got {which!r}")
    return s


def closed_box_scene(face: str = "-x", opening: float = 0.12) -> Scene:
    """One closed box (0.4 m cube) with one square opening in `face`, 0.6-1.0 m in front of the origin."""
    s = Scene()
    _floor(s)
    s.add_closed_box((0.6, -0.2, 0.0), (1.0, 0.2, 0.4), 0.02, face, opening, opening)
    return s


def cluttered_scene() -> Scene:
    """A room corner with twelve crates and closed boxes (benchmark scene)."""
    s = Scene()
    _floor(s, 3.0)
    s.add_box((-3, 3, 0), (3, 3.05, 2.0))
    s.add_box((3, -3, 0), (3.05, 3, 2.0))
    for i in range(4):
        for j in range(3):
            x, y = 0.5 + 0.6 * i, -1.2 + 0.8 * j
            if (i + j) % 2:
                s.add_crate((x, y, 0), (x + 0.4, y + 0.4, 0.3), 0.02)
            else:
                s.add_closed_box((x, y, 0), (x + 0.45, y + 0.4, 0.35), 0.02, "-x", 0.12, 0.1)
    s.add_board((0.3, 1.2, 0.0), (1.5, 1.25, 0.5))
    return s


def scene_region(scene: Scene, margin: float = 0.05) -> np.ndarray:
    """The search space S (2, 3) (lo, hi rows): the bounds of the scene's objects (boxes no wider
    than 2 m, so floors and walls are left out), grown by `margin`, from the floor (z = 0) up."""
    objs = [(np.asarray(lo), np.asarray(hi)) for lo, hi in scene.boxes
            if np.max((np.asarray(hi) - np.asarray(lo))[:2]) < 2.0]
    if not objs:
        lo, hi = scene.bounds()
        return np.array([lo, hi], float)
    lo = np.min([o[0] for o in objs], axis=0) - margin
    hi = np.max([o[1] for o in objs], axis=0) + margin
    lo[2] = 0.0
    return np.array([lo, hi])
