"""The viewer's colour scale: reachability values in [0, 1] -> RGB (uint8), and the fixed colours of the scene."""
from __future__ import annotations

import numpy as np

# Fixed colours (RGB) of the scene's parts; tests look for them in screenshots.
ROBOT = (170, 174, 182)
SURFACE = (150, 105, 60)
ROOM = (95, 135, 190)  # the room's obstacles: walls, cabinets, other surfaces
FOOTPRINT = (20, 20, 20)
ARROW = (230, 30, 120)
SELECTED = (255, 0, 255)
OCCUPIED = (90, 90, 100)
FRONTIER = (255, 140, 0)
VOID = (40, 120, 255)
ELLIPSOID = (40, 200, 255)
FRUSTUM = (220, 20, 20)
SLICE_PLANE = (200, 200, 255)


def scale(values, vmax: float | None = None) -> np.ndarray:
    """(N, 3) uint8 colours of values on matplotlib's 'turbo' map, normalised by vmax (default: their max):
    red low, blue high, as in octoreach.plots and the octovis exports."""
    from matplotlib import colormaps

    v = np.asarray(values, dtype=float).reshape(-1)
    top = float(vmax) if vmax is not None else (float(v.max()) if v.size else 1.0)
    t = np.clip(v / top, 0.0, 1.0) if top > 0 else np.zeros_like(v)
    # turbo's two ends are dark; use its bright middle 0.95 .. 0.1 (red -> yellow -> green -> blue).
    rgba = colormaps["turbo"](0.95 - 0.85 * t)
    # The browser renders the colours lighter than given (sRGB output of lit materials); darkening them by
    # the sRGB gamma here keeps the scale's saturated look on screen.
    return (rgba[:, :3] ** 2.2 * 255).round().astype(np.uint8)
