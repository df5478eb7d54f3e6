"""The semantic attachments of Section III-C of the surface-map paper, planner-independent.

* **condition** (``condition(pose, surface)`` -> R_S): may the robot work at a surface from a base pose?
  One lookup in the surface's combined (either arm) surface map; R_S = 0 discards the pose before any
  inverse kinematics.
* **grounding** (``ground(surface, k)`` -> (k, 4)): new base poses for the planning state, drawn from the
  surface map by ``octoreach.PoseSampler``, each discounted (eq. 3) against every pose drawn for that surface
  so far, across calls (one sampler per surface lives as long as the attachments; ``reset()`` starts a new
  task). A drawn pose keeps the robot's body clear of the room: by default the body the surface map recorded
  (``SurfaceMap.room``: the links off the arm at the map's reference posture, the posture the map rated the
  pose with; the arm is checked at its grasps by the map and by the reachability attachment); with a
  ``reference`` posture, the whole robot, arm included, at that posture.
* **reachability** (``reach(pose, point, surface)`` -> {arm: R_P}): can an arm grasp an object at `point`
  from `pose`? For each arm the share of grasps that inverse kinematics reaches free of collision with the
  surface and the room (``octoreach.surface_maps.GraspCheck``, the brute-force check the map tests use, with
  the gripper checked against the surface slab too), asked only when the condition holds and the arm's
  capability map has a reachable direction in the point's voxel; results are cached per (pose, point). A
  point that does not lie on its surface (inside its outline, within ON_SURFACE of its top) is a ValueError.

Example (any planner can call these three)::

    att = Attachments.build(robot, room, resolution=0.1)
    if att.condition(pose, "table") > 0:            # cheap: one map lookup
        rp = att.reach(pose, obj_xyz, "table")      # expensive: IK of both arms
    new_poses = att.ground("table", 2)              # (2, 4), spread out by eq. (3)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .. import arms as _arms
from .._core import PoseSampler, Robot, SurfaceMap
from ..surface_maps import GraspCheck

__all__ = ["Attachments", "OBJECT_HEIGHT", "ON_SURFACE"]

OBJECT_HEIGHT = 0.05  # grasp point above the surface (the surface maps' grasp_height)
#: How far an object's base may lie off its surface's top (m): half the grasp height, so that its grasp point
#: stays nearer the height the surface maps were built for than the top itself.
ON_SURFACE = OBJECT_HEIGHT / 2


def _configuration(robot: Robot, reference):
    """`reference` as a full configuration (None stays None; a {joint: value} dict fills in from home);
    ValueError unless it has one finite value per joint."""
    if reference is None:
        return None
    q = robot.configuration(reference) if isinstance(reference, dict) else np.asarray(reference, float)
    if q.shape != (robot.dof,) or not np.all(np.isfinite(q)):
        raise ValueError(f"reference must be a robot configuration of {robot.dof} finite values, got "
                         f"{np.round(q, 3).tolist()}")
    return q


@dataclass
class Attachments:
    """Condition, grounding and reachability attachments over the surfaces of one room.

    robot, room (``octoreach.rooms.Room``), caps {arm: CapabilityMap with solutions}, maps {surface: combined
    SurfaceMap (either arm)}. ``Attachments.build`` makes the maps. reference: the robot's posture (a full
    configuration, ``robot.configuration({...})``) or None. Given, it is the posture of the joints off the arm
    (torso, head, other arm) for the maps (``SurfaceMap.build(reference=...)``), the reachability check and the
    camera, and the whole robot, arm included, is checked against the room in it when poses are sampled (the
    posture the robot drives in, e.g. its arm tucked). None: ``octoreach.default_reference`` of the first arm,
    and sampled poses are checked with the body the surface map recorded (its links off the arm, at the map's
    reference posture), so the sampler accepts the poses the map rated. Counters: ``ik_calls`` (IK targets solved
    by the reachability attachment), ``condition_calls``, ``pruned`` (reachability questions answered by the
    condition alone)."""

    robot: Robot
    room: object
    caps: dict
    maps: dict
    seed: int = 0
    attempts: int = 8  # IK restarts per grasp of the reachability check (the map tests use 20)
    candidates: int | None = None  # PoseSampler candidates per sample (None: its default, the paper's 40)
    reference: object = None  # the robot's posture (see above; a {joint: value} dict fills in from home)
    _samplers: dict = field(default_factory=dict, repr=False)
    _checks: dict = field(default_factory=dict, repr=False)
    _cache: dict = field(default_factory=dict, repr=False)
    condition_calls: int = 0
    pruned: int = 0

    def __post_init__(self):
        self.reference = _configuration(self.robot, self.reference)

    @classmethod
    def build(cls, robot: Robot, room, resolution: float = 0.1, directions: int | None = None, caps: dict = None,
              seed: int = 0, progress: bool = False, reference=None, **kwargs) -> "Attachments":
        """Capability maps of every arm of the robot (unless `caps` gives them; `directions` None: the
        CapabilityMapOptions default) and one combined surface map per surface of `room`, the capability and the
        surface maps built in the posture `reference` (a full robot configuration; None: the default reference;
        see the class), the surface maps with the room's other obstacles (``Room.surface_maps``)."""
        reference = _configuration(robot, reference)
        if caps is None:
            extra = {} if directions is None else {"directions": directions}
            if reference is not None:
                extra["reference"] = reference  # the arms' maps rate their cells in the same posture
            caps = {arm.name: _arms.capability_map(robot, arm.name, resolution=resolution, seed=seed, progress=progress,
                                                   **extra) for arm in _arms.find_arms(robot)}
        if not caps:
            raise ValueError("the robot has no arm to grasp with")
        per_arm = [room.surface_maps(robot, cap, progress=progress, resolution=resolution, z_range=(0, 0),
                                     grasp_height=OBJECT_HEIGHT, reference=reference) for cap in caps.values()]
        maps = {name: SurfaceMap.combine([m[name] for m in per_arm], "max") for name in room.surfaces}
        return cls(robot=robot, room=room, caps=dict(caps), maps=maps, seed=seed, reference=reference, **kwargs)

    def posture(self, arm: str | None = None) -> np.ndarray:
        """The robot configuration the attachments use off `arm` (None: the first arm): `reference`, or the
        default reference of that arm."""
        if self.reference is not None:
            return np.asarray(self.reference, float)
        return _arms.default_reference(self.robot, arm if arm is not None else next(iter(self.caps)))

    # ------------------------------------------------------------------ condition
    def condition(self, pose, surface: str) -> float:
        """R_S of base pose (x, y, z, theta) at `surface` (0: the robot cannot work at it from there)."""
        self.condition_calls += 1
        return float(self._map(surface).reachability(np.asarray(pose, float).reshape(1, 4))[0])

    def _map(self, surface: str) -> SurfaceMap:
        try:
            return self.maps[surface]
        except KeyError:
            raise KeyError(f"no surface {surface!r} (surfaces: {', '.join(self.maps)})") from None

    # ------------------------------------------------------------------ grounding
    def sampler(self, surface: str) -> PoseSampler:
        """The surface's PoseSampler (made on first use, kept: its history is every pose drawn so far)."""
        if surface not in self._samplers:
            smap = self._map(surface)
            index = list(self.maps).index(surface) if surface in self.maps else 0
            extra = {} if self.candidates is None else {"candidates": self.candidates}
            if self.reference is not None or smap.room.empty or not smap.room.body:
                # the whole robot at the posture (a map without a recorded body: the default reference)
                extra["in_collision"] = (self.robot, self.room.obstacles(), self.posture())
            self._samplers[surface] = PoseSampler(smap, seed=self.seed * 1009 + index, **extra)
        return self._samplers[surface]

    def ground(self, surface: str, k: int = 1) -> np.ndarray:
        """k new base poses (k, 4) for `surface`, discounted against every pose drawn for it so far (fewer rows
        when the sampler finds no valid candidate: a surface no pose reaches gives (0, 4))."""
        if k < 1:
            raise ValueError(f"k must be at least 1, got {k!r}")
        sampler = self.sampler(surface)
        out = []
        for _ in range(k):
            pose = sampler.sample()
            if pose is None:
                break
            out.append(np.asarray(pose, float))
        return np.array(out).reshape(-1, 4)

    def reset(self, seed: int | None = None) -> None:
        """A new task: forget the poses drawn so far (with a `seed`, the samplers start new random streams from
        it). The reachability answers stay cached: they depend on the pose and point only."""
        if seed is not None:
            self.seed = int(seed)
            self._samplers.clear()
        for sampler in self._samplers.values():
            sampler.reset()

    # ------------------------------------------------------------------ reachability
    def reach(self, pose, point, surface: str) -> dict:
        """{arm: R_P} of grasping an object at `point` (x, y, z of its base on `surface`, world frame) from base
        pose `pose`: the share of grasps each arm reaches by IK. Empty when the condition attachment rejects
        the pose (R_S = 0 at that surface): no IK is run then."""
        pose = np.asarray(pose, float).reshape(4)
        self.check_position(point, surface)
        key = (tuple(np.round(pose, 6)), tuple(np.round(np.asarray(point, float), 6)), surface)
        if key in self._cache:
            return self._cache[key]
        if self.condition(pose, surface) <= 0.0:
            self.pruned += 1
            self._cache[key] = {}
            return {}
        target = np.asarray(point, float).reshape(1, 3) + OBJECT_HEIGHT * np.asarray(self.room.surfaces[surface].normal)
        out = {}
        for arm, cap in self.caps.items():
            check = self._check(arm, surface)
            in_arm = check.frames(pose)[1] @ np.append(target[0], 1.0)
            if cap.reachability(in_arm[None, :3])[0] <= 0.0:  # no reachable direction in its voxel: skip IK
                continue
            share = float(check.shares(pose, target)[0])
            if share > 0.0:
                out[arm] = share
        self._cache[key] = out
        return out

    def check_position(self, point, surface: str) -> None:
        """ValueError unless `point` (x, y, z of an object's base, world frame) lies on `surface`: inside its
        outline and within ON_SURFACE of its top."""
        p = np.asarray(point, float).reshape(-1)
        s = self.room.surfaces.get(surface)
        if s is None:
            raise KeyError(f"no surface {surface!r} (surfaces: {', '.join(self.room.surfaces)})")
        if p.shape != (3,) or not np.all(np.isfinite(p)):
            raise ValueError("an object position must be 3 finite numbers (x, y, z in m), got "
                             f"{np.round(p, 3).tolist()}")
        normal = np.asarray(s.normal, float)
        height = float((p - np.asarray(s.vertices, float)[0]) @ normal)  # above the top along the normal
        where = f"object position {np.round(p, 3).tolist()} is not on surface {surface!r}"
        if abs(height) > ON_SURFACE:
            raise ValueError(f"{where}: {abs(height):.3f} m {'above' if height > 0 else 'under'} its top (at most "
                             f"{ON_SURFACE} m, planning.attachments.ON_SURFACE)")
        if not s.contains(p[None])[0]:
            raise ValueError(f"{where}: outside its outline")

    def _check(self, arm: str, surface: str) -> GraspCheck:
        if (arm, surface) not in self._checks:
            self._checks[(arm, surface)] = GraspCheck(self.robot, self.caps[arm], self.room.surfaces[surface],
                                                      reference=self.reference, attempts=self.attempts, seed=self.seed,
                                                      obstacles=self.room.obstacles(without=surface),
                                                      tool_checks_slab=True)
        return self._checks[(arm, surface)]

    @property
    def ik_calls(self) -> int:
        """IK targets solved by the reachability attachment so far."""
        return sum(c.ik_calls for c in self._checks.values())
