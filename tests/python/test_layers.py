"""The layering of docs/architecture.md holds (scripts/check_layers.py): includes written from cpp/src, no layer
including a higher one, every file the architecture table names present, each recipe at most eight files; and the
checker catches a violation."""
from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "check_layers.py"
pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source tree (scripts/check_layers.py)")


@pytest.fixture(scope="module")
def layers():
    spec = importlib.util.spec_from_file_location("check_layers", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_tree_keeps_its_layers():
    r = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "4 recipes" in r.stdout


def _tree(tmp_path: Path, include: str, table_row: str, recipe_files: int) -> Path:
    (tmp_path / "cpp/include/octoreach").mkdir(parents=True)
    (tmp_path / "cpp/include/octoreach/types.hpp").write_text("")
    (tmp_path / "cpp/src/collision").mkdir(parents=True)
    (tmp_path / "cpp/src/maps").mkdir(parents=True)
    (tmp_path / "cpp/src/maps/m.cpp").write_text("")
    (tmp_path / "cpp/src/collision/c.cpp").write_text(f'#include "{include}"\n')
    steps = "\n".join(f"{i}. `cpp/src/f{i}.cpp`" for i in range(1, recipe_files + 1))
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs/architecture.md").write_text(
        "| concept | header | source | binding | Python |\n|---|---|---|---|---|\n" + table_row +
        f"\n\n## Recipe: do a thing\n\n{steps}\n")
    return tmp_path


def test_an_upward_include_a_missing_file_and_a_long_recipe_are_caught(layers, tmp_path):
    good = _tree(tmp_path / "good", "common/x.hpp", "| a | `types.hpp` | `maps/m.cpp` | | |", 8)
    assert layers.include_problems(good) == []
    assert layers.table_problems(good)[1] == []
    assert layers.recipe_problems(good)[1] == []
    bad = _tree(tmp_path / "bad", "maps/m.hpp", "| a | `types.hpp` | `maps/gone.cpp` | | |", 9)
    assert any("includes the higher layer maps" in p for p in layers.include_problems(bad))
    assert any("maps/gone.cpp" in p for p in layers.table_problems(bad)[1])
    assert any("more than 8" in p for p in layers.recipe_problems(bad)[1])
    relative = _tree(tmp_path / "relative", "../maps/m.hpp", "| a | | | | |", 1)
    assert any("write includes from cpp/src" in p for p in layers.include_problems(relative))
