"""Paper experiments (octoreach.experiments) and the `octoreach experiment` subcommand: small, fast runs."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

experiments = pytest.importorskip("octoreach.experiments")


def run(*args):
    # the interpreter running the tests (an `octoreach` script beside it may belong to another environment)
    return subprocess.run([sys.executable, "-m", "octoreach.cli"] + [str(a) for a in args], capture_output=True,
                          text=True, timeout=300)


def test_cli_tidy_up_tiny_run(pr2, tmp_path):
    pytest.importorskip("up_fast_downward")
    png = tmp_path / "tidy.png"
    r = run("experiment", "tidy-up", "--runs", 1, "--runs-table2", 1, "--objects", 1, "--scenes", "paper",
            "--directions", 30, "--plot", png, "--quiet")
    assert r.returncode == 0, r.stderr
    for text in ("Table I", "sampling", "4 poses", "Table II", "T [min]", "# move", "Scenes", "paper"):
        assert text in r.stdout
    assert png.stat().st_size > 1000


def test_cli_tidy_up_with_a_robot_written_here(tmp_path):
    """Any robot with an arm and a camera: the URDF of own_robot.py (no SRDF), its camera found by name."""
    pytest.importorskip("up_fast_downward")
    from own_robot import urdf

    path = tmp_path / "own_robot.urdf"
    path.write_text(urdf())
    r = run("experiment", "tidy-up", "--urdf", path, "--runs", 1, "--runs-table2", 1, "--objects", 1, "--scenes",
            "paper", "--directions", 30, "--plot", tmp_path / "tidy.png", "--quiet")
    assert r.returncode == 0, r.stderr
    assert "Table I" in r.stdout and "Scenes" in r.stdout


def test_cli_tidy_up_asks_for_the_camera_of_a_robot_without_one():
    from octoreach import robots

    r = run("experiment", "tidy-up", "--urdf", robots.project_urdf("test_arm"), "--quiet")
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "no link that is unambiguously its camera" in lines[0] and "--camera-link" in lines[0]


@pytest.mark.parametrize("args, message", [
    (("experiment", "tidy-up", "--runs", 0), "--runs must be at least 1"),
    (("experiment", "tidy-up", "--scenes", "kitchen"), "unknown scene 'kitchen'"),
    (("experiment", "exploration", "--scene", 5), "--scene must be 1 or 2"),
])
def test_cli_bad_input_is_one_line(args, message):
    r = run(*args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("octoreach: error:") and message in lines[0]


def test_exploration_tables_tiny():
    res = experiments.exploration_tables(scenes=(1,), verbose=False, max_views=2, width=80, height=60,
                                         resolution=0.05, capability_map=None)
    rows = res[1].rows
    assert 1 <= len(rows) <= 2
    assert all(np.isfinite(r.utility_dm3) and r.void_cells >= 0 for r in rows)
