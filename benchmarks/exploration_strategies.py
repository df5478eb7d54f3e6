"""Exploration strategies against each other; prints JSON.

Strategies (octoreach.exploration.STRATEGIES): frontier_void (ours, next_best_view), random
reachable views, most frontier cells in view, most unknown cells in view (nbvplanner's gain). Same
robot (the explorer, fixed base, its coarse capability map), camera (58 degrees, noise growing with
depth^2, its missing returns), start view, reach checks, safe-view rule, view budget and stopping
rule (explore(strategy=...)). Scenes: the paper's two and seeded USAR-like scenes (usar_scene(k):
crates and closed boxes with openings on different faces, debris, a hidden target).

The reference of every coverage figure is the observable interior (observable_cells: cells of the
box interiors that some collision-free reachable camera pose sees, by brute force), computed once
per scene in the same run. A view whose arm touches the true scene is not taken (it counts as a
view and adds nothing: only physically valid views count).

Per strategy and scene, over the seeds: views to reach 90 % of the observable interior (runs that
never reach it count as budget + 1 in `views_to_90_mean_censored`; `reached_90` says how many did),
coverage after 5 and 10 views, target seen (share of runs) and after how many views, time per view,
and the seen/expected void ratio of every view (median, share of views under 0.1). `goals` checks
the issue's goals on these figures.

Every strategy stops by the same stated rule: its chosen view's utility at or below --min-utility
(exploration.STOP_UTILITY) for --patience (STOP_PATIENCE) views in a row, or utility 0, or no valid
view; the budget (--views, 70: paper scene 2 takes 49-58 views) is large so that the rule, not the
budget, ends the runs.

Run: .venv/bin/python benchmarks/exploration_strategies.py [--seeds 10] [--generated 4] [--views 70]
     [--plot docs/images/exploration_strategies.png] [--markdown table.md]
Quick: --seeds 2 --generated 2 --views 8 --image 160 120 --resolution 0.05
In parts (two cores): --scenes paper_1 usar_0 > a.json; --scenes paper_2 usar_1 > b.json; then
     --combine a.json b.json --plot p.png --markdown t.md (parts may also split the seeds:
     --seeds 5 > a.json; --seeds 5 --first-seed 5 > b.json; the same code and settings, checked)
"""
from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

import octoreach
from octoreach import DepthCamera
from octoreach import exploration as ex
from octoreach import testing

START = ((0.45, 0.0, 1.1), (0.9, 0.0, 0.0))  # eye, target of the first view (robot at the origin)


def _scenes(generated: int):
    out = [("paper_1", ex.paper_scene(1), None), ("paper_2", ex.paper_scene(2), None)]
    for k in range(generated):
        u = testing.usar_scene(k)
        out.append((f"usar_{k}", u.scene, u.target))
    return out


def _camera(a, seed):
    extra = {} if a.max_incidence is None else {"max_incidence": np.deg2rad(a.max_incidence)}
    return DepthCamera(a.image[0], a.image[1], np.deg2rad(58.0), 4.0, noise=a.noise, seed=seed, **extra)


def explorer_setup(strategies):
    """Checks the strategy names, then makes the explorer robot's camera chain and its capability map: (chain,
    map, seconds the map took)."""
    for s in strategies:
        ex.strategies.check_strategy(s)
    _, chain = ex.explorer_robot()
    t0 = time.perf_counter()
    return chain, ex.explorer_capability_map(chain), time.perf_counter() - t0


def _code_version() -> str:
    """The commit of this checkout (+ "-dirty" with local changes), else the package version: parts of
    a record must come from the same code."""
    import os
    import subprocess
    try:
        return subprocess.run(["git", "describe", "--always", "--dirty"], cwd=os.path.dirname(os.path.abspath(__file__)),
                              capture_output=True, text=True, timeout=10, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return getattr(octoreach, "__version__", "unknown")


def _run(a, scene, target, strategy, seed, oracle, cmap, chain):
    cover = []

    def on_view(row, emap, info):
        cover.append(oracle.share(emap))

    r = ex.explore(scene, _camera(a, seed), ex.look_at(*START), robot=True, strategy=strategy, max_views=a.views,
                   resolution=a.resolution, seed=seed, capability_map=cmap, target=target, min_utility=a.min_utility,
                   patience=a.patience, enclosure_power=a.enclosure_power, unexposed_weight=a.unexposed_weight,
                   second_look=not a.no_second_look, beyond_voids=bool(a.beyond_voids),
                   ground_is_obstacle=bool(a.ground_is_obstacle),
                   score_size=tuple(a.score) if a.score else None, on_view=on_view)
    views = len(r.rows)
    per_view = [x.integration_s + x.search_s for x in r.rows]
    return {
        "seed": seed,
        "coverage": [round(c, 4) for c in cover],
        "views": views,
        "stop_reason": r.stop_reason,
        "views_to_90": ex.views_to_reach(cover, 0.9),
        "coverage_5": ex.coverage_after(cover, 5),
        "coverage_10": ex.coverage_after(cover, 10),
        "final_coverage": cover[-1] if cover else 0.0,
        "interior_share_raw": r.interior_share,
        "target_seen_view": r.target_seen_view() if target is not None else None,
        "time_per_view_s": statistics.mean(per_view) if per_view else 0.0,
        "search_s": [round(x.search_s, 3) for x in r.rows],
        "ratios": [round(x, 3) for x in ex.seen_expected_ratios(r.rows)],
        "expected_seen": [[round(x.expected_void, 1), x.void_seen] for x in r.rows if x.void_seen is not None],
        "physically_invalid_views": sum(not x.physically_valid for x in r.rows),
        "seen_unobservable": oracle.seen_unobservable(r.map),
    }


def _summary(runs, views_budget, has_target):
    v90 = [r["views_to_90"] for r in runs]
    ratios = [x for r in runs for x in r["ratios"]]
    seen = [r["target_seen_view"] for r in runs if r["target_seen_view"] is not None]
    s = {
        "runs": len(runs),
        "reached_90": sum(v is not None for v in v90),
        "views_to_90_mean_censored": statistics.mean([v if v is not None else views_budget + 1 for v in v90]),
        "coverage_5_mean": statistics.mean(r["coverage_5"] for r in runs),
        "coverage_10_mean": statistics.mean(r["coverage_10"] for r in runs),
        "final_coverage_mean": statistics.mean(r["final_coverage"] for r in runs),
        "views_mean": statistics.mean(r["views"] for r in runs),
        "stop_reasons": {k: sum(r["stop_reason"] == k for r in runs) for k in {r["stop_reason"] for r in runs}},
        "time_per_view_s_median": statistics.median(r["time_per_view_s"] for r in runs),
        "ratio_median": statistics.median(ratios) if ratios else None,
        "ratio_share_below_0.1": (sum(x < 0.1 for x in ratios) / len(ratios)) if ratios else None,
        "ratio_views": len(ratios),
        "physically_invalid_views": sum(r["physically_invalid_views"] for r in runs),
        "seen_unobservable_max": max(r["seen_unobservable"] for r in runs),
    }
    if has_target:
        s["target_seen_share"] = len(seen) / len(runs)
        s["target_seen_after_views_mean"] = statistics.mean(seen) if seen else None
    return s


def _goals(summary, strategies):
    """The issue's goals on the measured figures (True / False / None when not measurable here)."""
    ours, base = "frontier_void", [s for s in strategies if s != "frontier_void"]
    out = {}
    if ours not in strategies or not base:
        return out
    gen = [k for k in summary if k.startswith("usar_")]
    if gen:
        mean = {s: statistics.mean(summary[k][s]["views_to_90_mean_censored"] for k in gen) for s in strategies}
        best = min(mean[s] for s in base)
        out["generated_views_to_90_mean"] = mean
        out["generated_25pct_fewer_views_than_best_baseline"] = bool(mean[ours] <= 0.75 * best)
    for k in ("paper_1", "paper_2"):
        if k in summary:
            for n in (5, 10):
                key = f"coverage_{n}_mean"
                out[f"{k}_beats_every_baseline_after_{n}"] = all(
                    summary[k][ours][key] > summary[k][s][key] for s in base)
    for k, need in (("paper_1", 0.95), ("paper_2", 0.90)):
        if k in summary:
            s = summary[k][ours]
            out[f"{k}_ends_by_itself_with_{int(need * 100)}pct"] = bool(
                s["final_coverage_mean"] >= need and s["stop_reasons"].get("view budget", 0) == 0)
    ratios_all = [summary[k][s]["ratio_median"] for k in summary for s in strategies
                  if summary[k][s]["ratio_median"] is not None]
    out["ratio_median_of_medians_all_strategies"] = statistics.median(ratios_all) if ratios_all else None
    return out


def _markdown(summary, strategies):
    head = "| scene | strategy | views to 90 % (reached) | coverage 5 / 10 views | final (views, stop) | target seen (after) | s/view | seen/expected median (<0.1) |"
    lines = [head, "|" + "---|" * 8]
    for k, per in summary.items():
        for s in strategies:
            x = per[s]
            tgt = "-" if "target_seen_share" not in x else (
                f"{x['target_seen_share']:.0%} ({x['target_seen_after_views_mean']:.1f})"
                if x["target_seen_after_views_mean"] is not None else f"{x['target_seen_share']:.0%}")
            stops = ", ".join(f"{r} x{n}" for r, n in sorted(x["stop_reasons"].items()))
            ratio = "-" if x["ratio_median"] is None else f"{x['ratio_median']:.2f} ({x['ratio_share_below_0.1']:.0%})"
            lines.append(f"| {k} | {s} | {x['views_to_90_mean_censored']:.1f} ({x['reached_90']}/{x['runs']}) | "
                         f"{x['coverage_5_mean']:.0%} / {x['coverage_10_mean']:.0%} | "
                         f"{x['final_coverage_mean']:.0%} ({x['views_mean']:.1f}, {stops}) | {tgt} | "
                         f"{x['time_per_view_s_median']:.2f} | {ratio} |")
    return "\n".join(lines)


# Settings that only frontier_void reads: a baselines file may differ in them (and in its code).
FRONTIER_VOID_ONLY = {"enclosure_power", "unexposed_weight", "second_look", "beyond_voids"}


def _same_run(new_cov, old_run, lower_threshold: bool) -> bool:
    """A baseline run measured again is the earlier one: the same coverage curve, or, under a lower stopping
    threshold, the earlier curve followed by more views when the earlier run stopped by the rule."""
    old_cov = old_run["coverage"]
    if not lower_threshold or old_run["stop_reason"] == "view budget":
        return new_cov == old_cov
    return new_cov[:len(old_cov)] == old_cov


def _baselines_part(path, parts):
    """The baseline runs (every strategy but frontier_void) of an earlier record `path` that the new parts do
    not measure, for a record whose change did not touch the baselines' code path. Its setup must agree but
    for the code and frontier_void's own settings; a lower stopping threshold (min_utility) is allowed when
    every borrowed run ended at the view budget (the rule never stopped it, so a lower threshold would not
    either). Every baseline run the new parts measured again (same scene, strategy and seed) must have the
    very same coverage curve, or under a lower threshold the earlier curve and then more views (checked,
    counted in baselines_from["checked_runs"])."""
    old = json.load(open(path))
    ignore = {"scenes", "strategies", "seeds", "first_seed", "capability_map_s", "note", "code"} | FRONTIER_VOID_ONLY
    new = parts[0]["setup"]
    lower = new.get("min_utility", 0) < old["setup"].get("min_utility", 0)
    if lower:
        ignore.add("min_utility")
    diff = sorted(k for k in set(old["setup"]) | set(new) if k not in ignore and old["setup"].get(k) != new.get(k))
    if diff:
        raise SystemExit(f"--baselines-from: {path} has another setup ({', '.join(diff)})")
    checked = 0
    measured = set()
    for p in parts:
        for scene, per in p["runs"].items():
            for strategy, runs in per.items():
                if strategy == "frontier_void":
                    continue
                earlier = {r["seed"]: r for r in old["runs"].get(scene, {}).get(strategy, [])}
                for r in runs:
                    measured.add((scene, strategy, r["seed"]))
                    if r["seed"] in earlier:
                        if not _same_run(r["coverage"], earlier[r["seed"]], lower):
                            raise SystemExit(f"--baselines-from: {strategy} on {scene} seed {r['seed']} differs from "
                                             f"{path}: the baselines' code path changed, measure them again")
                        checked += 1
    runs = {}
    for scene, per in old["runs"].items():
        for strategy, rs in per.items():
            if strategy == "frontier_void":
                continue
            borrowed = [r for r in rs if (scene, strategy, r["seed"]) not in measured]
            if lower and any(r["stop_reason"] != "view budget" for r in borrowed):
                raise SystemExit(f"--baselines-from: {strategy} on {scene} has runs that the earlier threshold "
                                 f"stopped; with a lower min_utility they must be measured again")
            if borrowed:
                runs.setdefault(scene, {})[strategy] = borrowed
    return {"setup": old["setup"], "oracle": old["oracle"], "runs": runs, "total_s": 0.0,
            "baselines_from": {"file": path, "code": old["setup"].get("code"), "checked_runs": checked,
                               "min_utility": old["setup"].get("min_utility")}}


def write_record(out, a, markdown) -> int:
    """The end of a record run (also the families benchmark's): the coverage plot (--plot), the table
    (--markdown, markdown(summary, strategies)) and the JSON on stdout."""
    strategies = out["setup"]["strategies"]
    if a.plot:
        ex.plot_coverage({k: {s: [r["coverage"] for r in runs] for s, runs in per.items()}
                          for k, per in out["runs"].items()}, a.plot)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(markdown(out["summary"], strategies) + "\n")
    print(json.dumps(out, indent=1, default=float))
    return 0


def _combine(a) -> int:
    """One output from several: their scenes and strategies side by side, and the runs of one (scene,
    strategy) from parts with other seeds (--first-seed) pooled, by seed (a later file's run of a seed
    replaces an earlier one's); summaries recomputed. The setups must agree but for the scenes,
    strategies and seeds (checked: a mix of code or settings is no record)."""
    parts = [json.load(open(f)) for f in a.combine]
    for p in parts:
        p["setup"].setdefault("beyond_voids", False)  # records from before the flag ran without the option
    ignore = {"scenes", "strategies", "seeds", "first_seed", "capability_map_s", "note"}
    for f, p in zip(a.combine[1:], parts[1:]):
        diff = sorted(k for k in set(p["setup"]) | set(parts[0]["setup"])
                      if k not in ignore and p["setup"].get(k) != parts[0]["setup"].get(k))
        if diff:
            raise SystemExit(f"--combine: {f} has another setup than {a.combine[0]} ({', '.join(diff)})")
    out = {"setup": dict(parts[0]["setup"]), "oracle": {}, "summary": {}, "runs": {}, "combined_from": a.combine}
    by_seed = {}
    if a.baselines_from:
        parts = [_baselines_part(a.baselines_from, parts)] + parts
        out["setup"]["baselines_from"] = parts[0]["baselines_from"]
    for p in parts:
        out["oracle"].update(p["oracle"])
        for scene, per in p["runs"].items():
            for strategy, runs in per.items():
                slot = by_seed.setdefault(scene, {}).setdefault(strategy, {})
                for i, r in enumerate(runs):
                    slot[r.get("seed", p["setup"].get("first_seed", 0) + i)] = r
    for scene, per in by_seed.items():
        has_target = out["oracle"][scene].get("has_target", not scene.startswith("paper"))
        for strategy, runs in per.items():
            out["runs"].setdefault(scene, {})[strategy] = [runs[k] for k in sorted(runs)]
            out["summary"].setdefault(scene, {})[strategy] = _summary(out["runs"][scene][strategy], out["setup"]["views"],
                                                                      has_target)
    seeds = sorted({k for per in by_seed.values() for runs in per.values() for k in runs})
    out["setup"].update(seeds=len(seeds), first_seed=seeds[0] if seeds else 0)
    names = {s for p in parts for s in p["setup"]["strategies"]}
    out["setup"]["strategies"] = [s for s in ex.STRATEGIES if s in names]
    for k in ("oracle", "summary", "runs"):  # paper scenes first, then usar_0, usar_1, ...
        out[k] = dict(sorted(out[k].items(), key=lambda kv: (not kv[0].startswith("paper"), kv[0])))
    out["goals"] = _goals(out["summary"], out["setup"]["strategies"])
    out["total_s"] = sum(p["total_s"] for p in parts)
    return write_record(out, a, _markdown)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=10, help="exploration seeds per strategy and scene (>= 10 for the record)")
    ap.add_argument("--first-seed", type=int, default=0,
                    help="seeds first_seed .. first_seed + seeds - 1 (a record in parts: --combine pools them)")
    ap.add_argument("--generated", type=int, default=4, help="generated USAR scenes (usar_scene(0..k-1))")
    ap.add_argument("--views", type=int, default=70,
                    help="view budget (large, so that the stopping rule ends the runs, not the budget)")
    ap.add_argument("--patience", type=int, default=ex.STOP_PATIENCE,
                    help="... for this many chosen views in a row (default: exploration.STOP_PATIENCE)")
    ap.add_argument("--min-utility", type=float, default=ex.STOP_UTILITY,
                    help="stop when the chosen view's utility (the strategy's expected gain, cells) is at or below "
                         "this (default: exploration.STOP_UTILITY; 0: the paper's utility 0)")
    ap.add_argument("--enclosure-power", type=float, default=ex.ExploreOptions().search.enclosure_power,
                    help="frontier_void: void cells also weighted by enclosure^power (0: the paper's plain count)")
    ap.add_argument("--unexposed-weight", type=float, default=ex.ExploreOptions().search.unexposed_weight,
                    help="frontier_void: void cells with no observed free neighbour count with this factor (1: the paper's count)")
    ap.add_argument("--no-second-look", action="store_true",
                    help="frontier_void: stop on next_best_view's answer alone (no aimed poses when it is low)")
    ap.add_argument("--beyond-voids", type=int, choices=(0, 1), default=int(ex.BEYOND_VOIDS),
                    help="frontier_void: views beyond the voids (ExploreOptions.beyond_voids)")
    ap.add_argument("--ground-is-obstacle", type=int, choices=(0, 1),
                    default=int(ex.ExploreOptions().search.ground_is_obstacle),
                    help="1: the ground is an obstacle for the arm's moved links (all strategies; default: the preset's)")
    ap.add_argument("--resolution", type=float, default=0.025)
    ap.add_argument("--image", type=int, nargs=2, default=(320, 240), metavar=("W", "H"))
    ap.add_argument("--score", type=int, nargs=2, default=None, metavar=("W", "H"), help="score ray grid")
    ap.add_argument("--noise", type=float, default=0.002, help="depth noise at 1 m (grows with depth^2)")
    ap.add_argument("--max-incidence", type=float, default=None, metavar="DEG",
                    help="no return where a ray meets a surface more than DEG degrees off its normal (grazing "
                         "dropouts; default: the camera's, none), e.g. 75")
    ap.add_argument("--strategies", nargs="+", default=list(ex.STRATEGIES))
    ap.add_argument("--scenes", nargs="+", default=None, help="subset of scene names (paper_1 paper_2 usar_0 ...)")
    ap.add_argument("--oracle-samples", type=int, default=2000, help="joint and aimed samples of the oracle, each")
    ap.add_argument("--plot", default=None, help="PNG of coverage against views (one panel per scene)")
    ap.add_argument("--markdown", default=None, help="write the table (strategies x scenes) as markdown here")
    ap.add_argument("--combine", nargs="+", default=None, metavar="JSON",
                    help="no runs: combine the JSON outputs of earlier runs (e.g. one per --scenes group) into one")
    ap.add_argument("--baselines-from", default=None, metavar="JSON",
                    help="with --combine: the baselines' runs from this earlier record (its code may differ where only "
                         "frontier_void passes; baseline runs measured again in the parts must equal its runs)")
    a = ap.parse_args(argv)
    if a.combine:
        return _combine(a)
    if a.seeds < 1 or a.views < 1 or a.generated < 0 or a.first_seed < 0:
        ap.error("--seeds and --views must be >= 1, --generated and --first-seed >= 0")
    t_all = time.perf_counter()
    chain, cmap, cmap_s = explorer_setup(a.strategies)
    out = {"setup": {"seeds": a.seeds, "first_seed": a.first_seed, "views": a.views, "min_utility": a.min_utility, "patience": a.patience, "enclosure_power": a.enclosure_power, "unexposed_weight": a.unexposed_weight, "second_look": not a.no_second_look, "beyond_voids": bool(a.beyond_voids), "ground_is_obstacle": bool(a.ground_is_obstacle), "resolution_m": a.resolution, "image": list(a.image),
                     "noise_at_1m": a.noise, "max_incidence_deg": a.max_incidence, "strategies": a.strategies, "capability_map_s": cmap_s,
                     "oracle_samples": 2 * a.oracle_samples, "note": "shared 2-core machine: timings are noisy",
                     "code": _code_version()},
           "oracle": {}, "summary": {}, "runs": {}}
    for name, scene, target in _scenes(a.generated):
        if a.scenes and name not in a.scenes:
            continue
        t0 = time.perf_counter()
        oracle = testing.observable_cells(scene, resolution=a.resolution, joint_samples=a.oracle_samples,
                                     aimed_samples=a.oracle_samples)
        out["oracle"][name] = {"seconds": time.perf_counter() - t0, "poses_valid": oracle.poses_valid,
                               "interior_points": len(oracle.points), "observable_points": oracle.count,
                               "observable_fraction": oracle.fraction, "has_target": target is not None}
        out["summary"][name], out["runs"][name] = {}, {}
        for s in a.strategies:
            runs = [_run(a, scene, target, s, seed, oracle, cmap, chain)
                    for seed in range(a.first_seed, a.first_seed + a.seeds)]
            out["runs"][name][s] = runs
            out["summary"][name][s] = _summary(runs, a.views, target is not None)
            print(f"# {name} {s}: {json.dumps(out['summary'][name][s])}", flush=True, file=__import__('sys').stderr)
    out["goals"] = _goals(out["summary"], a.strategies)
    out["total_s"] = time.perf_counter() - t_all
    return write_record(out, a, _markdown)


if __name__ == "__main__":
    raise SystemExit(main())
