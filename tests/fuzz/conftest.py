"""The fuzz suite: hypothesis profiles ("short", seeded, for `make test`; "long" for `make fuzz`) and the
path to the shared helpers of the robustness tests."""
from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))

settings.register_profile("short", max_examples=40, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile("long", max_examples=3000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.load_profile(os.environ.get("OCTOREACH_FUZZ_PROFILE", "short"))


@pytest.fixture(scope="session")
def world():
    """One coarse instance of each map and scene class of the test arm, shared by the fuzz tests."""
    import octoreach as o

    robot = o.robots.test_arm()
    chain = robot.chain("base_link", "tool0")
    cap = o.CapabilityMap.build(chain, resolution=0.2, directions=16, progress=False, seed=1)
    surface = o.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    sm = o.SurfaceMap.build(robot, cap, surface, resolution=0.2, theta_bins=8, z_range=(0, 0), progress=False)
    pm = o.InversePointMap.build(robot, cap, theta_bins=8, progress=False)
    m = o.ExplorationMap(resolution=0.1)
    m.insert(np.random.default_rng(0).uniform([1, -0.5, 0], [1.6, 0.5, 0.6], (800, 3)), [0, 0, 0.3])
    scene = o.Scene()
    scene.add_box([1, -1, 0], [1.2, 1, 1])
    obs = o.Obstacles()
    obs.add_box([0.2, 0.2, 0.2], np.eye(4))
    return dict(robot=robot, chain=chain, cap=cap, surface=surface, sm=sm, pm=pm, m=m, scene=scene, obs=obs)
