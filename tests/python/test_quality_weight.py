"""Quality-weighted point and surface maps (quality_weight=True) and the paper's maps without the weighting.

The files in data/ were written by the version before cell quality existed, from test_arm_format1.orcm: built
from that capability map without the weighting, point and surface maps keep their contents (header, sizes, compressed
payload; the container's format version, the octoreach version and the checksum over them aside).
"""
from __future__ import annotations

import os
import struct

import numpy as np
import pytest

import octoreach
from octoreach import robots

DATA = os.path.join(os.path.dirname(__file__), "data")


def _contents(data: bytes) -> tuple:
    """(kind, header lines but the octoreach version, payload sizes, compressed payload) of a map file: what the
    build decides (the container's format version, the version string and the checksum over them aside)."""
    at = 14 + 4  # magic, format version
    kind_len = struct.unpack_from("<I", data, at)[0]
    kind = data[at + 4:at + 4 + kind_len]
    at += 4 + kind_len
    text_len = struct.unpack_from("<I", data, at)[0]
    text = data[at + 4:at + 4 + text_len]
    at += 4 + text_len
    header = [line for line in text.split(b"\n") if not line.startswith(b"octoreach_version=")]
    compressed = struct.unpack_from("<Q", data, at + 8)[0]  # a format-2 file's sections follow the payload
    return kind, header, data[at:at + 16], data[at + 20:at + 20 + compressed]


@pytest.fixture(scope="module")
def robot():
    return robots.test_arm()


@pytest.fixture(scope="module")
def table():
    return octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)


@pytest.fixture(scope="module")
def cap(robot):
    return octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.1, directions=48, seed=3,
                                         progress=False)


def test_weighting_off_keeps_the_bytes(robot, table, tmp_path):
    old_cap = octoreach.CapabilityMap.load(os.path.join(DATA, "test_arm_format1.orcm"))
    pm = octoreach.InversePointMap.build(robot, old_cap, quality_weight=False, progress=False)
    pm.save(str(tmp_path / "p.orpm"))
    expected = open(os.path.join(DATA, "test_arm_format1_point.orpm"), "rb").read()
    assert _contents(open(tmp_path / "p.orpm", "rb").read()) == _contents(expected)
    sm = octoreach.SurfaceMap.build(robot, old_cap, table, z_range=(0, 0), progress=False)
    sm.save(str(tmp_path / "s.orsm"))
    expected = open(os.path.join(DATA, "test_arm_format1_surface.orsm"), "rb").read()
    assert _contents(open(tmp_path / "s.orsm", "rb").read()) == _contents(expected)
    assert pm.weight == sm.weight == ""


def test_weighted_point_map(robot, cap, tmp_path):
    plain = octoreach.InversePointMap.build(robot, cap, progress=False)
    weighted = octoreach.InversePointMap.build(robot, cap, quality_weight=True, progress=False)
    assert weighted.weight == "quality" and plain.weight == ""
    rng = np.random.default_rng(2)
    centres, _ = plain.voxels()
    rows = np.column_stack([centres[rng.integers(0, len(centres), 400)], rng.uniform(-np.pi, np.pi, 400)])
    a, b = plain.reachability(rows), weighted.reachability(rows)
    assert (b <= a + 1e-6).all() and ((b > 0) <= (a > 0)).all()
    assert b.max() > 0 and (b < a - 1e-6).any()
    weighted.save(str(tmp_path / "w.orpm"))
    again = octoreach.InversePointMap.load(str(tmp_path / "w.orpm"))
    assert again.weight == "quality"
    np.testing.assert_array_equal(again.reachability(rows), b)


def test_weighted_surface_map_and_sampler(robot, cap, table):
    plain = octoreach.SurfaceMap.build(robot, cap, table, z_range=(0, 0), progress=False)
    weighted = octoreach.SurfaceMap.build(robot, cap, table, z_range=(0, 0), quality_weight=True, progress=False)
    assert weighted.weight == "quality"
    centres, _ = plain.voxels()
    rows = np.column_stack([centres[:, 0], centres[:, 1], np.zeros(len(centres)),
                            np.zeros(len(centres))])
    a, b = plain.reachability(rows), weighted.reachability(rows)
    assert (b <= a + 1e-6).all() and b.max() > 0
    # The sampler on the weighted map prefers base poses whose grasps have good quality.
    picks = {}
    for name, smap in (("plain", plain), ("weighted", weighted)):
        sampler = octoreach.PoseSampler(smap, seed=4)
        poses = sampler.sample(8)
        picks[name] = weighted.reachability(poses).mean()
    assert picks["weighted"] >= picks["plain"]
    with pytest.raises(ValueError, match="quality"):
        octoreach.SurfaceMap.combine([plain, weighted], "max")


def test_quality_weight_needs_a_map_with_quality(robot, table):
    bare = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.2, directions=16,
                                         keep_solutions=False, progress=False)
    with pytest.raises(ValueError, match="rebuild"):
        octoreach.InversePointMap.build(robot, bare, quality_weight=True, progress=False)
    with pytest.raises(ValueError, match="rebuild"):
        octoreach.SurfaceMap.build(robot, bare, table, z_range=(0, 0), check_arm=False, quality_weight=True,
                                   progress=False)
