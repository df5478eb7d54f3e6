"""The surface-map paper's experiments (Section V, Tables I and II) with our planner in our simulation, and
the same comparison on the harder scenes.

* **Table I**: total time T (minutes, mean over the solved runs; '-' where no run was solved) of inspecting
  1-4 objects in the paper's room with 1-4 predefined poses per table and with sampling;
* **Table II**: `runs` tasks of 3 objects with the 4 predefined poses and with sampling: T, t_p, re-plans,
  moves and other actions per run, and their averages;
* **Scenes**: for every scene, tasks solved, mean T and moves with 2 and 4 predefined poses per surface and
  with sampling.

Each task places its objects with a seeded generator; the predefined and sampling strategies see the same
objects and the same random stream for grasp failures. ``octoreach experiment tidy-up`` runs ``tidy_up``.
"""
from __future__ import annotations

import json
import sys
from dataclasses import dataclass

import numpy as np

from .. import arms as _arms
from .. import robots as _robots
from ..atomic_write import save_figure
from .._core import camera_link as _camera_link
from .attachments import Attachments
from .continual import run_task
from .scenes import SCENES, place_objects, scene as _scene

__all__ = ["prepare", "experiment_camera", "table_one", "table_two", "scene_table", "format_table_one", "format_table_two",
           "format_scene_table", "plot", "tidy_up", "PAPER_TABLE_ONE", "PAPER_TABLE_TWO"]

STRATEGIES = (1, 2, 3, 4, "sampling")
DIRECTIONS = 100  # capability-map approach directions of the experiment (half the library's default: faster)

#: The paper's Table I (minutes; None: not solved) and Table II averages, for printing beside ours.
PAPER_TABLE_ONE = {1: (7.9, None, None, None), 2: (8.6, 19.5, None, None), 3: (10.7, 31.4, 43.0, None),
                   4: (8.6, 16.9, 34.5, 87.9), "sampling": (15.3, 36.4, 37.0, 64.1)}
PAPER_TABLE_TWO = {"predefined": {"T [min]": 38.0, "t_p [min]": 7.0, "# re-plan": 7.3, "# move": 3.9, "# other": 28.3},
                   "sampling": {"T [min]": 32.0, "t_p [min]": 7.42, "# re-plan": 9.3, "# move": 2.1, "# other": 28.6}}


#: The paper's PR2 carries its Kinect on the head plate: the camera of the experiment when the robot is the PR2
#: and no camera link is given (any other robot's is given, or found by octoreach.find_camera_link).
PR2_CAMERA_LINK = "head_plate_frame"


@dataclass
class Prepared:
    """A scene with its attachments (maps built once) and the robot's camera link."""

    scene: object
    attachments: Attachments
    camera_link: str = PR2_CAMERA_LINK


def experiment_camera(robot, camera_link: str | None = None) -> str:
    """The camera link of the experiment: `camera_link` when given, the PR2's Kinect mount (PR2_CAMERA_LINK) on
    the PR2, else the one octoreach.find_camera_link finds (ValueError asking for it when that is ambiguous)."""
    if camera_link is None and robot.name == "pr2" and robot.has_link(PR2_CAMERA_LINK):
        camera_link = PR2_CAMERA_LINK
    return _camera_link(robot, camera_link).link


def prepare(scenes=tuple(SCENES), resolution: float = 0.1, directions: int | None = None, seed: int = 0, robot=None,
            progress: bool = False, camera_link: str | None = None) -> dict:
    """{scene name: Prepared}: the robot (None: the PR2), its capability maps (built once) and each scene's surface
    maps; the robot must have an arm and a camera (experiment_camera), checked before any map is built."""
    robot = _robots.pr2() if robot is None else robot
    camera = experiment_camera(robot, camera_link)
    if not _arms.find_arms(robot):
        raise ValueError(f"robot {robot.name!r} has no arm that could be found: the tidy-up task needs one to grasp with")
    directions = DIRECTIONS if directions is None else directions
    caps = {arm.name: _arms.capability_map(robot, arm.name, resolution=resolution, directions=directions, seed=seed,
                                           progress=progress) for arm in _arms.find_arms(robot)}
    out, built = {}, {}
    for name in scenes:
        sc = _scene(name)
        key = json.dumps(sc.room.description, sort_keys=True)  # scenes in the same room share its maps
        if key not in built:
            if progress:
                print(f"tidy-up: surface maps of scene {name!r}", file=sys.stderr, flush=True)
            built[key] = Attachments.build(robot, sc.room, resolution=resolution, caps=caps, seed=seed)
        out[name] = Prepared(sc, built[key], camera)
    return out


def _label(strategy) -> str:
    return "sampling" if strategy == "sampling" else f"{strategy} pose{'s' if strategy != 1 else ''}"


def _runs(prep: Prepared, n: int, runs: int, seed: int, strategies, budget: int, progress: bool) -> dict:
    out = {s: [] for s in strategies}
    for r in range(runs):
        objects = place_objects(prep.scene, n, np.random.default_rng([seed, n, r]))
        for s in strategies:
            out[s].append(run_task(prep.scene, prep.attachments, objects, s, seed=seed * 1000 + r, budget=budget,
                                   camera_link=prep.camera_link))
            if progress:
                rec = out[s][-1]
                print(f"tidy-up: {prep.scene.name} {n} object(s) run {r + 1} {_label(s)}: "
                      f"{'solved' if rec.solved else rec.message}", file=sys.stderr, flush=True)
    return out


def table_one(prep: Prepared, objects=(1, 2, 3, 4), runs: int = 2, seed: int = 0, budget: int = 8,
              progress: bool = False) -> dict:
    """{(strategy, n): [RunRecord]}: 1-4 predefined poses per surface and sampling, for each object count."""
    out = {}
    for n in objects:
        for s, recs in _runs(prep, n, runs, seed, STRATEGIES, budget, progress).items():
            out[(s, n)] = recs
    return out


def table_two(prep: Prepared, runs: int = 7, objects: int = 3, seed: int = 1, budget: int = 8,
              progress: bool = False) -> dict:
    """{'predefined': [RunRecord] (4 poses per surface), 'sampling': [...]}, `runs` tasks of `objects` objects."""
    recs = _runs(prep, objects, runs, seed, (4, "sampling"), budget, progress)
    return {"predefined": recs[4], "sampling": recs["sampling"]}


def scene_table(prepared: dict, objects: int = 3, runs: int = 2, seed: int = 2, budget: int = 8,
                progress: bool = False) -> dict:
    """{scene: {'2 predefined': [RunRecord] (the long sides), '4 predefined': [...], 'sampling': [...]}} for every
    prepared scene."""
    out = {}
    for name, prep in prepared.items():
        recs = _runs(prep, objects, runs, seed, (2, 4, "sampling"), budget, progress)
        out[name] = {"2 predefined": recs[2], "4 predefined": recs[4], "sampling": recs["sampling"]}
    return out


# ------------------------------------------------------------------------------------------ printing


def _mean_solved_minutes(recs) -> float | None:
    solved = [r.T / 60 for r in recs if r.solved]
    return float(np.mean(solved)) if solved else None


def format_table_one(results: dict, paper: bool = True) -> str:
    """Table I: rows 1-4 poses and sampling, a column per object count; '12.3' (all runs solved), '12.3 (1/2)'
    (mean over the solved runs), '-' (none solved). With `paper`, the paper's figure follows in brackets."""
    counts = sorted({n for _, n in results})
    runs = max(len(v) for v in results.values())
    lines = [f"Table I: total time T [min] ({runs} run(s) per cell, mean over the solved ones; [paper])",
             f"{'':<10}" + "".join(f"{f'{n} object' + ('s' if n > 1 else ''):>20}" for n in counts)]
    for s in STRATEGIES:
        cells = []
        for n in counts:
            recs = results.get((s, n), [])
            m = _mean_solved_minutes(recs)
            ok = sum(r.solved for r in recs)
            text = "-" if m is None else f"{m:.1f}" + ("" if ok == len(recs) else f" ({ok}/{len(recs)})")
            if paper and n <= 4:
                ref = PAPER_TABLE_ONE[s][n - 1]
                text += f" [{'-' if ref is None else ref}]"
            cells.append(text)
        lines.append(f"{_label(s):<10}" + "".join(f"{c:>20}" for c in cells))
    return "\n".join(lines)


def _row_values(recs):
    return {"T [min]": [r.T / 60 for r in recs], "t_p [s]": [r.t_p for r in recs],
            "# re-plan": [r.replans for r in recs], "# move": [r.moves for r in recs],
            "# other": [r.other for r in recs], "solved": [int(r.solved) for r in recs]}


def format_table_two(results: dict, paper: bool = True) -> str:
    """Table II: per run and on average, predefined (4 poses per surface) on top, sampling below."""
    lines = []
    for key, title in (("predefined", "predefined poses (4 per table)"), ("sampling", "sampled poses")):
        recs = results[key]
        lines.append(f"Table II, {title}: {recs[0].objects if recs else '?'} objects")
        lines.append(f"{'':<11}" + "".join(f"{i + 1:>7}" for i in range(len(recs))) + f"{'average':>9}"
                     + (f"{'paper':>8}" if paper else ""))
        for label, values in _row_values(recs).items():
            fmt = "{:.1f}" if label in ("T [min]", "t_p [s]") else "{:d}"
            ref = ""
            if paper:
                pkey = "t_p [min]" if label == "t_p [s]" else label
                pv = PAPER_TABLE_TWO[key].get(pkey)
                ref = f"{'' if pv is None else (f'{pv * 60:.0f}' if label == 't_p [s]' else pv):>8}"
            lines.append(f"{label:<11}" + "".join(f"{fmt.format(v):>7}" for v in values)
                         + f"{np.mean(values) if values else float('nan'):>9.2f}" + ref)
        lines.append("")
    return "\n".join(lines).rstrip()


def format_scene_table(results: dict) -> str:
    """Per scene: solved runs, mean T [min] of the solved runs, mean moves, and the first failure's reason."""
    lines = ["Scenes: 2 and 4 predefined poses per surface against sampling",
             f"{'scene':<9}{'strategy':<14}{'solved':>7}{'T [min]':>9}{'moves':>7}{'sampled':>9}  why not solved (first)"]
    for name, by in results.items():
        for key, recs in by.items():
            m = _mean_solved_minutes(recs)
            why = next((r.message for r in recs if not r.solved), "")
            lines.append(f"{name:<9}{key:<14}{f'{sum(r.solved for r in recs)}/{len(recs)}':>7}"
                         f"{'-' if m is None else f'{m:.1f}':>9}{np.mean([r.moves for r in recs]):>7.1f}"
                         f"{np.mean([r.sampled for r in recs]):>9.1f}  {why}")
    return "\n".join(lines)


def plot(one: dict, two: dict, path) -> None:
    """Writes a PNG: Table I's T per object count and strategy (left), Table II's moves, re-plans and other
    actions per strategy with the paper's averages (right)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    counts = sorted({n for _, n in one})
    for s in STRATEGIES:
        ys = [_mean_solved_minutes(one.get((s, n), [])) for n in counts]
        ys = [np.nan if y is None else y for y in ys]  # unsolved: a gap in the line
        a.plot(counts, ys, "o-" if s == "sampling" else "s--", label=_label(s),
               linewidth=2.5 if s == "sampling" else 1.2)
    a.set_xlabel("objects")
    a.set_ylabel("total time T [min] (solved runs)")
    a.set_title("Table I: paper's room")
    a.set_xticks(counts)
    a.legend()
    keys = ["# move", "# re-plan", "# other"]
    x = np.arange(len(keys))
    for i, (key, colour) in enumerate((("predefined", "tab:orange"), ("sampling", "tab:blue"))):
        vals = _row_values(two[key])
        b.bar(x + (i - 0.5) * 0.38, [np.mean(vals[k]) for k in keys], 0.36, color=colour, label=f"ours: {key}")
        b.scatter(x + (i - 0.5) * 0.38, [PAPER_TABLE_TWO[key][k] for k in keys], marker="_", s=400, color="k",
                  zorder=3, label="paper" if i == 0 else None)
    b.set_xticks(x, keys)
    b.set_title("Table II: 3 objects, averages per run")
    b.legend()
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)


def tidy_up(runs: int = 2, runs_table_two: int = 7, objects=(1, 2, 3, 4), scenes=tuple(SCENES), seed: int = 0,
            resolution: float = 0.1, directions: int | None = None, budget: int = 8, plot_path=None, progress: bool = False,
            verbose: bool = True, robot=None, camera_link: str | None = None) -> dict:
    """Runs Table I (paper's room), Table II (paper's room, 3 objects) and the scene table with `robot` (None: the
    PR2; any robot with an arm and a camera: `camera_link`, or found); prints them when `verbose`; writes the plot
    to `plot_path`. Returns {'table_one', 'table_two', 'scenes'} of RunRecords."""
    if runs < 1 or runs_table_two < 1:
        raise ValueError(f"runs must be at least 1, got {runs!r} and {runs_table_two!r}")
    objects = tuple(int(n) for n in objects)
    if not objects or min(objects) < 1:
        raise ValueError(f"objects must be positive counts, got {objects!r}")
    unknown = [s for s in scenes if s not in SCENES]
    if unknown:
        raise ValueError(f"unknown scene(s) {', '.join(map(repr, unknown))} (scenes: {', '.join(SCENES)})")
    prepared = prepare(tuple(dict.fromkeys(("paper", *scenes))), resolution=resolution, directions=directions, seed=seed,
                       progress=progress, robot=robot, camera_link=camera_link)
    one = table_one(prepared["paper"], objects, runs, seed, budget, progress)
    two = table_two(prepared["paper"], runs_table_two, 3, seed + 1, budget, progress)
    sc = scene_table({k: v for k, v in prepared.items() if k in scenes}, 3, runs, seed + 2, budget, progress)
    if verbose:
        print(format_table_one(one))
        print()
        print(format_table_two(two))
        print()
        print(format_scene_table(sc))
    if plot_path is not None:
        plot(one, two, plot_path)
    return {"table_one": one, "table_two": two, "scenes": sc}
