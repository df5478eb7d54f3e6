"""Map builds spread over a Ray cluster (the ``cluster`` extra): many maps as tasks, or one capability map
cut into blocks of voxels.

``cluster`` arguments: ``"local"`` (default) starts Ray on this machine (a process that already joined a
cluster keeps it), ``"none"`` runs every task in this process (no Ray; the reference), ``"auto"``
joins the cluster this machine belongs to (``ray start`` ran here, or $RAY_ADDRESS), and ``"HOST:PORT"``
(or ``"ray://HOST:PORT"``) joins the cluster whose head is there; an address that does not answer
within ``timeout`` seconds raises ConnectionError before Ray is asked.

Results never depend on where a task ran: every task is a deterministic function of plain data (robot
spec and model hash, arm, options, seeds), maps carry no timing, so a task that Ray retries after a lost
worker returns the same bytes. The driver looks every map up in the map cache first (a hit is used only
when it agrees with its key: ``octoreach.cache_check``) and stores what the cluster built
(``octoreach.cache``); workers never touch the cache.
"""
from __future__ import annotations

import os
import socket
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from . import cache as _cache
from . import cache_check as _check
from . import jobs as _jobs
from .atomic_write import write_atomically

_remote: dict = {}


def _ray():
    try:
        import ray
    except ImportError:
        raise ImportError("cluster builds need Ray: pip install 'octoreach[cluster]' (or pip install ray)") from None
    return ray


def _check_reachable(address: str, timeout: float) -> None:
    """ConnectionError unless the address answers within `timeout` s: a TCP connection to its host and port,
    then (for a GCS address, not ray://) a Ray GCS that answers a client (a proxy or another service does not)."""
    import threading

    hostport = address.split("://", 1)[-1].rstrip("/")
    host, sep, port = hostport.rpartition(":")
    if not sep or not port.isdigit():
        raise ValueError(f"cluster address must be 'local', 'none', 'auto' or HOST:PORT, got {address!r}")
    hint = "start one with `ray start --head` there, or use --cluster local"
    t0 = time.monotonic()
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout):
            pass
    except OSError as e:
        reason = "timed out" if isinstance(e, socket.timeout) else (e.strerror or str(e))
        raise ConnectionError(f"cannot reach the Ray cluster at {address} within {timeout:g} s ({reason}); {hint}") from None
    if address.startswith("ray://"):
        return
    try:
        from ray._raylet import GcsClient  # Ray's own client of the head's GCS (a private module: optional)
    except ImportError:
        return
    answer: dict = {}

    def probe():
        try:
            GcsClient(address=hostport)
            answer["ok"] = True
        except Exception as e:  # noqa: BLE001  (any failure means: not a Ray head)
            answer["error"] = " ".join(str(e).split())[:200]

    thread = threading.Thread(target=probe, daemon=True)
    thread.start()
    thread.join(max(0.5, timeout - (time.monotonic() - t0)))
    if not answer.get("ok"):
        reason = answer.get("error", "no answer from a Ray GCS")
        raise ConnectionError(f"cannot reach the Ray cluster at {address} within {timeout:g} s: something answers "
                              f"there but not a Ray head ({reason}); {hint}")


def connect(cluster: str | None = "local", num_cpus: int | None = None, timeout: float = 5.0) -> str:
    """Joins or starts the Ray cluster of a `cluster` argument (see the module docstring); returns "none"
    for in-process runs, else the address joined."""
    if cluster in (None, "none", "inline"):
        return "none"
    if not isinstance(cluster, str):
        raise TypeError(f"cluster must be 'local', 'none', 'auto' or 'HOST:PORT', got {type(cluster).__name__}")
    if cluster not in ("local", "auto"):
        _check_reachable(cluster, timeout)
    ray = _ray()
    if ray.is_initialized():  # one cluster per process: the one joined first
        return "joined"
    os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
    quiet = {"include_dashboard": False, "log_to_driver": False, "configure_logging": False}
    if cluster == "local":
        ray.init(num_cpus=num_cpus, object_store_memory=256 * 1024 * 1024, **quiet)
        return "local"
    try:
        ray.init(address=cluster, **quiet)
    except (ConnectionError, RuntimeError, ValueError) as e:
        raise ConnectionError(f"cannot join the Ray cluster at {cluster}: {e}") from None
    return cluster


def _remote_function(name: str):
    """The Ray remote function of jobs.<name> (a task whose worker is lost is run again)."""
    ray = _ray()
    if name not in _remote:
        _remote[name] = ray.remote(max_retries=5, retry_exceptions=False)(getattr(_jobs, name))
    return _remote[name]


class _Done:
    """A finished in-process task's value, standing in for a Ray reference."""

    def __init__(self, value):
        self.value = value


class _Inline:
    """Runs each task at once in this process with every core (the one-process reference)."""

    def submit(self, name, *args, num_returns=1, threads=None):
        values = [a.value if isinstance(a, _Done) else a for a in args]
        out = getattr(_jobs, name)(*values, threads=0 if threads is None else threads)
        return _Done(out) if num_returns == 1 else [_Done(v) for v in out]

    def wait(self, pending):
        return pending[:1], pending[1:]

    def get(self, ref):
        return ref.value

    def put(self, value):
        return _Done(value)


class _Ray:
    """Submits tasks to the Ray cluster this process joined; each task takes `task_cpus` CPUs and as many threads."""

    def __init__(self, task_cpus: int):
        self.ray = _ray()
        self.task_cpus = task_cpus

    def submit(self, name, *args, num_returns=1, threads=None):
        return _remote_function(name).options(num_returns=num_returns, num_cpus=self.task_cpus).remote(
            *args, threads=self.task_cpus if threads is None else threads)

    def wait(self, pending):
        return self.ray.wait(pending, num_returns=1)

    def get(self, ref):
        return self.ray.get(ref)

    def put(self, value):
        return self.ray.put(value)


def _executor(cluster, task_cpus: int):
    where = connect(cluster)
    return _Inline() if where == "none" else _Ray(task_cpus)


class _Progress:
    """Whole-job progress on stderr: maps done of all, and seconds."""

    def __init__(self, total: int, label: str, enabled, callback=None):
        self.total, self.label, self.done = total, label, 0
        self.enabled, self.callback = enabled, callback
        self.t0 = time.perf_counter()

    def step(self, what: str) -> None:
        self.done += 1
        if self.callback is not None:
            self.callback(self.done, self.total, what)
        if self.enabled:
            end = "\n" if self.done == self.total else ""
            sys.stderr.write(f"\r{self.label}: {self.done}/{self.total} done, {time.perf_counter() - self.t0:.1f} s"
                             f" ({what[:60]}){' ' * 10}{end}")
            sys.stderr.flush()


@dataclass
class BuildReport:
    """What a job built: output files by task name, per-task figures (seconds, node, peak MB), cache hits."""
    files: dict = field(default_factory=dict)
    tasks: dict = field(default_factory=dict)
    cache_hits: int = 0
    seconds: float = 0.0


def _store(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomically(path, data, "map file")


def build_many(job, cluster: str | None = "local", out=None, cache=True, progress=True, task_cpus: int = 1,
               on_progress=None) -> BuildReport:
    """Builds every map of a job (a job file or dict, see octoreach.jobs) as tasks on a cluster, writing the
    files under the job's out folder; maps found in the cache are not built. The job is checked before
    anything starts. on_progress(done, total, name) is called after each map."""
    t0 = time.perf_counter()
    plan = _jobs.read_job(job, out=out)
    store = _cache.resolve(cache)
    ex = _executor(cluster, task_cpus)
    report = BuildReport()
    bar = _Progress(len(plan), "build-many", progress, on_progress)
    pending: dict = {}  # reference -> (kind, job)
    cap_refs = []

    def cached(kind, j):
        """The cached bytes of a map of the job (checked against its key), written to its output file; None on
        a miss."""
        if kind == "capability":
            verify = lambda m: _check.capability_mismatch(m, j.fields, j.robot)  # noqa: E731
        else:
            verify = lambda m: _check.surface_mismatch(m, j.fields, j.polygon)  # noqa: E731
        data = store.lookup_bytes(kind, j.fields, verify) if store else None
        if data is not None:
            report.cache_hits += 1
            _store(j.out, data)
            report.files[j.name] = str(j.out)
            bar.step(j.name + " (cache)")
        return data

    for cj in plan.capability:
        data = cached("capability", cj)
        if data is not None:
            cap_refs.append(ex.put(data))
            continue
        ref = ex.submit("capability_task", cj.spec, int(cj.robot.model_hash), cj.arm_tuple, cj.options,
                        num_returns=2)
        cap_refs.append(ref[0])
        pending[ref[1]] = ("capability", cj, ref[0])
    for sj in plan.surfaces:
        if cached("surface", sj) is not None:
            continue
        cj = plan.capability[sj.capability]
        ref = ex.submit("surface_task", cj.spec, int(cj.robot.model_hash), cap_refs[sj.capability], sj.room,
                        sj.base_dir, sj.surface, sj.height, sj.options, num_returns=2)
        pending[ref[1]] = ("surface", sj, ref[0])
    waiting = list(pending)
    while waiting:
        ready, waiting = ex.wait(waiting)
        for info_ref in ready:
            kind, j, data_ref = pending[info_ref]
            report.tasks[j.name] = ex.get(info_ref)
            data = ex.get(data_ref)
            _store(j.out, data)
            if store is not None:
                store.store_bytes(kind, j.fields, data)
            report.files[j.name] = str(j.out)
            bar.step(j.name)
    report.seconds = time.perf_counter() - t0
    return report


def build_capability_split(robot, arm, cluster: str | None = "local", block_size: int = 16, cache=None,
                           progress=True, task_cpus: int = 1, robot_spec: dict | None = None, report=None,
                           **options):
    """One capability map built as blocks of voxels on the cluster's workers and merged: the same bytes as
    ``CapabilityMap.build_for_arm(robot, arm, block_size=block_size, **options)`` in one process (see
    CapabilityBlocks). robot_spec tells workers how to load the robot ({"name": ...} by default, from
    robot.name); the model hash is checked on every worker. `report` (a BuildReport) collects per-task figures."""
    from ._core import Arm

    a = Arm.resolve(robot, arm)
    opts = _cache.capability_options(None, **{**options, "block_size": block_size})
    store = _cache.resolve(cache)
    fields = _cache.capability_key_fields(robot, a, opts)
    if store is not None:
        hit = store.lookup("capability", fields, lambda m: _check.capability_mismatch(m, fields, robot))
        if hit is not None:
            return hit
    spec = robot_spec or {"name": robot.name}
    fields_opts = {k: v for k, v in _cache.options_fields(opts).items() if k not in ("threads", "approach_axis")}
    arm_t = (a.base_link, a.tip_link, tuple(float(v) for v in a.approach_axis))
    model = int(robot.model_hash)
    plan = _jobs.blocks_plan(spec, model, arm_t, fields_opts)
    ex = _executor(cluster, task_cpus)
    report = report if report is not None else BuildReport()
    t0 = time.perf_counter()
    # Step 1 (one task): the FK sampling of the whole box, then one task per block, largest first.
    sampled = ex.submit("sample_task", spec, model, arm_t, fields_opts, num_returns=plan.count + 2)
    report.tasks["sample"] = ex.get(sampled[0])
    counts = ex.get(sampled[1])
    order = sorted(range(plan.count), key=lambda b: -counts[b])
    bar = _Progress(sum(1 for c in counts if c), f"capability blocks ({plan.count} of {plan.block_size} voxels)",
                    progress)
    results: list = [None] * plan.count
    pending = {}
    for b in order:
        if counts[b] == 0 and not opts.exhaustive:  # no seed: the empty result, without a task
            results[b] = plan.build_block(b, ex.get(sampled[2 + b]))
            continue
        ref = ex.submit("block_task", spec, model, arm_t, fields_opts, b, sampled[2 + b], num_returns=2)
        pending[ref[1]] = (b, ref[0])
    waiting = list(pending)
    while waiting:
        ready, waiting = ex.wait(waiting)
        for info_ref in ready:
            b, data_ref = pending[info_ref]
            report.tasks[f"block {b}"] = ex.get(info_ref)
            results[b] = ex.get(data_ref)
            bar.step(f"block {b}")
    m = plan.merge(results)
    report.seconds = time.perf_counter() - t0
    if store is not None and store.writable():
        store.store_bytes("capability", fields, _jobs.map_bytes(m, with_solutions=m.has_solutions))
    return m
