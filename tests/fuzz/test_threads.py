"""Every mutable object hammered from several Python threads at once (in a child process: a data race
that crashes fails the test, not the run). The C++ side of the same contract: tests/cpp/test_threads.cpp."""
from __future__ import annotations

from robust_util import run_python


def test_mutable_objects_from_many_threads():
    child = run_python("""
        import threading, numpy as np, octoreach as o
        rng = np.random.default_rng(0)
        m = o.ExplorationMap(resolution=0.05)
        scene = o.Scene(); scene.add_box([1, -1, 0], [1.2, 1, 1])
        cam = o.DepthCamera(48, 36, 1.0, 4.0, 0.002, 3)
        robot = o.robots.test_arm()
        cap = o.CapabilityMap.build(robot.chain('base_link', 'tool0'), resolution=0.15, directions=24, progress=False)
        sm = o.SurfaceMap.build(robot, cap, o.Surface.rectangle(0.6, 0.4, 0.4, x=0.55), resolution=0.15,
                                z_range=(0, 0), progress=False)
        sampler = o.PoseSampler(sm, seed=2)
        stop = threading.Event()
        errors = []
        def guard(f):
            def run():
                try:
                    while not stop.is_set():
                        f()
                except Exception as e:
                    errors.append(repr(e))
            return run
        pts = rng.uniform([1, -1, 0], [2, 1, 1], (4000, 3))
        k = iter(range(10**9))
        jobs = [
            lambda: m.insert(pts + 0.001 * next(k), [0, 0, 0.5]),
            lambda: (m.snapshot(), m.cells('free'), m.frontier_voids(), m.void_clusters()),
            lambda: (m.inside_hull([1.5, 0, 0.5]), m.state(pts[:50]), m.occupancy_digest()),
            lambda: scene.add_box([1.5, -1, 0], [1.6, 1, 1]),
            lambda: cam.capture(scene, o._core.look_at([0, 0, 0.5], [1, 0, 0.5])),
            lambda: cam.capture(scene, o._core.look_at([0, 0, 0.5], [1, 0.3, 0.5])),
            lambda: sampler.sample(),
            lambda: (cap.reachability(rng.uniform(-1, 1, (100, 3))), sm.reachability(np.zeros((10, 4)))),
        ]
        threads = [threading.Thread(target=guard(j)) for j in jobs]
        for t in threads: t.start()
        import time; time.sleep(4.0)
        stop.set()
        for t in threads: t.join()
        assert not errors, errors[:5]
        s, r = m.snapshot(), m.recompute_from_scratch()
        assert np.array_equal(s['frontier_cells'], r['frontier_cells'])
        print('OK')
    """, timeout=300)
    assert child.returncode == 0 and "OK" in child.stdout, (child.returncode, child.stderr[-3000:])
