"""Map files of any kind: the C++ registry of map kinds (load_any, map_kind, map_kinds), the provenance every map
records, and the Python layers that read map files through it (map_files, the viewer's loader, the cache)."""
from __future__ import annotations

import struct
import zlib

import numpy as np
import pytest

import octoreach
from octoreach import _core, map_files

MAGIC = b"OCTOREACH-MAP\n"


@pytest.fixture(scope="module")
def maps(tmp_path_factory):
    """A capability, an inverse point and a surface map of the test arm (coarse), saved with their usual extension."""
    d = tmp_path_factory.mktemp("map_files")
    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.15, directions=24,
                                        progress=False, seed=1)
    pm = octoreach.InversePointMap.build(robot, cap, theta_bins=4, progress=False)
    sm = octoreach.SurfaceMap.build(robot, cap, octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55), resolution=0.15,
                                    z_range=(0, 0), progress=False)
    paths = {"capability": d / "a.orcm", "point": d / "a.orpm", "surface": d / "a.orsm"}
    cap.save(str(paths["capability"]), with_solutions=True)
    pm.save(str(paths["point"]))
    sm.save(str(paths["surface"]))
    return robot, {"capability": cap, "point": pm, "surface": sm}, paths


def _map_file(kind: bytes, header: bytes = b"", payload: bytes = b"") -> bytes:
    """A well-formed map file container of any kind text (magic, version, kind, header, sizes, CRC, payload)."""
    compressed = zlib.compress(payload)
    crc = zlib.crc32(compressed, zlib.crc32(header, zlib.crc32(kind)))
    return (MAGIC + struct.pack("<II", _core.map_format_version(), len(kind)) + kind +
            struct.pack("<I", len(header)) + header + struct.pack("<QQI", len(payload), len(compressed), crc) + compressed)


def test_the_registry_names_every_kind_once():
    assert map_files.kinds() == {"capability": ".orcm", "point": ".orpm", "surface": ".orsm"}
    for cls in (octoreach.CapabilityMap, octoreach.InversePointMap, octoreach.SurfaceMap):
        assert map_files.kinds()[cls.kind] == cls.extension


@pytest.mark.parametrize("kind", ["capability", "point", "surface"])
def test_load_any_returns_each_kind(maps, kind, tmp_path):
    robot, built, paths = maps
    classes = {"capability": octoreach.CapabilityMap, "point": octoreach.InversePointMap,
               "surface": octoreach.SurfaceMap}
    for load in (_core.load_any, map_files.load):
        m = load(str(paths[kind]))
        assert type(m) is classes[kind] and m.kind == kind
        assert m.parameters == built[kind].parameters
        assert m.provenance == built[kind].provenance and m.provenance.matches(robot)
    assert map_files.kind(paths[kind]) == kind == _core.map_kind(str(paths[kind]))
    assert type(map_files.load(paths[kind], kind)) is classes[kind]
    # The header names the kind, not the extension.
    other = tmp_path / "map.data"
    other.write_bytes(paths[kind].read_bytes())
    assert type(map_files.load(other)) is classes[kind]


def test_every_map_records_the_same_provenance(maps):
    robot, built, _ = maps
    provenances = [m.provenance for m in built.values()]
    assert all(p == provenances[0] for p in provenances)
    p = provenances[0]
    assert (p.robot_name, p.urdf_hash, p.model_hash) == (robot.name, robot.urdf_hash, robot.model_hash)
    for m in built.values():
        assert (m.robot_name, m.urdf_hash, m.model_hash) == (p.robot_name, p.urdf_hash, p.model_hash)
        assert {k: m.parameters[k] for k in ("robot", "urdf_hash", "model_hash")} == {
            "robot": p.robot_name, "urdf_hash": str(p.urdf_hash), "model_hash": str(p.model_hash)}
    assert not p.matches(octoreach.robots.pr2())


def test_the_expected_kind_is_checked(maps):
    _, _, paths = maps
    with pytest.raises(OSError, match=r"holds a surface map, expected a capability map"):
        map_files.load(paths["surface"], "capability")
    with pytest.raises(ValueError, match="unknown map kind 'surfaces'.*capability, point and surface"):
        map_files.load(paths["surface"], "surfaces")


PNG = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x01\x00\x00\x00\x01\x08\x02\x00\x00\x00\x90wS\xde"


@pytest.mark.parametrize("content, why, tag", [
    (PNG, "not an octoreach map file", None),
    (b"", "not an octoreach map file", None),
    (b"robot: pr2\nsurfaces: []\n", "not an octoreach map file", None),
    (MAGIC, "truncated", None),
    (MAGIC + struct.pack("<I", 99), "format version 99", None),
    (_map_file(b"pointcloud"), "holds a pointcloud map, a kind this octoreach does not read", "pointcloud"),
    (_map_file(b"surf\xffce"), r"holds a surf\?ce map", "surf?ce"),
    (_map_file(b""), "holds a  map", ""),
])
def test_a_foreign_or_damaged_file_is_an_oserror_naming_it(tmp_path, content, why, tag):
    path = tmp_path / "not_a_map.orsm"
    path.write_bytes(content)
    for load in (map_files.load, lambda p: map_files.load(p, "surface")):
        with pytest.raises(OSError) as e:
            load(path)
        assert str(path) in str(e.value) and not isinstance(e.value, FileNotFoundError)
    with pytest.raises(OSError, match=why):
        map_files.load(path)
    if tag is None:  # not a map file container: no kind to read
        with pytest.raises(OSError, match=why):
            map_files.kind(path)
    else:  # a container naming a kind the registry does not hold: the kind, printable
        assert map_files.kind(path) == tag
    with pytest.raises(FileNotFoundError, match="no such file"):
        map_files.load(tmp_path / "missing.orsm")


def test_a_damaged_map_of_a_known_kind_is_an_oserror(maps, tmp_path):
    _, _, paths = maps
    data = bytearray(paths["point"].read_bytes())
    data[-5] ^= 0xFF
    path = tmp_path / "damaged.orpm"
    path.write_bytes(bytes(data))
    assert map_files.kind(path) == "point"  # the kind is read from the intact header
    with pytest.raises(OSError, match="checksum"):
        map_files.load(path)


def test_viewer_picks_the_layer_by_kind(maps):
    from octoreach.viewer import files

    _, built, paths = maps
    assert files.load(paths["surface"])[0] == "surface_map"
    assert files.load(str(paths["capability"]))[0] == "capability_map"
    assert files.load(built["surface"]) == ("surface_map", built["surface"])
    with pytest.raises(ValueError, match="a point map; the viewer shows surface and capability maps"):
        files.load(paths["point"])
    with pytest.raises(ValueError, match="InversePointMap: a point map"):
        files.load(built["point"])
    with pytest.raises(ValueError, match="cannot view a ndarray"):
        files.load(np.zeros(3))


def test_the_cache_loads_entries_through_the_registry_and_checks_their_kind(maps, tmp_path):
    from octoreach.cache import MapCache

    _, built, paths = maps
    cache = MapCache(tmp_path / "cache")
    fields = {"kind": "capability", "test": 1}
    assert cache.store_bytes("capability", fields, paths["capability"].read_bytes())
    assert type(cache.lookup("capability", fields)) is octoreach.CapabilityMap
    # An entry holding another kind than its name says is damage: reported, deleted, never returned.
    assert cache.store_bytes("capability", fields, paths["surface"].read_bytes())
    with pytest.warns(RuntimeWarning, match="holds a surface map, expected a capability map"):
        assert cache.lookup("capability", fields) is None
    assert cache.rebuilt_damaged == 1 and not cache.entries()
