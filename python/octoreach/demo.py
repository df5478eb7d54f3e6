"""The octoreach demo (`make demo`): loads the PR2, lists its arms, solves IK for a few poses."""
from __future__ import annotations

import time

import numpy as np

from . import robots


def main() -> int:
    t0 = time.perf_counter()
    robot = robots.pr2()
    print(f"{robot!r} loaded in {time.perf_counter() - t0:.2f} s "
          f"({len(robot.collision_links)} links with collision geometry, {robot.checked_pairs} pairs checked)")
    print(f"mimic joints (left out of chains): {', '.join(robot.mimic_joints) or 'none'}")
    arms = {name: g for name, g in robot.groups.items() if name in ("left_arm", "right_arm")}
    for name, (base, tip) in sorted(arms.items()):
        chain = robot.chain("base_footprint", tip)
        print(f"arm {name}: {chain!r}\n  joints: {', '.join(chain.joint_names)}")
        rng = np.random.default_rng(1)
        solved = 0
        for i in range(5):
            q = np.array([rng.uniform(lo if np.isfinite(lo) else -np.pi, hi if np.isfinite(hi) else np.pi)
                          for lo, hi in zip(chain.lower, chain.upper)])
            target = chain.fk(q)
            t = time.perf_counter()
            sol = chain.ik(target, rng_seed=i, self_collision=True)
            dt = (time.perf_counter() - t) * 1e3
            if sol is None:
                print(f"  pose {i}: x={target[:3, 3].round(3)} no collision-free solution ({dt:.1f} ms)")
                continue
            solved += 1
            err = np.linalg.norm(chain.fk(sol)[:3, 3] - target[:3, 3])
            print(f"  pose {i}: x={target[:3, 3].round(3)} solved in {dt:.1f} ms, position error {err:.1e} m")
        print(f"  {solved}/5 poses solved")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
