"""Exploration strategies on the scene families; prints JSON.

Frontier-void against random, most-frontier and most-unknown views (explore(strategy=...)) on every family
of octoreach.testing.scene_families (open crates, closed boxes, shelves, pipes, collapsed slabs, table tops,
rubble), --instances instances x --seeds exploration seeds each, with the same settings for every family:
the explorer (fixed base at the origin, its 0.1 m capability map), a 320 x 240 camera (58 degrees, depth
noise 2 mm at 1 m growing with depth^2), 2.5 cm cells, the families' start view, the loop's stop rule and
a --views budget.

The reference of every coverage figure is the instance's observable interior (observable_cells with the
safe-view clearance of the loop's camera, 5 cm: cells of the interiors that a collision-free reachable
camera pose keeping that distance from every surface sees), computed once per instance in the same run,
and whether such a pose sees the target (5 points of a 320 x 240 capture, as target_seen_view).

Per family and strategy, over instances x seeds: views to 90 % of the observable interior (median; a run
that never reaches it counts as never), the final share (median, min), both over the runs on instances with
an observable interior (a generated instance may have none: its opening faces away from every safe view), how
runs ended (stop reasons; "ends
by itself": any reason but the budget), the target seen in the runs where the oracle sees it, seen/expected
void ratios of the views (median, share under 0.1) and the loop's choice of a view in seconds (median,
90th percentile, max; CPU time on whatever machine ran it). `goals` checks the issue's goals.

Run: .venv/bin/python benchmarks/exploration_families.py [--families shelves pipes] [--instances 5]
     [--seeds 3] [--views 60] [--plot p.png] [--markdown t.md] > out.json
Quick: --instances 1 --seeds 1 --views 8 --image 160 120 --resolution 0.05 --oracle-samples 300
In parts: --families open_crates shelves > a.json; --families ... > b.json; then --combine a.json b.json
     --plot p.png --markdown t.md (the setups must agree but for the families and strategies)
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time

import numpy as np

from octoreach import DepthCamera
from octoreach import exploration as ex
from octoreach import testing
from octoreach.testing import scene_families

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exploration_strategies import _code_version, explorer_setup, write_record  # noqa: E402  (the sibling script: one definition)

LEVEL = 0.9  # the coverage the views are counted to


def _camera(a, seed) -> DepthCamera:
    return DepthCamera(a.image[0], a.image[1], np.deg2rad(58.0), 4.0, noise=a.noise, seed=seed)


def _run(a, inst, strategy, seed, oracle, cmap) -> dict:
    """One exploration; its coverage after every view (none when the instance has nothing observable: no
    curve in the plot, no coverage figure in the summary)."""
    cover = []
    r = ex.explore(inst.scene, _camera(a, seed), scene_families.start_pose(), robot=True, strategy=strategy,
                   max_views=a.views, resolution=a.resolution, seed=seed, capability_map=cmap, target=inst.target,
                   search_space=inst.search_space,
                   min_utility=a.min_utility, patience=a.patience, beyond_voids=bool(a.beyond_voids),
                   on_view=lambda row, emap, info: cover.append(oracle.share(emap)) if oracle.count else None)
    return {
        "instance": inst.seed, "seed": seed, "coverage": [round(c, 4) for c in cover], "views": len(r.rows),
        "stop_reason": r.stop_reason, "views_to_90": ex.views_to_reach(cover, LEVEL),
        "final_coverage": cover[-1] if cover else None, "target_seen_view": r.target_seen_view(),
        "choice_s": [round(x.search_s, 4) for x in r.rows],
        "ratios": [round(x, 3) for x in ex.seen_expected_ratios(r.rows)],
        "expected_seen": [[round(x.expected_void, 1), x.void_seen] for x in r.rows if x.void_seen is not None],
        "physically_invalid_views": sum(not x.physically_valid for x in r.rows),
        "beyond_views": sum(x.beyond for x in r.rows[:-1]),  # frontier-void's views beyond the voids taken
    }


def _pct(values, q):
    return float(np.percentile(values, q)) if len(values) else None


def _summary(runs, budget, oracle) -> dict:
    """The figures of one family and strategy over its runs (see the module). `oracle`: the family's oracle
    records by instance. The coverage figures (views to 90 %, final share) are of the runs on instances with
    an observable interior: 90 % of nothing is no figure (`runs_nothing_observable` counts the others)."""
    never = budget + 1
    covered = [r for r in runs if oracle[r["instance"]]["observable_points"] > 0]
    v90 = [r["views_to_90"] if r["views_to_90"] is not None else never for r in covered]
    ratios = [x for r in runs for x in r["ratios"]]
    choice = [x for r in runs for x in r["choice_s"]]
    can = [r for r in runs if oracle[r["instance"]]["target_observable"]]
    reasons = sorted({r["stop_reason"] for r in runs})
    med = statistics.median(v90) if v90 else never
    finals = [r["final_coverage"] for r in covered]
    return {
        "runs": len(runs), "runs_nothing_observable": len(runs) - len(covered),
        "reached_90": sum(r["views_to_90"] is not None for r in covered),
        "views_to_90_median": None if med >= never else med,
        "final_median": statistics.median(finals) if finals else None,
        "final_min": min(finals, default=None),
        "runs_under_90": sum(x < LEVEL for x in finals),
        "views_median": statistics.median(r["views"] for r in runs),
        "stop_reasons": {k: sum(r["stop_reason"] == k for r in runs) for k in reasons},
        "ended_by_itself": sum(r["stop_reason"] != "view budget" for r in runs),
        "target_runs_observable": len(can),
        "target_seen_where_observable": sum(r["target_seen_view"] is not None for r in can),
        "ratio_median": statistics.median(ratios) if ratios else None,
        "ratio_share_below_0.1": (sum(x < 0.1 for x in ratios) / len(ratios)) if ratios else None,
        "ratio_views": len(ratios),
        "choice_s_median": _pct(choice, 50), "choice_s_p90": _pct(choice, 90), "choice_s_max": max(choice, default=None),
        "physically_invalid_views": sum(r["physically_invalid_views"] for r in runs),
    }


def _goals(summary, runs, strategies) -> dict:
    """The issue's goals on the measured figures: per family and pooled over every family."""
    ours, base = "frontier_void", [s for s in strategies if s != "frontier_void"]
    if ours not in strategies:
        return {}
    out, fv_runs = {"per_family": {}}, []
    for fam, per in summary.items():
        s = per[ours]
        v = s["views_to_90_median"]
        best = [per[b]["views_to_90_median"] for b in base if per[b]["views_to_90_median"] is not None]
        out["per_family"][fam] = {
            "fewer_views_to_90_than_best_baseline": v is not None and (not best or v < min(best)),
            "best_baseline_views_to_90": min(best) if best else None,
            "final_median_at_least_90": s["final_median"] is not None and s["final_median"] >= LEVEL,
            "target_seen_wherever_observable": s["target_seen_where_observable"] == s["target_runs_observable"],
        }
        fv_runs += runs[fam][ours]
    ratios = [x for r in fv_runs for x in r["ratios"]]
    choice = [x for r in fv_runs for x in r["choice_s"]]
    ended = sum(r["stop_reason"] != "view budget" for r in fv_runs)
    out["pooled"] = {
        "ended_by_itself_share": ended / len(fv_runs) if fv_runs else None,
        "ratio_median": statistics.median(ratios) if ratios else None,
        "ratio_share_below_0.1": (sum(x < 0.1 for x in ratios) / len(ratios)) if ratios else None,
        "choice_s_median": _pct(choice, 50), "choice_s_p90": _pct(choice, 90), "choice_s_max": max(choice, default=None),
    }
    return out


def _markdown(summary, strategies) -> str:
    head = ("| family | strategy | views to 90 % (median; reached) | final share (median, min) | ends by itself "
            "(stop reasons) | target seen (where observable) | seen/expected median (< 0.1) | choice s median / p90 / max |")
    lines = [head, "|" + "---|" * 8]
    for fam, per in summary.items():
        for s in strategies:
            x = per[s]
            v90 = "never" if x["views_to_90_median"] is None else f"{x['views_to_90_median']:g}"
            stops = ", ".join(f"{k} x{n}" for k, n in x["stop_reasons"].items())
            ratio = "-" if x["ratio_median"] is None else f"{x['ratio_median']:.2f} ({x['ratio_share_below_0.1']:.0%})"
            final = "-" if x["final_median"] is None else f"{x['final_median']:.0%}, {x['final_min']:.0%}"
            lines.append(
                f"| {fam} | {s} | {v90} ({x['reached_90']}/{x['runs'] - x['runs_nothing_observable']}) | {final} | "
                f"{x['ended_by_itself']}/{x['runs']} ({stops}) | {x['target_seen_where_observable']}/"
                f"{x['target_runs_observable']} | {ratio} | {x['choice_s_median']:.2f} / {x['choice_s_p90']:.2f} / "
                f"{x['choice_s_max']:.2f} |")
    return "\n".join(lines)


def _finish(out, a) -> int:
    out["goals"] = _goals(out["summary"], out["runs"], out["setup"]["strategies"])
    return write_record(out, a, _markdown)


def _combine(a) -> int:
    """One record from parts with other families (and strategies): the setups must agree but for those."""
    parts = [json.load(open(f)) for f in a.combine]
    ignore = {"families", "strategies", "capability_map_s"}
    for f, p in zip(a.combine[1:], parts[1:]):
        diff = sorted(k for k in set(p["setup"]) | set(parts[0]["setup"])
                      if k not in ignore and p["setup"].get(k) != parts[0]["setup"].get(k))
        if diff:
            raise SystemExit(f"--combine: {f} has another setup than {a.combine[0]} ({', '.join(diff)})")
    out = {"setup": dict(parts[0]["setup"]), "oracle": {}, "summary": {}, "runs": {}, "combined_from": a.combine}
    for p in parts:
        for k in ("oracle", "runs"):
            for fam, v in p[k].items():
                out[k].setdefault(fam, {}).update(v)
    names = {s for p in parts for s in p["setup"]["strategies"]}
    out["setup"]["strategies"] = [s for s in ex.STRATEGIES if s in names]
    out["setup"]["families"] = [f for f in testing.FAMILIES if f in out["runs"]]
    for fam in out["setup"]["families"]:
        oracle = {int(k): v for k, v in out["oracle"][fam].items()}
        out["summary"][fam] = {s: _summary(out["runs"][fam][s], out["setup"]["views"], oracle)
                               for s in out["setup"]["strategies"] if s in out["runs"][fam]}
    out["total_s"] = sum(p["total_s"] for p in parts)
    return _finish(out, a)


def _parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--families", nargs="+", default=list(testing.FAMILIES), choices=testing.FAMILIES)
    ap.add_argument("--instances", type=int, default=5, help="instances per family (family seeds)")
    ap.add_argument("--first-instance", type=int, default=0)
    ap.add_argument("--seeds", type=int, default=3, help="exploration seeds per instance and strategy")
    ap.add_argument("--views", type=int, default=60, help="view budget (large: the stop rule should end the runs)")
    ap.add_argument("--min-utility", type=float, default=ex.STOP_UTILITY)
    ap.add_argument("--patience", type=int, default=ex.STOP_PATIENCE)
    ap.add_argument("--beyond-voids", type=int, choices=(0, 1), default=int(ex.BEYOND_VOIDS),
                    help="frontier_void: views beyond the voids (ExploreOptions.beyond_voids)")
    ap.add_argument("--resolution", type=float, default=0.025)
    ap.add_argument("--image", type=int, nargs=2, default=(320, 240), metavar=("W", "H"))
    ap.add_argument("--noise", type=float, default=0.002, help="depth noise at 1 m (grows with depth^2)")
    ap.add_argument("--clearance", type=float, default=0.05, help="the oracle's safe-view clearance (m)")
    ap.add_argument("--strategies", nargs="+", default=list(ex.STRATEGIES))
    ap.add_argument("--oracle-samples", type=int, default=2000, help="joint and aimed samples of the oracle, each")
    ap.add_argument("--plot", default=None, help="PNG of coverage against views (one panel per family)")
    ap.add_argument("--markdown", default=None, help="write the table (families x strategies) here")
    ap.add_argument("--combine", nargs="+", default=None, metavar="JSON", help="combine earlier outputs, no runs")
    return ap, ap.parse_args(argv)


def main(argv=None) -> int:
    ap, a = _parse(argv)
    if a.combine:
        return _combine(a)
    if min(a.instances, a.seeds, a.views) < 1 or a.first_instance < 0:
        ap.error("--instances, --seeds and --views must be >= 1, --first-instance >= 0")
    t_all = time.perf_counter()
    chain, cmap, cmap_s = explorer_setup(a.strategies)
    setup = {k: getattr(a, k) for k in ("instances", "first_instance", "seeds", "views", "min_utility", "patience",
                                        "beyond_voids", "resolution", "noise", "clearance", "oracle_samples",
                                        "families", "strategies")}
    setup.update(image=list(a.image), capability_map_s=cmap_s, code=_code_version())
    out = {"setup": setup, "oracle": {}, "summary": {}, "runs": {}}
    for fam in a.families:
        out["oracle"][fam], out["runs"][fam] = {}, {s: [] for s in a.strategies}
        for inst in testing.family_instances(fam, a.instances, a.first_instance):
            t0 = time.perf_counter()
            oracle = testing.observable_cells(inst.scene, resolution=a.resolution, joint_samples=a.oracle_samples,
                                              aimed_samples=a.oracle_samples, clearance=a.clearance)
            seen = oracle.sees_target(inst.scene, inst.target, *a.image)
            out["oracle"][fam][inst.seed] = {"seconds": time.perf_counter() - t0, "poses_valid": oracle.poses_valid,
                                             "interior_points": len(oracle.points), "observable_points": oracle.count,
                                             "observable_fraction": oracle.fraction, "target_observable": seen}
            for s in a.strategies:
                for seed in range(a.seeds):
                    out["runs"][fam][s].append(_run(a, inst, s, seed, oracle, cmap))
                    r = out["runs"][fam][s][-1]
                    share = "nothing observable" if r["final_coverage"] is None else f"{r['final_coverage']:.3f}"
                    print(f"# {inst.name} {s} seed {seed}: {r['views']} views, {share}, "
                          f"{r['stop_reason']}, 90 % after {r['views_to_90']}", file=sys.stderr, flush=True)
        out["summary"][fam] = {s: _summary(out["runs"][fam][s], a.views, out["oracle"][fam]) for s in a.strategies}
    out["total_s"] = time.perf_counter() - t_all
    return _finish(out, a)


if __name__ == "__main__":
    raise SystemExit(main())
