"""What the robot's head camera sees from a base pose: the perception of the simulated inspect-surface action.

The PR2 of the paper carries a Kinect on its head (57 x 43 degree field of view, depth from about 0.5 m to
4 m). Its head pans (+-168 degrees) and tilts (27 degrees up to 80 degrees down) to look at a surface, so
what limits the view is range and line of sight, not the field of view: a point is seen when its distance
from the camera lies in [MIN_RANGE, MAX_RANGE] and a thin box from the camera to it (stopping SKIP metres
short of the point, so the surface it lies on does not hide it) touches no obstacle of the room (table tops,
shelf boards, chairs, walls). The camera sits where the robot's camera link is in its reference posture: the link
given, or the one ``octoreach.find_camera_link`` finds (a link named like a camera on the head, else the head's
end); a robot without an unambiguous one is a ValueError asking for the link.
"""
from __future__ import annotations

import numpy as np

from .._core import Obstacles, Robot, base_pose, camera_link

MIN_RANGE = 0.5  # m, Kinect's nearest depth
MAX_RANGE = 4.0  # m, Kinect's useful depth indoors
RAY_WIDTH = 0.01  # m, cross-section of the line-of-sight box
SKIP = 0.04  # m, the end of the ray left unchecked (the object's own surface)


class HeadCamera:
    """Line-of-sight visibility of points from a base pose. `frame`: the camera's link (None: the robot's camera
    as ``octoreach.find_camera_link`` finds it; ValueError asking for it when that is ambiguous; the paper's PR2:
    ``head_plate_frame``, where its Kinect is mounted); `reference`: the posture it is taken in."""

    def __init__(self, robot: Robot, reference, frame: str | None = None):
        self.frame = camera_link(robot, frame).link
        self.in_root = robot.link_poses(np.asarray(reference, float))[self.frame][:3, 3].copy()

    def position(self, pose) -> np.ndarray:
        """Camera position (3,) in the world with the robot at base pose (x, y, z, theta)."""
        return (base_pose(np.asarray(pose, float)) @ np.append(self.in_root, 1.0))[:3]

    def visible(self, pose, points, obstacles: Obstacles) -> np.ndarray:
        """(N,) bool: which points (N, 3) the camera sees from base pose `pose` past `obstacles`."""
        eye = self.position(pose)
        points = np.asarray(points, float).reshape(-1, 3)
        out = np.zeros(len(points), bool)
        for i, q in enumerate(points):
            d = q - eye
            dist = float(np.linalg.norm(d))
            if not MIN_RANGE <= dist <= MAX_RANGE:
                continue
            out[i] = not obstacles.collides_box((dist - SKIP, RAY_WIDTH, RAY_WIDTH), _segment_pose(eye, d / dist, dist - SKIP))
        return out


def _segment_pose(start: np.ndarray, direction: np.ndarray, length: float) -> np.ndarray:
    """4x4 pose of a box whose local x axis runs along `direction`, centred on the segment's middle."""
    x = direction
    helper = np.array([0.0, 0.0, 1.0]) if abs(x[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    y = np.cross(helper, x)
    y /= np.linalg.norm(y)
    T = np.eye(4)
    T[:3, :3] = np.column_stack([x, y, np.cross(x, y)])
    T[:3, 3] = start + direction * length / 2
    return T
