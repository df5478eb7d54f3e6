"""benchmarks/exploration_strategies.py --combine: a record made in parts (scenes or seeds apart) is
the record made at once; parts of other code or settings are refused."""
import importlib.util
import json
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "exploration_strategies.py"


def _bench(name="exploration_strategies"):
    spec = importlib.util.spec_from_file_location(name, BENCH.parent / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _run(seed, views):
    cover = [min(1.0, 0.2 * (k + 1) + 0.01 * seed) for k in range(views)]
    return {"seed": seed, "coverage": cover, "views": views, "stop_reason": "utility below min_utility",
            "views_to_90": next((k + 1 for k, c in enumerate(cover) if c >= 0.9), None),
            "coverage_5": cover[min(4, views - 1)], "coverage_10": cover[min(9, views - 1)], "final_coverage": cover[-1],
            "target_seen_view": None, "time_per_view_s": 0.1 * (seed + 1), "ratios": [1.0, 0.05 * seed],
            "physically_invalid_views": 0, "seen_unobservable": seed}


def _part(mod, seeds, first, strategies=("frontier_void", "random"), code="abc"):
    runs = {s: [_run(k, 6 + k) for k in range(first, first + seeds)] for s in strategies}
    return {"setup": {"seeds": seeds, "first_seed": first, "views": 60, "resolution_m": 0.025, "code": code,
                      "strategies": list(strategies)},
            "oracle": {"paper_1": {"observable_points": 10}},
            "summary": {"paper_1": {s: mod._summary(r, 60, False) for s, r in runs.items()}},
            "runs": {"paper_1": runs}, "total_s": 1.0}


def test_seeds_in_parts_pool_into_the_whole(tmp_path, capsys):
    mod = _bench()
    whole = _part(mod, 4, 0)
    files = []
    for name, part in (("a", _part(mod, 2, 0)), ("b", _part(mod, 2, 2))):
        files.append(str(tmp_path / f"{name}.json"))
        Path(files[-1]).write_text(json.dumps(part))
    assert mod.main(["--combine", *files]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["setup"]["seeds"] == 4 and out["setup"]["first_seed"] == 0
    assert [r["seed"] for r in out["runs"]["paper_1"]["random"]] == [0, 1, 2, 3]
    assert out["summary"]["paper_1"] == json.loads(json.dumps(whole["summary"]["paper_1"]))


def test_parts_of_other_code_or_settings_are_refused(tmp_path):
    mod = _bench()
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.write_text(json.dumps(_part(mod, 2, 0)))
    b.write_text(json.dumps(_part(mod, 2, 2, code="def")))
    with pytest.raises(SystemExit, match="code"):
        mod.main(["--combine", str(a), str(b)])


def _with(part, strategy, **run_changes):
    for r in part["runs"]["paper_1"][strategy]:
        r.update(run_changes)
    return part


def _setup(part, **changes):
    part["setup"].update(changes)
    return part


def test_baselines_from_an_earlier_record_fill_what_the_parts_do_not_measure(tmp_path, capsys):
    """--baselines-from: the earlier record's baseline runs join the new frontier_void runs; a baseline run
    measured again must be the earlier run, else the baselines' code path changed and the record is refused."""
    mod = _bench()
    old = _setup(_part(mod, 2, 0, strategies=("frontier_void", "random", "frontiers"), code="old"), min_utility=20.0)
    new_fv = _setup(_part(mod, 2, 0, strategies=("frontier_void",), code="new"), min_utility=20.0)
    check = _setup(_part(mod, 1, 0, strategies=("random",), code="new"), min_utility=20.0)
    paths = {}
    for name, part in (("old", old), ("fv", new_fv), ("check", check)):
        paths[name] = tmp_path / f"{name}.json"
        paths[name].write_text(json.dumps(part))
    assert mod.main(["--combine", str(paths["fv"]), str(paths["check"]), "--baselines-from", str(paths["old"])]) == 0
    out = json.loads(capsys.readouterr().out)
    assert sorted(out["runs"]["paper_1"]) == ["frontier_void", "frontiers", "random"]
    assert out["setup"]["baselines_from"]["checked_runs"] == 1
    assert [r["seed"] for r in out["runs"]["paper_1"]["frontiers"]] == [0, 1]
    check["runs"]["paper_1"]["random"][0]["coverage"][-1] = 0.5  # the baseline's view changed
    paths["check"].write_text(json.dumps(check))
    with pytest.raises(SystemExit, match="code path changed"):
        mod.main(["--combine", str(paths["fv"]), str(paths["check"]), "--baselines-from", str(paths["old"])])


def test_a_lower_stopping_threshold_borrows_only_runs_the_rule_never_stopped(tmp_path, capsys):
    """With a lower min_utility than the earlier record's, a borrowed run must have ended at the view budget
    (the rule never stopped it, a lower threshold would not either); a run measured again may go on where the
    earlier threshold stopped it, but its first views must be the earlier run's."""
    mod = _bench()
    old = _setup(_part(mod, 2, 0, strategies=("frontier_void", "random", "frontiers"), code="old"), min_utility=20.0)
    _with(old, "frontiers", stop_reason="view budget")
    new_fv = _setup(_part(mod, 2, 0, strategies=("frontier_void",), code="new"), min_utility=10.0)
    longer = _setup(_part(mod, 2, 0, strategies=("random",), code="new"), min_utility=10.0)
    for r in longer["runs"]["paper_1"]["random"]:
        r["coverage"] = r["coverage"] + [1.0, 1.0]  # the earlier views, then two more
    paths = {}
    for name, part in (("old", old), ("fv", new_fv), ("random", longer)):
        paths[name] = tmp_path / f"{name}.json"
        paths[name].write_text(json.dumps(part))
    args = ["--combine", str(paths["fv"]), str(paths["random"]), "--baselines-from", str(paths["old"])]
    assert mod.main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["setup"]["baselines_from"]["checked_runs"] == 2 and out["setup"]["min_utility"] == 10.0
    assert [len(r["coverage"]) for r in out["runs"]["paper_1"]["random"]] == [8, 9]  # the new, longer runs
    # random's earlier runs stopped by the rule: without new runs of it, they cannot be borrowed
    with pytest.raises(SystemExit, match="measured again"):
        mod.main(["--combine", str(paths["fv"]), "--baselines-from", str(paths["old"])])
    # a run measured again whose first views differ is refused
    longer["runs"]["paper_1"]["random"][1]["coverage"][0] = 0.0
    paths["random"].write_text(json.dumps(longer))
    with pytest.raises(SystemExit, match="code path changed"):
        mod.main(args)


def test_families_leave_instances_with_nothing_observable_out_of_the_coverage_figures():
    """benchmarks/exploration_families.py: a run on an instance whose interior no safe reachable view sees has
    no coverage (90 % of nothing is no figure); the summary counts it apart and takes the coverage figures
    of the others."""
    mod = _bench("exploration_families")
    run = lambda inst, cover: {"instance": inst, "seed": 0, "coverage": cover, "views": 4, "stop_reason": "no valid view",
                               "views_to_90": mod.ex.views_to_reach(cover, mod.LEVEL),
                               "final_coverage": cover[-1] if cover else None, "target_seen_view": 2,
                               "choice_s": [0.1], "ratios": [1.0], "physically_invalid_views": 0}
    oracle = {0: {"observable_points": 50, "target_observable": True},
              1: {"observable_points": 0, "target_observable": False},
              2: {"observable_points": 40, "target_observable": True}}
    runs = [run(0, [0.5, 0.95]), run(1, []), run(2, [0.4, 0.7, 0.8])]
    s = mod._summary(runs, 30, oracle)
    assert (s["runs"], s["runs_nothing_observable"], s["reached_90"], s["runs_under_90"]) == (3, 1, 1, 1)
    assert (s["final_median"], s["final_min"]) == (pytest.approx(0.875), 0.8)
    assert s["views_to_90_median"] == pytest.approx(16.5)  # median of 2 and never (the budget + 1, 31)
    assert s["target_runs_observable"] == 2 and s["ended_by_itself"] == 3
    assert mod._summary([run(1, [])], 30, oracle)["final_median"] is None
    assert "| - |" in mod._markdown({"f": {"frontier_void": mod._summary([run(1, [])], 30, oracle)}}, ["frontier_void"])
