#!/usr/bin/env python3
"""Checks the layering that docs/architecture.md describes: every include in cpp/src is written from cpp/src
("robot/urdf.hpp", "octoreach/shape.hpp"), no layer includes a higher one, every file the architecture table
names exists, and each recipe names at most eight files. Prints what it checked; exit status 1 on a violation."""
from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# A layer may include itself and every layer of a lower rank (docs/architecture.md, "The layers").
RANK = {"common": 0, "collision": 1, "simulation": 2, "robot": 2, "kinematics": 3, "maps": 4, "exploration": 5}
# The layer of each public header (cpp/include/octoreach/<name>.hpp).
HEADER_LAYER = {
    "types": "common", "limits": "common", "shape": "collision", "collision": "collision",
    "simulation": "simulation", "robot": "robot", "self_collision_report": "robot", "camera_link": "robot",
    "arm_discovery": "kinematics", "chain": "kinematics", "manipulability": "kinematics", "aim": "kinematics", "arm": "maps", "arm_report": "maps",
    "orientation_set": "maps", "capability_map": "maps", "capability_blocks": "maps", "certified_lookup": "maps", "voxel_octree": "maps",
    "point_map": "maps", "pose_map": "maps", "surface": "maps", "surface_map": "maps", "pose_sampler": "maps",
    "map_files": "maps", "map_provenance": "maps", "map_room": "maps", "map_warnings": "maps", "exploration": "exploration",
    "next_best_view": "exploration", "explorer": "exploration", "view_choice": "exploration",
}
# Where a column of the architecture table looks for the names it lists.
COLUMN_ROOTS = {1: "cpp/include/octoreach", 2: "cpp/src", 3: "bindings", 4: "python/octoreach"}
MAX_RECIPE_FILES = 8


def include_problems(root: Path = ROOT) -> list[str]:
    problems = []
    headers = {p.stem for p in (root / "cpp/include/octoreach").glob("*.hpp")}
    for name in sorted(headers - HEADER_LAYER.keys()):
        problems.append(f"cpp/include/octoreach/{name}.hpp: no layer assigned in scripts/check_layers.py")
    for path in sorted((root / "cpp/src").glob("*/*")):
        layer = path.parent.name
        if layer not in RANK:
            problems.append(f"{path.relative_to(root)}: folder {layer!r} is not a layer")
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not m:
                continue
            inc = m.group(1)
            where = f"{path.relative_to(root)}:{n}: {inc}"
            if inc.startswith("."):
                problems.append(f"{where}: write includes from cpp/src")
                continue
            target = HEADER_LAYER.get(Path(inc).stem) if inc.startswith("octoreach/") else inc.split("/")[0]
            if target not in RANK:
                problems.append(f"{where}: not a layer's file")
            elif RANK[target] > RANK[layer] or (RANK[target] == RANK[layer] and target != layer):
                problems.append(f"{where}: {layer} includes the higher layer {target}")
    return problems


def _names(cell: str) -> list[str]:
    """The file names of a table cell (backticked, with a path or an extension), each folder carried on to the
    names after it (`exploration/a.cpp`, `b.*` is exploration/b.*)."""
    out, folder = [], ""
    for token in re.findall(r"`([^`]+)`", cell):
        token = token.split(":")[0].strip()
        if not re.search(r"\.(hpp|cpp|py|\*)$", token) and not token.endswith("/"):
            continue
        if "/" in token.rstrip("/"):
            folder = token.rsplit("/", 1)[0] + "/" if not token.endswith("/") else token
        elif token.endswith("/"):
            folder = token
        out.append(token if "/" in token else folder + token)
    return out


def table_problems(root: Path = ROOT) -> tuple[int, list[str]]:
    text = (root / "docs/architecture.md").read_text()
    problems, count = [], 0
    for line in text.splitlines():
        if not line.startswith("| ") or line.startswith("| concept") or line.startswith("|---"):
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        for col, base in COLUMN_ROOTS.items():
            if col >= len(cells):
                continue
            for name in _names(cells[col]):
                count += 1
                if name.startswith(("benchmarks/", "docs/", "tests/", "scripts/")):
                    matches = list(root.glob(name))
                else:
                    matches = list((root / base).glob(name))
                if not matches:
                    problems.append(f"docs/architecture.md names {base}/{name}, which does not exist")
    return count, problems


def recipe_problems(root: Path = ROOT) -> tuple[int, list[str]]:
    text = (root / "docs/architecture.md").read_text()
    recipes = re.split(r"^## Recipe: ", text, flags=re.M)[1:]
    problems = []
    for recipe in recipes:
        title = recipe.splitlines()[0]
        body = recipe.split("\n## ", 1)[0]
        files = {f for f in re.findall(r"`((?:cpp|bindings|python|tests|docs)/[^`\s]+)`", body)}
        numbered = [int(n) for n in re.findall(r"(?:^|\s)(\d+)\. ", body, flags=re.M)]
        if len(files) > MAX_RECIPE_FILES or (numbered and max(numbered) > MAX_RECIPE_FILES):
            problems.append(f"recipe {title!r} names {max(len(files), max(numbered or [0]))} files, more than "
                            f"{MAX_RECIPE_FILES}")
    return len(recipes), problems


def main() -> int:
    problems = include_problems()
    names, table = table_problems()
    recipes, recipe = recipe_problems()
    problems += table + recipe
    print(f"checked the includes of {sum(1 for _ in (ROOT / 'cpp/src').glob('*/*'))} files in cpp/src, "
          f"{names} file names of the architecture table, {recipes} recipes")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
