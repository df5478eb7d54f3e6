"""Room, polygon and job files within bounds: alias bombs, deep nesting, duplicate keys, special files, values
too large, names that cannot be file names, counts past the limits and robot names that are paths give one
clear error (in a child process with a memory cap and a timeout where they could hang or blow up), and the
command line prints one line for each."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from octoreach import limits, robots
from octoreach.jobs import JobError, read_job
from octoreach.rooms import Room
from robust_util import run_python

URDF = str(robots.project_urdf("test_arm"))
TABLE = {"name": "t", "rectangle": {"size": [0.6, 0.4], "height": 0.4, "x": 0.55}}


def bomb(levels: int = 9, width: int = 9) -> str:
    """YAML anchors a0..a<levels-1>, each a list of `width` aliases of the one before: width**levels values."""
    chain = ["&a0 [" + ", ".join(['"lol"'] * width) + "]"]
    chain += [f"&a{i} [" + ", ".join([f"*a{i - 1}"] * width) + "]" for i in range(1, levels)]
    return "[" + ", ".join(chain) + "]"


def cli(*args, timeout=120):
    return subprocess.run([sys.executable, "-m", "octoreach.cli", *map(str, args)], capture_output=True, text=True,
                          timeout=timeout)


def one_line_error(r, *fragments):
    assert r.returncode == 2, (r.returncode, r.stderr[-2000:])
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("octoreach: error:"), r.stderr[-2000:]
    for f in fragments:
        assert f in lines[0], lines[0]
    return lines[0]


# ---------------------------------------------------------------------------------------------- YAML bounds
def test_alias_bomb_in_a_room_file_is_refused_before_it_is_built(tmp_path):
    path = tmp_path / "bomb.yaml"  # ~1 KB: 9^9 = 387 million values once expanded
    path.write_text(f"boxes: {bomb()}\nsurfaces: *a8\n")
    assert path.stat().st_size < 1200
    child = run_python(f"""
        from octoreach.rooms import Room
        try:
            Room.load({str(path)!r})
        except ValueError as e:
            print("REFUSED", len(str(e)), e)
    """, timeout=60, mem_bytes=1 << 30)
    assert not child.hung and child.returncode == 0, child.stderr[-2000:]
    assert "REFUSED" in child.stdout and "MAX_DATA_NODES" in child.stdout
    assert int(child.stdout.split()[1]) < 400  # the message names the limit, it does not spell out the values
    r = cli("surface", "--urdf", URDF, "--scene", path, "--out", tmp_path / "maps", timeout=60)
    one_line_error(r, "bomb.yaml", "MAX_DATA_NODES")


@pytest.mark.parametrize("text", [
    "robots: [test_arm]\nresolutions: {bomb}\n",
    "robots: [test_arm]\nholder: {bomb}\n",  # an unknown key holding the bomb: refused on the key alone
    "robots: [{{name: test_arm, package_dirs: {bomb}}}]\ncapability: {{seed: *a8}}\n",
])
def test_alias_bomb_in_a_job_file_is_refused(tmp_path, text):
    path = tmp_path / "job.yaml"
    path.write_text(text.format(bomb=bomb()))
    child = run_python(f"""
        from octoreach.jobs import read_job, JobError
        try:
            read_job({str(path)!r})
        except JobError as e:
            print("REFUSED", len(str(e)))
    """, timeout=60, mem_bytes=1 << 30)
    assert not child.hung and child.returncode == 0, child.stderr[-2000:]
    assert "REFUSED" in child.stdout and int(child.stdout.split()[1]) < 400


def test_a_value_shown_in_a_message_is_cut_short(tmp_path):
    path = tmp_path / "room.yaml"  # 6^6 = 46,656 values: within the node limit, far too many to print
    path.write_text(f"surfaces:\n- name: t\n  boxes: {bomb(6, 6)}\n  rectangle: {{size: *a5, height: 0.4}}\n")
    with pytest.raises((ValueError, TypeError)) as e:
        Room.load(path)
    assert len(str(e.value)) < limits.MAX_SHOWN + 300 and "..." in str(e.value)


@pytest.mark.parametrize("text, message", [
    ("surfaces: &r [*r]\n", "recursive"),
    ("surfaces: &r {a: [1, *r]}\n", "recursive"),
    ('{"surfaces": ' + "[" * 100000 + "]" * 100000 + "}", "nests deeper"),
    ("surfaces:\n  " + "- " * 200 + "1\n", "nests deeper"),
    ("surfaces: " + "[" * 70 + "]" * 70 + "\n", "nests deeper"),
    ("surfaces: [&v {name: b, rectangle: {size: [1, 1], height: 1}}, " + ", ".join(["*v"] * 20000) + "]\n", "aliases"),
])
def test_recursive_deep_and_alias_heavy_files_are_refused(tmp_path, text, message):
    path = tmp_path / "room.yaml"
    path.write_text(text)
    child = run_python(f"""
        from octoreach.rooms import Room
        try:
            Room.load({str(path)!r})
            print("LOADED")
        except ValueError as e:
            print("REFUSED", e)
    """, timeout=60, mem_bytes=1 << 30)
    assert not child.hung and child.returncode == 0, child.stderr[-2000:]
    assert "REFUSED" in child.stdout and message in child.stdout, child.stdout


@pytest.mark.parametrize("text", [
    '{"surfaces": [], "surfaces": [%s]}' % json.dumps(TABLE),
    "surfaces: []\nsurfaces:\n- %s\n" % json.dumps(TABLE),
    "surfaces:\n- {name: t, name: u, rectangle: {size: [1, 1], height: 1}}\n",
])
def test_duplicate_keys_are_refused_not_dropped(tmp_path, text):
    path = tmp_path / "room.yaml"
    path.write_text(text)
    with pytest.raises(ValueError, match="given twice"):
        Room.load(path)


# ---------------------------------------------------------------------------------------------- special files
@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "fifo"
    os.mkfifo(path)
    return path


@pytest.mark.parametrize("reader", ["Room.load", "surface_from_file", "read_job"])
@pytest.mark.parametrize("target", ["/dev/zero", "fifo", "folder", "big", "link"])
def test_special_files_are_refused_before_reading(tmp_path, fifo, reader, target):
    paths = {"/dev/zero": "/dev/zero", "fifo": str(fifo), "folder": str(tmp_path)}
    big = tmp_path / "big.json"
    with open(big, "wb") as f:
        f.truncate(limits.MAX_DATA_FILE_BYTES + 1)
    paths["big"] = str(big)
    (tmp_path / "link").symlink_to("/dev/zero")
    paths["link"] = str(tmp_path / "link")
    child = run_python(f"""
        from octoreach.rooms import Room, surface_from_file
        from octoreach.jobs import read_job
        try:
            {reader}({paths[target]!r})
        except (OSError, ValueError) as e:
            print("REFUSED", e)
    """, timeout=60, mem_bytes=1 << 30)
    assert not child.hung and child.returncode == 0, child.stderr[-2000:]
    assert "REFUSED" in child.stdout
    expected = {"/dev/zero": "character device", "fifo": "FIFO", "folder": "folder", "big": "MAX_DATA_FILE_BYTES",
                "link": "character device"}[target]
    assert expected in child.stdout, child.stdout


def test_special_files_named_inside_a_room_are_refused(tmp_path, fifo):
    for key in ("meshes", "octomaps"):
        for target in (str(fifo), "/dev/zero", str(tmp_path), "/proc/self/mem"):
            with pytest.raises(OSError, match="not a regular file|is empty"):
                Room({key: [{"name": "x", "path": target}]})
    job = {"robots": [{"urdf": str(fifo)}], "surfaces": [TABLE]}
    child = run_python(f"""
        from octoreach.jobs import read_job, JobError
        try:
            read_job({job!r})
        except JobError as e:
            print("REFUSED", e)
    """, timeout=60, mem_bytes=1 << 30)
    assert not child.hung and "REFUSED" in child.stdout, (child.stdout, child.stderr[-1000:])


# ---------------------------------------------------------------------------------------------- one line, no traceback
@pytest.mark.parametrize("entry, fragment", [
    ({"name": "t", "rectangle": {"size": ["0.6", 0.4], "height": 0.4}}, "'size' must be a list of 2 numbers"),
    ({"name": "t", "rectangle": {"size": [0.6, 0.4], "height": int("9" * 400)}}, "'height' must be finite"),
    ({"name": "t", "vertices": [[0, 0, 1], [1, 0, 1], [0, int("9" * 400), 1]]}, "must be finite"),
])
def test_wrong_values_in_a_polygon_or_room_file_are_one_line(tmp_path, entry, fragment):
    for path, flag in ((tmp_path / "room.json", "--scene"), (tmp_path / "poly.json", "--polygon")):
        path.write_text(json.dumps({"surfaces": [entry]} if flag == "--scene" else
                                   {k: v for k, v in entry.items() if k != "name"}))
        if "rectangle" in entry and flag == "--polygon":
            continue
        r = cli("surface", "--urdf", URDF, flag, path, "--out", tmp_path / "out", "--quiet")
        one_line_error(r, fragment)


@pytest.mark.parametrize("robot, fragment", [
    ({"urdf": 123}, "urdf: must be a file path"),
    ({"name": "test_arm", "package_dirs": 5}, "package_dirs: must be a list of folder paths"),
    ({"name": "test_arm", "allowed_collisions": ["x"]}, "allowed_collisions"),
    ({"name": 7}, "name: must be a robot name"),
])
def test_wrong_types_in_a_job_file_are_one_line(tmp_path, robot, fragment):
    path = tmp_path / "job.json"
    path.write_text(json.dumps({"robots": [robot], "surfaces": [TABLE]}))
    with pytest.raises(JobError, match=fragment):
        read_job(path)
    one_line_error(cli("build-many", path, "--cluster", "none", "--no-cache"), fragment)


@pytest.mark.parametrize("out", [5, "", "a\x00b", ["maps"], {"x": 1}, None, True])
def test_a_bad_out_in_a_job_file_is_refused_even_when_the_command_line_replaces_it(tmp_path, out):
    path = tmp_path / "job.json"
    path.write_text(json.dumps({"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}],
                                "surfaces": [TABLE], "out": out}))
    for given in (None, tmp_path / "maps"):
        with pytest.raises(JobError, match=r"job file .*job\.json'?: out: must be a folder path"):
            read_job(path, out=given)
    r = cli("build-many", path, "--out", tmp_path / "maps", "--cluster", "none", "--no-cache", "--quiet")
    one_line_error(r, "job.json", "out: must be a folder path")
    assert not (tmp_path / "maps").exists()


def test_a_bad_out_argument_is_refused_before_any_work(tmp_path):
    job = {"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}], "surfaces": [TABLE], "out": "maps"}
    (tmp_path / "a_file").write_text("mine")
    for out, fragment in (("", "must be a folder path"), ("a\x00b", "must be a folder path"), (b"maps", "got b'maps'"),
                          (tmp_path / "a_file", "exists and is not a folder")):
        with pytest.raises(JobError, match=f"out \\(--out\\): .*{fragment}"):
            read_job(job, out=out)
    (tmp_path / "file_out").write_text("mine")
    with pytest.raises(JobError, match="job: out: .* exists and is not a folder"):
        read_job({**job, "out": str(tmp_path / "file_out")})
    path = tmp_path / "job.json"
    path.write_text(json.dumps(job))
    one_line_error(cli("build-many", path, "--out", "", "--cluster", "none", "--no-cache"), "out (--out)")
    assert (tmp_path / "a_file").read_text() == "mine" and not (tmp_path / "maps").exists()


def test_huge_integers_in_a_job_are_refused(tmp_path):
    for key in ("resolutions", "base_heights"):
        with pytest.raises(JobError, match="finite"):
            read_job({"robots": ["test_arm"], "surfaces": [TABLE], key: [int("9" * 400)]})
    with pytest.raises(JobError, match="capability.seed"):
        read_job({"robots": ["test_arm"], "surfaces": [TABLE], "capability": {"seed": int("9" * 400)}})
    with pytest.raises(JobError, match="must be a number, a string or a list of numbers"):
        read_job({"robots": ["test_arm"], "surfaces": [TABLE], "capability": {"seed": [[1] * 5] * 5}})


# ---------------------------------------------------------------------------------------------- names
@pytest.mark.parametrize("name, fragment", [
    ("a/b", "kept for shelf boards"), ("a\\b", "cannot be part of a file name"),
    ("a\x00b", "cannot be part of a file name"), ("x" * (limits.MAX_NAME_LENGTH + 1), "MAX_NAME_LENGTH"),
    ("new\nline", "cannot be part of a file name"),
])
def test_names_that_cannot_be_file_names_are_refused(name, fragment):
    with pytest.raises(ValueError, match=fragment):
        Room({"surfaces": [{**TABLE, "name": name}]})
    with pytest.raises(ValueError, match=fragment):
        Room().add_box(name, [1, 1, 1], [0, 0, 0])


def test_output_names_that_meet_are_refused(tmp_path):
    room = {"surfaces": [{**TABLE, "name": "s_0"}], "shelves": [{"name": "s", "size": [0.8, 0.35], "boards": [0.4]}]}
    (tmp_path / "room.json").write_text(json.dumps(room))
    r = cli("surface", "--urdf", URDF, "--scene", tmp_path / "room.json", "--out", tmp_path / "maps", "--quiet")
    one_line_error(r, "'s_0' and 's/0' would both be written to s_0.orsm")
    assert not (tmp_path / "maps").exists()
    room = {"surfaces": [{**TABLE, "name": "Table"}, {**TABLE, "name": "table"}]}
    (tmp_path / "room.json").write_text(json.dumps(room))
    r = cli("surface", "--urdf", URDF, "--scene", tmp_path / "room.json", "--out", tmp_path / "maps", "--quiet")
    one_line_error(r, "'Table' and 'table'")


@pytest.mark.parametrize("change, fragment", [
    ({"resolutions": [0.2, 0.2]}, "listed twice"),
    ({"base_heights": [0.1, 0.1]}, "listed twice"),
    ({"surfaces": [{**TABLE, "name": "a b"}, {**TABLE, "name": "a?b"}]}, "would both be written to"),
    ({"surfaces": [{**TABLE, "name": "A"}, {**TABLE, "name": "a"}]}, "would both be written to"),
    ({"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"], ["base_link", "tool0"]]}]},
     "would both be written to"),
])
def test_job_outputs_that_meet_are_refused(change, fragment):
    job = {"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}], "surfaces": [TABLE], **change}
    with pytest.raises(JobError, match=fragment):
        read_job(job)


def test_close_resolutions_and_heights_get_their_own_outputs():
    job = {"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}], "surfaces": [TABLE],
           "resolutions": [0.2, 0.2000001], "base_heights": [0.1, 0.1000001]}
    plan = read_job(job)
    outs = [str(j.out) for j in [*plan.capability, *plan.surfaces]]
    names = [j.name for j in [*plan.capability, *plan.surfaces]]
    assert len(outs) == len(set(outs)) == len(set(names)) == 2 + 2 * 2


def test_robot_names_are_never_paths(tmp_path):
    evil = tmp_path / "x" / "evil.urdf"
    evil.parent.mkdir()
    evil.write_text(Path(URDF).read_text())  # a loadable URDF outside the project's folder
    rel = os.path.relpath(evil.with_suffix(""), robots.project_urdf("test_arm").parent)
    with pytest.raises(ValueError, match="a name, not a path"):
        robots.project_urdf(rel)
    with pytest.raises(JobError, match="cannot load the robot"):
        read_job({"robots": [{"name": rel, "arms": [["base_link", "tool0"]]}], "surfaces": [TABLE]})
    pytest.importorskip("viser")
    from octoreach.viewer.files import robot_by_name

    with pytest.raises(ValueError):
        robot_by_name(rel)  # a map header's robot name


# ---------------------------------------------------------------------------------------------- counts
def test_counts_past_the_limits_are_refused_before_building():
    many = [{**TABLE, "name": f"t{i}"} for i in range(limits.MAX_SURFACES + 1)]
    with pytest.raises(ValueError, match="MAX_SURFACES"):
        Room({"surfaces": many})
    with pytest.raises(ValueError, match="MAX_BOARDS"):
        Room({"shelves": [{"name": "s", "size": [1, 0.3], "boards": [0.1] * (limits.MAX_BOARDS + 1)}]})
    boxes = [{"name": f"b{i}", "size": [1, 1, 1]} for i in range(limits.MAX_OBSTACLES + 1)]
    with pytest.raises(ValueError, match="MAX_OBSTACLES"):
        Room({"boxes": boxes})
    room = Room()
    with pytest.raises(ValueError, match="MAX_SURFACES"):
        for i in range(limits.MAX_SURFACES + 1):
            room.add_table(f"t{i}", 0.5, 0.5, 0.7, x=2.0 * i, legs=None)
    with pytest.raises(JobError, match="MAX_JOB_MAPS"):
        read_job({"robots": ["test_arm"], "surfaces": [TABLE], "resolutions": [0.1 + 1e-6 * i for i in range(400)],
                  "base_heights": [0.01 * i for i in range(400)]})


def test_scene_obstacles_are_built_per_surface_not_all_first(tmp_path, monkeypatch):
    import argparse

    from octoreach.cli.build import _surfaces

    room = Room()
    for i in range(50):
        room.add_table(f"t{i}", 0.5, 0.5, 0.7, x=2.0 * i)
    room.save(tmp_path / "room.json")
    calls = []
    real = Room.obstacles
    monkeypatch.setattr(Room, "obstacles", lambda self, without=None: calls.append(without) or real(self, without))
    surfaces = _surfaces(argparse.Namespace(scene=str(tmp_path / "room.json"), polygon=None))
    assert len(surfaces) == 50 and calls == []  # nothing built before the first map
    for name, _stem, _surface, obstacles_of in surfaces[:3]:
        assert len(obstacles_of()) > 0
    assert calls == ["t0", "t1", "t2"]


def test_room_save_uses_the_umask_and_refuses_special_targets(tmp_path, fifo):
    room = Room({"surfaces": [TABLE]})
    old = os.umask(0o022)
    try:
        room.save(tmp_path / "room.json")
        room.save(tmp_path / "room.yaml")
    finally:
        os.umask(old)
    assert (tmp_path / "room.json").stat().st_mode & 0o777 == 0o644
    assert Room.load(tmp_path / "room.yaml").description == room.description
    victim = tmp_path / "victim.txt"
    victim.write_text("mine")
    (tmp_path / "link.json").symlink_to(victim)
    for target, fragment in ((tmp_path / "link.json", "symbolic link"), (fifo, "FIFO"), ("/dev/null", "device")):
        with pytest.raises(OSError, match=fragment):
            room.save(target)
    assert victim.read_text() == "mine" and (tmp_path / "link.json").is_symlink()
    assert os.path.exists("/dev/null") and not os.path.isfile("/dev/null")
    assert not [p for p in tmp_path.iterdir() if ".tmp." in p.name]


@pytest.mark.parametrize("name", [float("nan"), 5, None, ["n"], "", "a\x00b"])
def test_names_of_a_surfaces_own_boxes_are_checked_too(name):
    entry = {**TABLE, "boxes": [{"name": name, "size": [0.1, 0.1, 0.1], "xyz": [0.55, 0, 0.45]}]}
    with pytest.raises((TypeError, ValueError), match=r"surfaces\[0\] \('t'\)\.boxes\[0\]: 'name'"):
        Room({"surfaces": [entry]})
