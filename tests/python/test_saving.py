"""Saves that refuse what they should not replace: the one Python writer (temporary file created exclusively
in the target folder, fsync, rename) refuses devices, FIFOs, folders and symbolic links and gives the umask's
mode; the viewer's page and screenshot go through it, and `octoreach view` checks its port, host, sample count
and outputs before it loads or serves anything (in a child with a timeout: these used to hang)."""
from __future__ import annotations

import importlib.util
import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import octoreach
from octoreach import limits
from octoreach.atomic_write import check_target, write_atomically


def test_the_writer_replaces_regular_files_only(tmp_path):
    target = tmp_path / "out.txt"
    write_atomically(target, "one")
    write_atomically(target, b"two")
    assert target.read_text() == "two"
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    victim = tmp_path / "victim"
    victim.write_text("mine")
    (tmp_path / "link").symlink_to(victim)
    (tmp_path / "folder").mkdir()
    for path, fragment in ((fifo, "FIFO"), (tmp_path / "link", "symbolic link"), (tmp_path / "folder", "folder"),
                           ("/dev/null", "character device"), ("/dev/full", "character device")):
        with pytest.raises(OSError, match=fragment):
            write_atomically(path, "x")
    assert victim.read_text() == "mine" and stat.S_ISFIFO(os.lstat(fifo).st_mode) and (tmp_path / "link").is_symlink()
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode) and stat.S_ISCHR(os.stat("/dev/null").st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo", "folder", "link", "out.txt", "victim"]


@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_the_writer_gives_the_umasks_mode(tmp_path, umask, mode):
    old = os.umask(umask)
    try:
        path = write_atomically(tmp_path / "f", "x")
    finally:
        os.umask(old)
    assert path.stat().st_mode & 0o777 == mode


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    target = tmp_path / "out.txt"
    target.write_text("old")

    def full(fd):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "fsync", full)
    with pytest.raises(OSError, match="No space left"):
        write_atomically(target, "new")
    assert target.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["out.txt"]


def test_plots_are_saved_through_the_writer(tmp_path):
    from octoreach import plots

    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.2, directions=16,
                                        progress=False)
    fifo = tmp_path / "plot.png"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match="FIFO"):
        plots.capability_slices(cap, [0.2], fifo)
    plots.capability_slices(cap, [0.2], tmp_path / "ok.png")
    assert (tmp_path / "ok.png").read_bytes().startswith(b"\x89PNG")


# ---------------------------------------------------------------------------------------------- octoreach view
needs_viewer = pytest.mark.skipif(importlib.util.find_spec("viser") is None, reason="the viewer extra is not installed")


@pytest.fixture(scope="module")
def map_file(tmp_path_factory):
    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.2, directions=16,
                                        progress=False)
    path = tmp_path_factory.mktemp("view") / "arm.orcm"
    cap.save(str(path))
    return path


def view(*args, env=None, timeout=120):
    return subprocess.run([sys.executable, "-m", "octoreach.cli", "view", *map(str, args)], capture_output=True,
                          text=True, timeout=timeout, env=env)


@pytest.mark.parametrize("args, fragment", [
    (("--port", "70000"), "port must be an integer in 0-65535"),
    (("--port", "-1"), "port must be an integer in 0-65535"),
    (("--host", "no-such-host.invalid"), "does not resolve"),
    (("--samples", "1000000000"), "MAX_VIEW_SAMPLES"),
    (("--html", "/dev/full"), "character device"),
    (("--png", "/dev/null"), "character device"),
])
@needs_viewer
def test_view_checks_its_arguments_before_serving(map_file, args, fragment):
    r = view(map_file, "--no-serve", *args, timeout=60)
    assert r.returncode == 2, (r.returncode, r.stdout, r.stderr[-2000:])
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], r.stderr[-2000:]
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode) and stat.S_ISCHR(os.stat("/dev/null").st_mode)


@needs_viewer
def test_view_html_refuses_a_link_and_writes_a_page(map_file, tmp_path):
    victim = tmp_path / "victim.html"
    victim.write_text("mine")
    (tmp_path / "link.html").symlink_to(victim)
    r = view(map_file, "--no-serve", "--port", "0", "--html", tmp_path / "link.html")
    assert r.returncode == 2 and "symbolic link" in r.stderr and victim.read_text() == "mine"
    r = view(map_file, "--no-serve", "--port", "0", "--html", tmp_path / "page.html")
    assert r.returncode == 0, r.stderr[-2000:]
    assert "<html" in (tmp_path / "page.html").read_text().lower()


@needs_viewer
def test_view_png_without_a_working_chromedriver_is_one_line(map_file, tmp_path):
    fake = tmp_path / "bin"
    fake.mkdir()
    for name in ("chromium", "chromedriver"):
        script = fake / name
        script.write_text("#!/bin/sh\necho 'broken' >&2\nexit 1\n")
        script.chmod(0o755)
    env = {**os.environ, "PATH": f"{fake}:{os.environ['PATH']}"}
    r = view(map_file, "--no-serve", "--port", "0", "--png", tmp_path / "shot.png", env=env, timeout=180)
    assert r.returncode == 2, r.stderr[-2000:]
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "chromedriver" in lines[0] and "Traceback" not in r.stderr, r.stderr[-2000:]
    assert not (tmp_path / "shot.png").exists()


def test_check_target_names_the_kind(tmp_path):
    with pytest.raises(OSError, match="cannot write HTML page '/dev/zero': it is a character device"):
        check_target("/dev/zero", "HTML page")
    assert check_target(tmp_path / "new.html") == Path(tmp_path / "new.html")
    assert limits.MAX_VIEW_SAMPLES >= 5
