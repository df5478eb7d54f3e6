"""The robot foundation through Python: FK, IK, collision checking, errors, command line.

Poses are 4x4 numpy arrays in the chain's base link frame (the robot's root frame for collision
checks). No test asserts a wall-clock time: the machines are shared (see benchmarks/ik.py for speed).
"""
from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from pose_helpers import pose_error, reachable_targets, rot_z, translation
import octoreach_bench as _bench
from octoreach import Obstacles, Robot, _core, robots

POS_TOL, ROT_TOL = 1e-4, 1e-3  # the IK defaults

# Test arm: shoulder leaned forward, elbow folded back, so the wrist comes down onto the base
# cylinder (radius 0.08 m, height 0.1 m): tool0 ends at about x = 0.076 m, z = -0.02 m.
ARM_FOLDED = {"shoulder_lift": 1.3, "elbow": 2.6}


def assert_solves(chain, q, T, mode="full"):
    """q is inside the limits and reaches T within the IK tolerances (in the given mode)."""
    assert q is not None
    assert chain.within_limits(q)
    F = chain.fk(q)
    dp, angle = pose_error(F, T)
    assert dp < POS_TOL
    if mode == "full":
        assert angle < ROT_TOL
    elif mode == "approach":
        assert np.arccos(np.clip(F[:3, 2] @ T[:3, 2], -1, 1)) < ROT_TOL


# ---------------------------------------------------------------------------------------------
# Forward kinematics


def test_fk_of_test_arm_by_hand(arm_chain):
    q = np.zeros(6)
    # Straight up: 0.1 + 0.1 + 0.4 + 0.3 + 0.05 + 0.05 + 0.05 = 1.05 m, frames aligned with the base.
    T = arm_chain.fk(q)
    np.testing.assert_allclose(T[:3, 3], [0, 0, 1.05], atol=1e-12)
    np.testing.assert_allclose(T[:3, :3], np.eye(3), atol=1e-12)
    # Shoulder lift +90 deg about y: the 0.85 m above the shoulder (z = 0.2) now point along +x.
    q[1] = np.pi / 2
    np.testing.assert_allclose(arm_chain.fk(q)[:3, 3], [0.85, 0, 0.2], atol=1e-12)
    # Pan +90 deg as well: along +y.
    q[0] = np.pi / 2
    np.testing.assert_allclose(arm_chain.fk(q)[:3, 3], [0, 0.85, 0.2], atol=1e-12)
    # Elbow +90 deg with the arm up: forearm and wrist (0.45 m) along +x from the elbow at z = 0.6.
    np.testing.assert_allclose(arm_chain.fk([0, 0, np.pi / 2, 0, 0, 0])[:3, 3], [0.45, 0, 0.6], atol=1e-12)
    assert arm_chain.fk(q)[3].tolist() == [0, 0, 0, 1]


def test_random_configurations_inside_limits_and_spread(pr2):
    chain = pr2.chain("base_footprint", "r_wrist_roll_link")
    Q = chain.random_configurations(2000, seed=7)
    assert Q.shape == (2000, chain.dof)
    lo = np.where(chain.continuous, -np.pi, chain.lower)
    hi = np.where(chain.continuous, np.pi, chain.upper)
    assert np.all(Q >= lo) and np.all(Q < hi)
    # Uniform: each joint's sample mean within 5 standard errors of the interval's middle.
    se = (hi - lo) / np.sqrt(12 * len(Q))
    assert np.all(np.abs(Q.mean(axis=0) - (lo + hi) / 2) < 5 * se)
    np.testing.assert_array_equal(Q[0], chain.random_configuration(7))
    np.testing.assert_array_equal(Q, chain.random_configurations(2000, seed=7))
    assert not np.array_equal(Q, chain.random_configurations(2000, seed=8))
    assert chain.random_configurations(0).shape == (0, chain.dof)
    with pytest.raises(ValueError, match="n must be >= 0"):
        chain.random_configurations(-1)


def test_fk_batch_equals_fk_rows(arm_chain, pr2):
    for chain in (arm_chain, pr2.chain("base_footprint", "r_wrist_roll_link")):
        Q = chain.random_configurations(25, seed=3)
        Ts = chain.fk_batch(Q)
        assert Ts.shape == (25, 4, 4)
        for q, T in zip(Q, Ts):
            np.testing.assert_array_equal(T, chain.fk(q))


def test_fk_matches_plain_kdl(arm_chain, pr2):
    for chain in (arm_chain, pr2.chain("base_footprint", "r_wrist_roll_link")):
        Q = chain.random_configurations(50, seed=4)
        np.testing.assert_allclose(_bench.kdl_fk_batch(chain, Q), chain.fk_batch(Q), atol=1e-12)


def test_link_poses_agree_with_chain_fk(arm):
    q = arm.configuration({"shoulder_pan": 0.3, "elbow": -1.0, "wrist_flex": 0.5})
    chain = arm.chain("base_link", "tool0")
    np.testing.assert_allclose(arm.link_poses(q)["tool0"], chain.fk(q[chain.robot_indices]), atol=1e-12)


# ---------------------------------------------------------------------------------------------
# Inverse kinematics


def test_ik_round_trip_test_arm(arm_chain):
    targets = reachable_targets(arm_chain, 100, seed=5)
    Q, ok = arm_chain.ik_batch(targets, rng_seed=1)
    assert ok.mean() >= 0.95
    assert np.isnan(Q[~ok]).all()
    for q, T in zip(Q[ok], targets[ok]):
        assert_solves(arm_chain, q, T)
    # The single-pose call honours the same contract.
    assert_solves(arm_chain, arm_chain.ik(targets[0]), targets[0])


@pytest.mark.parametrize("base", ["base_footprint", "torso_lift_link"])
def test_ik_round_trip_pr2_right_arm(pr2, base):
    chain = pr2.chain(base, "r_wrist_roll_link")
    targets = reachable_targets(chain, 60, seed=6)
    Q, ok = chain.ik_batch(targets, rng_seed=2)
    assert ok.mean() >= 0.95
    for q, T in zip(Q[ok], targets[ok]):
        assert_solves(chain, q, T)


def test_ik_returns_a_seed_that_already_solves(arm_chain):
    q0 = np.array([0.3, 0.4, -0.8, 1.0, 0.6, -0.2])
    q = arm_chain.ik(arm_chain.fk(q0), seed=q0)
    np.testing.assert_allclose(q, q0, atol=1e-9)


def test_ik_batch_is_deterministic_and_independent_of_threads(arm_chain):
    targets = reachable_targets(arm_chain, 48, seed=7)  # > 4 chunks of 4, so two threads really share it
    Q1, ok1 = arm_chain.ik_batch(targets, rng_seed=11, threads=1)
    Q1b, ok1b = arm_chain.ik_batch(targets, rng_seed=11, threads=1)
    Q2, ok2 = arm_chain.ik_batch(targets, rng_seed=11, threads=2)
    Q0, ok0 = arm_chain.ik_batch(targets, rng_seed=11, threads=0)
    for Q, ok in ((Q1b, ok1b), (Q2, ok2), (Q0, ok0)):
        np.testing.assert_array_equal(ok, ok1)
        np.testing.assert_array_equal(Q, Q1)  # bit for bit, NaN rows included
    # The seed matters: the arm has several solutions per pose and restarts pick among them.
    Q3, _ = arm_chain.ik_batch(targets, rng_seed=12, threads=1)
    assert not np.array_equal(Q3, Q1)


def test_ik_position_mode(arm_chain):
    targets = reachable_targets(arm_chain, 30, seed=8)
    # Any orientation will do: give every target an orientation the tip could not have there.
    targets[:, :3, :3] = np.diag([1.0, -1.0, -1.0])
    Q, ok = arm_chain.ik_batch(targets, mode="position", rng_seed=3)
    assert ok.mean() >= 0.95
    for q, T in zip(Q[ok], targets[ok]):
        assert_solves(arm_chain, q, T, mode="position")
    # Out of reach (the arm is 1.05 m long): no solution, not a wrong one.
    assert arm_chain.ik(translation(2.0, 0, 0.5), mode="position") is None


def test_ik_approach_mode(arm_chain):
    targets = reachable_targets(arm_chain, 30, seed=9)
    # Rolled about their own z axis, the targets leave full IK no exact match, approach IK one.
    rolled = np.array([T @ rot_z(1.0) for T in targets])
    Q, ok = arm_chain.ik_batch(rolled, mode="approach", rng_seed=4)
    assert ok.mean() >= 0.95
    for q, T in zip(Q[ok], rolled[ok]):
        assert_solves(arm_chain, q, T, mode="approach")
    # Another tip axis: the tip x axis must land on the target's x axis.
    T = targets[0]
    q = arm_chain.ik(T @ _rot_x(0.7), mode="approach", approach_axis=np.array([1.0, 0, 0]), rng_seed=5)
    assert q is not None
    F = arm_chain.fk(q)
    assert np.linalg.norm(F[:3, 3] - T[:3, 3]) < POS_TOL
    assert np.arccos(np.clip(F[:3, 0] @ T[:3, 0], -1, 1)) < ROT_TOL


def test_ik_approach_cone(arm_chain):
    # Tilted 0.3 rad about their x axis, the targets' z axes lie within a 0.35 rad cone of one the arm reaches
    # at the same position: approach IK with that cone solves them, the axis within the cone.
    targets = reachable_targets(arm_chain, 20, seed=11)
    tilted = np.array([T @ _rot_x(0.3) for T in targets])
    Q, ok = arm_chain.ik_batch(tilted, mode="approach", approach_cone=0.35, rng_seed=7)
    assert ok.mean() >= 0.95
    for q, T in zip(Q[ok], tilted[ok]):
        F = arm_chain.fk(q)
        assert np.linalg.norm(F[:3, 3] - T[:3, 3]) < POS_TOL
        assert np.arccos(np.clip(F[:3, 2] @ T[:3, 2], -1, 1)) < 0.35 + ROT_TOL
    for bad in (-0.1, np.pi, np.nan):
        with pytest.raises(ValueError, match="approach_cone"):
            arm_chain.ik(targets[0], mode="approach", approach_cone=bad)


def _rot_x(angle):
    c, s = np.cos(angle), np.sin(angle)
    T = np.eye(4)
    T[1:3, 1:3] = [[c, -s], [s, c]]
    return T


def test_ik_with_self_collision_on_pr2(pr2):
    chain = pr2.chain("torso_lift_link", "r_wrist_roll_link")
    targets = reachable_targets(chain, 20, seed=10)
    Q, ok = chain.ik_batch(targets, self_collision=True, rng_seed=6)
    assert ok.any()
    for q, T in zip(Q[ok], targets[ok]):
        assert_solves(chain, q, T)
        assert not pr2.in_self_collision(chain.to_robot_configuration(q))


def test_ik_with_obstacles_is_collision_free_or_none(arm, arm_chain):
    T = translation(0.45, 0, 0.45)
    # A slab in front of the shoulder where "elbow up" solutions put the elbow.
    obstacles = Obstacles()
    obstacles.add_box([0.12, 0.4, 0.12], translation(0.15, 0, 0.55))
    collided_without = 0
    for seed in range(8):
        q_free = arm_chain.ik(T, mode="position", rng_seed=seed)
        collided_without += arm.in_collision(arm_chain.to_robot_configuration(q_free), obstacles)
        q = arm_chain.ik(T, mode="position", rng_seed=seed, obstacles=obstacles)
        if q is not None:
            assert_solves(arm_chain, q, T, mode="position")
            assert not arm.in_collision(arm_chain.to_robot_configuration(q), obstacles)
    assert collided_without > 0  # the obstacle really was in the way of some plain solutions
    # A box around the target swallows the wrist: no collision-free solution exists.
    around = Obstacles()
    around.add_box([0.2, 0.2, 0.2], T)
    assert arm_chain.ik(T, mode="position", obstacles=around) is None
    Q, ok = arm_chain.ik_batch(np.array([T, T]), mode="position", obstacles=around)
    assert not ok.any() and np.isnan(Q).all()


# ---------------------------------------------------------------------------------------------
# Collision checking


def test_test_arm_self_collision(arm):
    assert not arm.in_self_collision(arm.home())
    assert arm.in_self_collision(arm.configuration(ARM_FOLDED))


def test_pr2_home_is_not_in_self_collision(pr2):
    assert not pr2.in_self_collision(pr2.home())


# PR2 with the right forearm folded back into its own torso. The upper arm hangs down in front of
# the shoulder (shoulder lift at its 1.396 rad limit, elbow at about x = 0.12, z = 0.40 m in
# base_footprint); an upper-arm roll of -3.0 rad turns the elbow's bending plane around so the fully
# flexed elbow (-2.32 rad) swings the forearm backwards and up: the wrist (r_wrist_flex_link) ends at
# about (-0.15, -0.15, 0.57), behind the shoulder line (x = -0.05) inside the torso column. The
# forearm, palm and fingers then overlap torso_lift_link (and the palm the base_link spine housing).
PR2_FOREARM_IN_TORSO = {
    "r_shoulder_pan_joint": 0.0,
    "r_shoulder_lift_joint": 1.396,
    "r_upper_arm_roll_joint": -3.0,
    "r_elbow_flex_joint": -2.32,
}


def test_pr2_forearm_folded_into_torso_is_in_self_collision(pr2, fresh_pr2):
    q = pr2.configuration(PR2_FOREARM_IN_TORSO)
    assert pr2.in_self_collision(q)
    wrist = pr2.link_poses(q)["r_wrist_flex_link"][:3, 3]
    assert wrist[0] < -0.1 and wrist[2] < 0.7  # behind and below the shoulder (0.791 m high)
    # It is the forearm in the torso, not some other contact: with every other pair involving a
    # right-arm link allowed, the single pair (r_forearm_link, torso_lift_link) still collides.
    robot = fresh_pr2()
    arm_links = [name for name in robot.collision_links if name.startswith("r_")]
    pairs = [(a, b) for a in arm_links for b in robot.collision_links
             if a != b and {a, b} != {"r_forearm_link", "torso_lift_link"}]
    only = robot.with_allowed_collisions(pairs)
    assert only.in_self_collision(q)
    assert not only.in_self_collision(only.home())


def test_in_collision_with_a_box(arm):
    obstacles = Obstacles()
    obstacles.add_box([0.2, 0.2, 0.05], translation(0, 0, 0.8))  # around the straight-up forearm
    assert len(obstacles) == 1
    assert arm.in_collision(arm.home(), obstacles)
    # The same robot placed 3 m away, and an obstacle moved with it.
    assert not arm.in_collision(arm.home(), obstacles, base_pose=translation(3, 0, 0))
    moved = Obstacles()
    moved.add_box([0.2, 0.2, 0.05], translation(3, 0, 0.8))
    assert arm.in_collision(arm.home(), moved, base_pose=translation(3, 0, 0))
    # Folded arm: no obstacle hit, but self-collision counts when asked for.
    folded = arm.configuration(ARM_FOLDED)
    assert not arm.in_collision(folded, Obstacles())
    assert arm.in_collision(folded, Obstacles(), self_collision=True)


def test_compute_allowed_collisions(fresh_pr2):
    def run(seed):
        arm = robots.test_arm()
        before = set(arm.allowed_collisions)
        pairs = arm.compute_allowed_collisions(samples=2000, seed=seed)
        # Robots never change: the sampled pairs make a new robot, the old one keeps its pairs.
        assert set(arm.allowed_collisions) == before
        return arm.with_allowed_collisions(pairs), before, len(pairs), arm

    arm, before, added, original = run(0)
    after = set(arm.allowed_collisions)
    assert isinstance(added, int) and added > 0
    assert before < after and len(after) - len(before) == added
    assert arm.model_hash != original.model_hash and arm.urdf_hash == original.urdf_hash
    # Deterministic for a seed; a second pass finds nothing new to allow.
    arm2, _, added2, _ = run(0)
    assert added2 == added and arm2.allowed_collisions == arm.allowed_collisions
    assert arm2.model_hash == arm.model_hash
    assert len(arm.compute_allowed_collisions(samples=2000, seed=0)) == 0
    # Pairs that do collide somewhere (the wrist on the base when folded) stay checked.
    assert arm.in_self_collision(arm.configuration(ARM_FOLDED))


# ---------------------------------------------------------------------------------------------
# Bad input: every error is the named exception, with a message naming the problem


MESH_URDF = textwrap.dedent("""\
    <robot name="m"><link name="a"><collision><geometry>
      <mesh filename="/nonexistent/octoreach/x.stl"/>
    </geometry></collision></link></robot>""")


@pytest.mark.parametrize(
    "call, exception, match",
    [
        (lambda arm, c: Robot.from_urdf("<robot name='x'><link name='a'/>"), ValueError, "URDF"),
        (lambda arm, c: Robot.from_urdf(""), ValueError, "URDF"),
        (lambda arm, c: Robot.from_urdf("/nonexistent/octoreach/robot.urdf"), OSError, "robot.urdf"),
        (lambda arm, c: Robot.from_urdf(MESH_URDF), OSError, "x.stl"),
        (lambda arm, c: arm.chain("base_link", "no_such_link"), ValueError, "no_such_link"),
        (lambda arm, c: arm.chain("tool0", "base_link"), ValueError, "ancestor"),
        (lambda arm, c: c.fk(np.zeros(5)), ValueError, "6"),
        (lambda arm, c: c.fk(np.zeros((6, 1))), ValueError, "6"),
        (lambda arm, c: c.fk_batch(np.zeros((3, 5))), ValueError, "shape"),
        (lambda arm, c: c.ik(c.fk(np.zeros(6)), seed=np.zeros(4)), ValueError, "seed"),
        (lambda arm, c: arm.in_self_collision(np.zeros(3)), ValueError, "7"),
        (lambda arm, c: c.ik(np.diag([2.0, 1, 1, 1])), ValueError, "rigid"),
        (lambda arm, c: c.ik(np.diag([1.0, 1, -1, 1])), ValueError, "rigid"),  # a reflection
        (lambda arm, c: c.ik_batch(np.array([np.eye(4), np.diag([1.0, 1, 1, 2])])), ValueError, "rigid"),
        (lambda arm, c: c.ik(np.eye(3)), ValueError, "4x4"),
        (lambda arm, c: arm.in_collision(arm.home(), Obstacles(), base_pose=np.eye(4) + 0.1), ValueError, "rigid"),
        (lambda arm, c: c.ik(np.eye(4), mode="bogus"), ValueError, "bogus"),
        (lambda arm, c: c.ik(np.eye(4), position_tolerance=0.0), ValueError, "tolerance"),
        (lambda arm, c: c.ik(np.eye(4), mode="approach", approach_axis=np.zeros(3)), ValueError, "approach_axis"),
        (lambda arm, c: arm.configuration({"no_such_joint": 1.0}), ValueError, "no_such_joint"),
        (lambda arm, c: robots.load("nope"), ValueError, "nope"),
        (lambda arm, c: _bench.kdl_ik_batch(c, c.fk_batch(np.zeros((1, 6))), "bogus"), ValueError, "bogus"),
    ],
)
def test_bad_input_raises(arm, arm_chain, call, exception, match):
    with pytest.raises(exception, match=match):
        call(arm, arm_chain)


def test_non_finite_seed_raises(arm_chain):
    with pytest.raises(ValueError):
        arm_chain.ik(arm_chain.fk(np.zeros(6)), seed=np.full(6, np.nan))


def test_ik_of_a_fixed_chain_at_its_own_pose(arm):
    chain = arm.chain("wrist_3_link", "tool0")  # a fixed joint only
    q = chain.ik(chain.fk(np.zeros(0)))
    assert q is not None and q.shape == (0,)


# ---------------------------------------------------------------------------------------------
# The plain-KDL reference used by benchmarks/ik.py


def test_kdl_reference_ik_meets_the_same_success_test(arm_chain):
    targets = reachable_targets(arm_chain, 10, seed=12)
    for solver in ("nr_jl", "lma"):
        Q, ok = _bench.kdl_ik_batch(arm_chain, targets, solver, rng_seed=1)
        assert Q.shape == (10, 6) and ok.shape == (10,)
        assert ok.mean() >= 0.9
        for q, T in zip(Q[ok], targets[ok]):
            assert_solves(arm_chain, q, T)
        Q2, ok2 = _bench.kdl_ik_batch(arm_chain, targets, solver, rng_seed=1)
        np.testing.assert_array_equal(Q2, Q)


# ---------------------------------------------------------------------------------------------
# Command line


def _cli(*args):
    # The installed console script when there is one (as a user types it), else the module.
    script = Path(sys.executable).with_name("octoreach")
    command = [str(script)] if script.is_file() else [sys.executable, "-m", "octoreach.cli"]
    return subprocess.run([*command, *args], capture_output=True, text=True, timeout=120)


def test_cli_robot_pr2(pr2):
    r = _cli("robot", "--robot", "pr2")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("pr2:")
    assert "  right_arm: chain torso_lift_link -> r_wrist_roll_link" in r.stdout
    assert "  right_arm: torso_lift_link -> r_gripper_tool_frame, approach axis (1.0, 0.0, 0.0)" in r.stdout


def test_cli_unknown_robot():
    r = _cli("robot", "--robot", "nope")
    assert r.returncode == 2
    assert r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("octoreach: error:") and "'nope'" in lines[0]
