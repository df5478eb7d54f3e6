"""The numeric limits of octoreach (octoreach._core.limits): readable from Python, checked before any work
or allocation with an error naming the value, agreed on by the builds and the loaders; the polygon checks
stay fast up to the vertex limit; absurd magnitudes are called out of range. Calls that could run long or
allocate much on a broken build run in a child process with a timeout and a memory cap."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import octoreach
from robust_util import SANITIZED, run_python

L = octoreach._core.limits


def test_limits_are_a_read_only_mapping_of_positive_numbers():
    expected = {"robot_file_bytes", "mesh_file_bytes", "octree_file_bytes", "map_file_bytes", "map_payload_bytes",
                "map_voxels", "coordinate", "min_map_resolution", "max_map_resolution", "polygon_vertices",
                "surface_points", "directions", "rolls", "image_pixels", "fk_samples", "view_candidates",
                "sampler_candidates"}
    assert expected <= set(L)
    assert all(isinstance(v, (int, float)) and v > 0 for v in L.values())
    with pytest.raises(TypeError):
        L["polygon_vertices"] = 10**9
    assert L["max_map_resolution"] > L["min_map_resolution"]


@pytest.fixture(scope="module")
def small_cap():
    chain = octoreach.robots.test_arm().chain("base_link", "tool0")
    return octoreach.CapabilityMap.build(chain, resolution=0.2, directions=16, progress=False, seed=1)


@pytest.fixture(scope="module")
def small_surface_map(small_cap):
    return octoreach.SurfaceMap.build(octoreach.robots.test_arm(), small_cap,
                                      octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55), resolution=0.2, theta_bins=8,
                                      z_range=(0, 0), progress=False)


def _circle(n, r=1.0, z=0.7):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[r * np.cos(t), r * np.sin(t), np.full(n, z)]


def _child_ok(code: str, timeout: float = 120, mem: int = 2 << 30):
    child = run_python("import math, numpy as np, octoreach as o\n" + code, timeout=timeout, mem_bytes=mem)
    assert not child.hung, f"still running after {timeout} s: {child.stdout[-500:]}"
    assert child.returncode == 0, child.stderr[-2000:]
    return child.stdout


# ---- counts checked before work ----

def test_polygon_vertex_limit():
    n = int(L["polygon_vertices"])
    with pytest.raises(ValueError, match=f"at most {n} vertices"):
        octoreach.Surface(_circle(n + 1))


def test_polygons_at_the_vertex_limit_are_checked_in_n_log_n():
    # A circle, a star of long spikes and a comb of long teeth (dense long edges: quadratic for any grid of
    # cells) at the limit, and the same star made self-intersecting: built or refused, never minutes.
    n = int(L["polygon_vertices"])
    out = _child_ok(f"""
n = {n}
t = np.linspace(0, 2 * np.pi, n, endpoint=False)
r = np.where(np.arange(n) % 2 == 0, 1.0, 0.05)
star = np.c_[r * np.cos(t), r * np.sin(t), np.full(n, 0.7)]
teeth = (n - 3) // 4
comb = [(x, y) for i in range(teeth) for x, y in ((2 * i, 0.1), (2 * i, 9.0), (2 * i + 1, 9.0), (2 * i + 1, 0.1))]
comb = np.array(comb + [(2 * teeth, 0.1), (2 * teeth, 0.0), (0, 0.0)]) * [0.01, 0.1]
comb = np.c_[comb, np.full(len(comb), 0.7)]
circle = np.c_[np.cos(t), np.sin(t), np.full(n, 0.7)]
for name, v in (('circle', circle), ('star', star), ('comb', comb)):
    print(name, round(o.Surface(v).area, 6), flush=True)
bad = star.copy()
bad[[10, n // 2]] = bad[[n // 2, 10]]
try:
    o.Surface(bad)
    print('ACCEPTED')
except ValueError as e:
    print('REFUSED', e)
""", timeout=300 if SANITIZED else 120)
    assert "circle 3.14" in out and "star" in out and "comb" in out and "REFUSED" in out, out
    assert "self-intersecting" in out


def test_image_size_limit():
    with pytest.raises(ValueError, match="pixels"):
        octoreach.DepthCamera(30000, 30000, 1.0, 3.0)
    side = int(math.isqrt(int(L["image_pixels"])))
    assert octoreach.DepthCamera(side, side, 1.0, 3.0).width == side


def test_fk_sample_limit(arm_chain):
    with pytest.raises(ValueError, match="fk_samples"):
        octoreach.CapabilityMap.build(arm_chain, resolution=0.3, directions=8, fk_samples=int(L["fk_samples"]) + 1,
                                      progress=False)


def test_view_search_budget_limits():
    m = octoreach.ExplorationMap(resolution=0.1)
    m.insert(np.random.default_rng(0).uniform([1, -0.5, 0], [1.6, 0.5, 0.6], (300, 3)), [0, 0, 0.3])
    cam = octoreach.DepthCamera(16, 12, 1.0, 3.0)
    big = int(L["view_candidates"])
    for kwargs in ({"max_candidate_cells": big, "orientations_per_cell": 2}, {"max_valid_poses": big + 1},
                   {"score_width": 5000, "score_height": 5000}):
        with pytest.raises(ValueError, match="at most"):
            octoreach._core.next_best_view(m, cam, **kwargs)


def test_sampler_and_surface_point_limits(small_surface_map):
    with pytest.raises(ValueError, match="candidates"):
        octoreach.PoseSampler(small_surface_map, candidates=int(L["sampler_candidates"]) + 1)
    s = octoreach.PoseSampler(small_surface_map, seed=1)
    with pytest.raises(ValueError, match="at most"):
        s.sample(int(L["sampler_candidates"]) + 1)
    assert len(s.history) == 0
    with pytest.raises(ValueError, match="grid points"):
        octoreach.Surface.rectangle(10.0, 10.0, 0.7).points(1e-4)


def test_map_build_grids_are_bounded_before_allocation(arm, small_cap):
    # 1 mm positions over a 2 m z range at 360 bins: about 1e13 values, refused before anything is allocated
    with pytest.raises(ValueError, match="grid .* more than the limit"):
        octoreach.InversePointMap.build(arm, small_cap, resolution=0.001, theta_bins=360, z_range=(-1.0, 1.0),
                                        progress=False)
    with pytest.raises(ValueError, match="grid .* more than the limit"):
        octoreach.SurfaceMap.build(arm, small_cap, octoreach.Surface.rectangle(1, 1, 0.5), resolution=0.001,
                                   theta_bins=360, z_range=(-1.0, 1.0), progress=False)


# ---- builds and loaders agree ----

def test_capability_resolution_range_is_the_same_in_build_and_load(arm_chain, tmp_path):
    for res in (200.0, 1e-4, math.nan, math.inf):
        with pytest.raises(ValueError, match="resolution"):
            octoreach.CapabilityMap.build(arm_chain, resolution=res, directions=8, progress=False)
    cap = octoreach.CapabilityMap.build(arm_chain, resolution=L["max_map_resolution"], directions=8, progress=False)
    cap.save(str(tmp_path / "coarse.orcm"))
    assert octoreach.CapabilityMap.load(str(tmp_path / "coarse.orcm")).resolution == L["max_map_resolution"]


def test_pose_map_resolution_range(arm, small_cap):
    with pytest.raises(ValueError, match="resolution"):
        octoreach.InversePointMap.build(arm, small_cap, resolution=200.0, progress=False)
    with pytest.raises(ValueError, match="resolution"):
        octoreach.SurfaceMap.build(arm, small_cap, octoreach.Surface.rectangle(1, 1, 0.5), resolution=200.0,
                                   progress=False)


# ---- absurd magnitudes ----

def test_absurd_magnitudes_are_out_of_range_not_misdescribed():
    with pytest.raises(ValueError, match="size_x .* out of range"):
        octoreach.Surface.rectangle(1e300, 1.0, 0.7)
    with pytest.raises(ValueError, match="x .* out of range"):
        octoreach.Surface.rectangle(1.0, 1.0, 0.7, x=1e300)
    with pytest.raises(ValueError, match=r"vertices\[0\] .* out of range"):
        octoreach.Surface([[1e300, 0, 0.7], [0, 1, 0.7], [0, 0, 0.7]])
    with pytest.raises(ValueError, match="out of range"):
        octoreach.Surface.rectangle(1.0, 1.0, 0.7).add_box([1e300, 1, 1], np.eye(4))
    big = L["coordinate"]
    assert octoreach.Surface.rectangle(1.0, 1.0, 0.7, x=big - 1).area == pytest.approx(1.0)


def test_obstacle_shapes_beyond_the_coordinate_limit_are_refused(tmp_path):
    # Boxes, cylinders, spheres and meshes of an Obstacles, a Scene or a room: a position or an extent past
    # `coordinate` (a sphere at 1e30 m, a mesh scaled by 1e300) is refused with its name, never placed where no
    # collision check or ray can hold it.
    from octoreach.rooms import Room

    far = np.eye(4)
    far[0, 3] = 1e300
    tri = tmp_path / "tri.stl"
    tri.write_text("solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                   "endfacet\nendsolid t\n")
    calls = {
        "box size": lambda: octoreach.Shape.box([1e300, 1, 1], np.eye(4)),
        "shape position": lambda: octoreach.Shape.box([1, 1, 1], far),
        "cylinder radius": lambda: octoreach.Shape.cylinder(1e7, 1.0, np.eye(4)),
        "cylinder length": lambda: octoreach.Shape.cylinder(0.1, 1e300, np.eye(4)),
        "sphere radius": lambda: octoreach.Shape.sphere(1e300, np.eye(4)),
        "out of range": lambda: octoreach.Obstacles().add_box([1, 1, 1], far),
        "mesh vertices": lambda: octoreach.Shape.triangle_mesh([[0, 0, 0], [1e300, 0, 0], [0, 1, 0]], [[0, 1, 2]], np.eye(4)),
        "has a vertex at": lambda: octoreach.Shape.mesh_file(str(tri), np.eye(4), [1e300, 1, 1]),
        "spheres[0]: shape position": lambda: Room({"spheres": [{"name": "b", "radius": 0.1, "xyz": [1e30, 0, 0]}]}),
        "cylinders[0]: cylinder length": lambda: Room({"cylinders": [{"name": "c", "radius": 0.1, "length": 1e300}]}),
        "boxes[0]: box size": lambda: Room({"boxes": [{"name": "w", "size": [1e9, 1, 1]}]}),
        "meshes[0]: mesh": lambda: Room({"meshes": [{"name": "m", "path": str(tri), "scale": [1e300, 1, 1]}]}),
    }
    for fragment, call in calls.items():
        with pytest.raises(ValueError, match=re.escape(fragment)):
            call()
    room = Room({"spheres": [{"name": "b", "radius": 0.5, "xyz": [L["coordinate"] - 1, 0, 0]}],
                 "meshes": [{"name": "m", "path": str(tri), "scale": [1000, 1000, 1000]}]})
    assert len(room.obstacles()) == 2
