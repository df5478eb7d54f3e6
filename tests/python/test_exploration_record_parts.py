"""benchmarks/exploration_strategies.py --combine: a record made in parts (scenes or seeds apart) is
the record made at once; parts of other code or settings are refused."""
import importlib.util
import json
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "exploration_strategies.py"


def _bench():
    spec = importlib.util.spec_from_file_location("exploration_strategies", BENCH)
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
