"""The robot's visual geometry from its URDF, drawn at a configuration and base pose.

Shapes are the URDF's <visual> elements (meshes read by mesh_files: STL with numpy, other formats through
trimesh; boxes, cylinders, spheres), or its
<collision> elements for links without visuals (the project's test arm has only those), one merged mesh
per link in the link's frame. Mesh URIs (package://, file://, relative) are resolved by the rule of
the C++ robot loader (cpp/src/urdf.cpp: resolve_mesh). Link poses come from the compiled
``Robot.link_poses``; the viewer only places the per-link meshes there.
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET

import numpy as np

from . import colours, mesh_files


def robot_files(name: str, urdf_hash: str = "") -> tuple[str, list[str]]:
    """(URDF path, package_dirs) of a robot that ``octoreach.robots.load(name)`` loads, of the project's own
    robots (``urdf/NAME.urdf``, whose robots are named "octoreach_NAME"), or of the robot of example-robot-data
    whose URDF declares the robot name `name` (a Robot's name; with that model hash when given; see
    robots.loadable_name)."""
    from .. import robots

    own = name[len("octoreach_"):] if name.startswith("octoreach_") else name
    try:
        return str(robots.project_urdf(own)), []
    except ValueError:
        pass
    urdf, _, dirs = robots.files(robots.loadable_name(name, urdf_hash))
    return str(urdf), dirs


def resolve_uri(uri: str, package_dirs, urdf_dir: str) -> str:
    """The file of a mesh URI, by the robot loader's rule; OSError naming the tried paths when missing."""
    candidates = []
    if uri.startswith("package://"):
        rest = uri[len("package://"):]
        package, _, inner = rest.partition("/")
        for d in package_dirs:
            candidates.append(os.path.join(d, rest))
            if os.path.basename(os.path.normpath(d)) == package:
                candidates.append(os.path.join(d, inner))
    elif uri.startswith("file://"):
        candidates.append(uri[len("file://"):])
    elif uri.startswith("/"):
        candidates.append(uri)
    else:
        candidates.append(os.path.join(urdf_dir, uri))
        candidates += [os.path.join(d, uri) for d in package_dirs]
    for c in candidates:
        if os.path.isfile(c):
            return c
    raise OSError(f"mesh {uri!r} not found; tried: {' '.join(candidates) or '(no package dirs)'}")


def _origin(el) -> np.ndarray:
    o = el.find("origin") if el is not None else None
    if o is None:
        return np.eye(4)
    return mesh_files.rpy_matrix(o.get("xyz", "0 0 0").split(), o.get("rpy", "0 0 0").split())


def _rgba(visual, materials: dict):
    m = visual.find("material")
    if m is None:
        return None
    c = m.find("color")
    if c is not None:
        return [float(v) for v in c.get("rgba").split()]
    return materials.get(m.get("name"))


def _geometry(geom, package_dirs, urdf_dir, cache: dict):
    shape = geom[0] if len(geom) else None
    if shape is None:
        return None
    if shape.tag == "mesh":
        path = resolve_uri(shape.get("filename", ""), package_dirs, urdf_dir)
        if path not in cache:
            cache[path] = mesh_files.read_mesh(path)
        mesh = cache[path]
        if shape.get("scale"):
            mesh = mesh.scaled([float(v) for v in shape.get("scale").split()])
        return mesh
    if shape.tag == "box":
        return mesh_files.box([float(v) for v in shape.get("size").split()])
    if shape.tag == "cylinder":
        return mesh_files.cylinder(float(shape.get("radius")), float(shape.get("length")))
    if shape.tag == "sphere":
        return mesh_files.sphere(float(shape.get("radius")))
    return None


class RobotMeshes:
    """Visual meshes of a robot, one per link (link frame), and their colours."""

    def __init__(self, robot, urdf: str | None = None, package_dirs=None):
        if urdf is None:
            urdf, default_dirs = robot_files(robot.name, robot.urdf_hash)
            package_dirs = default_dirs if package_dirs is None else package_dirs
        self.robot = robot
        try:
            tree = ET.parse(urdf)
        except (OSError, ET.ParseError) as e:
            raise OSError(f"cannot read URDF {urdf!r}: {e}") from None
        root = tree.getroot()
        materials = {}
        for m in root.findall("material"):
            c = m.find("color")
            if c is not None:
                materials[m.get("name")] = [float(v) for v in c.get("rgba").split()]
        urdf_dir = os.path.dirname(os.path.abspath(urdf))
        cache: dict = {}
        self.meshes: dict[str, mesh_files.Mesh] = {}
        self.colours: dict[str, tuple] = {}
        for link in root.findall("link"):
            parts, rgba = [], None
            for visual in link.findall("visual") or link.findall("collision"):
                geom = visual.find("geometry")
                mesh = _geometry(geom, package_dirs or [], urdf_dir, cache) if geom is not None else None
                if mesh is None or len(mesh.faces) == 0:
                    continue
                parts.append(mesh.transformed(_origin(visual)))
                rgba = rgba or _rgba(visual, materials)
            if parts:
                self.meshes[link.get("name")] = mesh_files.concatenate(parts)
                grey = rgba is None or (max(rgba[:3]) - min(rgba[:3]) < 0.05 and rgba[0] < 0.25)
                self.colours[link.get("name")] = colours.ROBOT if grey else tuple(int(255 * c) for c in rgba[:3])

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

    def set_base_pose(self, T) -> None:
        """Moves the root link to the 4x4 world pose T."""
        T = np.asarray(T, dtype=float)
        self.root.wxyz = _wxyz(T[:3, :3])
        self.root.position = T[:3, 3]
        self.base_pose = T
