"""The table of docs/exploration.md, "Round 13" (paper scene 2, frontier-void, seeds 0-19), from the JSON here.
Run: python3 docs/benchmarks/2026-11-25-round13/ab/summary.py"""
import json
import statistics
from pathlib import Path

HERE = Path(__file__).parent
ROUND12 = HERE.parents[1] / "2026-11-25-round12" / "exploration_strategies_record_shared.json"


def runs(files, scene="paper_2"):
    return [r for f in files for r in json.load(open(f))["runs"][scene]["frontier_void"]]


def row(name, rs):
    fin = [r["final_coverage"] for r in rs]
    ss = sorted(x for r in rs for x in r["search_s"])
    views = [r["views"] for r in rs]
    rat = [x for r in rs for x in r["ratios"]]
    return (f"| {name} | {sum(f >= 0.9 for f in fin)}/{len(fin)} | {100 * min(fin):.1f} | {100 * statistics.mean(fin):.1f} "
            f"| {min(views)}-{max(views)} ({statistics.mean(views):.1f}) | {statistics.median(ss):.2f} / "
            f"{ss[int(0.9 * len(ss))]:.2f} / {ss[-1]:.2f} | {100 * sum(x < 0.1 for x in rat) / len(rat):.1f} % |")


def both(stem):
    return [HERE / f"{stem}_seeds{s}_{p}.json" for s in ("0-9", "10-19") for p in "ab"]


print(row("round 12 (0930595), threshold 20", runs([ROUND12] + [HERE / f"round12_code_t20_seeds10-19_{p}.json" for p in "ab"])))
print(row("round 12, threshold 10", runs(both("round12_code_t10"))))
print(row("rays on every low view and at the last chance, threshold 20", runs(both("rays_every_low_view_t20"))))
print(row("the same, threshold 10", runs(both("rays_every_low_view_t10"))))
print(row("rays at the last chance only, threshold 10", runs(both("rays_last_chance_t10"))))
final = HERE.parent / "exploration_strategies_record_fv_a.json"
s10 = [HERE / f"final_code_t10_seeds10-19_{p}.json" for p in "ab"]
if all(f.exists() for f in s10):
    print(row("committed code: the record's seeds 0-9 and seeds 10-19", runs([final] + s10)))
