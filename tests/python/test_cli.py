"""The `octoreach` command line: build, inspect, query and sample maps; one clear line on bad input."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from octoreach import robots

URDF = str(robots.project_urdf("test_arm"))


def _command() -> list[str]:
    script = Path(sys.executable).with_name("octoreach")
    return [str(script)] if script.is_file() else [sys.executable, "-m", "octoreach.cli"]


def run(*args):
    return subprocess.run(_command() + [str(a) for a in args], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def maps(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli")
    cap = d / "arm.orcm"
    r = run("capability", "--urdf", URDF, "--base", "base_link", "--tip", "tool0", "--resolution", 0.2,
            "--directions", 24, "--with-solutions", "--quiet", "--out", cap)
    assert r.returncode == 0, r.stderr
    smap = d / "table.orsm"
    r = run("surface", "--urdf", URDF, "--arms", cap, "--table", 0.6, 0.4, 0.4, "--table-x", 0.55, "--resolution", 0.2,
            "--quiet", "--out", smap, "--plot", d / "table.png", "--octovis", d / "table.ot")
    assert r.returncode == 0, r.stderr
    return d, cap, smap


def test_build_info_query_sample_export(maps):
    d, cap, smap = maps
    assert (d / "table.png").read_bytes().startswith(b"\x89PNG")
    assert (d / "table.ot").read_bytes().startswith(b"# Octomap OcTree file")
    info = run("info", smap)
    assert info.returncode == 0 and "octoreach_test_arm" in info.stdout and "surface_points: 6" in info.stdout
    info = run("info", cap)
    assert "capability" not in info.stderr
    from octoreach import CapabilityMap

    m = CapabilityMap.load(str(cap))  # records (reachable or mixed cells) vs voxels with D > 0, labelled apart
    assert f"voxels: {m.voxel_count} (voxel records: a reachable or a mixed cell)" in info.stdout
    assert f"over {m.stats['voxels']} voxels with D > 0" in info.stdout
    sample = run("sample", smap, "--count", 3)
    assert sample.returncode == 0 and len(sample.stdout.strip().splitlines()) == 3
    rs = [float(line.split("R_S=")[1]) for line in sample.stdout.splitlines()]
    assert all(v > 0 for v in rs)
    query = run("query", smap, "--pose", 0.55, 0.0, 0.0, 0.0, "--pose", 5, 5, 0, 0)
    assert query.returncode == 0 and query.stdout.count("R_S=0.0000") == 2  # under the table, far away
    export = run("export", cap, "--out", d / "arm.ot")
    assert export.returncode == 0 and (d / "arm.ot").is_file()


def test_polygon_file(maps, tmp_path):
    d, cap, _ = maps
    poly = tmp_path / "l_table.json"
    poly.write_text(json.dumps({"vertices": [[0.3, -0.4, 0.4], [0.9, -0.4, 0.4], [0.9, 0.4, 0.4], [0.6, 0.4, 0.4],
                                             [0.6, -0.1, 0.4], [0.3, -0.1, 0.4]], "thickness": 0.02}))
    r = run("surface", "--urdf", URDF, "--arms", cap, "--polygon", poly, "--resolution", 0.2, "--quiet",
            "--out", tmp_path / "l.orsm")
    assert r.returncode == 0, r.stderr


def test_surface_resolution_defaults_to_the_capability_maps(maps, tmp_path):
    from octoreach import SurfaceMap

    _, cap, _ = maps
    out = tmp_path / "coarse.orsm"
    r = run("surface", "--urdf", URDF, "--arms", cap, "--table", 0.6, 0.4, 0.4, "--table-x", 0.55, "--quiet",
            "--out", out)
    assert r.returncode == 0, r.stderr
    assert SurfaceMap.load(str(out)).resolution == pytest.approx(0.2)  # the .orcm's, as SurfaceMap.build
    assert "capability map's" in run("surface", "--help").stdout
    both = tmp_path / "both.orsm"  # a saved map and an arm by name: the name's map is built on the same grid
    r = run("surface", "--urdf", URDF, "--arms", cap, "arm", "--directions", 24, "--table", 0.6, 0.4, 0.4,
            "--table-x", 0.55, "--quiet", "--out", both)
    assert r.returncode == 0, r.stderr
    assert SurfaceMap.load(str(both)).resolution == pytest.approx(0.2)


@pytest.mark.parametrize("args, message", [
    (("info", "/nonexistent/map.orsm"), "cannot open"),
    (("sample", "/nonexistent/map.orsm"), "cannot open"),
    (("surface", "--robot", "no_such_robot", "--out", "x.orsm"), "unknown robot"),
    (("capability", "--urdf", URDF, "--arm", "no_arm", "--out", "x.orcm"), "no arm"),
    (("capability", "--urdf", "/nonexistent.urdf", "--arm", "x", "--out", "x.orcm"), "cannot read URDF"),
])
def test_bad_input_is_one_line_and_non_zero(args, message):
    r = run(*args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("octoreach: error:") and message in lines[0]


def test_malformed_polygon_files(tmp_path, maps):
    _, cap, _ = maps
    bad = tmp_path / "bad.json"
    bad.write_text("[[0, 0, 1], [1, 0, 1]]")
    r = run("surface", "--urdf", URDF, "--arms", cap, "--polygon", bad, "--out", tmp_path / "x.orsm", "--quiet")
    assert r.returncode == 2 and "three vertices" in r.stderr
    bad.write_text("{not json")
    r = run("surface", "--urdf", URDF, "--arms", cap, "--polygon", bad, "--out", tmp_path / "x.orsm", "--quiet")
    assert r.returncode == 2 and r.stderr.count("\n") == 1
    r = run("surface", "--urdf", URDF, "--arms", cap, "--polygon", tmp_path / "missing.json", "--out",
            tmp_path / "x.orsm", "--quiet")
    assert r.returncode == 2 and "cannot read polygon file" in r.stderr


@pytest.mark.parametrize("early", [False, True])
def test_a_reader_that_stops_early_is_no_error(maps, early):
    """`octoreach ... | head -1`: the reader closes the pipe; the command stops quietly with status 0, whether it
    writes after the reader has gone (more lines than a pipe holds, 64 kB) or only flushes a few lines at its end
    (stdout buffered, the reader gone before the command started)."""
    import os

    _, _, smap = maps
    count = 1 if early else 3000
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
    p = subprocess.Popen(_command() + ["query", str(smap)] + ["--pose", "0.5", "0", "0", "0"] * count,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    try:
        if early:
            p.stdout.close()
        else:
            p.stdout.readline()
            p.stdout.close()  # before the command has written the rest
        err = p.stderr.read().decode()
        assert p.wait(timeout=120) == 0, err
        assert "rror" not in err and "Traceback" not in err, err
    finally:
        p.kill()


@pytest.mark.parametrize("value", ["0", "-0.1", "nan", "inf", "five"])
def test_a_resolution_must_be_a_length(value):
    r = run("surface", "--urdf", URDF, "--table", 0.6, 0.4, 0.4, "--resolution", value, "--quiet")
    assert r.returncode == 2 and "--resolution" in r.stderr and "metres" in r.stderr, r.stderr
