"""Paper experiments (octoreach.experiments) and the `octoreach experiment` subcommand: small, fast runs."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

experiments = pytest.importorskip("octoreach.experiments")


@pytest.fixture(scope="module")
def world(pr2):
    return experiments.build_world(1, resolution=0.1, robot=pr2)


@pytest.fixture(scope="module")
def rows(world):
    return experiments.tidy_up(trials=3, objects=(1, 2), tables=1, seed=0, world=world)


def test_rows_are_well_formed(rows):
    assert len(rows) == 5 * 2  # A with 1-4 poses and B, for 1 and 2 objects
    for r in rows:
        assert 0.0 <= r["solved"] <= 1.0
        assert r["poses_visited"] >= 1.0
        assert 0.0 <= r["useful_poses"] <= r["poses_visited"]
        assert r["time_s"] >= 0.0 and r["trials"] == 3
    text = experiments.format_tidy_up(rows)
    assert "sampling" in text and "4 poses" in text and "2 objects" in text


def test_sampling_solves_every_single_object_task(rows):
    # the objects lie where some pose reaches them: sampling from the surface map finds one
    b1 = next(r for r in rows if r["strategy"] == "B" and r["objects"] == 1)
    assert b1["solved"] == 1.0


def test_deterministic_for_a_seed(world, rows):
    again = experiments.tidy_up(trials=3, objects=(1, 2), tables=1, seed=0, world=world)
    strip = [{k: v for k, v in r.items() if k != "time_s"} for r in rows]
    assert strip == [{k: v for k, v in r.items() if k != "time_s"} for r in again]


def test_building_blocks(world):
    table = world.tables[0]
    poses = experiments.predefined_poses(table, 4)
    assert poses.shape == (4, 4)
    assert all(experiments.condition(table.smap, p) for p in poses)
    assert not experiments.condition(table.smap, [0.0, 0.0, 0.0, 0.0])  # under the table
    obj = [0.0, -0.1, 0.72 + experiments.OBJECT_HEIGHT]
    assert experiments.reachable(world.robot, "right_arm", poses[0], obj, table.obstacles, world=world) or \
        experiments.reachable(world.robot, "left_arm", poses[0], obj, table.obstacles, world=world)
    assert not experiments.reachable(world.robot, "right_arm", [3.0, 3.0, 0.0, 0.0], obj, table.obstacles,
                                     world=world)
    sampler = experiments.PoseSampler(table.smap, seed=1)
    pose = experiments.ground(sampler)
    assert pose.shape == (4,) and experiments.condition(table.smap, pose)


def test_bad_arguments(world):
    with pytest.raises(ValueError, match="tables"):
        experiments.tidy_up(trials=1, tables=3)
    with pytest.raises(ValueError, match="trials"):
        experiments.tidy_up(trials=0, world=world)


def run(*args):
    script = Path(sys.executable).with_name("octoreach")
    command = [str(script)] if script.is_file() else [sys.executable, "-m", "octoreach.cli"]
    return subprocess.run(command + [str(a) for a in args], capture_output=True, text=True, timeout=300)


def test_cli_tiny_run(pr2):
    r = run("experiment", "tidy-up", "--trials", 1, "--objects", 1, "--quiet")
    assert r.returncode == 0, r.stderr
    assert "share of tasks solved" in r.stdout and "sampling" in r.stdout


@pytest.mark.parametrize("args, message", [
    (("experiment", "tidy-up", "--tables", 3), "--tables must be 1 or 2"),
    (("experiment", "tidy-up", "--trials", 0), "--trials"),
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
