"""Paper experiments.

``tidy_up`` is the task of Section V of "Identifying Good Poses When Doing Your Household Chores" (Hertle &
Nebel): continual planning with the PDDL planner and the surface-map attachments in a simulation of the PR2,
printing the paper's Tables I and II with our figures. It lives in ``octoreach.planning.tidy_up`` (needs the
``planning`` extra); this module is its entry point beside the exploration paper's tables.

``exploration_tables`` prints the per-view tables of the frontier-void exploration paper (Dornhege & Kleiner)
for its two scenes by running ``octoreach.exploration.run_demo``.
"""
from __future__ import annotations

__all__ = ["tidy_up", "exploration_tables"]


def tidy_up(**kwargs) -> dict:
    """The tidy-up experiment (``octoreach.planning.tidy_up.tidy_up``: keywords runs, runs_table_two, objects,
    scenes, seed, resolution, budget, plot_path, progress, verbose)."""
    from .planning.tidy_up import tidy_up as run

    return run(**kwargs)


# ---------------------------------------------------------------------------- exploration


def exploration_tables(scenes=(1, 2), out=None, verbose: bool = True, **kwargs) -> dict:
    """Per-view tables of the frontier-void paper (Tables I and II: view, integration time, search
    time, void cells, utility dm^3) for its scenes, by octoreach.exploration.run_demo (no plots, no
    octree export; keyword arguments go to run_demo, e.g. max_views, resolution, width, height).
    Returns {scene: ExplorationResult}; prints the tables when `verbose`."""
    import tempfile
    from pathlib import Path

    from . import exploration

    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            folder = Path(out) / f"scene_{scene}" if out is not None else Path(tmp) / f"scene_{scene}"
            kwargs.setdefault("plots", False)
            kwargs.setdefault("export", False)
            res = exploration.run_demo(scene, out=folder, quiet=True, **kwargs)
            results[scene] = res
            if verbose:
                print(f"Table {'I' if scene == 1 else 'II'}: exploration of paper scene {scene} "
                      f"({res.total_s:.1f} s in total)")
                print(res.table())
                print()
    return results
