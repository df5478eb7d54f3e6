"""Camera poses for the exploration: where a camera stands and where it looks."""
from __future__ import annotations

import numpy as np

from .. import _core


def look_at(eye, target, roll: float = 0.0) -> np.ndarray:
    """Camera pose (4x4 camera -> world) at `eye` looking at `target`, image +y pointing down."""
    return _core.look_at(np.asarray(eye, float), np.asarray(target, float), float(roll))
