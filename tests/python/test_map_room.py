"""Surface maps remember their room: the obstacles they were built with and the body checked against them, saved in
the map file (format version 2, a section after the payload; version 1 files still load, with no room); the sampler
keeps the body out of that room by default; a room that differs from it is said."""
from __future__ import annotations

import io
import struct
from pathlib import Path

import numpy as np
import pytest

import octoreach
from octoreach import room_checks

OLD_MAP = Path(__file__).parent / "data" / "test_arm_table_format1.orsm"  # written by octoreach 0.1.0 (format 1)


@pytest.fixture(scope="module")
def arm():
    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.15, directions=24,
                                        progress=False)
    return robot, cap


def _room():
    """Every kind of obstacle: a box with a pose, a cylinder, a sphere, a mesh (a tetrahedron) and OctoMap cells."""
    obstacles = octoreach.Obstacles()
    T = np.eye(4)
    T[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    T[:3, 3] = [0.0, 0.9, 0.5]
    obstacles.add_shape(octoreach.Shape.box([1.0, 0.1, 1.0], T), "wall")
    obstacles.add_shape(octoreach.Shape.cylinder(0.1, 0.4, _at(-0.6, 0.0, 0.2)), "bin")
    obstacles.add_shape(octoreach.Shape.sphere(0.08, _at(-0.4, -0.6, 0.08)), "ball")
    tetra = octoreach.Shape.triangle_mesh([[0, 0, 0], [0.2, 0, 0], [0, 0.2, 0], [0, 0, 0.2]],
                                          [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], _at(0.5, -0.7, 0.0))
    obstacles.add_shape(tetra, "tetra")
    obstacles.add_points(np.array([[-0.8, 0.6, 0.05], [-0.8, 0.65, 0.05]]), 0.05, "scan")
    return obstacles


def _at(x, y, z):
    T = np.eye(4)
    T[:3, 3] = [x, y, z]
    return T


@pytest.fixture(scope="module")
def roomed(arm, tmp_path_factory):
    robot, cap = arm
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    table.add_legs()
    sm = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.15, z_range=(0, 0), obstacles=_room(),
                                    progress=False)
    path = tmp_path_factory.mktemp("room") / "table.orsm"
    sm.save(str(path))
    return table, sm, path


def test_a_surface_map_records_its_room_and_body(arm, roomed):
    robot, _ = arm
    table, sm, _ = roomed
    room = sm.room
    own = table.obstacles()
    assert room.surface_count == len(own) == 2 + 4  # the slab's two triangles and four legs, first
    assert list(room.obstacles.names[room.surface_count:]) == ["wall", "bin", "ball", "tetra", "scan"]
    assert room.body and set(room.body_links) <= set(robot.link_names)
    assert not room.empty and sm.format_version == 2 <= octoreach._core.map_format_version()


def test_the_room_survives_the_file(roomed):
    _, sm, path = roomed
    assert path.read_bytes()[14:18] == struct.pack("<I", 2)
    loaded = octoreach.SurfaceMap.load(str(path))
    assert loaded.room.differences(sm.room.obstacles) == []
    assert list(loaded.room.obstacles.names) == list(sm.room.obstacles.names)
    assert [s.kind for s in loaded.room.obstacles.shapes][-5:] == ["box", "cylinder", "sphere", "mesh", "octree"]
    assert loaded.room.body_links == sm.room.body_links
    for a, b in zip(loaded.room.body, sm.room.body):
        assert a.kind == b.kind and np.allclose(a.pose, b.pose)
    poses = np.array([[0.0, 0.0, 0.0, 0.3], [-0.6, 0.0, 0.0, 0.0], [0.5, 0.9, 0.0, 1.0]])
    assert list(loaded.room.body_collides(poses)) == list(sm.room.body_collides(poses))
    assert loaded.parameters == sm.parameters


def test_a_damaged_room_is_refused(roomed, tmp_path):
    _, _, path = roomed
    data = bytearray(path.read_bytes())
    data[-3] ^= 0xFF  # inside the room section's compressed bytes
    bad = tmp_path / "bad.orsm"
    bad.write_bytes(bytes(data))
    with pytest.raises(OSError, match="section 'room'"):
        octoreach.SurfaceMap.load(str(bad))
    (tmp_path / "short.orsm").write_bytes(bytes(path.read_bytes()[:-5]))
    with pytest.raises(OSError, match="truncated|damaged"):
        octoreach.SurfaceMap.load(str(tmp_path / "short.orsm"))


def test_old_map_files_still_load_with_no_room(tmp_path, capsys):
    assert OLD_MAP.read_bytes()[14:18] == struct.pack("<I", 1)
    old = octoreach.SurfaceMap.load(str(OLD_MAP))
    assert old.room.empty and not old.room.body and len(old.room.obstacles) == 0
    poses = np.array([[0.0, 0.0, 0.0, 0.0], [0.1, -0.2, 0.0, 1.0]])
    assert old.reachability(poses) == pytest.approx([0.4097222089767456, 0.3541666567325592])  # as 0.1.0 gave
    assert octoreach.map_files.load(OLD_MAP).voxel_count == 135
    sampler = room_checks.sampler(old, seed=1)
    assert not sampler.checks_room and "records no room" in capsys.readouterr().err
    assert sampler.sample(3).shape == (3, 4)
    old.save(str(tmp_path / "again.orsm"))  # saved again: the current format, still no room
    again = octoreach.SurfaceMap.load(str(tmp_path / "again.orsm"))
    assert again.room.empty and again.parameters == old.parameters
    with pytest.raises(ValueError, match="records no robot body"):
        room_checks.sampler(old, scene=_room())


def test_the_sampler_keeps_the_body_out_of_the_map_room(arm, roomed):
    robot, cap = arm
    _, sm, _ = roomed
    checked = octoreach.PoseSampler(sm, seed=4)
    assert checked.checks_room
    poses = checked.sample(60)
    assert not sm.room.body_collides(poses).any()
    unchecked = octoreach.PoseSampler(sm, seed=4, room_check=False)
    assert not unchecked.checks_room and unchecked.sample(60).shape == (60, 4)
    # A room given instead replaces the map's: a box over the map's cells keeps every pose off it.
    block = octoreach.Obstacles()
    lo, hi = sm.bounds
    block.add_shape(octoreach.Shape.box([0.4, 2.0, 1.0], _at(lo[0] + 0.2, (lo[1] + hi[1]) / 2, 0.5)), "block")
    other = octoreach.PoseSampler(sm, seed=4, in_collision=block)
    poses = other.sample(30)
    assert not sm.room.body_collides(poses, block).any()
    assert sm.room.touched(np.array([[lo[0] + 0.2, (lo[1] + hi[1]) / 2, 0.0, 0.0]]), block) == ["block"]


def test_a_room_that_differs_is_said(roomed):
    _, sm, _ = roomed
    same = octoreach.Obstacles()
    for shape, name in zip(sm.room.obstacles.shapes, sm.room.obstacles.names):
        same.add_shape(shape, name + "_renamed")
    assert sm.room.differences(same) == []  # names and order do not matter
    moved = octoreach.Obstacles()
    for shape, name in zip(sm.room.obstacles.shapes, sm.room.obstacles.names):
        if name != "wall":
            moved.add_shape(shape, name)
    moved.add_shape(octoreach.Shape.box([1.0, 0.1, 1.0], _at(0.0, 1.0, 0.5)), "wall")
    found = sm.room.differences(moved)
    assert len(found) == 2 and "'wall'" in found[0] and "map's room only" in found[0] and "not in the map's room" in found[1]
    out = io.StringIO()
    room_checks.warn_differences(sm, moved, "kitchen.json", file=out)
    assert out.getvalue().startswith("octoreach: warning: kitchen.json differs from the room the map was built with")


def test_combined_maps_keep_the_shared_room(arm, roomed):
    _, sm, _ = roomed
    both = octoreach.SurfaceMap.combine([sm, sm], "max")
    assert both.room.differences(sm.room.obstacles) == [] and len(both.room.body) == len(sm.room.body)


def test_a_polygon_is_triangulated_for_any_simple_outline():
    # An L-shaped counter (2.64 m2): a fan from its first vertex would cover 6 m2 and the floor in the corner.
    L = [[-1.0, 0.9, 0.9], [0.9, 0.9, 0.9], [0.9, -1.0, 0.9], [1.5, -1.0, 0.9], [1.5, 1.5, 0.9], [-1.0, 1.5, 0.9]]
    s = octoreach.Surface(L)
    tri = np.asarray(s.triangles)
    v = np.asarray(s.vertices)
    areas = np.linalg.norm(np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]]), axis=1) / 2
    assert len(tri) == 4 and areas.sum() == pytest.approx(s.area) == pytest.approx(2.64)
