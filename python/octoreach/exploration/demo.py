"""The exploration demo: one exploration of a paper scene with the explorer robot, its table, a picture
per view and the final map; ``python -m octoreach.exploration`` runs main()."""
from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from .._core import DepthCamera
from ._options import given
from .camera import look_at
from .loop import VIEW_BUDGET, explore
from .plots import plot_map
from .robot import arm_base_pose, base_ring, explorer_capability_map, explorer_robot
from .scenes import paper_scene, scene_region
from .strategies import STRATEGIES

DEMO_SCENE = 2
DEMO_OUT = "exploration_out"
# Exactly 58 degrees (a Kinect): DepthCamera's default fov is the rounded 1.0123, which would change the images.
DEMO_FOV = np.deg2rad(58.0)


def _printer(out: Path, scene_id: int, plots: bool, quiet: bool, camera, region):
    """on_view for explore(): a progress line and a picture per view (with the chosen view's frustum)."""
    poses_so_far = []

    def on_view(row, emap, info):
        poses_so_far.append(np.array(row.pose))
        if not quiet:
            print(f"view {row.view}: integration {row.integration_s:.3f} s, search {row.search_s:.3f} s, "
                  f"next view expects {row.expected_void:.0f} void cells ({row.utility_dm3:.2f} dm^3), "
                  f"observed {row.observed_share:.1%}, interiors {row.interior_share:.1%}", flush=True)
        if plots:
            plot_map(emap, out / f"view_{row.view:02d}.png", poses=poses_so_far, next_pose=info["best_pose"],
                     camera=camera, region=region,
                     title=f"scene {scene_id}, after view {row.view}: {row.void_total} void cells, "
                           f"interiors {row.interior_share:.0%}")

    return on_view


def _write_outputs(result, out: Path, scene_id: int, export: bool) -> None:
    (out / "table.txt").write_text(result.table() + "\n")
    (out / "table.json").write_text(json.dumps({"scene": scene_id, "resolution": result.map.resolution,
                                                "strategy": result.strategy, "stop_reason": result.stop_reason,
                                                "total_s": result.total_s, "rows": result.to_dicts()},
                                               indent=1, default=_plain))
    if export:
        result.map.write_bt(str(out / "map.bt"))  # OctoMap prints a progress line to stdout


def _plain(x):
    """numpy scalars and arrays for json."""
    return x.tolist() if hasattr(x, "tolist") else str(x)


def run_demo(scene_id: int = DEMO_SCENE, out=DEMO_OUT, max_views: int = VIEW_BUDGET, resolution=None,
             width=None, height=None, seed: int = 0, plots: bool = True, quiet: bool = False,
             export: bool = True, capability_map="auto", move_base: bool = False, strategy: str = "frontier_void",
             min_utility=None):
    """One exploration of a paper scene with the explorer robot; writes table.txt, table.json,
    view_NN.png and map.bt into `out`. `resolution` (map cell edge) and `width`, `height` (image
    size): None keeps the ExplorationMap and DepthCamera defaults. `capability_map`: a CapabilityMap
    of the arm, "auto" (build a coarse one) or None (IK only). `move_base`: the base may also drive
    to the four poses of base_ring(scene_region(scene)) between views. `strategy`, `min_utility`: as
    explore() (None: ExploreOptions' default). Returns the ExplorationResult."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    scene = paper_scene(scene_id)
    camera = DepthCamera(fov=DEMO_FOV, seed=seed, **given(width=width, height=height))
    robot, chain = explorer_robot()
    base_link = arm_base_pose(robot, chain)
    start = look_at((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))
    if isinstance(capability_map, str) and capability_map == "auto":
        capability_map = explorer_capability_map(chain, seed=seed)
    moves = [F @ base_link for F in base_ring(scene_region(scene))] if move_base else None
    result = explore(scene, camera, start, robot=robot, chain=chain, base_pose=base_link, max_views=max_views,
                     resolution=resolution, seed=seed, capability_map=capability_map, base_moves=moves,
                     strategy=strategy, min_utility=min_utility,
                     on_view=_printer(out, scene_id, plots, quiet, camera, scene_region(scene)))
    _write_outputs(result, out, scene_id, export)
    if not quiet:
        print(result.table())
        print(f"whole exploration {result.total_s:.1f} s; wrote {out}/table.txt, table.json, "
              f"view_*.png, map.bt (open with octovis)")
    return result


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m octoreach.exploration",
                                 description="Frontier-void exploration demo (Dornhege & Kleiner)")
    ap.add_argument("--scene", type=int, default=DEMO_SCENE, choices=(1, 2), help="paper experiment 1 or 2")
    ap.add_argument("--out", default=DEMO_OUT, help="output folder")
    ap.add_argument("--views", type=int, default=VIEW_BUDGET, help="view budget")
    ap.add_argument("--resolution", type=float, help="map cell edge in metres (default: ExplorationMap's)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--no-capability-map", action="store_true", help="prune view cells by IK only")
    ap.add_argument("--move-base", action="store_true", help="let the base drive to 4 poses around the scene")
    ap.add_argument("--strategy", default="frontier_void", choices=STRATEGIES, help="how views are chosen")
    ap.add_argument("--min-utility", type=float, default=None,
                    help="stop when the best view's gain is at or below this (default: ExploreOptions().min_utility)")
    a = ap.parse_args(argv)
    run_demo(a.scene, a.out, a.views, a.resolution, seed=a.seed, plots=not a.no_plots,
             capability_map=None if a.no_capability_map else "auto", move_base=a.move_base, strategy=a.strategy,
             min_utility=a.min_utility)
    return 0
