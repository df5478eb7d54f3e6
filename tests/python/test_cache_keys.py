"""A map cache that can be shared: an entry is used only when it is a regular file holding the bytes its note
records and agreeing with its key (copied bytes, another robot's map, an entry swapped with one whose header
reads the same, altered payloads, forged headers with a recomputed checksum and a rewritten note are
reported, deleted and rebuilt, also by build-many), planted links redirect nothing, a full disk loses no
build, and `cache clear` deletes only what the cache wrote."""
from __future__ import annotations

import errno
import json
import os
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import octoreach
from octoreach import arms, robots
from octoreach.cache import MARKER, MapCache, capability_key_fields, capability_options, key_of
from robust_util import forge, read_map, reseal, run_python, write_map

KW = dict(directions=16, seed=1, progress=False)
KW_OPTS = {k: v for k, v in KW.items() if k != "progress"}  # the key's options
ARM = ("base_link", "tool0")
URDF = str(robots.project_urdf("test_arm"))


@pytest.fixture(scope="module")
def robot():
    return robots.test_arm()


def entry_of(cache, robot, arm, **options):
    a = octoreach.Arm.resolve(robot, arm)
    return cache.path("capability", key_of(capability_key_fields(robot, a, capability_options(None, **options))))


def cached(cache, robot, arm=ARM, **options):
    """The map of the cache and the warnings it gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        m = arms.capability_map(robot, arm, cache=cache, **KW, **options)
    return m, [str(w.message) for w in caught]


@pytest.mark.parametrize("options", [dict(directions=50), dict(directions=7, rolls=2), dict(symmetry=2),
                                     dict(block_size=2), dict(fk_samples=5000), dict(keep_solutions=False),
                                     dict(position_tolerance=0.002, orientation_tolerance=0.02), dict(exhaustive=True),
                                     dict(self_collision=False), dict(approach_axis=(1.0, 0.0, 0.0))])
def test_an_honest_entry_is_a_hit_whatever_its_options(robot, tmp_path, options):
    cache = MapCache(tmp_path)
    opts = {**KW, "resolution": 0.3, **options}
    first = arms.capability_map(robot, ARM, cache=cache, **opts)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        again = arms.capability_map(robot, ARM, cache=cache, **opts)
    assert cache.hits == 1 and cache.builds == 1 and again.voxel_count == first.voxel_count
    assert again.orientations.directions.shape == first.orientations.directions.shape


@pytest.mark.parametrize("resealed", [False, True])
def test_copied_bytes_of_another_resolution_are_rebuilt(robot, tmp_path, resealed):
    cache = MapCache(tmp_path)
    cached(cache, robot, resolution=0.1)
    cached(cache, robot, resolution=0.2)
    dst = entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS)
    shutil.copy(entry_of(cache, robot, ARM, resolution=0.1, **KW_OPTS), dst)
    if resealed:  # the note rewritten to match the copy: the header check catches it
        reseal(dst)
    m, said = cached(cache, robot, resolution=0.2)
    assert m.resolution == 0.2 and cache.rebuilt_mismatched == 1
    expected = ("does not match its key", "resolution") if resealed else ("SHA-256 differs",)
    assert any(all(e in s for e in expected) for s in said), said
    m, said = cached(cache, robot, resolution=0.2)  # rebuilt and stored: a plain hit now
    assert m.resolution == 0.2 and not said and m.stats["ik_calls"] == 0


def test_another_robots_map_under_the_key_is_rebuilt(robot, pr2, tmp_path):
    cache = MapCache(tmp_path)
    theirs = arms.capability_map(pr2, "right_arm", cache=cache, resolution=0.2, **KW)
    mine, _ = cached(cache, robot, resolution=0.2)
    shutil.copy(entry_of(cache, pr2, "right_arm", resolution=0.2, **KW_OPTS),
                entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS))
    reseal(entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS))
    m, said = cached(cache, robot, resolution=0.2)
    assert m.robot_name == robot.name and m.model_hash == robot.model_hash and m.voxel_count == mine.voxel_count
    assert any("model_hash" in s for s in said), said
    assert theirs.robot_name != robot.name


def test_a_forged_resolution_with_a_recomputed_checksum_is_caught_by_its_content(robot, tmp_path):
    cache = MapCache(tmp_path)
    cached(cache, robot, resolution=0.2)
    src = entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS)
    dst = entry_of(cache, robot, ARM, resolution=0.1, **KW_OPTS)
    forge(src, dst, resolution="0.10000000000000001")  # header says 0.1, the checksum is right
    reseal(dst)  # and the note records the forged bytes
    assert octoreach.CapabilityMap.load(str(dst)).resolution == 0.1  # it loads: only the content betrays it
    m, said = cached(cache, robot, resolution=0.1)
    assert any("stored joint solution" in s for s in said), said
    fresh = octoreach.CapabilityMap.build_for_arm(robot, ARM, resolution=0.1, **KW)
    assert m.resolution == 0.1 and m.voxel_count == fresh.voxel_count and m.bounds[1][2] == fresh.bounds[1][2]


def test_the_right_arm_relabelled_as_the_left_is_caught(pr2, tmp_path):
    cache = MapCache(tmp_path)
    arms.capability_map(pr2, "right_arm", cache=cache, resolution=0.2, **KW)
    left = octoreach.Arm.resolve(pr2, "left_arm")
    dst = entry_of(cache, pr2, "left_arm", resolution=0.2, **KW_OPTS)
    forge(entry_of(cache, pr2, "right_arm", resolution=0.2, **KW_OPTS), dst, base_link=left.base_link,
          tip_link=left.tip_link)
    reseal(dst)
    m, said = cached(cache, pr2, "left_arm", resolution=0.2)
    assert any("stored joint solution" in s for s in said), said
    fresh = octoreach.CapabilityMap.build_for_arm(pr2, "left_arm", resolution=0.2, **KW)
    probe = [[0.4, 0.3, -0.2], [0.4, -0.3, -0.2], [0.6, 0.2, 0.0]]
    assert m.tip_link == left.tip_link and list(m.reachability(probe)) == list(fresh.reachability(probe))


@pytest.mark.parametrize("field, value", [("directions", "24"), ("seed", "7"), ("approach_axis", "1 0 0"),
                                          ("model_hash", "1"), ("position_tolerance", "0.5"), ("self_collision", "0"),
                                          ("block_size", "2"), ("tip_link", "wrist_3_link")])
def test_every_key_input_in_the_header_is_checked(robot, tmp_path, field, value):
    cache = MapCache(tmp_path)
    cached(cache, robot, resolution=0.2)
    path = entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS)
    forge(path, path, **{field: value})
    reseal(path)
    _, said = cached(cache, robot, resolution=0.2)
    assert any("does not match its key" in s and field in s for s in said), said


JOB = {"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}], "resolutions": [0.2],
       "capability": {"directions": 16, "seed": 1},
       "surfaces": [{"name": "t1", "rectangle": {"size": [0.4, 0.3], "height": 0.3, "x": 0.45}},
                    {"name": "t2", "rectangle": {"size": [0.5, 0.3], "height": 0.5, "x": 0.4, "y": 0.2}}],
       "surface": {"theta_bins": 4}}


def test_build_many_never_copies_a_swapped_entry_into_its_outputs(tmp_path):
    from octoreach import cluster

    cache = MapCache(tmp_path / "cache")
    first = cluster.build_many(JOB, cluster="none", out=tmp_path / "a", cache=cache, progress=False)
    surfaces = {e["fields"]["surface"]: Path(e["file"]) for e in cache.entries() if e["kind"] == "surface"}
    t1, t2 = surfaces["t1"], surfaces["t2"]
    t1_bytes = t1.read_bytes()
    for resealed, problem in ((False, "SHA-256 differs"), (True, "does not match its key .*polygon")):
        shutil.copy(t2, t1)  # t2's map under t1's key
        if resealed:
            reseal(t1)
        with pytest.warns(RuntimeWarning, match=problem):
            report = cluster.build_many(JOB, cluster="none", out=tmp_path / f"b{resealed}", cache=cache,
                                        progress=False)
        assert report.cache_hits == 2  # the capability map and t2; t1 was rebuilt
        out = Path(report.files["test_arm/tool0/0.2/t1"])
        assert out.read_bytes() == t1_bytes == Path(first.files["test_arm/tool0/0.2/t1"]).read_bytes()
        assert read_map(out).header["polygon"] != read_map(t2).header["polygon"]


def room_job(tmp_path, name, boxes):
    """A job of one table in a room of its own (with `boxes` beside the table)."""
    folder = tmp_path / name
    folder.mkdir()
    (folder / "room.json").write_text(json.dumps({"surfaces": [JOB["surfaces"][0]], "boxes": boxes}))
    return {**JOB, "surfaces": [{"room": str(folder / "room.json")}]}


def test_a_swapped_surface_entry_whose_header_reads_the_same_is_rebuilt(tmp_path):
    # The same table in two rooms: one with a wall beside it, one without. Their surface maps' headers agree on
    # everything the header check reads (robot, arm, polygon, height, options); only the room differs, and with
    # it the map. The entry of the room without the wall under the key of the room with it, alone or with its
    # note: caught by the digest the key's note records, rebuilt, and the output is the honest map.
    from octoreach import cluster, cache_check

    cache = MapCache(tmp_path / "cache")
    walled = room_job(tmp_path, "walled", [{"name": "wall", "size": [0.1, 1.0, 1.0], "xyz": [0.2, 0.0, 0.5]}])
    open_ = room_job(tmp_path, "open", [])
    honest = cluster.build_many(walled, cluster="none", out=tmp_path / "w", cache=cache, progress=False)
    other = cluster.build_many(open_, cluster="none", out=tmp_path / "o", cache=cache, progress=False)
    name = "test_arm/tool0/0.2/t1"
    honest_bytes, other_bytes = (Path(r.files[name]).read_bytes() for r in (honest, other))
    assert honest_bytes != other_bytes
    entries = {json_room(e): Path(e["file"]) for e in cache.entries() if e["kind"] == "surface"}
    mine, theirs = entries["walled"], entries["open"]
    plan = octoreach.jobs.read_job(walled)
    assert cache_check.surface_mismatch(octoreach.map_files.load(theirs), plan.surfaces[0].fields,
                                        plan.surfaces[0].polygon) is None  # the header check alone lets it in
    for with_note in (False, True):
        shutil.copy(theirs, mine)
        if with_note:
            shutil.copy(theirs.with_suffix(".json"), mine.with_suffix(".json"))
        with pytest.warns(RuntimeWarning, match="SHA-256 differs" if not with_note else "has no note of its key"):
            report = cluster.build_many(walled, cluster="none", out=tmp_path / f"again{with_note}", cache=cache,
                                        progress=False)
        assert Path(report.files[name]).read_bytes() == honest_bytes and report.cache_hits == 1
        assert mine.read_bytes() == honest_bytes  # rebuilt and stored again


def json_room(entry) -> str:
    """'walled' or 'open': which room a surface entry's note says it was built in."""
    return "walled" if entry["fields"]["room"].get("boxes") else "open"


def test_an_altered_payload_with_a_recomputed_checksum_is_rebuilt(robot, tmp_path):
    # A capability map without joint solutions has no content check: a changed reachability value, with the
    # map's checksum recomputed, loads and reads like the honest map. Its note's digest catches it.
    cache = MapCache(tmp_path)
    honest, _ = cached(cache, robot, resolution=0.2, keep_solutions=False)
    path = entry_of(cache, robot, ARM, resolution=0.2, keep_solutions=False, **KW_OPTS)
    good = path.read_bytes()
    m = read_map(path)
    _, values = honest.voxels()
    for i in range(len(m.payload()) // 2, len(m.payload())):  # the first one-bit change past the middle that loads
        payload = bytearray(m.payload())
        payload[i] ^= 1
        write_map(path, m, bytes(payload))
        try:
            forged = octoreach.CapabilityMap.load(str(path))
        except OSError:
            continue
        if list(forged.voxels()[1]) != list(values):
            break
    else:
        pytest.fail("no loadable one-bit change of the payload")
    again, said = cached(cache, robot, resolution=0.2, keep_solutions=False)
    assert any("SHA-256 differs" in s for s in said), said
    assert path.read_bytes() == good and cache.rebuilt_mismatched == 1 and cache.builds == 2


# ---------------------------------------------------------------------------------------------- planted files
def test_a_symlink_entry_is_not_followed(robot, tmp_path):
    cache = MapCache(tmp_path / "cache")
    cached(cache, robot, resolution=0.2)
    entry = entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS)
    other = tmp_path / "someone_elses.orcm"
    shutil.copy(entry, other)
    victim_bytes = other.read_bytes()
    entry.unlink()
    entry.symlink_to(other)
    m, said = cached(cache, robot, resolution=0.2)
    assert any("symbolic link" in s for s in said), said
    assert not entry.is_symlink() and entry.is_file() and other.read_bytes() == victim_bytes
    assert m.voxel_count > 0


def test_planted_lock_and_special_entries_change_no_file(robot, tmp_path):
    cache = MapCache(tmp_path / "cache")
    cache.writable()
    entry = entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS)
    key = entry.name.split("-", 1)[1].split(".")[0]
    victim = tmp_path / "victim"
    victim.write_text("mine")
    (cache.directory / f"{key}.lock").symlink_to(victim)
    os.mkfifo(entry)  # an entry that is a FIFO: never opened for reading
    child = run_python(f"""
        import warnings
        warnings.simplefilter("ignore")
        from octoreach import arms, robots
        from octoreach.cache import MapCache
        m = arms.capability_map(robots.test_arm(), ("base_link", "tool0"), cache=MapCache({str(cache.directory)!r}),
                                resolution=0.2, directions=16, seed=1, progress=False)
        print("VOXELS", m.voxel_count)
    """, timeout=120)
    assert not child.hung and child.returncode == 0, child.stderr[-2000:]
    assert victim.read_text() == "mine" and entry.is_file() and not entry.is_symlink()


def test_lock_files_are_removed_after_a_build(robot, tmp_path):
    cache = MapCache(tmp_path)
    cached(cache, robot, resolution=0.2)
    assert not list(tmp_path.glob("*.lock")) and (tmp_path / MARKER).is_file()


# ---------------------------------------------------------------------------------------------- a full disk
def test_an_entry_that_cannot_be_written_still_returns_the_build(robot, tmp_path):
    cache = MapCache(tmp_path)

    def full_disk(m):
        raise OSError(errno.ENOSPC, "cannot write map file: No space left on device")

    fields = capability_key_fields(robot, octoreach.Arm.resolve(robot, ARM), capability_options(None, resolution=0.2))
    with pytest.warns(RuntimeWarning, match="cannot store .*No space left"):
        m = cache.get_or_build("capability", fields, lambda: octoreach.CapabilityMap.build_for_arm(
            robot, ARM, resolution=0.2, **KW), full_disk)
    assert m.voxel_count > 0 and cache.builds == 1 and cache.entries() == []


def test_the_cli_writes_its_output_when_the_cache_entry_cannot_be_stored(tmp_path):
    cache = tmp_path / "cache"
    args = [sys.executable, "-m", "octoreach.cli", "capability", "--urdf", URDF, "--base", "base_link", "--tip",
            "tool0", "--resolution", "0.2", "--directions", "16", "--quiet", "--cache-dir", str(cache), "--out"]
    first = subprocess.run(args + [str(tmp_path / "first.orcm")], capture_output=True, text=True, timeout=300)
    assert first.returncode == 0, first.stderr
    [entry] = MapCache(cache).entries()
    Path(entry["file"]).unlink()
    Path(entry["file"]).mkdir()  # something in the way of the entry: it cannot be replaced
    r = subprocess.run(args + [str(tmp_path / "arm.orcm")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "cannot store" in r.stderr and (tmp_path / "arm.orcm").read_bytes() == (tmp_path / "first.orcm").read_bytes()


# ---------------------------------------------------------------------------------------------- clear and list
def run(*args, env=None):
    return subprocess.run([sys.executable, "-m", "octoreach.cli", *map(str, args)], capture_output=True, text=True,
                          env=env, timeout=300)


def test_clear_deletes_only_what_the_cache_wrote(robot, tmp_path):
    cache = MapCache(tmp_path)
    cached(cache, robot, resolution=0.2)
    mine = {"room.json": '{"surfaces": []}', "my_table.orsm": "not the cache's", "notes.json": "{}",
            "capability-123.orcm": "close, but not the cache's name", "capability-x.json": "{}"}
    for name, text in mine.items():
        (tmp_path / name).write_text(text)
    r = run("cache", "clear", "--cache-dir", tmp_path)
    assert r.returncode == 0 and "deleted 1 maps" in r.stdout, r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([*mine, MARKER])
    user = tmp_path / "user"
    user.mkdir()
    (user / "room.json").write_text("{}")
    (user / ("capability-" + "0" * 40 + ".orcm")).write_text("a cache's name, but not a cache")
    r = run("cache", "clear", "--cache-dir", user)
    assert r.returncode == 2 and "not an octoreach map cache" in r.stderr and len(list(user.iterdir())) == 2


@pytest.mark.parametrize("note", ["{not json", '{"kind": "capability", "key": "%s", "fields": {"robot": [1, 2], '
                                  '"arm": "x", "options": 5}}', '[1, 2, 3]', ""])
def test_cache_list_survives_damaged_notes(robot, tmp_path, note):
    cache = MapCache(tmp_path)
    cached(cache, robot, resolution=0.2)
    [entry] = cache.entries()
    path = Path(entry["file"]).with_suffix(".json")
    path.write_text(note % entry["key"] if "%s" in note else note)
    r = run("cache", "list", "--cache-dir", tmp_path)
    assert r.returncode == 0 and "1 maps" in r.stdout and "Traceback" not in r.stderr, r.stderr
    assert len(MapCache(tmp_path).entries()) == 1


@pytest.mark.parametrize("other", ["surface", "point"])
def test_a_map_of_another_kind_under_a_capability_key_is_rebuilt(robot, tmp_path, other):
    # Every map kind of the registry loads through map_files.load: a surface or point map's bytes at a capability
    # entry's name are refused by kind, reported and rebuilt, never used.
    cache = MapCache(tmp_path)
    honest, _ = cached(cache, robot, resolution=0.2)
    entry = entry_of(cache, robot, ARM, resolution=0.2, **KW_OPTS)
    if other == "surface":
        m = octoreach.SurfaceMap.build(robot, honest, octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55),
                                       resolution=0.2, theta_bins=8, z_range=(0, 0), progress=False)
    else:
        m = octoreach.InversePointMap.build(robot, honest, theta_bins=8, progress=False)
    entry.unlink()
    m.save(str(entry))
    again, said = cached(cache, robot, resolution=0.2)
    assert any("deleting and rebuilding" in s for s in said), said
    assert again.voxel_count == honest.voxel_count and cache.builds == 2
    assert octoreach.map_files.kind(entry) == "capability"
