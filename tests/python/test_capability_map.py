"""CapabilityMap and OrientationSet: the map against brute-force IK, queries, files, bad input.

Everything runs on the small test arm (base_link -> tool0) at coarse resolutions, so the whole
file stays fast. The brute-force reference runs IK at every voxel centre of the map's bounds
(plus a margin of one voxel) for every orientation, with the map's own criteria: approach mode,
self-collision, tolerances 1e-3 m and 1e-2 rad.
"""
from __future__ import annotations

import glob
import os

import numpy as np
import pytest

import octoreach
from octoreach import robots

RES, DIRS, SEED = 0.2, 24, 1
POS_TOL, ROT_TOL = 1e-3, 1e-2
IK_KW = dict(mode="approach", self_collision=True, position_tolerance=POS_TOL, orientation_tolerance=ROT_TOL)


# ----------------------------------------------------------------------------- fixtures and helpers

@pytest.fixture(scope="module")
def robot():
    return robots.test_arm()


@pytest.fixture(scope="module")
def chain(robot):
    return robot.chain("base_link", "tool0")


def build(chain, resolution=RES, directions=DIRS, **kw):
    kw.setdefault("seed", SEED)
    return octoreach.CapabilityMap.build(chain, resolution=resolution, directions=directions, progress=False, **kw)


@pytest.fixture(scope="module")
def cmap(chain):
    return build(chain)


@pytest.fixture(scope="module")
def small(chain):
    """A coarser map for the tests that build several maps or only need some map."""
    return build(chain, resolution=0.25, directions=16)


def grid_centres(m, margin=1):
    """(V, 3) voxel centres covering the map's bounds plus `margin` voxels on every side."""
    lo, hi = m.bounds
    r = m.resolution
    axes = [np.arange(lo[i] + r / 2 - margin * r, hi[i] + margin * r - r / 4, r) for i in range(3)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    return np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)


def rotations(m):
    return np.array([m.orientations.rotation(o, m.approach_axis) for o in range(len(m.orientations))])


def cell_poses(m, P):
    """(V * O, 4, 4) tool poses of every (centre, orientation) cell, orientation fastest."""
    R = rotations(m)
    O = len(R)
    T = np.tile(np.eye(4), (len(P) * O, 1, 1))
    T[:, :3, :3] = np.tile(R, (len(P), 1, 1))
    T[:, :3, 3] = np.repeat(P, O, axis=0)
    return T


def cells(m, P):
    """(V, O) bool: reachable_cell of every centre and orientation."""
    O = len(m.orientations)
    return np.array([[m.reachable_cell(p, o) for o in range(O)] for p in P], dtype=bool)


def solutions(m, P, C):
    """{(v, o): stored solution} of every reachable cell in C."""
    return {(v, o): m.solution(P[v], o) for v, o in zip(*np.nonzero(C))}


def assert_same_maps(a, b, with_solutions=True):
    ca, da = a.voxels()
    cb, db = b.voxels()
    assert a.voxel_count == b.voxel_count
    np.testing.assert_array_equal(ca, cb)
    np.testing.assert_array_equal(da, db)
    assert a.resolution == b.resolution and len(a.orientations) == len(b.orientations)
    np.testing.assert_array_equal(a.orientations.directions, b.orientations.directions)
    np.testing.assert_array_equal(a.approach_axis, b.approach_axis)
    P = grid_centres(a)
    Ca, Cb = cells(a, P), cells(b, P)
    np.testing.assert_array_equal(Ca, Cb)
    if with_solutions:
        sa, sb = solutions(a, P, Ca), solutions(b, P, Cb)
        assert sa.keys() == sb.keys()
        for k in sa:
            np.testing.assert_array_equal(sa[k], sb[k])


@pytest.fixture(scope="module")
def brute(chain, cmap):
    """IK at every cell of the bounds plus one voxel: (P, T, ik_ok (V, O), map_ok (V, O))."""
    P = grid_centres(cmap)
    T = cell_poses(cmap, P)
    _, ok = chain.ik_batch(T, attempts=30, rng_seed=0, approach_axis=cmap.approach_axis, **IK_KW)
    O = len(cmap.orientations)
    return P, T, ok.reshape(len(P), O), cells(cmap, P)


# ----------------------------------------------------------------------------- the map against IK

def test_build_stats(cmap, brute):
    s = cmap.stats
    P, _, _, C = brute
    assert s["reachable_cells"] == C.sum() > 0
    # stats count the voxels with D > 0; the tree also holds voxels with mixed cells only
    assert s["voxels"] == np.count_nonzero(C.any(axis=1)) <= cmap.voxel_count
    assert s["cells"] >= s["reachable_cells"] and s["cells"] % len(cmap.orientations) == 0
    assert s["ik_calls"] > 0 and s["fk_samples"] > 0
    assert cmap.base_link == "base_link" and cmap.tip_link == "tool0"
    assert cmap.robot_name == "octoreach_test_arm"


def test_no_false_positives(chain, cmap, brute):
    """Every cell the map marks reachable has an IK solution (re-checked with many restarts)."""
    P, T, ok, C = brute
    doubtful = np.nonzero((C & ~ok).ravel())[0]
    if len(doubtful):
        _, ok2 = chain.ik_batch(T[doubtful], attempts=200, rng_seed=7, approach_axis=cmap.approach_axis, **IK_KW)
        doubtful = doubtful[~ok2]
    assert len(doubtful) == 0, f"{len(doubtful)} map cells have no IK solution, e.g. pose\n{T[doubtful[0]]}"


def test_few_false_negatives(cmap, brute):
    """Cells IK reaches but the map misses: only a few whose solutions sit on a joint limit."""
    P, T, ok, C = brute
    missed = np.count_nonzero(ok & ~C)
    assert ok.sum() > 1000  # the test arm reaches a good share of its bounding box
    assert missed <= 0.002 * ok.size, f"{missed} of {ok.size} IK-reachable cells missing from the map"


def test_stored_solutions_reach_their_cells(robot, chain, cmap, brute):
    P, _, _, C = brute
    assert cmap.has_solutions
    v, o = np.nonzero(C)
    Q = np.array([cmap.solution(P[i], j) for i, j in zip(v, o)])
    assert Q.shape == (len(v), chain.dof) and np.isfinite(Q).all()
    F = chain.fk_batch(Q)
    # solutions are stored as float32: allow a hair over the IK tolerances
    pos_err = np.linalg.norm(F[:, :3, 3] - P[v], axis=1)
    assert pos_err.max() <= POS_TOL + 1e-5
    dirs = cmap.orientations.directions[o]
    axis = np.asarray(cmap.approach_axis)
    cosang = np.einsum("nij,j,ni->n", F[:, :3, :3], axis, dirs)
    assert np.arccos(np.clip(cosang, -1, 1)).max() <= ROT_TOL + 1e-4
    lower, upper = np.asarray(chain.lower), np.asarray(chain.upper)
    assert (Q >= lower - 1e-6).all() and (Q <= upper + 1e-6).all()
    hits = [i for i, q in enumerate(Q) if robot.in_self_collision(chain.to_robot_configuration(q))]
    assert not hits, f"{len(hits)} stored solutions in self-collision"
    # unreachable cells have no solution
    vu, ou = np.nonzero(~C)
    for i, j in list(zip(vu, ou))[:200]:
        assert cmap.solution(P[i], j) is None


# ----------------------------------------------------------------------------- queries

def test_reachability_is_share_of_orientations(cmap, brute):
    P, _, _, C = brute
    D = cmap.reachability(P)
    np.testing.assert_allclose(D, C.mean(axis=1), rtol=0, atol=1e-6)
    # anywhere inside a voxel gives the voxel's value
    rng = np.random.default_rng(3)
    jitter = rng.uniform(-0.45, 0.45, size=P.shape) * cmap.resolution
    np.testing.assert_array_equal(cmap.reachability(P + jitter), D)
    # the voxels() listing agrees
    centres, values = cmap.voxels()
    np.testing.assert_allclose(cmap.reachability(centres), values, atol=0)
    assert (values > 0).all() and (values <= 1).all()


def test_reachability_zero_outside(cmap):
    far = np.array([[100.0, 0, 0], [0, -50.0, 3.0], [0, 0, 1e6], [-1e9, 1e9, 0]])
    np.testing.assert_array_equal(cmap.reachability(far), 0.0)
    lo, hi = cmap.bounds
    beyond = np.array([hi + cmap.resolution, lo - cmap.resolution])
    np.testing.assert_array_equal(cmap.reachability(beyond), 0.0)
    assert cmap.reachability(np.zeros((0, 3))).shape == (0,)


def test_reachable_poses_use_nearest_orientation(cmap, brute):
    P, T, _, C = brute
    # poses exactly at the cell orientations
    np.testing.assert_array_equal(cmap.reachable(T), C.ravel())
    # random poses: the nearest direction of the approach axis decides
    rng = np.random.default_rng(11)
    n = 5000
    lo, hi = cmap.bounds
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    R = np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], 1)
    poses = np.tile(np.eye(4), (n, 1, 1))
    poses[:, :3, :3] = R
    poses[:, :3, 3] = rng.uniform(lo, hi, size=(n, 3))
    approach = R @ np.asarray(cmap.approach_axis)
    nearest = np.argmax(approach @ cmap.orientations.directions.T, axis=1)
    expected = np.array([cmap.reachable_cell(p, int(o)) for p, o in zip(poses[:, :3, 3], nearest)])
    got = cmap.reachable(poses, lookup="nearest_cell")  # the vote: test_default_lookup_is_the_vote
    assert got.dtype == bool
    np.testing.assert_array_equal(got, expected)
    assert 0 < got.sum() < n
    # non-finite poses are rejected, not answered (no silent answer for NaN)
    bad = poses[:3].copy()
    bad[0, 0, 3] = np.nan
    with pytest.raises(ValueError, match="pose 0"):
        cmap.reachable(bad)
    bad = poses[:3].copy()
    bad[1, :3, :3] = np.inf
    with pytest.raises(ValueError, match="pose 1"):
        cmap.reachable(bad)


def random_poses(lo, hi, n, rng):
    """(n, 4, 4) poses: positions uniform in [lo, hi], rotations uniform on SO(3)."""
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    T = np.tile(np.eye(4), (n, 1, 1))
    T[:, :3, :3] = np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], 1)
    T[:, :3, 3] = rng.uniform(lo, hi, size=(n, 3))
    return T


def corner_answers(m, poses):
    """For each of the 8 voxel centres around each position: its trilinear weights (N,) and the nearest-cell
    answers (N,) of the poses moved there with their rotations."""
    r = m.resolution
    g = poses[:, :3, 3] / r - 0.5
    i0 = np.floor(g)
    f = g - i0
    q = poses.copy()
    for d in np.ndindex(2, 2, 2):
        q[:, :3, 3] = (i0 + np.asarray(d) + 0.5) * r
        yield np.prod(np.where(np.asarray(d, dtype=bool), f, 1 - f), axis=1), m.reachable(q, lookup="nearest_cell")


def numpy_vote(m, poses):
    """The vote lookup by brute force: the 8 voxel centres around each position asked by nearest cell with
    the pose's rotation, weighted trilinearly; yes when the reachable ones weigh at least one half."""
    vote = np.zeros(len(poses))
    for w, yes in corner_answers(m, poses):
        vote += w * yes
    return vote, vote >= 0.5


def test_default_lookup_is_the_vote(cmap):
    assert octoreach.CapabilityMap.DEFAULT_LOOKUP == octoreach.CapabilityLookup.vote
    rng = np.random.default_rng(5)
    lo, hi = cmap.bounds
    poses = random_poses(lo - cmap.resolution, hi + cmap.resolution, 20000, rng)
    weight, expected = numpy_vote(cmap, poses)
    clear = np.abs(weight - 0.5) > 1e-9  # a weight of exactly one half may round either way in numpy
    got = cmap.reachable(poses)
    np.testing.assert_array_equal(got[clear], expected[clear])
    assert (got != cmap.reachable(poses, lookup="nearest_cell")).any()  # the two rules differ somewhere
    np.testing.assert_array_equal(cmap.reachable(poses, lookup=octoreach.CapabilityLookup.vote), got)
    # one pose at a time gives the batch's answer; reachable_cell is the stored cell (the nearest_cell rule)
    nearest = np.argmax((poses[:, :3, :3] @ np.asarray(cmap.approach_axis)) @ cmap.orientations.directions.T, axis=1)
    for i in range(300):
        assert cmap.reachable(poses[i:i + 1])[0] == got[i]
        assert cmap.reachable_cell(poses[i, :3, 3], int(nearest[i])) == \
            cmap.reachable(poses[i:i + 1], lookup="nearest_cell")[0]
    # at the voxel centres the vote is the stored cell
    centres, _ = cmap.voxels()
    T = cell_poses(cmap, centres[:50])
    np.testing.assert_array_equal(cmap.reachable(T), cmap.reachable(T, lookup="nearest_cell"))
    with pytest.raises(ValueError, match="lookup"):
        cmap.reachable(poses[:2], lookup="trilinear")
    with pytest.raises(TypeError, match="lookup must be .* got int"):
        cmap.reachable(poses[:2], lookup=3)


def test_the_any_lookup_says_no_only_where_every_cell_around_does(cmap):
    """lookup="any": yes when one of the 8 voxel centres around the position holds the pose's cell (brute force
    as numpy_vote), so it says yes wherever the vote does; a no is certain for the map."""
    rng = np.random.default_rng(6)
    lo, hi = cmap.bounds
    poses = random_poses(lo - cmap.resolution, hi + cmap.resolution, 20000, rng)
    expected = np.zeros(len(poses), bool)
    for _, yes in corner_answers(cmap, poses):
        expected |= yes
    got = cmap.reachable(poses, lookup="any")
    np.testing.assert_array_equal(got, expected)
    np.testing.assert_array_equal(cmap.reachable(poses, lookup=octoreach.CapabilityLookup.any), got)
    weight, vote = numpy_vote(cmap, poses)
    assert not (vote & ~got).any()
    assert (got & ~vote).mean() > 0.01  # where the cells around disagree
    for i in range(200):
        assert cmap.reachable(poses[i:i + 1], lookup="any")[0] == got[i]


def test_vote_agrees_with_ik_at_least_as_well_as_the_nearest_cell(chain):
    """Coarse map (0.1 m, 24 directions) against IK at the exact pose: the vote is at least as right."""
    m = build(chain, resolution=0.1, directions=24)
    lo, hi = m.bounds
    poses = random_poses(lo, hi, 4000, np.random.default_rng(8))
    _, truth = chain.ik_batch(poses, attempts=20, rng_seed=3, approach_axis=m.approach_axis, **IK_KW)
    vote = m.reachable(poses)
    nearest = m.reachable(poses, lookup="nearest_cell")
    assert 0.2 < truth.mean() < 0.9
    agree_vote, agree_nearest = (vote == truth).mean(), (nearest == truth).mean()
    assert agree_vote >= agree_nearest, (agree_vote, agree_nearest)
    assert (vote & ~truth).mean() <= (nearest & ~truth).mean() + 0.002  # no more false positives to speak of


def test_orientation_rotation_points_the_approach_axis(cmap):
    D = cmap.orientations.directions
    axis = np.asarray(cmap.approach_axis)
    for o in range(len(cmap.orientations)):
        R = cmap.orientations.rotation(o, axis)
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
        assert np.linalg.det(R) == pytest.approx(1.0)
        np.testing.assert_allclose(R @ axis, D[o], atol=1e-12)
    with pytest.raises(ValueError):
        cmap.reachable_cell(np.zeros(3), len(cmap.orientations))
    with pytest.raises(ValueError):
        cmap.reachable_cell(np.zeros(3), -1)


# ----------------------------------------------------------------------------- files and determinism

def test_save_load_round_trip(cmap, tmp_path):
    path = str(tmp_path / "arm.map")
    cmap.save(path)
    loaded = octoreach.CapabilityMap.load(path)
    assert not loaded.has_solutions
    assert_same_maps(cmap, loaded, with_solutions=False)
    assert loaded.parameters == cmap.parameters
    assert loaded.stats["voxels"] == cmap.stats["voxels"]
    assert loaded.stats["reachable_cells"] == cmap.stats["reachable_cells"]
    assert loaded.robot_name == cmap.robot_name and loaded.urdf_hash == cmap.urdf_hash
    with pytest.raises(ValueError, match="save it with save\\(path, with_solutions=True\\)"):
        loaded.solution(cmap.voxels()[0][0], 0)

    path2 = str(tmp_path / "arm_solutions.map")
    cmap.save(path2, with_solutions=True)
    loaded2 = octoreach.CapabilityMap.load(path2)
    assert loaded2.has_solutions
    assert_same_maps(cmap, loaded2, with_solutions=True)
    assert os.path.getsize(path2) > os.path.getsize(path)
    # a loaded map saves to the same bytes
    path3 = str(tmp_path / "again.map")
    loaded2.save(path3, with_solutions=True)
    assert open(path3, "rb").read() == open(path2, "rb").read()


def test_same_seed_same_map(chain):
    a = build(chain, resolution=0.25, directions=16, seed=5)
    b = build(chain, resolution=0.25, directions=16, seed=5)
    assert_same_maps(a, b)
    assert a.stats["ik_calls"] == b.stats["ik_calls"]


def test_threads_do_not_change_the_map(chain):
    a = build(chain, resolution=0.25, directions=16, threads=1)
    b = build(chain, resolution=0.25, directions=16, threads=2)
    assert_same_maps(a, b)


def test_keep_solutions_false(chain, small):
    m = build(chain, resolution=0.25, directions=16, keep_solutions=False)
    assert not m.has_solutions
    assert_same_maps(m, small, with_solutions=False)
    c, _ = m.voxels()
    with pytest.raises(ValueError, match="holds no joint solutions|does not hold"):
        m.solution(c[0], 0)


def test_save_is_atomic_and_replaces(small, tmp_path):
    path = tmp_path / "replace.map"
    path.write_bytes(b"old contents that are not a map")
    small.save(str(path))
    loaded = octoreach.CapabilityMap.load(str(path))
    assert loaded.voxel_count == small.voxel_count
    assert sorted(os.listdir(tmp_path)) == ["replace.map"]
    assert not glob.glob(str(tmp_path / "*.tmp*"))
    with pytest.raises(OSError):
        small.save(str(tmp_path / "no_such_dir" / "x.map"))
    assert sorted(os.listdir(tmp_path)) == ["replace.map"]


def test_export_octovis(small, tmp_path):
    path = tmp_path / "arm.ot"
    small.export_octovis(str(path))
    data = path.read_bytes()
    assert data.startswith(b"# Octomap OcTree file")
    assert b"ColorOcTree" in data[:200]
    assert len(data) > 200
    assert not glob.glob(str(tmp_path / "*.tmp*"))


# ----------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("resolution", [0.0, -0.1, float("nan"), float("inf")])
def test_bad_resolution(chain, resolution):
    with pytest.raises(ValueError):
        build(chain, resolution=resolution)


def test_bad_query_shapes(small):
    with pytest.raises(ValueError):
        small.reachability(np.zeros((4, 2)))
    with pytest.raises(ValueError):
        small.reachability(np.zeros(3))
    with pytest.raises(ValueError):
        small.reachable(np.tile(np.eye(3), (4, 1, 1)))
    with pytest.raises(ValueError):
        small.reachable(np.eye(4))


@pytest.mark.parametrize("lookup", ["vote", "nearest_cell"])
def test_non_rigid_poses_raise(small, lookup):
    """A scaled or sheared rotation is a pose nobody meant: named, never answered (the vote would normalise the
    approach direction of a scaled one and tilt a sheared one)."""
    poses = np.tile(np.eye(4), (3, 1, 1))
    poses[:, :3, 3] = small.bounds[0] + 0.5 * (small.bounds[1] - small.bounds[0])
    small.reachable(poses, lookup=lookup)
    for broken in (np.diag([2.0, 2.0, 2.0]), np.array([[1.0, 0.5, 0], [0, 1, 0], [0, 0, 1]]), np.zeros((3, 3))):
        bad = poses.copy()
        bad[2, :3, :3] = broken
        with pytest.raises(ValueError, match="pose 2 is not a rigid transform"):
            small.reachable(bad, lookup=lookup)
    bad = poses.copy()
    bad[1, 3, 2] = 0.1
    with pytest.raises(ValueError, match="pose 1 is not a rigid transform"):
        small.reachable(bad, lookup=lookup)


@pytest.fixture(scope="module")
def saved_bytes(small, tmp_path_factory):
    path = tmp_path_factory.mktemp("maps") / "small.map"
    small.save(str(path), with_solutions=True)
    return path.read_bytes()


def _load_bytes(tmp_path, data):
    path = tmp_path / "damaged.map"
    path.write_bytes(data)
    return octoreach.CapabilityMap.load(str(path))


def test_missing_file(tmp_path):
    with pytest.raises(OSError):
        octoreach.CapabilityMap.load(str(tmp_path / "missing.map"))
    with pytest.raises(OSError):
        octoreach.CapabilityMap.load(str(tmp_path))  # a directory


def test_truncated_files(saved_bytes, tmp_path):
    n = len(saved_bytes)
    for cut in sorted({0, 1, 13, 14, 17, 20, 30, 100, n // 3, n // 2, n - 5, n - 1}):
        with pytest.raises(OSError):
            _load_bytes(tmp_path, saved_bytes[:cut])


def test_garbage_files(saved_bytes, tmp_path):
    rng = np.random.default_rng(0)
    with pytest.raises(OSError):
        _load_bytes(tmp_path, b"")
    for size in (10, 1000, 100000):
        with pytest.raises(OSError):
            _load_bytes(tmp_path, rng.bytes(size))
    # right magic, random rest
    with pytest.raises(OSError):
        _load_bytes(tmp_path, saved_bytes[:14] + rng.bytes(500))
    # flipped bytes in the payload: the checksum catches them
    for pos in (n := len(saved_bytes)) - 1, n - 50, n - 200:
        data = bytearray(saved_bytes)
        data[pos] ^= 0x5A
        with pytest.raises(OSError):
            _load_bytes(tmp_path, bytes(data))
    # trailing bytes after the payload are ignored or refused, never a crash
    try:
        _load_bytes(tmp_path, saved_bytes + b"\0" * 16)
    except OSError:
        pass


def test_other_kinds_of_file(saved_bytes, tmp_path):
    # wrong magic
    with pytest.raises(OSError, match="magic"):
        _load_bytes(tmp_path, b"OCTOREACH-MAX\n" + saved_bytes[14:])
    # an octoreach map of another kind ("surface" instead of "capability")
    kind_len = int.from_bytes(saved_bytes[18:22], "little")
    assert saved_bytes[22:22 + kind_len] == b"capability"
    other = saved_bytes[:18] + (7).to_bytes(4, "little") + b"surface" + saved_bytes[22 + kind_len:]
    with pytest.raises(OSError, match="surface"):
        _load_bytes(tmp_path, other)
    # a future format version
    with pytest.raises(OSError, match="version"):
        _load_bytes(tmp_path, saved_bytes[:14] + (99).to_bytes(4, "little") + saved_bytes[18:])
    # an OctoMap file is not a capability map
    with pytest.raises(OSError):
        _load_bytes(tmp_path, b"# Octomap OcTree file\nid ColorOcTree\nsize 0\nres 0.1\ndata\n")


def test_damaged_header_number_is_a_file_error(saved_bytes, tmp_path):
    i = saved_bytes.index(b"\nseed=") + len(b"\nseed=")
    data = saved_bytes[:i] + b"z" + saved_bytes[i + 1:]
    with pytest.raises(OSError):
        _load_bytes(tmp_path, data)


def test_damaged_header_parameter_is_detected(saved_bytes, tmp_path):
    assert b"\ndirections=16\n" in saved_bytes
    data = saved_bytes.replace(b"\ndirections=16\n", b"\ndirections=20\n")
    with pytest.raises(OSError):
        _load_bytes(tmp_path, data)


# ----------------------------------------------------------------------------- OrientationSet

@pytest.mark.parametrize("count,symmetry", [(16, 4), (24, 4), (200, 4), (200, 1), (60, 3)])
def test_orientation_set_spread(count, symmetry):
    s = octoreach.OrientationSet.sphere(count, 1, symmetry)
    D = s.directions
    assert D.shape == (len(s), 3)
    assert len(D) % symmetry == 0 and abs(len(D) - count) <= symmetry / 2
    np.testing.assert_allclose(np.linalg.norm(D, axis=1), 1.0, atol=1e-12)
    ideal = np.sqrt(4 * np.pi / len(D))  # spacing of an ideal even spread
    G = np.clip(D @ D.T, -1, 1)
    np.fill_diagonal(G, -1)
    assert np.arccos(G.max(axis=1)).min() > 0.7 * ideal
    # covering radius: no direction on the sphere is far from the set
    rng = np.random.default_rng(0)
    V = rng.normal(size=(20000, 3))
    V /= np.linalg.norm(V, axis=1, keepdims=True)
    assert np.arccos(np.clip((V @ D.T).max(axis=1), -1, 1)).max() < 1.0 * ideal
    # balanced: the mean direction is near the origin
    assert np.linalg.norm(D.mean(axis=0)) < 0.05


@pytest.mark.parametrize("symmetry", [4, 2, 8])
def test_orientation_set_z_symmetry(symmetry):
    s = octoreach.OrientationSet.sphere(200, 1, symmetry)
    assert s.symmetry == symmetry
    D = s.directions
    a = 2 * np.pi / symmetry
    Rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    image = D @ Rz.T
    G = image @ D.T
    match = G.argmax(axis=1)
    np.testing.assert_allclose(G.max(axis=1), 1.0, atol=1e-12)
    assert len(set(match)) == len(D)  # a permutation


def test_orientation_set_subsets():
    s = octoreach.OrientationSet.sphere(200)
    D = s.directions
    z = D[:, 2]
    eps = 1e-9
    expect = {
        "all": np.arange(len(D)),
        "upper_hemisphere": np.nonzero(z <= eps)[0],
        "lower_hemisphere": np.nonzero(z >= -eps)[0],
        "top": np.nonzero(z <= -np.cos(np.radians(30)) + eps)[0],
        "side": np.nonzero(np.abs(z) <= 0.5 + eps)[0],
    }
    for name, idx in expect.items():
        got = np.asarray(s.subset(name))
        np.testing.assert_array_equal(np.sort(got), idx)
        assert len(got) > 0
    assert len(s.subset("upper_hemisphere")) + len(s.subset("lower_hemisphere")) >= len(D)
    with pytest.raises(ValueError, match="unknown"):
        s.subset("sideways")


def test_orientation_set_nearest_direction_is_exact():
    s = octoreach.OrientationSet.sphere(200)
    D = s.directions
    rng = np.random.default_rng(5)
    V = rng.normal(size=(3000, 3))
    V /= np.linalg.norm(V, axis=1, keepdims=True)
    # also the axes and cube-map edges and corners
    V = np.vstack([V, np.eye(3), -np.eye(3), np.array([[1, 1, 1], [-1, 1, 0], [1, 0, -1]]) / np.sqrt([[3], [2], [2]])])
    for v in V:
        i = s.nearest_direction(v)
        assert D[i] @ v >= (D @ v).max() - 1e-12


def test_orientation_set_bad_input():
    with pytest.raises(ValueError):
        octoreach.OrientationSet.sphere(0)
    with pytest.raises(ValueError):
        octoreach.OrientationSet.sphere(10, 0)
    with pytest.raises(ValueError):
        octoreach.OrientationSet.sphere(10, 1, 0)
    s = octoreach.OrientationSet.sphere(8, 3)
    assert len(s) == 24 and s.rolls == 3
    with pytest.raises(ValueError):
        s.rotation(24)
