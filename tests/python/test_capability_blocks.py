"""The block build of a capability map (CapabilityBlocks): split, built in any order, merged, the same bytes.

On the small test arm at coarse resolutions. The one-process build with block_size is the reference:
blocks built one by one, in reverse order, twice, or with seeds passed through bytes give its bytes.
"""
from __future__ import annotations

import numpy as np
import pytest

import octoreach
from octoreach import robots

RES, DIRS, SEED = 0.1, 24, 3
ARM = ("base_link", "tool0")


@pytest.fixture(scope="module")
def robot():
    return robots.test_arm()


def file_bytes(m, tmp_path, name, with_solutions=True) -> bytes:
    path = tmp_path / name
    m.save(str(path), with_solutions=with_solutions)
    return path.read_bytes()


@pytest.fixture(scope="module")
def plan(robot):
    return octoreach.CapabilityBlocks(robot, ARM, resolution=RES, directions=DIRS, seed=SEED, block_size=4)


@pytest.fixture(scope="module")
def whole(robot):
    """The one-process build with the same options (CapabilityMap.build runs the block steps itself)."""
    return octoreach.CapabilityMap.build_for_arm(robot, ARM, resolution=RES, directions=DIRS, seed=SEED, block_size=4,
                                                 progress=False)


def test_plan_cuts_the_box_into_blocks(plan):
    assert plan.block_size == 4 and plan.count > 8  # the test arm's box at 0.1 m is about 14 voxels a side
    assert plan.options.block_size == 4 and plan.options.resolution == RES
    seeds = plan.sample()
    assert len(seeds) == plan.count and all(isinstance(s, bytes) for s in seeds)
    counts = [octoreach.CapabilityBlocks.seed_count(s) for s in seeds]
    assert sum(counts) > 0 and 0 in counts  # corners of the box hold no sample


def test_split_equals_whole_build_byte_for_byte(robot, plan, whole, tmp_path):
    seeds = plan.sample()
    order = list(reversed(range(plan.count)))  # any order, blocks built independently
    results = {b: plan.build_block(b, seeds[b]) for b in order}
    merged = plan.merge([results[b] for b in range(plan.count)])
    assert whole.parameters["block_size"] == "4"
    assert merged.voxel_count == whole.voxel_count > 0
    assert file_bytes(merged, tmp_path, "m.orcm") == file_bytes(whole, tmp_path, "w.orcm")
    # a block built again (a retried task) gives the same bytes; a fresh plan (another worker) too
    other = octoreach.CapabilityBlocks(robot, ARM, resolution=RES, directions=DIRS, seed=SEED, block_size=4)
    b = int(np.argmax([octoreach.CapabilityBlocks.seed_count(s) for s in seeds]))
    assert other.fingerprint == plan.fingerprint
    assert other.build_block(b, seeds[b]) == results[b] == plan.build_block(b, seeds[b])
    assert merged.stats["ik_calls"] == whole.stats["ik_calls"] > 0


def test_one_block_is_the_plain_build(robot, tmp_path):
    """A block as large as the box is the plain build: the blocks change only where floods stop."""
    kw = dict(resolution=0.2, directions=DIRS, seed=SEED, progress=False)
    plain = octoreach.CapabilityMap.build_for_arm(robot, ARM, **kw)
    one = octoreach.CapabilityMap.build_for_arm(robot, ARM, block_size=4096, **kw)
    a, b = plain.parameters, one.parameters
    assert a.pop("block_size") == "0" and b.pop("block_size") == "4096" and a == b
    cells = lambda m: (m.voxels()[0].tolist(), m.voxels()[1].tolist())  # noqa: E731
    assert cells(plain) == cells(one)


def test_blocks_agree_with_the_plain_build(robot, whole):
    """Blocks flood on their own: near their faces a cell may miss a seed from across; the map stays close."""
    plain = octoreach.CapabilityMap.build_for_arm(robot, ARM, resolution=RES, directions=DIRS, seed=SEED, progress=False)
    assert abs(whole.stats["reachable_cells"] - plain.stats["reachable_cells"]) <= 0.05 * plain.stats["reachable_cells"]


def test_foreign_or_damaged_pieces_are_refused(robot, plan):
    seeds = plan.sample()
    b = int(np.argmax([octoreach.CapabilityBlocks.seed_count(s) for s in seeds]))
    with pytest.raises(ValueError, match="out of range"):
        plan.build_block(plan.count, seeds[b])
    with pytest.raises(OSError, match="expected block"):
        plan.build_block((b + 1) % plan.count, seeds[b])
    with pytest.raises(OSError, match="length"):
        plan.build_block(b, seeds[b][:-3])
    with pytest.raises(OSError, match="not a seed list"):
        plan.build_block(b, b"nonsense")
    other = octoreach.CapabilityBlocks(robot, ARM, resolution=RES, directions=DIRS, seed=SEED + 1, block_size=4)
    with pytest.raises(OSError, match="another plan"):
        other.build_block(b, seeds[b])
    results = [plan.build_block(i, s) for i, s in enumerate(seeds)]
    with pytest.raises(ValueError, match="all"):
        plan.merge(results[:-1])
    with pytest.raises(OSError, match="expected block"):
        plan.merge(results[::-1])
    with pytest.raises(TypeError, match="list of bytes"):
        plan.merge(["x"] * plan.count)
    with pytest.raises(ValueError, match="block_size"):
        octoreach.CapabilityMap.build_for_arm(robot, ARM, resolution=RES, block_size=-1, progress=False)
