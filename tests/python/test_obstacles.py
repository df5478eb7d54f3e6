"""Environment obstacles of every kind against the robot: boxes, meshes (STL through assimp), triangle
arrays, OctoMap files and point sets, each checked both ways (touching and clear)."""
from __future__ import annotations

import numpy as np
import pytest

import octoreach
from octoreach import robots


def at(x, y, z):
    T = np.eye(4)
    T[:3, 3] = [x, y, z]
    return T


@pytest.fixture(scope="module")
def arm():
    return robots.test_arm()


def _cube_triangles(size):
    h = size / 2
    v = np.array([[x, y, z] for x in (-h, h) for y in (-h, h) for z in (-h, h)], float)
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6),
             (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return v, np.array(faces)


def test_triangle_mesh_obstacle(arm):
    v, f = _cube_triangles(0.2)
    hit, clear = octoreach.Obstacles(), octoreach.Obstacles()
    hit.add_triangles(v, f, at(0, 0, 0.8))  # around the straight-up forearm
    clear.add_triangles(v, f, at(1.0, 0, 0.8))
    assert arm.in_collision(arm.home(), hit)
    assert not arm.in_collision(arm.home(), clear)
    with pytest.raises(ValueError, match="vertex"):
        octoreach.Obstacles().add_triangles(v, np.array([[0, 1, 99]]))


def test_stl_mesh_obstacle(arm):
    path = robots.data_dir() / "robots" / "pr2_description" / "meshes" / "base_v0" / "base.stl"
    hit, clear = octoreach.Obstacles(), octoreach.Obstacles()
    hit.add_mesh(str(path), at(0, 0, 0.5))  # the PR2 base (about 0.65 m wide) around the upper arm
    clear.add_mesh(str(path), at(3.0, 0, 0.5))
    assert arm.in_collision(arm.home(), hit)
    assert not arm.in_collision(arm.home(), clear)
    with pytest.raises(OSError, match="mesh file .*no such file|cannot read mesh"):
        octoreach.Obstacles().add_mesh("/nonexistent/mesh.stl")


def test_octomap_obstacles(arm, tmp_path):
    # Occupied cells around the forearm, as a point set and as a .bt file written by an ExplorationMap.
    pts = np.array([[x, y, 0.8] for x in np.arange(-0.1, 0.11, 0.05) for y in np.arange(-0.1, 0.11, 0.05)])
    obs = octoreach.Obstacles()
    obs.add_points(pts, 0.05)
    assert arm.in_collision(arm.home(), obs)
    assert not arm.in_collision(arm.home(), obs, base_pose=at(2.0, 0, 0))
    emap = octoreach.ExplorationMap(resolution=0.05)
    emap.insert(pts, np.array([0.0, 0.0, 2.0]), 5.0)
    path = tmp_path / "cells.bt"
    emap.write_bt(str(path))
    from_file = octoreach.Obstacles()
    from_file.add_octree_file(str(path))
    assert arm.in_collision(arm.home(), from_file)
    assert not arm.in_collision(arm.home(), from_file, base_pose=at(2.0, 0, 0))
    with pytest.raises(OSError):
        octoreach.Obstacles().add_octree_file(str(tmp_path / "missing.bt"))
    with pytest.raises(ValueError, match="finite"):
        octoreach.Obstacles().add_points(np.array([[0, 0, np.nan]]), 0.05)
