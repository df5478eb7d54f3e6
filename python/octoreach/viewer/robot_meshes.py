"""The robot's visual geometry, drawn at a configuration and base pose.

Shapes come from the robot loader (``Robot.visuals``: the URDF's <visual> elements, mesh files resolved by the
loader), or from its collision shapes (``Robot.collision_shapes``) for links without visuals (the project's test
arm has only those) or whose visual meshes were not found; one merged mesh per link in the link's frame. Mesh
files are read by mesh_files (STL with numpy, other formats through trimesh). Link poses come from the compiled
``Robot.link_poses``; the viewer only places the per-link meshes there.
"""
from __future__ import annotations

import numpy as np

from . import colours, mesh_files


def _mesh(shape, cache: dict, from_file: bool):
    """A shape as a triangle mesh in the link frame (None for a kind with no surface to draw here). Visual meshes
    are read from their files (`from_file`); collision meshes come from the loader's triangles."""
    if shape.kind == "mesh" and from_file:
        if shape.mesh_path not in cache:
            cache[shape.mesh_path] = mesh_files.read_mesh(shape.mesh_path)
        mesh = cache[shape.mesh_path].scaled(shape.scale).transformed(shape.pose)
    else:
        mesh = mesh_files.shape_mesh(shape)
    return mesh if mesh is not None and len(mesh.faces) else None


class RobotMeshes:
    """Visual meshes of a robot, one per link (link frame), and their colours. `missing`: the visual mesh files
    the loader did not find (those links are drawn with their collision shapes)."""

    def __init__(self, robot):
        self.robot = robot
        self.meshes: dict[str, mesh_files.Mesh] = {}
        self.colours: dict[str, tuple] = {}
        self.missing: list[str] = []
        visuals, collisions = robot.visuals, robot.collision_shapes
        cache: dict = {}
        for link in robot.link_names:
            lost = [v.mesh_uri for v in visuals.get(link, []) if v.shape.kind == "mesh" and not v.shape.mesh_path]
            self.missing += lost
            drawn = visuals.get(link, []) if not lost else []
            parts = [_mesh(v.shape, cache, True) for v in drawn] or \
                [_mesh(s, cache, False) for s in collisions.get(link, [])]
            parts = [p for p in parts if p is not None]
            if parts:
                self.meshes[link] = mesh_files.concatenate(parts)
                rgba = next((v.rgba for v in drawn if v.rgba is not None), None)
                grey = rgba is None or (max(rgba[:3]) - min(rgba[:3]) < 0.05 and rgba[0] < 0.25)
                self.colours[link] = colours.ROBOT if grey else tuple(int(255 * c) for c in rgba[:3])

    def footprint(self, q) -> np.ndarray:
        """Closed xy outline (K, 2) of the robot's visual geometry below 0.35 m at q (root frame): the convex
        hull of its vertices, what the base covers on the floor."""
        poses = self.robot.link_poses(q)
        pts = []
        for name, mesh in self.meshes.items():
            T = poses[name]
            v = mesh.vertices @ T[:3, :3].T + T[:3, 3]
            pts.append(v[v[:, 2] < 0.35, :2])
        pts = np.concatenate(pts) if pts else np.zeros((0, 2))
        if len(pts) < 3:
            return np.array([[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]])
        return _convex_hull(np.unique(np.round(pts, 2), axis=0))


def _convex_hull(p: np.ndarray) -> np.ndarray:
    """Counter-clockwise convex hull (Andrew's monotone chain) of distinct, sorted 2D points."""
    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for pt in p:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], pt) <= 0:
            lower.pop()
        lower.append(tuple(pt))
    for pt in p[::-1]:
        while len(upper) >= 2 and cross(upper[-2], upper[-1], pt) <= 0:
            upper.pop()
        upper.append(tuple(pt))
    return np.array(lower[:-1] + upper[:-1])


def _wxyz(R: np.ndarray) -> np.ndarray:
    import viser.transforms as tf

    return tf.SO3.from_matrix(R).wxyz


class RobotLayer:
    """The robot in the scene: a frame node `/robot` at the base pose with one mesh node per link."""

    def __init__(self, scene, meshes: RobotMeshes, q=None, base_pose=None, name: str = "/robot"):
        self.scene, self.meshes, self.name = scene, meshes, name
        self.q = np.asarray(q if q is not None else meshes.robot.home(), dtype=float)
        self.root = scene.add_frame(name, show_axes=False)
        self.links = {}
        for link, mesh in meshes.meshes.items():
            self.links[link] = scene.add_mesh_simple(f"{name}/{link}", np.asarray(mesh.vertices, np.float32),
                                                     np.asarray(mesh.faces, np.uint32),
                                                     color=meshes.colours[link], cast_shadow=False)
        self.set_configuration(self.q)
        self.set_base_pose(np.eye(4) if base_pose is None else base_pose)

    def set_configuration(self, q) -> None:
        """Places every link at robot.link_poses(q) (root frame)."""
        self.q = np.asarray(q, dtype=float)
        poses = self.meshes.robot.link_poses(self.q)
        for link, handle in self.links.items():
            T = poses[link]
            handle.wxyz = _wxyz(T[:3, :3])
            handle.position = T[:3, 3]

    def points(self) -> np.ndarray:
        """The robot's mesh vertices (N, 3) in the world frame, at its configuration and base pose."""
        poses = self.meshes.robot.link_poses(self.q)
        pts = []
        for link, mesh in self.meshes.meshes.items():
            T = self.base_pose @ poses[link]
            pts.append(mesh.vertices @ T[:3, :3].T + T[:3, 3])
        return np.vstack(pts) if pts else np.zeros((1, 3))

    def set_base_pose(self, T) -> None:
        """Moves the root link to the 4x4 world pose T."""
        T = np.asarray(T, dtype=float)
        self.root.wxyz = _wxyz(T[:3, :3])
        self.root.position = T[:3, 3]
        self.base_pose = T
