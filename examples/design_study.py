"""Design study: how much of a table can one robot reach, for a list of mounting heights of its base?

The kind of study a robot maker runs with REACH: one capability map of the arm, then one surface map of
the table per mounting height (the base's reference frame raised by h), built as tasks on a Ray cluster
(``octoreach build-many`` underneath), then the best reachable share of the table (max R_S over base
positions and headings) for each height, printed and plotted.

    python examples/design_study.py                               # PR2 right arm, Ray on this machine
    python examples/design_study.py --cluster HEAD:6379           # a real cluster (`ray start --head` there)
    python examples/design_study.py --robot test_arm --arm base_link tool0 --table 0.4 0.3 0.25 --cluster none

Writes <out>/share_vs_height.png and <out>/share_vs_height.json; the maps stay in <out>/maps (and in the map
cache, so a second run with more heights builds only the new ones).
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np


def study(robot: str, arm, heights, table, resolution: float, directions: int, cluster: str, out: Path,
          cache=True, progress=True) -> dict:
    """{height: best R_S} of the table for each mounting height, built on the cluster."""
    from octoreach import cluster as octo_cluster
    from octoreach._core import SurfaceMap

    sx, sy, top = table
    job = {"robots": [{"name": robot, "arms": [arm]}], "resolutions": [resolution],
           "capability": {"directions": directions},
           "surfaces": [{"name": "table", "rectangle": {"size": [sx, sy], "height": top}, "legs": 0.05}],
           "surface": {"theta_bins": 16}, "base_heights": list(heights)}
    report = octo_cluster.build_many(job, cluster=cluster, out=out / "maps", cache=cache, progress=progress)
    shares = {}
    for name, path in report.files.items():
        if "/table" not in name:  # the capability map
            continue
        smap = SurfaceMap.load(path)
        h = float(name.rsplit("@z", 1)[1]) if "@z" in name else 0.0
        shares[h] = float(smap.max_reachability)
    return dict(sorted(shares.items()))


def plot(shares: dict, path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.2), dpi=120)
    h = np.array(list(shares))
    ax.plot(h, [100 * v for v in shares.values()], "o-")
    ax.set_xlabel("mounting height of the base (m)")
    ax.set_ylabel("best reachable share of the table (%)")
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--robot", default="pr2", help="robot by name (example-robot-data, or test_arm)")
    p.add_argument("--arm", nargs="+", default=["right_arm"], help="arm name, or base and tip links")
    p.add_argument("--heights", type=float, nargs="+", default=[-0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.4],
                   help="mounting heights of the base's reference frame (m)")
    p.add_argument("--table", type=float, nargs=3, default=[1.4, 0.65, 0.72], metavar=("SX", "SY", "TOP"),
                   help="table size and top height (m)")
    p.add_argument("--resolution", type=float, default=0.1, help="map resolution (m)")
    p.add_argument("--directions", type=int, default=100, help="approach directions of the capability map")
    p.add_argument("--cluster", default="local", help="local (Ray on this machine), none (no Ray) or HOST:PORT")
    p.add_argument("--out", default="design_out", help="output folder")
    p.add_argument("--no-cache", action="store_true", help="do not use the map cache")
    args = p.parse_args(argv)
    arm = args.arm[0] if len(args.arm) == 1 else list(args.arm[:2])
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    shares = study(args.robot, arm, args.heights, args.table, args.resolution, args.directions, args.cluster, out,
                   cache=not args.no_cache)
    print("height (m)  best share of the table")
    for h, v in shares.items():
        print(f"{h:+9.2f}   {100 * v:5.1f} %")
    title = f"{args.robot} {' '.join(args.arm)}: {args.table[0]} x {args.table[1]} m table at {args.table[2]} m"
    plot(shares, out / "share_vs_height.png", title)
    (out / "share_vs_height.json").write_text(json.dumps({"robot": args.robot, "arm": args.arm, "table": args.table,
                                                          "shares": {str(h): v for h, v in shares.items()}}, indent=1))
    print(f"wrote {out / 'share_vs_height.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
