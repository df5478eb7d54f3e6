"""Rooms: every obstacle checked against body and arm, scene files, and the conventions (floor, radians, NaN)."""
from __future__ import annotations

import itertools
import json
from pathlib import Path

import numpy as np
import pytest

import octoreach
from octoreach import robots, rooms, surface_maps
from octoreach import testing

WALL_Y = 0.45  # a wall along x at y = 0.45, between the table (y in [-0.2, 0.2]) and poses with y > 0.5


@pytest.fixture(scope="module")
def arm_room():
    robot = robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.1, directions=48,
                                        progress=False, seed=3)
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4)
    wall = octoreach.Obstacles()
    pose = np.eye(4)
    pose[:3, 3] = [0.0, WALL_Y, 1.0]
    wall.add_box(np.array([2.0, 0.05, 2.0]), pose, "wall")
    open_map = octoreach.SurfaceMap.build(robot, cap, table, progress=False)
    walled = octoreach.SurfaceMap.build(robot, cap, table, obstacles=wall, progress=False)
    return robot, cap, table, wall, open_map, walled


def _values_behind(sm, y_min):
    centres, values = sm.voxels()
    return values[centres[:, 1] > y_min]


def test_a_wall_stops_the_arm(arm_room):
    robot, cap, table, wall, open_map, walled = arm_room
    # Without the wall the arm reaches the table from beyond y = 0.5; with it, never.
    assert _values_behind(open_map, WALL_Y + 0.05).max() > 0.05
    assert _values_behind(walled, WALL_Y + 0.05).size == 0 or _values_behind(walled, WALL_Y + 0.05).max() == 0
    behind = np.array([[0.0, 0.8, 0.0, -np.pi / 2], [0.2, 0.7, 0.0, -np.pi / 2]])
    assert np.all(open_map.reachability(behind) > 0)  # the pose: reached through the wall before
    assert np.all(walled.reachability(behind) == 0)
    # In front of the wall the map is unchanged where the arm keeps clear of it.
    front = np.array([[0.0, -0.5, 0.0, np.pi / 2], [0.6, 0.0, 0.0, np.pi]])
    assert np.allclose(walled.reachability(front), open_map.reachability(front))
    assert walled.stats["arm_rejections"] > open_map.stats["arm_rejections"]
    assert "room: 1 obstacles" in walled.parameters["checks"]


def test_the_sampler_never_stands_behind_the_wall(arm_room):
    robot, _, _, wall, _, walled = arm_room
    poses = octoreach.PoseSampler(walled, seed=4, in_collision=(robot, wall)).sample(20)
    assert np.all(poses[:, 1] < WALL_Y)


def test_the_arm_check_matches_brute_force_with_a_wall(arm_room):
    robot, cap, table, wall, _, walled = arm_room
    centres, _ = walled.voxels()
    rng = np.random.default_rng(5)
    idx = rng.choice(len(centres), size=min(12, len(centres)), replace=False)
    poses = np.column_stack([centres[idx, :2], np.zeros(len(idx)), rng.integers(0, 16, len(idx)) * np.pi / 8])
    # Poses right behind the wall too: the map and brute force must both say 0 there.
    poses = np.vstack([poses, [[0.0, 0.8, 0.0, -np.pi / 2], [0.3, 0.6, 0.0, -np.pi / 2]]])
    brute = testing.direct_reachability(robot, cap, table, poses, attempts=10, obstacles=wall)
    mapped = walled.reachability(poses)
    assert np.all(brute[-2:] == 0) and np.all(mapped[-2:] == 0)
    diff = mapped - brute
    assert np.max(diff) <= 0.05, f"map above brute force by {np.max(diff):.3f}"
    assert np.mean(np.abs(diff)) <= 0.08
    assert brute.max() > 0.2


# ----------------------------------------------------------------- TIAGo at a table beside a wall, brute force


def _tiago():
    """TIAGo by name once the robot loader knows it, else by path; with its reference posture free of
    self-collision (allowed-collision sampling) either way."""
    try:
        robot = robots.load("tiago")
    except (ValueError, KeyError, FileNotFoundError, OSError):
        try:
            root = robots.data_dir()
        except FileNotFoundError as e:
            pytest.skip(f"example-robot-data unavailable: {e}")
        urdf = root / "robots" / "tiago_description" / "robots" / "tiago.urdf"
        if not urdf.exists():
            pytest.skip("TIAGo is not in this example-robot-data")
        robot = octoreach.Robot.from_urdf(str(urdf), package_dirs=[str(root.parent), str(root / "robots")])
    chain = robot.chain("torso_lift_link", "hand_grasping_frame")
    ref = octoreach.default_reference(robot, chain)
    if robot.in_self_collision(ref):  # before the loader samples allowed collisions: sample them here
        robot = robot.with_allowed_collisions(robot.compute_allowed_collisions(samples=300, seed=1))
        allowed = {tuple(sorted(p)) for p in robot.allowed_collisions}
        rest = [p for p in itertools.combinations(sorted(robot.collision_links), 2) if p not in allowed]
        robot = robot.with_allowed_collisions(
            [p for p in rest if robot.with_allowed_collisions([c for c in rest if c != p]).in_self_collision(ref)])
    return robot


def test_tiago_at_a_table_beside_a_wall_matches_brute_force():
    robot = _tiago()
    arm = ("torso_lift_link", "hand_grasping_frame", (1.0, 0.0, 0.0))
    cap = octoreach.CapabilityMap.build_for_arm(robot, arm, resolution=0.15, directions=30, progress=False)
    room = rooms.Room()
    room.add_table("table", 0.8, 0.6, 0.75, x=0.0, y=0.0)
    room.add_box("wall", [0.05, 2.0, 2.0], [0.75, 0.0, 1.0])  # beside the table, along its +x edge
    (name, sm), = room.surface_maps(robot, cap, resolution=0.15, theta_bins=8, progress=False).items()
    assert name == "table" and sm.voxel_count > 0
    # Nowhere behind the wall.
    centres, values = sm.voxels()
    assert values[centres[:, 0] > 0.75].size == 0 or values[centres[:, 0] > 0.75].max() == 0
    rng = np.random.default_rng(0)
    idx = rng.choice(len(centres), size=min(6, len(centres)), replace=False)
    poses = np.column_stack([centres[idx, :2], np.zeros(len(idx)), rng.integers(0, 8, len(idx)) * np.pi / 4])
    poses = np.vstack([poses, [[1.3, 0.0, 0.0, np.pi]]])  # behind the wall, facing the table
    brute = testing.direct_reachability(robot, cap, room.surfaces["table"], poses, resolution=0.15,
                                             attempts=8, obstacles=room.obstacles(without="table"))
    mapped = sm.reachability(poses)
    assert brute[-1] == 0 and mapped[-1] == 0
    diff = mapped - brute
    assert np.max(diff) <= 0.08, f"map above brute force by {np.max(diff):.3f}"
    assert np.mean(np.abs(diff)) <= 0.1
    assert brute.max() > 0.1


# ----------------------------------------------------------------- rooms and scene files

SCENE = {
    "surfaces": [{"name": "table", "rectangle": {"size": [0.6, 0.4], "height": 0.4, "x": 0.0, "y": 0.0, "yaw": 0.0},
                  "legs": 0.04}],
    "shelves": [{"name": "shelf", "size": [0.6, 0.3], "boards": [0.2, 0.45, 0.7], "x": 0.0, "y": -0.9,
                 "yaw": 0.0}],
    "boxes": [{"name": "wall", "size": [0.05, 4.0, 2.0], "xyz": [0.6, 0.0, 1.0]}],  # beyond every surface
}


def test_a_room_with_a_shelf_of_three_boards_and_a_wall(arm_room, tmp_path):
    robot, cap = arm_room[:2]
    path = tmp_path / "room.json"
    path.write_text(json.dumps(SCENE))
    room = rooms.Room.load(path)
    assert list(room.surfaces) == ["table", "shelf/0", "shelf/1", "shelf/2"]
    # The table's map sees the wall, the shelf boards and panels; the boards see the table and the wall.
    boards = sum(len(room.surfaces[f"shelf/{i}"].obstacles()) for i in range(3))
    assert len(room.obstacles(without="table")) == 1 + 3 + boards  # the wall, three panels, three boards
    maps = room.surface_maps(robot, cap, progress=False)
    assert set(maps) == set(room.surfaces)
    for name, sm in maps.items():
        centres, values = sm.voxels()
        assert sm.voxel_count > 0, name
        # Never behind the wall at x = 0.6.
        assert values[centres[:, 0] > 0.65].size == 0 or values[centres[:, 0] > 0.65].max() == 0, name
    # Each map respects every obstacle: with the room the table map is never above the table alone.
    alone = octoreach.SurfaceMap.build(robot, cap, room.surfaces["table"], progress=False)
    centres, _ = alone.voxels()
    poses = np.column_stack([centres[:, :2], np.zeros(len(centres)), np.zeros(len(centres))])
    assert np.all(maps["table"].reachability(poses) <= alone.reachability(poses) + 1e-6)


def _cli_scene_maps(arm_room, tmp_path):
    from octoreach import cli

    cap = arm_room[1]
    cap_path = tmp_path / "arm.orcm"
    cap.save(str(cap_path), with_solutions=True)
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(SCENE))
    out, plots_dir = tmp_path / "maps", tmp_path / "plots"
    # The map was built from robots.test_arm() (the URDF's own allowed pairs): load the same model.
    assert cli.main(["surface", "--urdf", str(robots.project_urdf("test_arm")), "--allowed-collisions", "srdf",
                     "--arms", str(cap_path), "--scene", str(path), "--theta-bins", "8", "--quiet", "--out", str(out)]) == 0
    written = sorted(p.name for p in out.iterdir())
    assert written == ["shelf_0.orsm", "shelf_1.orsm", "shelf_2.orsm", "table.orsm"]
    table = octoreach.SurfaceMap.load(str(out / "table.orsm"))
    others = len(rooms.Room(SCENE).obstacles(without="table"))
    assert table.voxel_count > 0 and f"room: {others} obstacles" in table.parameters["checks"]
    assert not plots_dir.exists()
    return table, out / "table.orsm", others


def test_the_cli_writes_one_map_per_surface(arm_room, tmp_path):
    _cli_scene_maps(arm_room, tmp_path)


def test_info_tells_the_rooms_counts_apart(arm_room, tmp_path, capsys):
    from octoreach import cli

    table, path, others = _cli_scene_maps(arm_room, tmp_path)
    capsys.readouterr()
    assert cli.main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    own = table.room.surface_count
    assert f"room: {others + own} obstacles: {own} of the surface (slab, legs, boxes) and {others} others" in out
    assert f"(room: {others} obstacles) (obstacles besides the surface's own" in out
    assert f"over {table.voxel_count} voxels x 8 headings" in out


def test_scene_file_round_trip(tmp_path):
    room = rooms.Room(SCENE)
    room.add_box("cupboard", [0.5, 0.5, 1.8], [-1.0, 1.0, 0.9], rpy=[0.0, 0.0, 0.3])
    room.save(tmp_path / "a.json")
    back = rooms.Room.load(tmp_path / "a.json")
    assert back.description == room.description
    assert list(back.surfaces) == list(room.surfaces)
    assert len(back.obstacles()) == len(room.obstacles())
    for name in room.surfaces:
        assert np.allclose(back.surfaces[name].vertices, room.surfaces[name].vertices)
    pytest.importorskip("yaml")
    room.save(tmp_path / "a.yaml")
    assert rooms.Room.load(tmp_path / "a.yaml").description == room.description


def _cube_stl(path: Path, half: float) -> None:
    """An ASCII STL cube of side 2 * half centred at the origin."""
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float) * half
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
         [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {a} {b} {c}\n" for a, b, c in v[t]) +
                     "endloop\nendfacet\n" for t in f)
    path.write_text(f"solid cube\n{facets}endsolid cube\n")


def test_every_shape_kind_of_a_room_is_an_obstacle_and_seen(tmp_path):
    _cube_stl(tmp_path / "cube.stl", 0.1)
    cells = octoreach.ExplorationMap(resolution=0.05)
    cells.insert(np.array([[x, y, 0.5] for x in (-2.05, -2.0, -1.95) for y in (-2.05, -2.0, -1.95)]), [-2.0, -2.0, 2.0])
    cells.write_bt(str(tmp_path / "cells.bt"))
    room = rooms.Room({
        "surfaces": [{"name": "table", "rectangle": {"size": [0.6, 0.4], "height": 0.7}, "legs": 0.05,
                      "boxes": [{"size": [0.1, 0.1, 0.1], "xyz": [0.2, 0.0, 0.75]}],
                      "meshes": [{"path": "cube.stl", "xyz": [-0.2, 0.0, 0.8]}]}],
        "shelves": [{"name": "shelf", "size": [0.6, 0.3], "boards": [0.4, 0.8], "x": 2.0}],
        "boxes": [{"name": "crate", "size": [0.3, 0.2, 0.4], "xyz": [0.0, 2.0, 0.3], "rpy": [0.3, 0.2, 0.7]}],
        "cylinders": [{"name": "bin", "radius": 0.1, "length": 0.6, "xyz": [2.0, 2.0, 0.3]}],
        "spheres": [{"name": "ball", "radius": 0.2, "xyz": [-2.0, 0.0, 0.2]}],
        "meshes": [{"name": "cube", "path": "cube.stl", "xyz": [0.0, -2.0, 0.5], "rpy": [0.0, 0.0, 0.5]}],
        "octomaps": [{"name": "scan", "path": "cells.bt"}]}, base_dir=tmp_path)
    obstacles, scene = room.obstacles(), room.scene()
    kinds = [s.kind for s in obstacles.shapes]
    assert [s.kind for s in scene.shapes] == kinds
    assert set(kinds) == {"box", "cylinder", "sphere", "mesh", "octree"}
    # (x, y, top z, bottom z) of something that stands there: a ray down from above meets its top, and a small box
    # crossing its top collides
    probes = {"table top": (0.0, 0.15, 0.7, 0.67), "box on the table": (0.2, 0.0, 0.8, 0.7),
              "mesh on the table": (-0.2, 0.0, 0.9, 0.7), "shelf board": (2.0, 0.0, 0.8, 0.78),
              "tilted box": (0.0, 2.0, 0.6, 0.0), "cylinder": (2.0, 2.0, 0.6, 0.0), "sphere": (-2.0, 0.0, 0.4, 0.0),
              "mesh": (0.0, -2.0, 0.6, 0.4), "octomap": (-2.0, -2.0, 0.55, 0.45)}
    for what, (x, y, top, bottom) in probes.items():
        t = scene.raycast([x, y, 3.0], [0, 0, -1], max_range=5.0)
        assert t is not None and bottom - 1e-6 <= 3.0 - t <= top + 1e-6, (what, t)  # STL: single precision
        pose = np.eye(4)
        pose[:3, 3] = [x, y, 3.0 - t]
        assert obstacles.collides_box([0.02, 0.02, 0.02], pose), what
    assert scene.raycast([1.0, 1.0, 3.0], [0, 0, -1], max_range=5.0) is None  # nothing between them


@pytest.mark.parametrize("scene, message", [
    ({"surfaces": [], "walls": []}, "unknown key 'walls'"),
    ({"boxes": [{"name": "w", "size": [1, 1, 1], "xyz": [0, 0, 0], "colour": "red"}]}, "unknown key 'colour'"),
    ({"surfaces": [{"name": "t", "rectangle": {"size": [1, 1], "height": 0.7, "heigth": 0.7}}]}, "unknown key 'heigth'"),
    ({"shelves": [{"name": "s", "size": [1, 0.3], "boards": [0.5], "bords": [1]}]}, "unknown key 'bords'"),
    ({"surfaces": [{"name": "t", "rectangle": {"size": [1, 1], "height": 0.7}, "vertices": [[0, 0, 0]]}]},
     "exactly one of"),
    ({"boxes": [{"name": "w", "size": [1, 1, 1]}, {"name": "w", "size": [1, 1, 1]}]},
     r"boxes\[1\]: the name 'w' is already used by a box of this room"),
])
def test_scene_errors_name_the_key(tmp_path, scene, message):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(scene))
    with pytest.raises(ValueError, match=message) as e:
        rooms.Room.load(path)
    assert "bad.json" in str(e.value)


@pytest.mark.parametrize("scene, message", [
    ({"boxes": [{"name": "w", "size": "big"}]}, "'size' must be a list of 3 numbers"),
    ({"surfaces": [{"name": "t", "rectangle": {"size": [1, 1], "height": "high"}}]}, "'height' must be a number"),
    ({"surfaces": "table"}, "'surfaces' must be a list"),
    ([1, 2], "room must be a mapping"),
])
def test_scene_wrong_types_are_type_errors(scene, message):
    with pytest.raises(TypeError, match=message):
        rooms.Room(scene)


def test_polygon_file_carries_boxes_and_rejects_unknown_keys(arm_room, tmp_path):
    robot, cap = arm_room[:2]
    poly = {"vertices": [[-0.3, -0.2, 0.4], [0.3, -0.2, 0.4], [0.3, 0.2, 0.4], [-0.3, 0.2, 0.4]],
            "boxes": [{"size": [2.0, 0.05, 2.0], "xyz": [0.0, WALL_Y, 1.0]}]}
    path = tmp_path / "poly.json"
    path.write_text(json.dumps(poly))
    surface, others = rooms.surface_from_file(path)
    assert len(surface.boxes) == 1 and len(others) == 0
    sm = octoreach.SurfaceMap.build(robot, cap, surface, progress=False)
    assert sm.reachability(np.array([[0.0, 0.8, 0.0, -np.pi / 2]]))[0] == 0  # the box is a wall
    path.write_text(json.dumps({**poly, "boxs": []}))
    with pytest.raises(ValueError, match="unknown key 'boxs'"):
        rooms.surface_from_file(path)


# ----------------------------------------------------------------- conventions


def test_the_base_stands_on_the_floor_by_default(arm_room):
    *_, open_map, _ = arm_room
    assert octoreach.SurfaceMapOptions().z_range == (0.0, 0.0)
    assert open_map.z_range == (0.0, 0.0)
    centres, _ = open_map.voxels()
    assert np.all(np.abs(centres[:, 2]) <= open_map.resolution / 2 + 1e-6)
    poses = octoreach.PoseSampler(open_map, seed=1).sample(5)
    assert np.all(poses[:, 2] == 0.0)


def test_a_floating_base_only_when_asked(arm_room):
    robot, cap, table = arm_room[:3]
    floating = octoreach.SurfaceMap.build(robot, cap, table, z_range=(-0.3, 0.3), progress=False)
    assert floating.z_range == (-0.3, 0.3)
    assert len(np.unique(np.round(floating.voxels()[0][:, 2], 6))) > 1


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_nan_or_infinite_poses_are_errors(arm_room, bad):
    *_, open_map, _ = arm_room
    for column in range(4):
        pose = np.array([[0.0, -0.5, 0.0, 0.0]])
        pose[0, column] = bad
        with pytest.raises(ValueError, match="not finite"):
            open_map.reachability(pose)


def test_wrong_types_name_the_argument(arm_room):
    robot, cap, table = arm_room[:3]
    with pytest.raises(TypeError, match="obstacles"):
        octoreach.SurfaceMap.build(robot, cap, table, obstacles="a wall", progress=False)
    with pytest.raises(TypeError, match="robot"):
        rooms.Room(SCENE).surface_maps("pr2", cap)


def test_cli_angles_are_radians_or_say_deg(arm_room, tmp_path, capsys):
    from octoreach import cli

    *_, open_map, _ = arm_room
    path = str(tmp_path / "m.orsm")
    open_map.save(path)
    assert cli.main(["query", path, "--pose", "0", "-0.5", "0", "1.5707963267948966"]) == 0
    rad = capsys.readouterr().out
    assert cli.main(["query", path, "--pose", "0", "-0.5", "0", "90deg"]) == 0
    assert capsys.readouterr().out == rad
    assert cli.main(["query", path, "--pose", "0", "-0.5", "0", "nan"]) == 2
    assert "not finite" in capsys.readouterr().err
    parser = cli.build_parser()
    for command in ("surface", "query"):
        sub = next(a for a in parser._subparsers._group_actions[0].choices.items() if a[0] == command)[1]
        helps = " ".join(a.help or "" for a in sub._actions)
        assert "rad" in helps
        assert "degrees" not in helps.replace("degrees as", "")  # no bare degrees anywhere


def test_a_surfaces_boxes_and_legs_keep_their_names():
    room = rooms.Room({"surfaces": [
        {"name": "bench", "vertices": [[1.2, -1.0, 0.85], [1.8, -1.0, 0.85], [1.8, 1.0, 0.85], [1.2, 1.0, 0.85]],
         "boxes": [{"name": "drawers", "size": [0.5, 1.8, 0.8], "xyz": [1.5, 0.0, 0.4]},
                   {"size": [0.2, 0.2, 0.2], "xyz": [1.5, 0.5, 0.95]}]},
        {"name": "island", "rectangle": {"size": [1.0, 0.6], "height": 0.8, "x": -0.3, "y": 1.5}, "legs": 0.05}]})
    names = room.obstacles(without="island").names
    assert "bench/drawers" in names and "bench/box" in names and "surface_box" not in names
    assert [n for n in room.obstacles(without="bench").names if n.startswith("island/")] == \
        [f"island/leg_{k}" for k in range(1, 5)]


def test_a_name_clash_in_code_names_the_entry_holding_the_name():
    room = rooms.Room()
    room.add_table("desk", 1.0, 0.6, 0.75)
    with pytest.raises(ValueError, match="'desk' is already used by a surface of this room"):
        room.add_cylinder("desk", 0.1, 0.5, (0, 0, 0.25))
    room.add_cylinder("bin", 0.1, 0.5, (1, 1, 0.25))
    with pytest.raises(ValueError, match="'bin' is already used by a cylinder of this room"):
        room.add_box("bin", (1, 1, 1), (2, 2, 0.5))
