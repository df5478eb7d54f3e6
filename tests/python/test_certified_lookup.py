"""Mixed cells, cell quality and the certified lookup on the small test arm (coarse maps, quick).

The certified lookup answers from the map where the 8 cells around a pose agree and from IK where they do not;
its yes answers from IK come with a solution that the tests check against the pose, the limits and
self-collision. Cell quality is the manipulability and joint-limit penalty of the stored solution, recomputed
here with numpy.
"""
from __future__ import annotations

import os

import numpy as np
import pytest

import octoreach
from octoreach import robots
from octoreach.testing import reach_truth

RES, DIRS, SEED = 0.2, 24, 1
DATA = os.path.join(os.path.dirname(__file__), "data")


@pytest.fixture(scope="module")
def robot():
    return robots.test_arm()


@pytest.fixture(scope="module")
def chain(robot):
    return robot.chain("base_link", "tool0")


@pytest.fixture(scope="module")
def cmap(chain):
    return octoreach.CapabilityMap.build(chain, resolution=RES, directions=DIRS, seed=SEED, progress=False)


@pytest.fixture(scope="module")
def check(cmap, robot):
    return octoreach.CertifiedLookup(cmap, robot)


@pytest.fixture(scope="module")
def poses_and_truth(robot, chain, cmap):
    ref = robot.home()
    poses, known = reach_truth.check_poses(robot, chain, ref, 400, seed=3)
    truth = reach_truth.ik_truth(chain, poses, cmap.approach_axis, ref, known, rounds=3, seed=3)
    return poses, truth


def numpy_quality(chain, q):
    """(manipulability, joint-limit penalty) recomputed from q with numpy."""
    s = np.linalg.svd(chain.jacobian(q), compute_uv=False)
    manip = float(np.prod(s[:chain.jacobian_rank]))
    lo, hi = np.asarray(chain.lower), np.asarray(chain.upper)
    bounded = ~np.asarray(chain.continuous)
    prod = np.prod(np.clip((q - lo) * (hi - q), 0, None)[bounded] / (hi - lo)[bounded] ** 2)
    return manip, 1.0 - np.exp(-(4.0 ** bounded.sum()) * prod)


def test_mixed_cells_are_marked_apart_from_reachable_ones(cmap):
    assert cmap.has_cell_data and cmap.stats["mixed_cells"] > 0
    r = cmap.resolution
    found = 0
    lo, hi = cmap.bounds
    for x in np.arange(lo[0] + r / 2, hi[0], r):
        for y in np.arange(lo[1] + r / 2, hi[1], r):
            for z in np.arange(lo[2] + r / 2, hi[2], r):
                p = np.array([x, y, z])
                for o in range(len(cmap.orientations)):
                    if not cmap.mixed_cell(p, o):
                        continue
                    assert not cmap.reachable_cell(p, o)  # a cell is reachable or mixed, never both
                    found += 1
    assert found > 0


def test_cell_quality_is_recomputed_from_the_stored_solution(chain, cmap):
    assert cmap.has_quality and cmap.jacobian_rank == chain.jacobian_rank == 6
    centres, _ = cmap.voxels()
    checked = 0
    for p in centres[::7]:
        for o in range(len(cmap.orientations)):
            q = cmap.solution(p, o)
            if q is None:
                assert cmap.quality(p, o) is None
                continue
            manip, penalty = cmap.quality(p, o)
            m_np, p_np = numpy_quality(chain, q)
            assert manip == pytest.approx(m_np, rel=1e-5, abs=1e-9)
            assert penalty == pytest.approx(p_np, rel=1e-5, abs=1e-7)
            assert manip == pytest.approx(chain.manipulability(q), rel=1e-6)
            assert 0 <= penalty <= 1
            checked += 1
    assert checked > 20
    best = max(cmap.voxel_quality("max"))
    assert best == pytest.approx(cmap.max_quality, rel=1e-6)
    rel = cmap.voxel_quality("mean", relative=True)
    assert len(rel) == len(centres) and (rel >= 0).all() and (rel <= 1).all()


def test_joint_limit_penalty_ends_and_middle(chain):
    lo, hi = np.asarray(chain.lower), np.asarray(chain.upper)
    mid = np.where(np.asarray(chain.continuous), 0.0, (np.where(np.isfinite(lo), lo, 0) + np.where(np.isfinite(hi), hi, 0)) / 2)
    assert chain.joint_limit_penalty(mid) == pytest.approx(1 - np.exp(-1), rel=1e-12)
    at_limit = mid.copy()
    at_limit[0] = lo[0]
    assert chain.joint_limit_penalty(at_limit) == 0.0
    assert chain.joint_limit_penalty(np.where(np.isfinite(hi), hi + 0.1, mid)) == 0.0  # past a limit: 0, no clamp


def test_quality_needs_solutions(chain, robot, tmp_path):
    bare = octoreach.CapabilityMap.build(chain, resolution=0.3, directions=8, keep_solutions=False, progress=False)
    assert not bare.has_quality
    with pytest.raises(ValueError, match="rebuild"):
        bare.voxel_quality()
    with pytest.raises(ValueError, match="rebuild"):
        bare.quality(bare.voxels()[0][0], 0)
    with pytest.raises(ValueError, match="rebuild"):
        octoreach.CertifiedLookup(bare, robot)


def test_certified_agrees_with_ik(check, cmap, poses_and_truth):
    poses, truth = poses_and_truth
    answer = check.reachable(poses)
    agree = (answer == truth.reachable).mean()
    assert agree >= 0.99, f"certified lookup agrees with IK on {100 * agree:.1f} % of the poses"
    assert (answer == truth.reachable).mean() > (cmap.reachable(poses) == truth.reachable).mean()


def test_certified_answers_equal_ik_on_boundary_cells(check, chain, robot, cmap, poses_and_truth):
    """Where the cells disagree the answer is IK's: every yes comes with a solution that reaches the pose inside
    the limits and free of self-collision, and the no answers are IK's (saturated truth)."""
    poses, truth = poses_and_truth
    boundary = np.flatnonzero(~check.certain(poses))
    assert len(boundary) > 20
    answer = check.reachable(poses[boundary])
    axis = np.asarray(cmap.approach_axis)
    for i, yes in zip(boundary, answer):
        q = check.solution(poses[i])
        assert (q is not None) == bool(yes)
        if q is None:
            continue
        F = chain.fk(q)
        assert np.linalg.norm(F[:3, 3] - poses[i][:3, 3]) <= 1e-3 + 1e-9
        assert np.arccos(np.clip((F[:3, :3] @ axis) @ (poses[i][:3, :3] @ axis), -1, 1)) <= 1e-2 + 1e-9
        assert chain.within_limits(q)
        assert not robot.in_self_collision(chain.to_robot_configuration(q))
    assert (answer == truth.reachable[boundary]).mean() >= 0.98


def test_a_pose_reached_in_self_collision_gets_more_branches():
    """Tool poses of configurations in self-collision (the UR5's: its own test arm seldom collides): often reachable
    free by another configuration, which the stored configurations around them, collision-free themselves, do not
    lead to. After a descent that reached the pose in collision the lookup tries collided_branch_seeds other
    branches instead of branch_seeds: it says yes to every pose the smaller budget does and to more, each with a
    collision-free solution of the pose; branch_seeds=0 still tries no other branch."""
    ur5 = robots.load("ur5")
    arm = octoreach.Arm.resolve(ur5, "arm")
    chain = ur5.chain(arm.base_link, arm.tip_link)
    ref = np.asarray(octoreach.arms.default_reference(ur5, "arm"))
    cmap = octoreach.arms.capability_map(ur5, "arm", resolution=RES, directions=DIRS, progress=False)
    Q = chain.random_configurations(2000, 7)
    colliding = np.array([q for q in Q if ur5.in_self_collision(chain.to_robot_configuration(q, ref))])
    poses = chain.fk_batch(colliding)
    fewer = octoreach.CertifiedLookup(cmap, ur5, collided_branch_seeds=0)
    more = octoreach.CertifiedLookup(cmap, ur5)
    a, b = np.asarray(fewer.reachable(poses)), np.asarray(more.reachable(poses))
    assert len(poses) > 200 and np.all(b[a]) and b.sum() > a.sum()
    corners_only = [octoreach.CertifiedLookup(cmap, ur5, branch_seeds=0, collided_branch_seeds=c) for c in (0, 16)]
    np.testing.assert_array_equal(*(c.reachable(poses) for c in corners_only))  # branch_seeds 0: no other branch
    axis = np.asarray(cmap.approach_axis)
    for i in np.flatnonzero(b & ~a):
        q = more.solution(poses[i])
        F = chain.fk(q)
        assert np.linalg.norm(F[:3, 3] - poses[i][:3, 3]) <= 1e-3 + 1e-9
        assert np.arccos(np.clip((F[:3, :3] @ axis) @ (poses[i][:3, :3] @ axis), -1, 1)) <= 1e-2 + 1e-9
        assert chain.within_limits(q) and not ur5.in_self_collision(chain.to_robot_configuration(q, ref))


def test_certified_does_not_depend_on_threads(check, poses_and_truth):
    poses, _ = poses_and_truth
    np.testing.assert_array_equal(check.reachable(poses, threads=1), check.reachable(poses, threads=2))


def test_certified_bad_input(check, robot, cmap):
    with pytest.raises(ValueError, match="shape"):
        check.reachable(np.zeros((3, 4)))
    bad = np.tile(np.eye(4), (2, 1, 1))
    bad[1, 0, 3] = np.nan
    with pytest.raises(ValueError, match="pose 1 is not finite"):
        check.reachable(bad)
    sheared = np.tile(np.eye(4), (2, 1, 1))
    sheared[1, 0, 1] = 0.5
    for call in (check.reachable, check.certain):
        with pytest.raises(ValueError, match="pose 1 is not a rigid transform"):
            call(sheared)
    with pytest.raises(ValueError, match="pose is not a rigid transform"):
        check.solution(2.0 * np.eye(4))
    with pytest.raises(ValueError, match="another robot model"):
        octoreach.CertifiedLookup(cmap, robots.load("ur5"))
    with pytest.raises(ValueError, match="seeds"):
        octoreach.CertifiedLookup(cmap, robot, seeds=0)
    with pytest.raises(ValueError, match="branch_seeds"):
        octoreach.CertifiedLookup(cmap, robot, branch_seeds=-1)
    with pytest.raises(ValueError, match="collided_branch_seeds must be at least 0"):
        octoreach.CertifiedLookup(cmap, robot, collided_branch_seeds=-1)
    with pytest.raises(ValueError, match="reference configuration entry 0 is not finite"):
        octoreach.CertifiedLookup(cmap, robot, reference=np.full(robot.dof, np.nan))
    # the options are fixed when the lookup is made: changing the copy it returns changes nothing
    c = octoreach.CertifiedLookup(cmap, robot)
    c.options.seeds = -1
    assert c.options.seeds == octoreach.CertifiedLookupOptions().seeds


def test_format_1_files_still_load(robot, tmp_path):
    """A map file written before maps marked mixed cells loads with its cells and solutions; the certified lookup
    and the quality say how to rebuild."""
    old = octoreach.CapabilityMap.load(os.path.join(DATA, "test_arm_format1.orcm"))
    assert old.has_solutions and not old.has_cell_data and not old.has_quality
    assert old.stats["reachable_cells"] > 0 and old.stats["mixed_cells"] == 0
    with pytest.raises(ValueError, match="older octoreach"):
        octoreach.CertifiedLookup(old, robot)
    # it saves and loads again as what it is
    path = str(tmp_path / "again.orcm")
    old.save(path, with_solutions=True)
    again = octoreach.CapabilityMap.load(path)
    assert not again.has_cell_data and again.stats == old.stats


def test_cell_data_round_trips_through_files(cmap, check, poses_and_truth, robot, tmp_path):
    path = str(tmp_path / "map.orcm")
    cmap.save(path, with_solutions=True)
    loaded = octoreach.CapabilityMap.load(path)
    assert loaded.has_cell_data and loaded.has_quality and loaded.stats["mixed_cells"] == cmap.stats["mixed_cells"]
    assert loaded.max_quality == cmap.max_quality
    np.testing.assert_array_equal(loaded.voxel_quality(), cmap.voxel_quality())
    np.testing.assert_array_equal(loaded.reference, cmap.reference)
    poses, _ = poses_and_truth
    np.testing.assert_array_equal(octoreach.CertifiedLookup(loaded, robot).reachable(poses), check.reachable(poses))
    bare = str(tmp_path / "bare.orcm")
    cmap.save(bare)
    without = octoreach.CapabilityMap.load(bare)
    assert without.has_cell_data and not without.has_solutions and not without.has_quality
