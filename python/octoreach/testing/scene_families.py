"""Seeded scene families for exploration benchmarks and tests: open crates, closed boxes with openings on
any face, shelves and bookcases, pipes and tunnels, collapsed slabs and wedges, cluttered table tops and
USAR-like rubble piles (family_containers, family_debris).

Every instance stands in front (+x) of the explorer at the origin, inside its arm's reach, records its
interiors (the regions an exploration should see: crate and box insides, cubbies, bores, wedges, the clutter
layer of a table, a pile's box), states the search space when it is not the scene's region (a table top)
and hides a small target: a cube that does not overlap any solid and that
the families' start view (START) does not see. `family_scene(family, seed)` draws everything from a
generator seeded by the family's name and `seed`: the same (family, seed) gives the same scene, bit for
bit, whatever else was drawn before.
"""
from __future__ import annotations

import zlib
from dataclasses import dataclass, field

import numpy as np

from .._core import DepthCamera, Scene
from ..exploration.camera import look_at
from ..exploration.metrics import points_on
from ..exploration.scenes import scene_region
from . import family_containers, family_debris

# The builders, by family name (each: rng -> (scene without its target, target (2, 3), parts)).
BUILDERS = {
    "open_crates": family_containers.open_crates,
    "closed_boxes": family_containers.closed_boxes,
    "shelves": family_containers.shelves,
    "pipes": family_debris.pipes,
    "collapsed_slabs": family_debris.collapsed_slabs,
    "table_tops": family_containers.table_tops,
    "rubble": family_debris.rubble,
}
FAMILIES = tuple(BUILDERS)
# The families' first view (eye, looked-at point): above the robot's front, looking down at the scene.
START = ((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
# A target the start view sees with this many points or more (a 320 x 240 noiseless capture) is not hidden.
HIDDEN_POINTS = 5
MAX_DRAWS = 50  # draws of one instance until its target is clear of every solid and hidden


@dataclass
class FamilyScene:
    """One instance of a family: the Scene (target included), its target ((2, 3) lo, hi rows), the parts it
    was built from ((name, lo, hi) rows, for plots and reports) and how many draws it took."""

    family: str
    seed: int
    scene: Scene
    target: np.ndarray
    parts: list = field(default_factory=list)
    draws: int = 1

    @property
    def name(self) -> str:
        return f"{self.family}_{self.seed}"

    @property
    def search_space(self) -> np.ndarray:
        """The region the exploration searches ((2, 3) lo, hi): the family's "search_space" part when it has
        one (a table top: the layer above the table), else scene_region(scene)."""
        for name, lo, hi in self.parts:
            if name == "search_space":
                return np.array([lo, hi], float)
        return scene_region(self.scene)

    def target_points(self, points, margin: float = 0.015) -> int:
        """How many of `points` (N, 3) lie on the target (metrics.points_on)."""
        return points_on(self.target, points, margin)


def start_pose() -> np.ndarray:
    """The families' first camera pose (4x4 camera -> world)."""
    return look_at(*START)


def _target_clear(scene: Scene, target, samples: int = 4) -> bool:
    """True when no point of a grid inside the target (shrunk by 1 mm) lies in a solid of `scene`."""
    lo, hi = np.asarray(target, float) + np.array([[1e-3], [-1e-3]])
    if np.any(hi <= lo):
        return False
    axes = [np.linspace(lo[a], hi[a], samples) for a in range(3)]
    pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    return not np.any(scene.solid(pts))


def _hidden(scene: Scene, target) -> bool:
    """True when the start view (a noiseless 320 x 240 capture) sees fewer than HIDDEN_POINTS on the target."""
    cam = DepthCamera(320, 240, np.deg2rad(58.0), 4.0, noise=0.0, seed=0)
    return points_on(target, cam.capture(scene, start_pose())) < HIDDEN_POINTS


def family_scene(family: str, seed: int) -> FamilyScene:
    """Instance `seed` of `family` (one of FAMILIES). ValueError for an unknown family or a negative seed;
    RuntimeError when MAX_DRAWS draws gave no clear, hidden target (not the case for seeds 0-99)."""
    if family not in BUILDERS:
        raise ValueError(f"unknown family {family!r}; choose one of {', '.join(FAMILIES)}")
    if not isinstance(seed, (int, np.integer)) or isinstance(seed, bool) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    rng = np.random.default_rng([zlib.crc32(family.encode()), int(seed)])
    for draw in range(1, MAX_DRAWS + 1):
        scene, target, parts = BUILDERS[family](rng)
        target = np.asarray(target, float)
        if not _target_clear(scene, target):
            continue
        scene.add_box(target[0], target[1])
        if _hidden(scene, target):
            return FamilyScene(family=family, seed=int(seed), scene=scene, target=target, parts=parts, draws=draw)
    raise RuntimeError(f"{family} seed {seed}: no clear, hidden target in {MAX_DRAWS} draws")


def family_instances(family: str, count: int = 5, first_seed: int = 0) -> list:
    """`count` instances of `family`: seeds first_seed .. first_seed + count - 1."""
    return [family_scene(family, s) for s in range(first_seed, first_seed + count)]
