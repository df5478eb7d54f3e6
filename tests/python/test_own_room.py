"""Your robot in your room, from the command line: a robot written here (own_robot.py: mobile base, torso lift, 6-DOF
arm, pan/tilt head with a camera link, no SRDF) and a kitchen written here (own_room.py: an L-shaped counter on base
cabinets, walls, a wall cabinet, a bin). The map remembers the kitchen: 100 samples from `octoreach sample` never
stand in it; `octoreach query` names what a pose stands in; the viewer draws the robot and the kitchen (pixels
checked in headless Chromium) and the counter's L without a triangle over the floor."""
from __future__ import annotations

import json
import re
import subprocess
import sys

import numpy as np
import pytest

import octoreach
from octoreach.viewer import colours
from octoreach.viewer.browser import Browser, chromium_missing

from browser_helpers import changed as _changed, free_port as _free_port
from own_robot import urdf
from own_room import COUNTER, COUNTER_AREA, room

_MISSING = chromium_missing()
POSE = re.compile(r"x=([-+.\d]+) y=([-+.\d]+) z=([-+.\d]+) theta=([-+.\d]+)\s+R_S=([.\d]+)(.*)")


def _cli(*args, check=True):
    r = subprocess.run([sys.executable, "-m", "octoreach.cli", *map(str, args)], capture_output=True, text=True)
    if check:
        assert r.returncode == 0, r.stderr
    return r


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory):
    d = tmp_path_factory.mktemp("kitchen")
    (d / "robot.urdf").write_text(urdf("my_mobile_manipulator"))
    (d / "kitchen.json").write_text(json.dumps(room()))
    _cli("surface", "--urdf", d / "robot.urdf", "--scene", d / "kitchen.json", "--resolution", 0.1, "--directions", 40,
         "--out", d / "maps", "--quiet")
    return d, octoreach.SurfaceMap.load(str(d / "maps" / "counter.orsm"))


def _poses(text: str) -> np.ndarray:
    return np.array([[float(g) for g in m.groups()[:4]] for m in POSE.finditer(text)]).reshape(-1, 4)


def _in_room(d, smap, poses) -> np.ndarray:
    """Whether the robot's body (the links the map's arm does not move, at home) stands in the kitchen at each pose:
    Robot.in_collision against the room file's obstacles, not the map's own check."""
    robot = octoreach.Robot.from_urdf(str(d / "robot.urdf"))
    obstacles = octoreach.Room.load(d / "kitchen.json").obstacles()
    body = sorted(set(smap.room.body_links))
    return np.array([robot.in_collision(robot.home(), obstacles, octoreach.base_pose(p), links=body) for p in poses])


def test_the_map_remembers_the_kitchen(kitchen):
    d, smap = kitchen
    assert smap.voxel_count > 0 and smap.room.surface_count == 4 + 2  # the L's four triangles, two cabinet rows
    names = list(smap.room.obstacles.names)
    assert {"wall_north", "wall_east", "wall_cabinet", "bin"} <= set(names)
    assert smap.room.differences(octoreach.Room.load(d / "kitchen.json").obstacles()) == []
    assert {"base_link", "torso_link"} <= set(smap.room.body_links)


def test_a_hundred_cli_samples_none_in_the_kitchen(kitchen):
    d, smap = kitchen
    out = _cli("sample", d / "maps" / "counter.orsm", "--count", 100, "--seed", 3).stdout
    poses = _poses(out)
    assert len(poses) == 100 and not _in_room(d, smap, poses).any()
    # The same with the room file given: the same room, so no warning.
    r = _cli("sample", d / "maps" / "counter.orsm", "--count", 5, "--scene", d / "kitchen.json")
    assert "differs" not in r.stderr and len(_poses(r.stdout)) == 5


def test_query_names_what_a_pose_stands_in_and_a_moved_room_is_said(kitchen, tmp_path):
    d, smap = kitchen
    r = _cli("query", d / "maps" / "counter.orsm", "--pose", -0.9, -0.6, 0, 0, "--pose", -0.2, 0.3, 0, "90deg")
    lines = r.stdout.splitlines()
    assert "in collision with 'bin'" in lines[0] and "in collision" not in lines[1]
    moved = room()
    moved["cylinders"][0]["xyz"] = [-0.2, 0.3, 0.25]
    (tmp_path / "moved.json").write_text(json.dumps(moved))
    r = _cli("query", d / "maps" / "counter.orsm", "--pose", -0.2, 0.3, 0, "90deg", "--scene", tmp_path / "moved.json")
    assert "differs from the room the map was built with" in r.stderr and "'bin'" in r.stderr
    assert "in collision with 'bin'" in r.stdout
    r = _cli("query", d / "maps" / "counter.orsm", "--pose", -0.9, -0.6, 0, 0, "--no-room-check")
    assert "in collision" not in r.stdout


def test_the_l_shaped_counter_is_drawn_with_its_own_area():
    from octoreach.viewer.surfaces import slab, top_area

    v, f = slab(COUNTER, 0.04)
    assert top_area(v, f) == pytest.approx(COUNTER_AREA)
    a, b, c = (v[f[:, i]].astype(float) for i in range(3))
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0  # > 0 when every face points outwards
    assert volume == pytest.approx(COUNTER_AREA * 0.04, rel=1e-4)
    centroids = (a + b + c) / 3
    top = np.cross(b - a, c - a)[:, 2] > 0
    assert octoreach.Surface(COUNTER).contains(centroids[top]).all()  # no triangle over the floor in the corner


@pytest.mark.skipif(_MISSING is not None, reason=f"no headless browser: {_MISSING}")
def test_the_viewer_shows_your_robot_in_your_kitchen(kitchen, tmp_path):
    d, _ = kitchen
    robot = octoreach.Robot.from_urdf(str(d / "robot.urdf"))
    v = octoreach.view(str(d / "maps" / "counter.orsm"), robot=robot, samples=2, block=False, port=_free_port(),
                       verbose=False)
    try:
        assert v.room_layer is not None and set(v.room_layer.handles) == {"surface", "obstacles"}
        assert v.has_node("/room/obstacles") and v.has_node("/room/surface") and v.robot_layer is not None
        assert {"wall_cabinet", "bin"} <= set(v.room_layer.names)
        with Browser(900, 640) as b:
            b.open(v.url, v)
            px = b.screenshot(tmp_path / "kitchen.png") and b.pixels()
            assert px.std() > 20, "blank page"
            v.robot_layer.root.visible = False
            no_robot = _changed(b, px, timeout=15.0)
            robot_px = np.abs(px.astype(int) - no_robot).max(axis=-1) > 8
            assert robot_px.sum() > 300, int(robot_px.sum())
            v.room_layer.visible = False
            no_room = _changed(b, no_robot, timeout=15.0)
            room_px = np.abs(no_robot.astype(int) - no_room).max(axis=-1) > 8
            assert room_px.sum() > 5000, int(room_px.sum())
            # The room's own colours: the blue-grey of its obstacles and the counter's brown, lit.
            shown = no_robot[room_px].astype(int)
            bluish = (shown[:, 2] > shown[:, 0] + 25).sum()
            brownish = (shown[:, 0] > shown[:, 2] + 25).sum()
            assert bluish > 1000 and brownish > 200, (int(bluish), int(brownish))
            assert colours.ROOM[2] > colours.ROOM[0] and colours.SURFACE[0] > colours.SURFACE[2]
    finally:
        v.close()


def test_view_your_urdf_alone_and_your_room_alone(kitchen, tmp_path):
    d, _ = kitchen
    r = _cli("view", "--urdf", d / "robot.urdf", "--scene", d / "kitchen.json", "--html", tmp_path / "k.html",
             "--no-serve", "--port", 0)
    assert "wrote" in r.stdout and (tmp_path / "k.html").stat().st_size > 100_000
    v = octoreach.view(robot=octoreach.Robot.from_urdf(str(d / "robot.urdf")), block=False, port=_free_port(),
                       verbose=False)
    try:
        assert v.robot_layer is not None and {"base_link", "head_tilt_link"} <= set(v.robot_layer.links)
    finally:
        v.close()
    r = _cli("view", "--no-serve", check=False)
    assert r.returncode == 2 and "nothing to view" in r.stderr
