"""Sampled base poses in the scene: the robot's footprint at each pose and an arrow along its heading; their R_S
listed in the control panel (`table`). No text in the 3D scene: the browser rasterises label glyphs a few per
frame, which cost a software-rendering browser up to a second of extra frames when the page opens."""
from __future__ import annotations

import numpy as np

from . import colours


def outline_segments(footprint: np.ndarray, pose4, lift: float = 0.04) -> np.ndarray:
    """Line segments (K, 2, 3) of a closed xy outline (K, 2) placed at base pose (x, y, z, theta), `lift` m up."""
    from .._core import base_pose

    T = base_pose(np.asarray(pose4, dtype=float))
    p = np.column_stack([footprint, np.full(len(footprint), lift)])
    w = p @ T[:3, :3].T + T[:3, 3]
    return np.stack([w, np.roll(w, -1, axis=0)], axis=1)


class SamplesLayer:
    """Poses (N, 4) drawn as footprints plus arrows; `table()` lists them with their R_S."""

    def __init__(self, scene, poses, rs, footprint: np.ndarray, name: str = "/samples", lift: float = 0.04):
        """`lift`: height relative to each pose's z at which outlines and arrows are drawn (just above the map's
        tiles; negative when the tiles lie on the floor below the robot's reference frame)."""
        from .._core import base_pose

        self.lift = lift
        self.poses = np.asarray(poses, dtype=float).reshape(-1, 4)
        self.rs = np.asarray(rs, dtype=float).reshape(-1)
        if len(self.poses) == 0:
            return
        segs = np.concatenate([outline_segments(footprint, p, lift) for p in self.poses])
        scene.add_line_segments(f"{name}/footprints", segs.astype(np.float32), colours.FOOTPRINT, thickness=0.015)
        reach = float(np.ptp(footprint, axis=0).max()) * 0.6
        arrows = []
        for p in self.poses:
            T = base_pose(p)
            start = T[:3, 3] + [0.0, 0.0, lift + 0.02]
            arrows.append([start, start + T[:3, 0] * max(reach, 0.15)])
        scene.add_arrows(f"{name}/headings", np.asarray(arrows, dtype=np.float32),
                         np.tile(np.array(colours.ARROW, np.uint8), (len(arrows), 1)),
                         shaft_radius=0.015, head_radius=0.04, head_length=0.08)

    def table(self) -> str:
        """The poses and their R_S as a markdown list (for the control panel)."""
        return "\n".join([f"**Sampled poses** ({len(self.poses)}, the arrows):", ""] + [
            f"{i + 1}. R_S = {r:.2f} at x = {p[0]:+.2f}, y = {p[1]:+.2f} m, theta = {np.degrees(p[3]):.0f} deg"
            for i, (p, r) in enumerate(zip(self.poses, self.rs))])


def sample_poses(smap, count: int, seed: int = 1, in_collision=None):
    """`count` well spread base poses from the compiled PoseSampler and their R_S: checked against the room the
    map was built with, or `in_collision` (PoseSampler's: Obstacles, (robot, obstacles, reference), a callable)."""
    from .._core import PoseSampler

    if count <= 0:
        return np.zeros((0, 4)), np.zeros(0)
    kwargs = {} if in_collision is None else {"in_collision": in_collision}
    sampler = PoseSampler(smap, seed=seed, **kwargs)
    poses = np.asarray(sampler.sample(count), dtype=float).reshape(-1, 4)
    return poses, smap.reachability(poses)
