"""The tasks of ``octoreach build-many`` and of a split capability map: plain functions of plain data (robot
spec and model hash, arm, options, seeds, map bytes), run in this process or by a cluster's workers
(``octoreach.cluster``). Each returns its result's bytes and an info dict (seconds, node, peak memory); a
robot is loaded once per process and its model hash checked against the driver's.
"""
from __future__ import annotations

import os
import resource
import tempfile
import time
from pathlib import Path

from . import cache as _cache
from . import map_files
from .cache_files import map_bytes  # the file bytes of a map (the cache writes its entries from them)
from ._core import CapabilityBlocks, CapabilityMap, Robot, SurfaceMap

# ---------------------------------------------------------------------------------------------- robots
_robots: dict[str, Robot] = {}  # per process: a worker loads each robot once


def load_robot(spec: dict) -> Robot:
    """The robot of a spec: {"name": N} (example-robot-data, or a project URDF such as test_arm) or
    {"urdf": path, "srdf": path, "package_dirs": [...], "allowed_collisions": "auto"}; loaded once per process."""
    from . import robots

    key = repr(sorted(spec.items()))
    if key not in _robots:
        if "urdf" in spec:
            _robots[key] = robots.from_urdf(spec["urdf"], spec.get("package_dirs", ()), spec.get("srdf"),
                                            spec.get("allowed_collisions", "auto"))
        else:
            name = spec["name"]
            try:
                path = robots.project_urdf(name)
            except ValueError:
                path = None
            _robots[key] = (Robot.from_urdf(str(path)) if path is not None else
                            robots.load(name, allowed_collisions=spec.get("allowed_collisions", "auto")))
    return _robots[key]


def _checked_robot(spec: dict, model_hash: int) -> Robot:
    robot = load_robot(spec)
    if int(robot.model_hash) != int(model_hash):
        raise RuntimeError(f"robot {spec} loads with model hash {robot.model_hash} on this machine, the job was "
                           f"planned for {model_hash}: every machine needs the same robot files and octoreach build")
    return robot


# ---------------------------------------------------------------------------------------------- map bytes
def map_from_bytes(kind: str, data: bytes):
    """A map of `kind` ("capability", "surface") loaded from file bytes (the loader checks the kind and the
    checksum)."""
    with tempfile.TemporaryDirectory(prefix="octoreach-") as d:
        path = os.path.join(d, "map")
        Path(path).write_bytes(data)
        return map_files.load(path, kind)


def _task_info(t0: float) -> dict:
    """Seconds, node and the process's peak memory (MB) of a task, for the job report."""
    node = ""
    try:
        import ray

        if ray.is_initialized():
            node = ray.get_runtime_context().get_node_id()
    except ImportError:
        pass
    return {"seconds": time.perf_counter() - t0, "node": node, "pid": os.getpid(),
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}


# ---------------------------------------------------------------------------------------------- tasks
def capability_task(spec: dict, model_hash: int, arm: tuple, options: dict, threads: int = 0):
    """(file bytes with solutions, info) of a capability map."""
    t0 = time.perf_counter()
    robot = _checked_robot(spec, model_hash)
    o = _cache.capability_options(None, **options)
    o.threads = threads
    m = CapabilityMap.build_for_arm(robot, arm, o, progress=False)
    return map_bytes(m, with_solutions=True), _task_info(t0)


def surface_task(spec: dict, model_hash: int, capability: bytes, room: dict, base_dir: str, surface: str,
                 height: float, options: dict, threads: int = 0):
    """(file bytes, info) of the surface map of one surface of a room, base at `height`."""
    from .rooms import Room

    t0 = time.perf_counter()
    robot = _checked_robot(spec, model_hash)
    cap = map_from_bytes("capability", capability)
    r = Room(room, base_dir=base_dir)
    obstacles = r.obstacles(without=surface)
    m = SurfaceMap.build(robot, cap, r.surfaces[surface], obstacles=obstacles if len(obstacles) else None,
                         z_range=(height, height), threads=threads, progress=False, **options)
    return map_bytes(m), _task_info(t0)


def blocks_plan(spec: dict, model_hash: int, arm: tuple, options: dict) -> CapabilityBlocks:
    return CapabilityBlocks(_checked_robot(spec, model_hash), arm, _cache.capability_options(None, **options))


def sample_task(spec: dict, model_hash: int, arm: tuple, options: dict, threads: int = 0):
    """[info, seed counts, seeds of block 0, 1, ...]: step 1 of a block build."""
    t0 = time.perf_counter()
    plan = blocks_plan(spec, model_hash, arm, {**options, "threads": threads})
    seeds = plan.sample()
    return [_task_info(t0), [CapabilityBlocks.seed_count(s) for s in seeds], *seeds]


def block_task(spec: dict, model_hash: int, arm: tuple, options: dict, block: int, seeds: bytes, threads: int = 0):
    """(result bytes, info) of one block: step 2 of a block build."""
    t0 = time.perf_counter()
    plan = blocks_plan(spec, model_hash, arm, {**options, "threads": threads})
    return plan.build_block(block, seeds), _task_info(t0)
