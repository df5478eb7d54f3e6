"""Inverse point maps: grid against direct capability-map evaluation, against brute-force IK, yaw symmetry."""
from __future__ import annotations

import numpy as np
import pytest

import octoreach


@pytest.fixture(scope="module")
def setup():
    robot = octoreach.robots.test_arm()
    chain = robot.chain("base_link", "tool0")
    cap = octoreach.CapabilityMap.build(chain, resolution=0.1, directions=48, progress=False, seed=2)
    pm = octoreach.InversePointMap.build(robot, cap, grasps="upper_hemisphere", theta_bins=16, progress=False)
    return robot, chain, cap, pm


def test_grid_equals_direct_evaluation(setup):
    _, _, cap, pm = setup
    centres, values = pm.voxels()
    rng = np.random.default_rng(0)
    idx = rng.choice(len(centres), 400)
    k = rng.integers(0, 16, 400)
    poses = np.column_stack([centres[idx], k * 2 * np.pi / 16])
    direct = octoreach.InversePointMap.direct_reachability(cap, pm.reference_to_arm, pm.grasp_orientations, poses)
    assert np.allclose(pm.reachability(poses), direct, atol=1e-6)
    assert np.allclose(values[idx, k], direct, atol=1e-6)


def test_yaw_symmetry_is_exact(setup):
    robot, _, cap, pm = setup
    assert pm.used_symmetry
    full = octoreach.InversePointMap.build(robot, cap, grasps="upper_hemisphere", theta_bins=16, use_symmetry=False,
                                          progress=False)
    c1, v1 = pm.voxels()
    c2, v2 = full.voxels()
    assert np.array_equal(c1, c2)
    assert np.abs(v1 - v2).max() < 1e-6
    # And the symmetry itself: R_P(Rz(90 deg) p, theta + 90 deg) = R_P(p, theta).
    rng = np.random.default_rng(1)
    idx = rng.choice(len(c1), 200)
    p = c1[idx]
    th = rng.integers(0, 16, 200) * 2 * np.pi / 16
    rot = np.column_stack([-p[:, 1], p[:, 0], p[:, 2]])
    a = pm.reachability(np.column_stack([p, th]))
    b = pm.reachability(np.column_stack([rot, th + np.pi / 2]))
    assert np.abs(a - b).max() < 1e-6


def test_matches_brute_force_ik(setup):
    """R_P by IK at the exact target (no map) for sampled base poses, against the map."""
    robot, chain, cap, pm = setup
    centres, values = pm.voxels()
    rng = np.random.default_rng(3)
    idx = rng.choice(len(centres), 60, replace=False)
    k = rng.integers(0, 16, 60)
    dirs = cap.orientations.directions
    grasp_rots = [cap.orientations.rotation(g) for g in pm.grasp_orientations]
    brute = []
    for i, kk in zip(idx, k):
        x, y, z = centres[i]
        th = kk * 2 * np.pi / 16
        c, s = np.cos(th), np.sin(th)
        B = np.array([[c, -s, 0, x], [s, c, 0, y], [0, 0, 1, z], [0, 0, 0, 1.0]])
        Binv = np.linalg.inv(B)
        Ts = []
        for R in grasp_rots:
            T = np.eye(4)
            T[:3, :3] = R
            Ts.append(Binv @ T)  # target at the origin, grasp rotation in the world
        _, ok = chain.ik_batch(np.array(Ts), mode="approach", self_collision=True, attempts=20,
                               position_tolerance=1e-3, orientation_tolerance=1e-2)
        brute.append(ok.mean())
    brute = np.array(brute)
    mapped = values[idx, k]
    assert dirs.shape[1] == 3 and brute.max() > 0.3
    # The map quantises the target to capability voxel centres and yawed grasps to the nearest direction.
    assert np.mean(np.abs(mapped - brute)) < 0.12
    assert np.corrcoef(mapped, brute)[0, 1] > 0.8


def test_save_load_and_bad_input(setup, tmp_path):
    robot, chain, cap, pm = setup
    path = tmp_path / "point.orpm"
    pm.save(str(path))
    back = octoreach.InversePointMap.load(str(path))
    assert np.array_equal(back.voxels()[1], pm.voxels()[1])
    assert back.grasp_orientations == pm.grasp_orientations
    assert np.allclose(back.reference_to_arm, pm.reference_to_arm)
    data = path.read_bytes()
    (tmp_path / "cut.orpm").write_bytes(data[:-7])
    with pytest.raises(OSError):
        octoreach.InversePointMap.load(str(tmp_path / "cut.orpm"))
    with pytest.raises(ValueError, match="empty"):
        octoreach.InversePointMap.build(robot, cap, grasps=[], progress=False)
    with pytest.raises(ValueError, match="subset"):
        octoreach.InversePointMap.build(robot, cap, grasps="sideways", progress=False)
    with pytest.raises(ValueError, match=r"\(N, 4\)"):
        pm.reachability(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="theta_bins"):
        octoreach.InversePointMap.build(robot, cap, theta_bins=0, progress=False)
    pr2 = octoreach.robots.pr2()
    with pytest.raises(ValueError, match="robot"):
        octoreach.InversePointMap.build(pr2, cap, progress=False)
