"""Arms of example-robot-data against saturated IK at a coarse resolution (the full panel is benchmarks/arm_panel.py).

Per arm: a map at 0.15 m (100 directions), 240 seeded check poses (half from collision-free configurations, half
uniform in the workspace box), truth by IK (3 rounds of 20 restarts). The certified lookup must agree on at least
98 % of the poses (the benchmark's 0.05 m maps reach 99.5 % and more on every arm; 240 poses measure to about
+-0.9 %), and more often than the map's own cells do (the vote).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import octoreach
from octoreach import arms, robots
from octoreach.testing import reach_truth

try:
    robots.data_dir()
except FileNotFoundError:  # pragma: no cover - the robots extra installs it
    pytest.skip("example-robot-data is not installed", allow_module_level=True)

ARMS = [("pr2", "right_arm"), ("panda", "arm"), ("ur5", "arm"), ("kinova", "end_effector"), ("so101", "arm"),
        ("z1", "arm")]
FLOOR = 0.98


@pytest.mark.parametrize("robot_name, arm_name", ARMS)
def test_certified_lookup_agrees_with_ik(robot_name, arm_name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = robots.load(robot_name)
    arm = octoreach.Arm.resolve(robot, arm_name)
    chain = robot.chain(arm.base_link, arm.tip_link)
    reference = arms.default_reference(robot, arm_name)
    cmap = arms.capability_map(robot, arm_name, resolution=0.15, directions=100, progress=False)
    poses, known = reach_truth.check_poses(robot, chain, reference, 240, seed=7)
    truth = reach_truth.ik_truth(chain, poses, arm.approach_axis, reference, known, rounds=3, seed=7).reachable
    answer = octoreach.CertifiedLookup(cmap, robot).reachable(poses)
    agree = float((answer == truth).mean())
    vote = float((cmap.reachable(poses) == truth).mean())
    assert agree >= FLOOR, (f"{robot_name} {arm_name}: certified {100 * agree:.1f} % (vote {100 * vote:.1f} %), "
                            f"{np.count_nonzero(answer & ~truth)} false positives, "
                            f"{np.count_nonzero(~answer & truth)} false negatives")
    assert agree >= vote


def test_user_path_map_is_byte_identical_for_any_thread_count(tmp_path):
    """arms.capability_map (the user's and the benchmark's call, joint solutions, mixed cells and quality kept) writes
    the same bytes on one thread as on two."""
    robot = robots.load("pr2")
    paths = []
    for threads in (1, 2):
        cmap = arms.capability_map(robot, "right_arm", resolution=0.2, directions=24, threads=threads, progress=False)
        assert cmap.has_solutions and cmap.has_cell_data and cmap.has_quality
        paths.append(tmp_path / f"t{threads}.orcm")
        cmap.save(str(paths[-1]), with_solutions=True)
    assert paths[0].read_bytes() == paths[1].read_bytes()


def test_other_branches_reach_what_the_seeds_miss():
    """When the descents from the corners' stored configurations fail, configurations of other IK branches stored
    around the corners are tried (branch_seeds): the answers are the seeds-only answers plus poses IK reaches from
    them, each with a solution (checked here; the saturated IK truth may miss a pose itself), none lost. The iCub
    arm stores other branches (elbow, wrist) in neighbouring cells at 0.1 m, so some reachable poses need them."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = robots.load("icub")
        arm = octoreach.Arm.resolve(robot, "l_arm")
        cmap = arms.capability_map(robot, "l_arm", resolution=0.1, directions=100, progress=False)
    chain = robot.chain(arm.base_link, arm.tip_link)
    reference = arms.default_reference(robot, "l_arm")
    poses, known = reach_truth.check_poses(robot, chain, reference, 400, seed=7)
    truth = reach_truth.ik_truth(chain, poses, arm.approach_axis, reference, known, rounds=3, seed=7).reachable
    seeds_only = octoreach.CertifiedLookup(cmap, robot, branch_seeds=0)
    check = octoreach.CertifiedLookup(cmap, robot)
    assert check.options.branch_seeds > 0
    before, after = seeds_only.reachable(poses), check.reachable(poses)
    assert not (before & ~after).any()
    gained = np.flatnonzero(after & ~before)
    assert len(gained) > 0
    assert np.count_nonzero(~after & truth) < np.count_nonzero(~before & truth)
    axis = np.asarray(arm.approach_axis)
    for i in gained:
        assert seeds_only.solution(poses[i]) is None
        q = check.solution(poses[i])
        F = chain.fk(q)
        assert np.linalg.norm(F[:3, 3] - poses[i][:3, 3]) <= 1e-3 + 1e-9
        assert np.arccos(np.clip((F[:3, :3] @ axis) @ (poses[i][:3, :3] @ axis), -1, 1)) <= 1e-2 + 1e-9
        assert chain.within_limits(q)
        assert not robot.in_self_collision(chain.to_robot_configuration(q, reference))
