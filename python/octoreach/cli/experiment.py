"""`octoreach experiment`: the papers' experiments (tidy-up with surface maps, exploration with frontier voids)."""
from __future__ import annotations

from .args import load_robot, metres, robot_args


def _cmd_experiment(args) -> int:
    from .. import experiments

    if args.name == "tidy-up":
        from ..planning import SCENES, require_planner

        for flag in ("runs", "runs_table2", "budget"):
            if getattr(args, flag) < (0 if flag == "budget" else 1):
                raise ValueError(f"--{flag.replace('_', '-')} must be at least {0 if flag == 'budget' else 1}, "
                                 f"got {getattr(args, flag)}")
        scenes = tuple(args.scenes or SCENES)
        unknown = [s for s in scenes if s not in SCENES]
        if unknown:
            raise ValueError(f"--scenes: unknown scene {unknown[0]!r} (scenes: {', '.join(SCENES)})")
        try:
            require_planner()
        except ImportError as e:  # PlannerMissing: says which extra to install
            raise RuntimeError(str(e)) from None
        experiments.tidy_up(runs=args.runs, runs_table_two=args.runs_table2, objects=tuple(args.objects),
                            scenes=scenes, seed=args.seed, resolution=args.resolution, directions=args.directions,
                            budget=args.budget, plot_path=args.plot, progress=not args.quiet, robot=load_robot(args),
                            camera_link=args.camera_link)
        if args.plot:
            print(f"plot: {args.plot}")
        return 0
    if args.scene not in (1, 2):
        raise ValueError(f"--scene must be 1 or 2, got {args.scene}")
    if args.views < 1:
        raise ValueError(f"--views must be at least 1, got {args.views}")
    experiments.exploration_tables(scenes=(args.scene,), max_views=args.views, seed=args.seed,
                                   strategy=args.strategy)
    return 0


def add_commands(sub):
    """experiment: the papers' experiments."""
    sp = sub.add_parser("experiment", help="paper experiments: tidy-up (surface maps) or exploration (frontier voids)")
    sp.add_argument("name", choices=["tidy-up", "exploration"], help="which experiment")
    sp.add_argument("--runs", type=int, default=2, help="tidy-up: runs per Table I cell and per scene (default 2)")
    sp.add_argument("--runs-table2", type=int, default=7, help="tidy-up: runs per strategy in Table II (default 7)")
    sp.add_argument("--objects", type=int, nargs="+", default=[1, 2, 3, 4], help="tidy-up: Table I object counts (default 1 2 3 4)")
    sp.add_argument("--scenes", nargs="+", help="tidy-up: scenes of the scene table (default all: paper chairs corners "
                    "shelf l_table narrow)")
    sp.add_argument("--resolution", type=metres, default=0.1, help="tidy-up: map resolution in m (default 0.1)")
    sp.add_argument("--directions", type=int, help="tidy-up: capability-map directions (default 100, the experiment's)")
    sp.add_argument("--budget", type=int, default=8, help="tidy-up: sampled poses per surface and task (default 8)")
    robot_args(sp)  # tidy-up: any robot with an arm and a camera (default: the paper's PR2)
    sp.add_argument("--camera-link", help="tidy-up: the robot's camera link (default: the PR2's head_plate_frame, or "
                                          "found from the link names: a camera on the head)")
    sp.add_argument("--plot", default="tidy_up.png", help="tidy-up: PNG to write (default tidy_up.png)")
    sp.add_argument("--scene", type=int, default=1, help="exploration: paper scene 1 or 2 (default 1)")
    sp.add_argument("--views", type=int, default=10, help="exploration: view budget (default 10)")
    from ..exploration.strategies import STRATEGIES

    sp.add_argument("--strategy", default="frontier_void", choices=STRATEGIES,
                    help="exploration: how views are chosen (default frontier_void, the paper's)")
    sp.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sp.add_argument("--quiet", action="store_true", help="no progress line")
    sp.set_defaults(func=_cmd_experiment)
