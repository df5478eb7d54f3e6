"""Triangle meshes for the robot's shapes: STL files read with numpy (binary and ASCII), boxes, cylinders and
spheres, other formats (DAE, OBJ, ...) through trimesh.

Reading STL here keeps trimesh (and the SciPy it imports, seconds on a slow machine) out of the viewer's start
for robots described in STL, such as the PR2.
"""
from __future__ import annotations

import numpy as np


class Mesh:
    """Vertices (V, 3) float and triangles (F, 3) int of one mesh."""

    def __init__(self, vertices, faces):
        self.vertices = np.asarray(vertices, dtype=float).reshape(-1, 3)
        self.faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)

    def transformed(self, T) -> "Mesh":
        T = np.asarray(T, dtype=float)
        return Mesh(self.vertices @ T[:3, :3].T + T[:3, 3], self.faces)

    def scaled(self, scale) -> "Mesh":
        return Mesh(self.vertices * np.asarray(scale, dtype=float), self.faces)


def concatenate(meshes) -> Mesh:
    """One mesh of several (their triangles re-indexed)."""
    offsets = np.cumsum([0] + [len(m.vertices) for m in meshes])
    return Mesh(np.vstack([m.vertices for m in meshes]),
                np.vstack([m.faces + o for m, o in zip(meshes, offsets)]))


def _welded(corners: np.ndarray) -> Mesh:
    """A mesh of a triangle soup (F, 3, 3) with equal corners merged into one vertex (smooth normals)."""
    flat = corners.reshape(-1, 3)
    vertices, inverse = np.unique(flat, axis=0, return_inverse=True)
    return Mesh(vertices, inverse.reshape(-1, 3))


def _mesh_bytes(path: str) -> bytes:
    """The bytes of a mesh file: a regular file within the compiled library's mesh_file_bytes limit (a URDF's
    visual mesh may name a FIFO or a device, which would block the viewer or fill its memory)."""
    from .._core import limits
    from ..data_files import read_bytes

    return read_bytes(path, "mesh file", int(limits["mesh_file_bytes"]), "octoreach._core.limits['mesh_file_bytes']")


def read_stl(path: str) -> Mesh:
    """An STL file (binary or ASCII); OSError naming the file when it is neither."""
    data = _mesh_bytes(path)
    if len(data) >= 84:
        count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0])
        if 84 + 50 * count == len(data):
            rec = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
            return _welded(np.frombuffer(data, dtype=rec, count=count, offset=84)["corners"].astype(float))
    text = data.decode("ascii", errors="replace")
    if text.lstrip().startswith("solid"):
        rows = [line.split()[1:4] for line in text.splitlines() if line.strip().startswith("vertex")]
        try:
            corners = np.asarray(rows, dtype=float)
        except ValueError:
            corners = None
        if corners is not None and corners.ndim == 2 and corners.shape[1] == 3 and len(corners) % 3 == 0:
            return _welded(corners.reshape(-1, 3, 3))
    raise OSError(f"{path}: not a binary or ASCII STL file")


def read_mesh(path: str) -> Mesh:
    """A mesh file: STL here, anything else through trimesh."""
    if path.lower().endswith(".stl"):
        return read_stl(path)
    import io
    import os

    import trimesh

    data = _mesh_bytes(path)  # trimesh reads what it is given: the checked bytes, never the path again
    loaded = trimesh.load(io.BytesIO(data), file_type=os.path.splitext(path)[1].lstrip(".").lower(), force="mesh",
                          resolver=trimesh.resolvers.FilePathResolver(path))
    return Mesh(loaded.vertices, loaded.faces)


def box(size) -> Mesh:
    """An axis-aligned box of extents `size` (3,), centred at 0."""
    h = np.asarray(size, dtype=float) / 2.0
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float) * h
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
         [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return Mesh(v, f)


def cylinder(radius: float, length: float, sections: int = 24) -> Mesh:
    """A closed cylinder along z, centred at 0."""
    a = 2.0 * np.pi * np.arange(sections) / sections
    ring = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
    v = np.vstack([np.column_stack([ring, np.full(sections, -length / 2)]),
                   np.column_stack([ring, np.full(sections, length / 2)]),
                   [[0.0, 0.0, -length / 2], [0.0, 0.0, length / 2]]])
    i = np.arange(sections)
    j = (i + 1) % sections
    bottom, top = 2 * sections, 2 * sections + 1
    f = np.vstack([np.column_stack([i, j, sections + j]), np.column_stack([i, sections + j, sections + i]),
                   np.column_stack([np.full(sections, bottom), j, i]),
                   np.column_stack([np.full(sections, top), sections + i, sections + j])])
    return Mesh(v, f)


def sphere(radius: float, rings: int = 12, sections: int = 24) -> Mesh:
    """A UV sphere centred at 0."""
    polar = np.pi * np.arange(1, rings) / rings
    a = 2.0 * np.pi * np.arange(sections) / sections
    p, q = np.meshgrid(polar, a, indexing="ij")
    v = np.column_stack([(np.sin(p) * np.cos(q)).ravel(), (np.sin(p) * np.sin(q)).ravel(), np.cos(p).ravel()])
    v = np.vstack([v, [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]]) * radius
    north, south = len(v) - 2, len(v) - 1
    faces = []
    for r in range(rings - 2):
        for s in range(sections):
            a0, a1 = r * sections + s, r * sections + (s + 1) % sections
            b0, b1 = a0 + sections, a1 + sections
            faces += [[a0, b0, b1], [a0, b1, a1]]
    last = (rings - 2) * sections
    for s in range(sections):
        faces.append([north, s, (s + 1) % sections])
        faces.append([south, last + (s + 1) % sections, last + s])
    return Mesh(v, faces)


def shape_mesh(shape) -> Mesh | None:
    """A box, cylinder, sphere or mesh Shape (a mesh from its triangles) as a triangle mesh in its parent frame
    (its pose applied); None for an OctoMap."""
    if shape.kind == "box":
        mesh = box(shape.size)
    elif shape.kind == "cylinder":
        mesh = cylinder(shape.radius, shape.length)
    elif shape.kind == "sphere":
        mesh = sphere(shape.radius)
    elif shape.kind == "mesh":
        mesh = Mesh(*shape.mesh_triangles())
    else:
        return None
    return mesh.transformed(shape.pose)
