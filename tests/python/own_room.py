"""A kitchen written here, as a user would write one: an L-shaped counter (2.64 m2) on base cabinets along two
walls, a wall cabinet above it and a bin on the floor."""
from __future__ import annotations

H = 0.9  # counter height (m)

# The counter's outline, counter-clockwise seen from above: 2.5 x 0.6 m along the north wall, 0.6 x 1.9 m along
# the east wall.
COUNTER = [[-1.0, 0.9, H], [0.9, 0.9, H], [0.9, -1.0, H], [1.5, -1.0, H], [1.5, 1.5, H], [-1.0, 1.5, H]]
COUNTER_AREA = 2.64


def room() -> dict:
    """The room file's description (rooms.Room reads it)."""
    return {
        "surfaces": [{"name": "counter", "vertices": COUNTER, "thickness": 0.04, "boxes": [
            {"name": "cabinets_north", "size": [2.5, 0.55, H - 0.04], "xyz": [0.25, 1.225, (H - 0.04) / 2]},
            {"name": "cabinets_east", "size": [0.55, 1.9, H - 0.04], "xyz": [1.225, -0.05, (H - 0.04) / 2]}]}],
        "boxes": [{"name": "wall_north", "size": [3.2, 0.1, 2.4], "xyz": [0.1, 1.55, 1.2]},
                  {"name": "wall_east", "size": [0.1, 3.2, 2.4], "xyz": [1.55, 0.1, 1.2]},
                  {"name": "wall_cabinet", "size": [1.2, 0.35, 0.7], "xyz": [0.0, 1.325, 1.75]}],
        "cylinders": [{"name": "bin", "radius": 0.15, "length": 0.5, "xyz": [-0.9, -0.6, 0.25]}],
    }
