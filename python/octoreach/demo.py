"""The octoreach demo (`make demo`): where should the PR2 stand to work at a table?

1. loads the PR2 (example-robot-data) and solves IK for a few poses of each arm;
2. builds coarse capability maps of both arms and their surface maps for the paper's
   1.4 x 0.65 m table (0.72 m high), combined for "either arm" and "both arms";
3. samples a handful of well spread base poses and checks them (condition attachment);
4. writes plots (PNG) and octovis files to the output folder.

    python -m octoreach.demo [--out demo_out] [--resolution 0.1] [--directions 100]
"""
from __future__ import annotations

import argparse
import os
import time

import numpy as np

from . import arms, plots, robots
from ._core import PoseSampler, Surface, SurfaceMap


def _ik_check(robot) -> None:
    for name in ("left_arm", "right_arm"):
        base, tip, axis = arms.resolve(robot, name)
        chain = robot.chain(base, tip)
        Q = chain.random_configurations(20, seed=1)
        t = time.perf_counter()
        _, ok = chain.ik_batch(chain.fk_batch(Q), rng_seed=1)
        dt = (time.perf_counter() - t) / len(Q) * 1e3
        print(f"  {name}: {chain!r}, IK solved {ok.sum()}/{len(Q)} random poses, {dt:.2f} ms each")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="demo_out", help="output folder for plots and map files (default demo_out)")
    p.add_argument("--resolution", type=float, default=0.1, help="map resolution in m (default 0.1)")
    p.add_argument("--directions", type=int, default=100, help="approach directions (default 100)")
    p.add_argument("--samples", type=int, default=5, help="base poses to sample (default 5)")
    args = p.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    t0 = time.perf_counter()

    robot = robots.pr2()
    print(f"{robot!r}: {len(robot.collision_links)} links with collision geometry, "
          f"{robot.checked_pairs} link pairs checked for self-collision")
    _ik_check(robot)

    table = Surface.rectangle(1.4, 0.65, 0.72)  # the paper's table, centred at the origin
    table.add_legs()
    print(f"table: 1.4 x 0.65 m at 0.72 m, {len(table.points(args.resolution))} surface points at "
          f"{args.resolution} m")
    maps = {}
    for name in ("right_arm", "left_arm"):
        cap = arms.capability_map(robot, name, resolution=args.resolution, directions=args.directions)
        print(f"  {cap!r} in {cap.stats['seconds']:.1f} s")
        sm = SurfaceMap.build(robot, cap, table, resolution=args.resolution, z_range=(0.0, 0.0),
                              reference=arms.default_reference(robot, name))
        maps[name] = sm
        st = sm.stats
        print(f"  {name} surface map: {sm.voxel_count} voxels, best R_S {sm.max_reachability:.2f}, "
              f"{st['candidate_poses']} candidate poses, {st['valid_poses']} valid, {st['seconds']:.1f} s")
        if name == "right_arm":
            plots.capability_slices(cap, plots.default_heights(cap, 4), os.path.join(args.out, "capability_right_arm.png"))
            cap.export_octovis(os.path.join(args.out, "capability_right_arm.ot"))
    either = SurfaceMap.combine([maps["right_arm"], maps["left_arm"]], "max")
    both = SurfaceMap.combine([maps["right_arm"], maps["left_arm"]], "min")
    print(f"either arm: best R_S {either.max_reachability:.2f}; both arms: best R_S {both.max_reachability:.2f}")
    either.save(os.path.join(args.out, "table_either_arm.orsm"))
    either.export_octovis(os.path.join(args.out, "table_either_arm.ot"))

    world = table.obstacles()
    sampler = PoseSampler(either, seed=1, in_collision=(robot, world, arms.default_reference(robot, "right_arm")))
    poses = sampler.sample(args.samples)
    rs = either.reachability(poses)
    print(f"{args.samples} sampled base poses (x, y, z, theta) of base_footprint, with R_S:")
    for pose, r in zip(poses, rs):
        print(f"  x={pose[0]:+.2f} y={pose[1]:+.2f} z={pose[2]:.2f} theta={np.degrees(pose[3]):+7.1f} deg  "
              f"R_S={r:.2f}")
    written = [
        plots.surface_slices(either, os.path.join(args.out, "surface_map_either_arm.png")),
        plots.sample_comparison(either, os.path.join(args.out, "samples_discount.png"), count=500, seed=2),
        os.path.join(args.out, "capability_right_arm.png"),
    ]
    print("wrote " + ", ".join(written) + f" and .ot files for octovis in {args.out}/")
    print(f"demo done in {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
