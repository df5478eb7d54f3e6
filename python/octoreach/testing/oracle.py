"""The observable interior of a scene, by brute force: a test and benchmark utility, not the planner.

A cell is observable when a camera pose the arm can reach without touching the scene's true geometry
(with the links the chain moves: Chain.moved_links) or itself sees it: a ray of a noiseless capture from that pose passes through it (free) or ends in it (hit).
The oracle samples camera poses densely in two ways and keeps the collision-free ones:

- random joint configurations of the arm (forward kinematics: reachable by construction), and
- aimed poses: from sample points of the interiors, random directions whose segment leaves the
  point without meeting a surface give an eye position 0.15-0.7 m away looking back at the point;
  IK (approach mode, obstacles = the true scene, self-collision checked) decides whether the arm gets the camera there.

With `clearance` > 0 (the safe-view rule of the exploration: its camera keeps min_distance from every
surface) only the poses whose camera keeps that distance per axis (Chebyshev: near a box's edges and corners
stricter than the search's distance to the nearest point of a cell) from every solid box of the scene are
kept. Each kept pose's capture (noiseless, low resolution) is integrated into one map at the exploration's
resolution; the observable cells are the interior sample points that map knows. The same sample
points (metrics.region_points) measure what an exploration saw, so `Observable.share(emap)` is the
share of the observable interior an exploration map knows.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._core import DepthCamera, ExplorationMap, Scene
from ..exploration.metrics import points_on, region_points
from ..exploration.physics import robot_root
from ..exploration.robot import arm_base_pose, arm_reach, explorer_robot


@dataclass
class Observable:
    """The oracle's answer: sample points of the regions (non-solid), which of them are observable,
    and how many camera poses were sampled and kept."""

    points: np.ndarray  # (N, 3) sample points (metrics.region_points of the regions)
    observable: np.ndarray  # (N,) bool
    resolution: float
    poses_sampled: int
    poses_valid: int
    fov: float = np.deg2rad(58.0)  # the captures' camera
    max_range: float = 4.0
    width: int = 64
    height: int = 48
    poses: np.ndarray = field(default_factory=lambda: np.zeros((0, 4, 4)))  # (poses_valid, 4, 4) the kept camera poses

    def sees(self, pose, scene, points=None) -> np.ndarray:
        """Which of `points` (default: the regions' sample points) a noiseless capture from `pose` (4x4)
        turns known, as the oracle's own captures do."""
        pts = self.points if points is None else np.asarray(points, float).reshape(-1, 3)
        return _known_after(scene, [np.asarray(pose, float)], pts, self.resolution, self.fov, self.max_range,
                            self.width, self.height)

    @property
    def count(self) -> int:
        return int(np.count_nonzero(self.observable))

    @property
    def fraction(self) -> float:
        """Share of the regions' sample points that are observable at all."""
        return self.count / len(self.points) if len(self.points) else 0.0

    def share(self, emap: ExplorationMap) -> float:
        """Share (0-1) of the observable sample points that `emap` knows (free or occupied)."""
        if self.count == 0:
            return 0.0
        known = emap.state(self.points[self.observable]) != 0
        return float(np.count_nonzero(known)) / self.count

    def sees_target(self, scene, target, width: int = 320, height: int = 240, min_points: int = 5) -> bool:
        """True when a kept pose's noiseless `width` x `height` capture (the exploration's image) has at least
        `min_points` points on `target` ((2, 3) lo, hi; metrics.points_on), the criterion of
        ExplorationResult.target_seen_view. Only poses with the target's centre in their field of view are
        captured."""
        target = np.asarray(target, float)
        if len(self.poses) == 0:
            return False
        c = target.mean(axis=0)
        cam = DepthCamera(width, height, self.fov, self.max_range, noise=0.0, seed=0)
        half = np.tan(self.fov / 2)
        for T in self.poses:
            p = np.linalg.inv(T) @ np.append(c, 1.0)
            if p[2] <= 0 or abs(p[0] / p[2]) > half or abs(p[1] / p[2]) > half * height / width:
                continue
            if points_on(target, cam.capture(scene, T)) >= min_points:
                return True
        return False

    def seen_unobservable(self, emap: ExplorationMap) -> int:
        """Sample points `emap` knows that the oracle calls unobservable (a check of its density: should be ~0)."""
        rest = self.points[~self.observable]
        return int(np.count_nonzero(emap.state(rest) != 0)) if len(rest) else 0


def _known_after(scene, poses, points, resolution, fov, max_range, width, height, seed=0) -> np.ndarray:
    """Which of `points` a map knows after noiseless captures of `scene` from `poses` (the oracle's captures)."""
    cam = DepthCamera(width, height, fov, max_range, noise=0.0, seed=seed)
    emap = ExplorationMap(resolution=resolution, track_voids=False)
    for T in poses:
        pts = cam.capture(scene, T)
        if len(pts):
            emap.insert(pts, T[:3, 3], max_range)
    return emap.state(points) != 0 if len(points) else np.zeros(0, bool)


def _clear_of_boxes(scene, points, clearance) -> np.ndarray:
    """(N,) bools: each of `points` (N, 3) is farther than `clearance` (Chebyshev) from every solid box of `scene`."""
    points = np.asarray(points, float).reshape(-1, 3)
    boxes = np.array([(lo, hi) for lo, hi in scene.boxes], float).reshape(-1, 2, 3)
    near = np.zeros(len(points), bool)
    for i in range(0, len(boxes), 256):  # bounded memory: (N, 256, 3) at a time
        b = boxes[i:i + 256]
        inside = (points[:, None, :] > b[None, :, 0] - clearance) & (points[:, None, :] < b[None, :, 1] + clearance)
        near |= inside.all(axis=2).any(axis=1)
    return ~near


def _joint_poses(robot, chain, chain_base, root, obstacles, links, n, rng):
    """Camera poses (world) of `n` random joint configurations whose `links` are clear of `obstacles` and
    whose robot is clear of itself."""
    lo = np.where(np.isfinite(chain.lower), chain.lower, -np.pi)
    hi = np.where(np.isfinite(chain.upper), chain.upper, np.pi)
    Q = rng.uniform(lo, hi, size=(n, chain.dof))
    tips = chain.fk_batch(Q)
    out = []
    for q, T in zip(Q, tips):
        if not robot.in_collision(chain.to_robot_configuration(q), obstacles, root, self_collision=True, links=links):
            out.append(chain_base @ T)
    return out


def _aimed_poses(scene, robot, chain, chain_base, root, obstacles, links, points, n, rng, reach, ik_attempts):
    """Camera poses (world) looking at random sample points from random clear directions, kept when IK
    with the true scene as obstacles reaches them (approach mode: position and optical axis)."""
    from ..exploration.camera import look_at

    if len(points) == 0 or n == 0:
        return []
    shoulder = chain_base[:3, 3]
    eyes, targets = [], []
    tries = 0
    while len(eyes) < n and tries < 20 * n:
        tries += 1
        p = points[rng.integers(len(points))]
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        dist = rng.uniform(0.15, 0.7)
        eye = p + dist * d
        if eye[2] < 0.05 or np.linalg.norm(eye - shoulder) > reach:
            continue
        if scene.raycast(p, d, dist) is not None:
            continue
        eyes.append(eye)
        targets.append(p)
    if not eyes:
        return []
    inv = np.linalg.inv(chain_base)
    Ts = np.array([inv @ look_at(e, t) for e, t in zip(eyes, targets)])
    Q, ok = chain.ik_batch(Ts, mode="approach", approach_axis=(0.0, 0.0, 1.0), attempts=ik_attempts,
                           position_tolerance=1e-3, orientation_tolerance=1e-2, obstacles=obstacles, self_collision=True,
                           base_pose=root, rng_seed=int(rng.integers(1 << 31)), obstacle_links=links)
    return [chain_base @ chain.fk(q) for q in Q[ok]]


def observable_cells(scene: Scene, chain=None, base_pose=None, robot=None, regions=None, resolution: float = 0.025,
                     fov: float = np.deg2rad(58.0), max_range: float = 4.0, width: int = 64, height: int = 48,
                     joint_samples: int = 2000, aimed_samples: int = 2000, ik_attempts: int = 4,
                     seed: int = 0, clearance: float = 0.0) -> Observable:
    """The observable part of `regions` ((lo, hi) pairs; default the scene's interiors) for the arm
    `chain` of `robot` whose base link sits at `base_pose` (4x4, world). `robot=None` (or True) with
    `chain=None` uses the explorer standing at the origin. Captures are `width` x `height`, noiseless,
    with `fov` and `max_range` of the exploration's camera; the map has the exploration's `resolution`.
    `joint_samples` random configurations and `aimed_samples` aimed poses are tried (see the module);
    `clearance` (m) keeps only the poses whose camera is that far from every solid box (the safe-view rule)."""
    if resolution <= 0 or not np.isfinite(resolution):
        raise ValueError(f"resolution must be a positive number of metres, got {resolution!r}")
    if not np.isfinite(clearance) or clearance < 0:
        raise ValueError(f"clearance must be a number of metres >= 0, got {clearance!r}")
    if min(joint_samples, aimed_samples) < 0 or joint_samples + aimed_samples == 0:
        raise ValueError("joint_samples and aimed_samples must be >= 0, and not both 0")
    if chain is None:
        if robot not in (None, True):
            raise ValueError("pass chain= with a robot other than the explorer")
        robot, chain = explorer_robot()
    elif robot is None or robot is True:
        raise ValueError("pass robot= (the Robot the chain belongs to) with chain=")
    chain_base = arm_base_pose(robot, chain) if base_pose is None else np.asarray(base_pose, float)
    root = robot_root(robot, chain, chain_base)
    regions = list(scene.interiors) if regions is None else list(regions)
    points = region_points(scene, regions, resolution)
    rng = np.random.default_rng(seed)
    obstacles = scene.obstacles()
    reach = arm_reach(chain, seed)
    links = chain.moved_links
    poses = _joint_poses(robot, chain, chain_base, root, obstacles, links, joint_samples, rng)
    poses += _aimed_poses(scene, robot, chain, chain_base, root, obstacles, links, points, aimed_samples, rng, reach,
                          ik_attempts)
    if clearance > 0:
        keep = _clear_of_boxes(scene, [T[:3, 3] for T in poses], clearance)
        poses = [T for T, k in zip(poses, keep) if k]
    seen = _known_after(scene, poses, points, resolution, fov, max_range, width, height, seed)
    return Observable(points=points, observable=seen, resolution=resolution,
                      poses_sampled=joint_samples + aimed_samples, poses_valid=len(poses),
                      poses=np.array(poses, float).reshape(-1, 4, 4), fov=fov, max_range=max_range, width=width,
                      height=height)
