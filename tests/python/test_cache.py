"""The map cache: content keys, hits without a build, damaged entries rebuilt, concurrent writers, the CLI."""
from __future__ import annotations

import os
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import octoreach
from octoreach import arms, robots
from octoreach.cache import MapCache, capability_key_fields, capability_options, key_of

KW = dict(resolution=0.2, directions=24, seed=1, progress=False)
ARM = ("base_link", "tool0")
URDF = str(robots.project_urdf("test_arm"))


@pytest.fixture(scope="module")
def robot():
    return robots.test_arm()


def test_key_follows_what_decides_the_bytes(robot):
    a = octoreach.Arm.resolve(robot, ARM)
    key = lambda **kw: key_of(capability_key_fields(robot, a, capability_options(None, **kw)))  # noqa: E731
    assert key(resolution=0.2) == key(resolution=0.2, threads=1) == key(resolution=0.2, directions=200)
    assert len({key(resolution=0.2), key(resolution=0.1), key(resolution=0.2, seed=5),
                key(resolution=0.2, block_size=4), key(resolution=0.2, keep_solutions=False)}) == 5
    other = robot.with_allowed_collisions([("base_link", "forearm_link")])
    assert key_of(capability_key_fields(other, a, capability_options())) != key()
    with pytest.raises(TypeError, match="unknown capability map option 'resolutoin'"):
        capability_options(None, resolutoin=0.1)
    with pytest.raises(TypeError, match="'directions'"):
        capability_options(None, directions="many")


def test_hit_returns_the_same_bytes_without_building(robot, tmp_path):
    cache = MapCache(tmp_path / "c")
    first = arms.capability_map(robot, ARM, cache=cache, **KW)
    assert (cache.builds, cache.hits) == (1, 0)
    [entry] = cache.entries()
    data = Path(entry["file"]).read_bytes()
    second = arms.capability_map(robot, ARM, cache=cache, **KW)
    assert (cache.builds, cache.hits) == (1, 1)
    assert second.stats["ik_calls"] == 0  # loaded, not built
    path = tmp_path / "again.orcm"
    second.save(str(path), with_solutions=True)
    assert path.read_bytes() == data
    # an independent build has the same bytes (maps hold no timing)
    fresh = octoreach.CapabilityMap.build_for_arm(robot, ARM, **KW)
    fresh.save(str(path), with_solutions=True)
    assert path.read_bytes() == data and first.voxel_count == fresh.voxel_count
    assert entry["fields"]["options"]["resolution"] == 0.2 and entry["fields"]["model_hash"] == robot.model_hash


def test_damaged_entry_is_detected_and_rebuilt(robot, tmp_path):
    cache = MapCache(tmp_path)
    arms.capability_map(robot, ARM, cache=cache, **KW)
    path = Path(cache.entries()[0]["file"])
    good = path.read_bytes()
    damaged = bytearray(good)
    damaged[-20] ^= 0xFF  # one flipped byte in the compressed payload: the checksum fails
    path.write_bytes(bytes(damaged))
    with pytest.warns(RuntimeWarning, match="damaged.*checksum"):
        m = arms.capability_map(robot, ARM, cache=cache, **KW)
    assert cache.rebuilt_damaged == 1 and cache.builds == 2 and m.stats["ik_calls"] > 0
    assert path.read_bytes() == good
    path.write_bytes(good[:100])  # truncated
    with pytest.warns(RuntimeWarning, match="damaged"):
        arms.capability_map(robot, ARM, cache=cache, **KW)
    assert path.read_bytes() == good


def test_unwritable_directory_builds_anyway_and_warns_once(robot, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    cache = MapCache(blocker / "cache")
    with pytest.warns(RuntimeWarning, match="not writable") as record:
        a = arms.capability_map(robot, ARM, cache=cache, **KW)
        b = arms.capability_map(robot, ARM, cache=cache, **KW)
    assert len([w for w in record if "not writable" in str(w.message)]) == 1
    assert a.voxel_count == b.voxel_count > 0 and cache.builds == 2 and cache.entries() == []


_WRITER = """
import sys
from octoreach import arms, robots
from octoreach.cache import MapCache
cache = MapCache(sys.argv[1])
m = arms.capability_map(robots.test_arm(), ("base_link", "tool0"), cache=cache, resolution=0.2, directions=24, seed=1,
                        progress=False)
print(cache.builds, cache.hits, m.voxel_count)
"""


def test_concurrent_writers_leave_one_whole_entry(robot, tmp_path):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    procs = [subprocess.Popen([sys.executable, "-c", _WRITER, str(tmp_path)], stdout=subprocess.PIPE, text=True, env=env)
             for _ in range(4)]
    outs = [p.communicate(timeout=300)[0].split() for p in procs]
    assert all(p.returncode == 0 for p in procs)
    assert sum(int(o[0]) for o in outs) == 1  # the lock: one process built, the others loaded its entry
    assert len({o[2] for o in outs}) == 1
    [entry] = MapCache(tmp_path).entries()
    assert not [p for p in tmp_path.iterdir() if ".tmp." in p.name]
    ref = tmp_path / "ref.orcm"
    octoreach.CapabilityMap.build_for_arm(robot, ARM, **KW).save(str(ref), with_solutions=True)
    assert Path(entry["file"]).read_bytes() == ref.read_bytes()


def run(*args, env=None):
    return subprocess.run([sys.executable, "-m", "octoreach.cli", *map(str, args)], capture_output=True, text=True,
                          env=env, timeout=300)


def test_cli_capability_uses_the_cache_and_cache_list_clear(tmp_path):
    env = {**os.environ, "OCTOREACH_CACHE_DIR": str(tmp_path / "cache")}
    args = ("capability", "--urdf", URDF, "--base", "base_link", "--tip", "tool0", "--resolution", 0.2,
            "--directions", 24, "--quiet", "--with-solutions")
    r1 = run(*args, "--out", tmp_path / "a.orcm", env=env)
    assert r1.returncode == 0, r1.stderr
    listing = run("cache", "list", env=env)
    assert listing.returncode == 0 and "1 maps" in listing.stdout and "base_link -> tool0 at 0.2 m" in listing.stdout
    r2 = run(*args, "--out", tmp_path / "b.orcm", env=env)
    assert r2.returncode == 0 and (tmp_path / "a.orcm").read_bytes() == (tmp_path / "b.orcm").read_bytes()
    r3 = run(*args, "--out", tmp_path / "c.orcm", "--no-cache", "--cache-dir", tmp_path / "other", env=env)
    assert r3.returncode == 0 and not (tmp_path / "other").exists()
    assert (tmp_path / "c.orcm").read_bytes() == (tmp_path / "a.orcm").read_bytes()
    cleared = run("cache", "clear", env=env)
    assert cleared.returncode == 0 and "deleted 1 maps" in cleared.stdout
    assert "0 maps" in run("cache", "list", env=env).stdout
