"""The 3D viewer (octoreach.viewer) in a real browser: headless Chromium loads the page, the screenshot shows
the robot and the map, a real mouse click on a cell reports the cell's R_S (checked against reachability())."""
from __future__ import annotations

import re
import socket
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import octoreach
from octoreach.viewer import Viewer, colours
from octoreach.viewer.browser import Browser, chromium_missing

from browser_helpers import changed as _changed, free_port as _free_port

_MISSING = chromium_missing()
OLD_MAP = Path(__file__).parent / "data" / "test_arm_table_format1.orsm"  # written by octoreach 0.1.0 (format 1)
needs_chromium = pytest.mark.skipif(_MISSING is not None, reason=f"no headless browser: {_MISSING}")


@pytest.fixture(scope="module")
def arm_map():
    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.15, directions=24,
                                        progress=False)
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    sm = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.15, z_range=(0, 0), progress=False)
    return robot, cap, sm


@pytest.fixture
def viewer():
    v = Viewer(port=_free_port(), verbose=False)
    yield v
    v.close()


def _hue_bins(rgb: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Of RGB colours (..., 3): which are saturated (max - min > 40 of 255) and their hue in 10-degree bins."""
    c = np.asarray(rgb, dtype=float).reshape(-1, 3)
    hi, lo = c.max(axis=1), c.min(axis=1)
    d = np.where(hi > lo, hi - lo, 1.0)
    r, g, b = c.T
    h = np.where(hi == r, ((g - b) / d) % 6, np.where(hi == g, (b - r) / d + 2, (r - g) / d + 4)) * 60.0
    return (hi - lo) > 40, (h // 10).astype(int) % 36


def test_scene_nodes_and_theta_slider(arm_map, viewer):
    robot, _, sm = arm_map
    layer = viewer.add_surface_map(sm, samples=3)  # the robot comes from the map's robot name
    for node in ("/robot", "/robot/base_link", "/robot/tool0" if "tool0" in viewer.robot_layer.links else
                 "/robot/wrist_3_link", "/room/surface", "/surface_map", "/surface_map/best", "/surface_map/theta_00",
                 f"/surface_map/theta_{sm.theta_bins - 1:02d}", "/samples/footprints", "/samples/headings"):
        assert viewer.has_node(node), node
    # The sampled poses' R_S (the map's own lookup) listed in the control panel, one line a pose.
    samples = viewer.samples
    assert len(samples.poses) == 3 and np.allclose(samples.rs, sm.reachability(samples.poses))
    assert all(f"{i + 1}. R_S = {r:.2f} at" in samples.table() for i, r in enumerate(samples.rs))
    centres, values = sm.voxels()
    centres, values = np.asarray(centres), np.asarray(values)
    # Best theta: every voxel with R_S > 0 is shown; one theta bin: exactly the voxels with R_S > 0 there.
    assert len(layer.shown) == len(centres)
    for k in (0, 5):
        viewer.show_theta(k)
        assert set(layer.shown) == set(np.flatnonzero(values[:, k] > 0))
        # A move shows bin k's node (its cells: those with R_S > 0 at k, in its colours) and hides the others.
        handle = layer.handle
        assert handle is viewer.scene.get_handle_by_name(f"/surface_map/theta_{k:02d}")
        assert [h.visible for h in layer.handles.values()].count(True) == 1 and handle.visible
        shown = np.flatnonzero(values[:, k] > 0)
        assert np.allclose(handle.batched_positions, centres[shown] - [0, 0, centres[:, 2].min()], atol=1e-6)
        assert np.array_equal(handle.batched_colors, colours.scale(values[shown, k], layer.vmax))
        assert np.array_equal(layer.colours_at(k)[shown], handle.batched_colors)
        assert [layer.cell_of(k, j) for j in range(len(shown))] == list(shown)  # a click's instance -> cell
        i = int(layer.shown[np.argmax(values[layer.shown, k])])
        pose = layer.cell_pose(i)
        assert pose[3] == pytest.approx(2 * np.pi * k / sm.theta_bins)
        sel = viewer.select_cell(i)
        assert sel["rs"] == pytest.approx(float(sm.reachability(pose[None, :])[0]))
        assert sel["rs"] == pytest.approx(float(values[i, k]), abs=1e-6)
        # The robot stands at the clicked pose: its root link (= the map's reference frame) there.
        assert np.allclose(viewer.robot_layer.base_pose, octoreach.base_pose(pose))
    with pytest.raises(ValueError, match="theta bin"):
        layer.show(sm.theta_bins)


def test_capability_map_slice(arm_map, viewer):
    _, cap, _ = arm_map
    layer = viewer.add_capability_map(cap)
    centres = np.asarray(cap.voxels()[0])
    z = float(np.median(centres[:, 2]))
    layer.cut(z)
    assert len(layer.shown) == int((centres[:, 2] <= z + 1e-9).sum()) > 0
    # Drawn: exactly the voxels below the cut with a face neighbour missing (brute force over the set).
    below = {tuple(np.floor(c / cap.resolution).astype(int)) for c in centres[layer.shown]}
    steps = [np.eye(3, dtype=int)[a] * s for a in range(3) for s in (-1, 1)]
    outer = [i for i in layer.shown
             if any(tuple(np.floor(centres[i] / cap.resolution).astype(int) + d) not in below for d in steps)]
    assert sorted(layer.drawn) == outer and 0 < len(outer) <= len(layer.shown)
    assert len(layer.handle.batched_positions) == len(layer.drawn)
    assert np.allclose(layer.handle.batched_positions, centres[layer.drawn], atol=1e-6)
    sel = viewer._select_voxel(0)  # what a click on instance 0 reports
    assert sel["index"] == layer.drawn[0]
    assert sel["value"] == pytest.approx(float(cap.reachability(centres[layer.drawn[:1]])[0]))


def test_capability_map_of_another_robot_is_said(arm_map):
    # A capability map shown with a robot of another model is drawn at that robot's link of the same name, and the
    # viewer says the voxels are not that robot's reach; with its own robot it says nothing.
    robot, cap, _ = arm_map
    other = octoreach.Robot.from_urdf('<robot name="other"><link name="base_link"><visual><geometry>'
                                      '<box size="0.1 0.1 0.1"/></geometry></visual></link></robot>')
    v = octoreach.view(cap, robot=other, port=_free_port(), verbose=False, serve=False)
    assert any("built for another robot model" in n and "'other'" in n for n in v.notes), v.notes
    v = octoreach.view(cap, robot=robot, port=_free_port(), verbose=False, serve=False)
    assert not any("another robot model" in n for n in v.notes), v.notes


def test_surface_obstacles_drawn_or_said_missing(arm_map, viewer):
    robot, cap, sm = arm_map
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    table.add_legs()
    viewer.add_surface_map(sm, samples=0, surface=table)
    assert len(table.boxes) == 4 and all(viewer.has_node(f"/surface/boxes/{i}") for i in range(4))
    assert not viewer.has_node("/surface/boxes/4")
    assert not viewer.notes
    other = Viewer(port=_free_port(), verbose=False)
    try:
        other.add_surface_map(sm, samples=0)  # the room the map was built with: its table
        assert other.has_node("/room/surface") and not other.notes
    finally:
        other.close()
    old = Viewer(port=_free_port(), verbose=False)
    try:  # a file written before maps recorded their room: the polygon only, and a note saying so
        old.add_surface_map(octoreach.SurfaceMap.load(str(OLD_MAP)), samples=2)
        assert old.has_node("/surface") and not old.has_node("/room")
        assert any("records no room" in n for n in old.notes) and len(old.samples.poses) == 2
    finally:
        old.close()


def test_map_files_load_any_kind(arm_map, tmp_path):
    from octoreach import map_files

    _, cap, sm = arm_map
    cap.save(str(tmp_path / "a.orcm"))
    sm.save(str(tmp_path / "b.orsm"))
    assert isinstance(map_files.load(tmp_path / "a.orcm"), octoreach.CapabilityMap)
    assert isinstance(map_files.load(str(tmp_path / "b.orsm")), octoreach.SurfaceMap)
    (tmp_path / "c.orsm").write_text("not a map\n")
    with pytest.raises(OSError, match="not an octoreach map"):
        map_files.load(tmp_path / "c.orsm")


def test_static_html(arm_map, viewer, tmp_path):
    viewer.add_surface_map(arm_map[2], samples=2)
    path = viewer.save_html(tmp_path / "scene.html")
    text = open(path, encoding="utf-8").read()
    assert "__VISER_EMBED_DATA__" in text and len(text) > 100_000


def test_cells_and_samples_lie_on_the_floor_when_the_reference_frame_is_above_it(arm_map, viewer):
    # A robot whose reference frame stands 0.3 m above its feet (as Baxter's torso, or a base link on wheels):
    # the map's z is 0.3, the robot stands there, and the cells, outlines and arrows lie on the floor, not in the air.
    robot, cap, _ = arm_map
    table = octoreach.Surface.rectangle(0.6, 0.4, 0.7, x=0.55)
    sm = octoreach.SurfaceMap.build(robot, cap, table, resolution=0.15, z_range=(0.3, 0.3), progress=False)
    layer = viewer.add_surface_map(sm, robot=robot, samples=2)
    z = layer.centres[0, 2]  # the voxel's centre: 0.3 m up to half a voxel
    assert 0.3 <= z < 0.3 + sm.resolution and np.allclose(layer.centres[:, 2], z) and layer.floor_offset == z
    assert np.allclose(layer.handle.batched_positions[:, 2], 0.0, atol=1e-6)
    i = int(layer.shown[0])
    assert layer.cell_pose(i)[2] == pytest.approx(z)  # poses and R_S keep the map's z
    assert viewer.select_cell(i)["rs"] == pytest.approx(float(sm.reachability(layer.cell_pose(i)[None, :])[0]))
    assert viewer.robot_layer.base_pose[2, 3] == pytest.approx(z)
    outline_z = np.asarray(viewer.scene.get_handle_by_name("/samples/footprints").points)[..., 2]
    assert np.allclose(outline_z, layer.tile_height / 2 + 0.02, atol=1e-4), outline_z.min()
    # A click is picked on the tiles where they are drawn.
    top = layer.drawn_centres[i] + [0.0, 0.0, 1.0]
    assert layer.pick(top, [0.0, 0.0, -1.0]) == i


def test_port_in_use_picks_another(arm_map):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen(1)
        port = s.getsockname()[1]
        v = Viewer(port=port, verbose=False)
        try:
            assert v.server.get_port() != port and v.url.endswith(f":{v.server.get_port()}")
        finally:
            v.close()


def test_cli_not_a_map(tmp_path):
    bad = tmp_path / "notes.orsm"
    bad.write_text("not a map\n")
    r = subprocess.run([sys.executable, "-m", "octoreach.cli", "view", str(bad)], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.startswith("octoreach: error:") and "not an octoreach map" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


@needs_chromium
def test_browser_shows_robot_and_map_and_click_reports_rs(arm_map, viewer, tmp_path):
    robot, _, sm = arm_map
    layer = viewer.add_surface_map(sm, robot=robot, samples=3)
    rs_shown = layer.values[layer.shown].max(axis=1)
    cell_colours = colours.scale(rs_shown, layer.vmax)
    with Browser(1024, 700) as b:
        b.open(viewer.url, viewer)
        shot = b.screenshot(tmp_path / "viewer.png")
        px = b.pixels()
        assert open(shot, "rb").read().startswith(b"\x89PNG")
        assert px.std() > 20, "blank page"
        # The robot: grey, unsaturated pixels, neither background nor GUI white.
        def grey_pixels(img):
            spread = img.max(axis=-1).astype(int) - img.min(axis=-1)
            mean = img.mean(axis=-1)
            return int(((spread < 12) & (mean > 90) & (mean < 215)).sum())

        # Both must be the scene's own: hiding the robot, then the map, removes those pixels.
        viewer.robot_layer.root.visible = False
        no_robot = _changed(b, px)
        assert grey_pixels(px) - grey_pixels(no_robot) > 500, (grey_pixels(px), grey_pixels(no_robot))
        layer.root.visible = False
        no_map = _changed(b, no_robot)
        # The map's pixels (those hiding it changes) carry the colour scale: lighting washes a colour towards
        # white but keeps its hue, so the hues of the cells' colours (10-degree bins) must be on screen, at
        # least half of them, and no saturated hue the scale does not have.
        mine = np.abs(no_robot.astype(int) - no_map).max(axis=-1) > 8
        assert mine.sum() > 2000, int(mine.sum())
        expected = set(np.unique(_hue_bins(255.0 * (cell_colours / 255.0) ** (1 / 2.2))[1]))  # as on screen
        sat, bins = _hue_bins(no_robot[mine])
        counts = np.bincount(bins[sat], minlength=36)
        shown = {int(k) for k in np.flatnonzero(counts > 20)}
        assert len(shown & expected) >= max(1, (len(expected) + 1) // 2), (sorted(shown), sorted(expected))
        foreign = counts[sorted(set(range(36)) - {(k + d) % 36 for k in expected for d in (-1, 0, 1)})].sum()
        assert foreign < 0.02 * sat.sum(), (int(foreign), int(sat.sum()))
        viewer.robot_layer.root.visible = True
        layer.root.visible = True
        px = _changed(b, no_map)

        # A theta move (the bin's node shown, the best theta's hidden) reaches the page; then back to the best theta.
        k = int(np.argmin([(layer.values[:, j] > 0).sum() for j in range(sm.theta_bins)]))
        viewer.show_theta(k)
        moved = _changed(b, px)
        viewer.show_theta(-1)
        px = _changed(b, moved)

        # A real click on a cell: aim at the cell nearest the camera (least likely to be hidden).
        client = next(iter(viewer.server.get_clients().values()))
        canvas = b.canvas()
        w, h = canvas.size["width"], canvas.size["height"]
        top = layer.drawn_centres[layer.shown] + [0.0, 0.0, layer.tile_height / 2]
        pix = np.array([b.project(client.camera, p) for p in top])
        ok = (pix[:, 0] > 40) & (pix[:, 0] < 0.6 * w) & (pix[:, 1] > 40) & (pix[:, 1] < h - 40)
        assert ok.any()
        nearest = int(np.flatnonzero(ok)[np.argmax(pix[ok, 1])])
        target = int(layer.shown[nearest])  # the click's instance index: the cell's index in layer.centres
        b.click(*pix[nearest])
        sel = viewer.wait_for_click(10.0)
        assert sel is not None, "the click reached no cell"
        assert sel["index"] == target
        pose = layer.cell_pose(target)
        assert sel["rs"] == pytest.approx(float(sm.reachability(pose[None, :])[0]))
        assert sel["rs"] > 0
        assert np.allclose(viewer.robot_layer.base_pose, octoreach.base_pose(pose))


def test_exploration_layers(viewer):
    from types import SimpleNamespace

    from octoreach.viewer import ExplorationRecorder

    emap = octoreach.ExplorationMap(resolution=0.05)
    g = np.linspace(-0.4, 0.4, 30)
    origin = np.array([0.0, 0.0, 0.5])
    recorder = ExplorationRecorder()
    emap.insert(np.array([[1.0, y, z] for y in g[:15] for z in g + 0.5]), origin)  # view 0: half the wall
    recorder(None, emap, None)
    emap.insert(np.array([[1.0, y, z] for y in g for z in g + 0.5]), origin)  # view 1: all of it
    recorder(None, emap, None)
    poses = [octoreach.exploration.camera.look_at(origin, [1.0, 0.0, 0.5]),
             octoreach.exploration.camera.look_at([0.0, 0.3, 0.6], [1.0, 0.0, 0.5])]
    layer = viewer.add_exploration(SimpleNamespace(map=emap, poses=poses, rows=[]), steps=recorder)
    assert layer.counts["occupied"] == len(emap.cells("occupied")) > 0
    assert layer.counts["frontier"] == len(emap.cells("frontier"))
    assert layer.counts["void"] == len(emap.cells("void"))
    assert layer.counts["ellipsoids"] == len(emap.void_clusters())
    for node in ("/exploration/occupied", "/exploration/frontiers", "/exploration/voids", "/exploration/views/0",
                 "/exploration/views/1"):
        assert viewer.has_node(node), node
    assert not layer.void.visible  # voids start hidden
    layer.step(0)
    assert layer.frusta[0].visible and not layer.frusta[1].visible
    assert layer.counts["occupied"] == len(recorder.states[0]["occupied"]) < len(emap.cells("occupied"))
    layer.set_visible("voids", True)
    layer.step(1)
    assert layer.void.visible and layer.frusta[1].visible
    assert layer.counts["occupied"] == len(emap.cells("occupied"))


def test_package_view_with_joints(arm_map):
    robot, _, sm = arm_map
    name = robot.joint_names[1]
    v = octoreach.view(sm, joints={name: 0.7}, samples=1, block=False, port=_free_port(), verbose=False)
    try:
        assert v.robot_layer.q[1] == 0.7
        T = robot.link_poses(v.robot_layer.q)["upper_arm_link"]
        assert np.allclose(v.robot_layer.links["upper_arm_link"].position, T[:3, 3], atol=1e-6)
    finally:
        v.close()
    with pytest.raises(ValueError, match=f"no moving joint named 'elbw'; did you mean {robot.joint_names[2]}"):
        octoreach.view(sm, joints={"elbw": 1.0}, samples=0, block=False, port=_free_port(), verbose=False)
    with pytest.raises(ValueError, match="outside its limits"):
        octoreach.view(sm, joints={name: 99.0}, samples=0, block=False, port=_free_port(), verbose=False)


ROVER = str(Path(__file__).resolve().parents[2] / "docs" / "examples" / "rover.urdf")


@pytest.mark.parametrize("joint, message", [("lift_joint=0.2", "no moving joint named 'lift_joint'"),
                                            ("elbow=5", "'elbow' value 5.0+ is outside its limits \\[-2.6")])
def test_cli_bad_joint_is_an_error_before_the_viewer_starts(joint, message):
    r = subprocess.run([sys.executable, "-m", "octoreach.cli", "view", "--urdf", ROVER, "--joint", joint,
                        "--port", str(_free_port())], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and re.search(message, r.stderr), r.stderr
    assert "viewer at" not in r.stdout and "Server stopped" not in r.stdout


def test_cli_no_serve_writes_the_page_quietly(tmp_path):
    page = tmp_path / "rover.html"
    r = subprocess.run([sys.executable, "-m", "octoreach.cli", "view", "--urdf", ROVER, "--joint", "elbow=1.2",
                        "--no-serve", "--html", str(page), "--port", str(_free_port())],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert page.is_file() and r.stdout.strip() == f"octoreach: wrote {page}"


def test_empty_surface_map_warns(arm_map, viewer, capsys):
    robot, cap, _ = arm_map
    empty = octoreach.SurfaceMap.build(robot, cap, octoreach.Surface.rectangle(0.3, 0.3, 5.0), resolution=0.15,
                                       z_range=(0, 0), progress=False)
    layer = viewer.add_surface_map(empty, samples=3)
    assert len(layer.shown) == 0 and len(viewer.samples.poses) == 0
    assert "empty surface map" in capsys.readouterr().err


def test_surface_slab_faces_outwards():
    from octoreach.viewer.surfaces import slab

    square = [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
    for poly in (square, square[::-1]):  # counter-clockwise and clockwise seen from above
        v, f = slab(poly, 0.1)
        a, b, c = (v[f[:, i]].astype(float) for i in range(3))
        volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0  # > 0 when every face points outwards
        assert volume == pytest.approx(0.1)
        normals = np.cross(b - a, c - a)
        assert (normals[:, 2] > 0).sum() == 2 and (normals[:, 2] < 0).sum() == 2  # top up, bottom down


def test_map_of_a_robot_loaded_under_another_name_draws_it(viewer):
    # xarm7's URDF calls its robot "UF_ROBOT", the name a map records: the viewer finds the robot (and its meshes)
    # by the URDF's declared name and model hash
    robot = octoreach.robots.load("xarm7")
    assert robot.name != "xarm7"
    cap = octoreach.arms.capability_map(robot, octoreach.arms.default_arm(robot), resolution=0.2, directions=12,
                                        progress=False)
    sm = octoreach.SurfaceMap.build(robot, cap, octoreach.Surface.rectangle(0.6, 0.4, 0.3, x=0.6), resolution=0.2,
                                    z_range=(0, 0), progress=False)
    viewer.add_surface_map(sm, samples=1)
    assert viewer.robot_layer is not None and viewer.robot_layer.meshes.robot.urdf_hash == robot.urdf_hash
    assert viewer.robot_layer.links  # its meshes were found


def test_map_of_an_unknown_robot_is_drawn_without_it_and_says_so(arm_map, viewer):
    robot, _, _ = arm_map
    text = (octoreach.robots.project_urdf("test_arm")).read_text()
    stranger = octoreach.Robot.from_urdf(text.replace(f'name="{robot.name}"', 'name="somebody_elses_arm"', 1))
    assert stranger.name == "somebody_elses_arm"
    cap = octoreach.CapabilityMap.build(stranger.chain("base_link", "tool0"), resolution=0.2, directions=12,
                                        progress=False)
    sm = octoreach.SurfaceMap.build(stranger, cap, octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55),
                                    resolution=0.2, z_range=(0, 0), progress=False)
    layer = viewer.add_surface_map(sm, samples=2)
    assert viewer.robot_layer is None and len(layer.centres)
    assert any("somebody_elses_arm" in n and "--robot" in n for n in viewer.notes)


_OWN_URDF = """<robot name="{name}">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base">
    <visual><geometry><box size="0.4 0.3 0.1"/></geometry><material name="red"/></visual>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <visual><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.05" length="0.4"/></geometry></visual>
  </link>
  <link name="tool">
    <visual><origin xyz="0 0 0.05" rpy="0 0 0.3"/><geometry><mesh filename="meshes/tool.stl" scale="2 2 2"/></geometry>
    </visual>
  </link>
  <link name="sensor">
    <collision><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="mount" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="0 0 0.4"/></joint>
  <joint name="eye" type="fixed"><parent link="tool"/><child link="sensor"/><origin xyz="0.1 0 0"/></joint>
</robot>
"""


def _tool_stl(path) -> np.ndarray:
    """A binary STL tetrahedron; returns its vertices."""
    v = np.array([[0, 0, 0], [0.05, 0, 0], [0, 0.05, 0], [0, 0, 0.05]], np.float32)
    tris = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    rec = np.zeros(len(tris), dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
    rec["corners"] = [v[list(t)] for t in tris]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"\0" * 80 + np.uint32(len(tris)).tobytes() + rec.tobytes())
    return v.astype(float)


def test_a_robot_from_its_own_urdf_file_is_drawn(arm_map, tmp_path):
    # A robot example-robot-data does not know, loaded from a URDF file path: the viewer draws its visuals (box,
    # cylinder, a mesh file beside the URDF) from Robot.visuals, and a link without visuals with its collision shape.
    tool = _tool_stl(tmp_path / "meshes" / "tool.stl")
    (tmp_path / "own.urdf").write_text(_OWN_URDF.format(name="my_own_robot"))
    robot = octoreach.Robot.from_urdf(str(tmp_path / "own.urdf"))
    assert robot.source.urdf == str(tmp_path / "own.urdf") and robot.source.srdf == ""
    visuals = robot.visuals
    assert [v.shape.kind for v in visuals["base"]] == ["box"] and visuals["base"][0].rgba == (1, 0, 0, 1)
    assert visuals["tool"][0].shape.mesh_path == str(tmp_path / "meshes" / "tool.stl")
    assert np.allclose(visuals["tool"][0].shape.scale, 2) and "sensor" not in visuals
    with pytest.raises(ValueError, match="my_own_robot"):
        octoreach.robots.loadable_name(robot.name, robot.urdf_hash)
    _, _, sm = arm_map
    v = octoreach.view(sm, robot=robot, samples=0, block=False, port=_free_port(), verbose=False)
    try:
        layer = v.robot_layer
        assert layer is not None and set(layer.links) == {"base", "arm", "tool", "sensor"}
        assert all(v.has_node(f"/robot/{link}") for link in layer.links)
        meshes = layer.meshes.meshes
        assert np.allclose(np.ptp(meshes["base"].vertices, axis=0), [0.4, 0.3, 0.1])
        assert layer.meshes.colours["base"] == (255, 0, 0)
        arm = meshes["arm"].vertices
        assert np.allclose(np.ptp(arm, axis=0), [0.1, 0.1, 0.4], atol=1e-3) and arm[:, 2].min() == pytest.approx(0.0)
        R = np.array([[np.cos(0.3), -np.sin(0.3), 0], [np.sin(0.3), np.cos(0.3), 0], [0, 0, 1]])
        expected = (2 * tool) @ R.T + [0, 0, 0.05]  # the file's vertices, scaled and placed at the visual origin
        assert sorted(map(tuple, np.round(meshes["tool"].vertices, 6))) == sorted(map(tuple, np.round(expected, 6)))
        assert np.allclose(np.linalg.norm(meshes["sensor"].vertices, axis=1), 0.03)  # collision sphere
        T = robot.link_poses(layer.q)["tool"]
        assert np.allclose(layer.links["tool"].position, T[:3, 3], atol=1e-6)
    finally:
        v.close()


def test_a_visual_mesh_that_is_missing_falls_back_to_collision_and_says_so(viewer, tmp_path):
    urdf = _OWN_URDF.format(name="lost_meshes").replace(
        "</link>\n  <link name=\"sensor\">",
        "<collision><geometry><box size=\"0.02 0.02 0.02\"/></geometry></collision></link>\n  <link name=\"sensor\">")
    (tmp_path / "lost.urdf").write_text(urdf)
    robot = octoreach.Robot.from_urdf(str(tmp_path / "lost.urdf"))  # the visual mesh's file is missing: still loads
    assert robot.visuals["tool"][0].shape.mesh_path == "" and robot.visuals["tool"][0].mesh_uri == "meshes/tool.stl"
    viewer.add_robot(robot)
    assert np.allclose(np.ptp(viewer.robot_layer.meshes.meshes["tool"].vertices, axis=0), 0.02)
    assert any("meshes/tool.stl" in n for n in viewer.notes)
