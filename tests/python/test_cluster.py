"""Builds on a Ray cluster on this machine: a head and a separate worker node process (ray.cluster_utils),
one cluster for the whole module (Ray starts slowly), small CPU and memory limits for a 2-core machine.

The one-process build (cluster="none") is the reference: the cluster gives the same bytes, also when the
worker node is killed in the middle of the job, and the split capability map equals the block build.
"""
from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

ray = pytest.importorskip("ray", reason="the cluster extra (ray) is not installed")
from ray.cluster_utils import Cluster  # noqa: E402

import octoreach  # noqa: E402
from octoreach import cluster as octo_cluster  # noqa: E402
from octoreach import robots  # noqa: E402

NODE = {"num_cpus": 1, "object_store_memory": 80 * 1024 * 1024}
JOB = {
    "robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}],
    "resolutions": [0.2, 0.15],
    "capability": {"directions": 24, "seed": 2},
    "surfaces": [{"name": f"t{i}", "rectangle": {"size": [0.4, 0.3], "height": 0.2 + 0.1 * i, "x": 0.3}} for i in range(3)],
    "surface": {"theta_bins": 4},
}


@pytest.fixture(scope="module")
def cluster():
    os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
    c = Cluster(initialize_head=True, head_node_args={**NODE, "include_dashboard": False})
    c.worker = c.add_node(**NODE)
    ray.init(address=c.address, log_to_driver=False, configure_logging=False)
    c.wait_for_nodes()
    yield c
    ray.shutdown()
    c.shutdown()


def tree_bytes(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*.or*m"))}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The job in this process, without Ray."""
    out = tmp_path_factory.mktemp("inline")
    report = octo_cluster.build_many(JOB, cluster="none", out=out, cache=False, progress=False)
    assert len(report.files) == 2 + 2 * 3
    return tree_bytes(out)


def test_job_on_the_cluster_survives_a_killed_worker(cluster, reference, tmp_path):
    killed = []

    def kill_worker_once(done, total, name):
        if not killed:  # first map finished: the worker node is busy with another task; kill its raylet
            cluster.remove_node(cluster.worker, allow_graceful=False)
            killed.append(done)

    report = octo_cluster.build_many(JOB, cluster="local", out=tmp_path / "out", cache=tmp_path / "cache",
                                     progress=False, on_progress=kill_worker_once)
    assert killed and len(report.files) == len(reference)
    assert tree_bytes(tmp_path / "out") == reference  # same bytes as one process, though tasks were lost and retried
    assert len({t["pid"] for t in report.tasks.values()}) >= 1
    cluster.worker = cluster.add_node(**NODE)  # for the next tests
    cluster.wait_for_nodes()
    # everything is in the cache now: a second run builds nothing
    again = octo_cluster.build_many(JOB, cluster="local", out=tmp_path / "again", cache=tmp_path / "cache",
                                    progress=False)
    assert again.cache_hits == len(reference) and not again.tasks
    assert tree_bytes(tmp_path / "again") == reference


def test_tasks_run_on_both_nodes(cluster, tmp_path):
    job = {**JOB, "resolutions": [0.25], "surfaces": JOB["surfaces"] * 1, "capability": {"directions": 16, "seed": 5}}
    report = octo_cluster.build_many(job, cluster="local", out=tmp_path, cache=False, progress=False)
    assert {t["node"] for t in report.tasks.values()} <= {n["NodeID"] for n in ray.nodes()}
    assert all(t["seconds"] > 0 and t["peak_mb"] > 0 for t in report.tasks.values())


def test_split_capability_map_equals_the_block_build(cluster, tmp_path):
    robot = robots.test_arm()
    kw = dict(resolution=0.1, directions=24, seed=3)
    whole = octoreach.CapabilityMap.build_for_arm(robot, ("base_link", "tool0"), block_size=4, progress=False, **kw)
    report = octo_cluster.BuildReport()
    split = octo_cluster.build_capability_split(robot, ("base_link", "tool0"), cluster="local", block_size=4,
                                                progress=False, robot_spec={"name": "test_arm"}, report=report, **kw)
    a, b = tmp_path / "whole.orcm", tmp_path / "split.orcm"
    whole.save(str(a), with_solutions=True)
    split.save(str(b), with_solutions=True)
    assert a.read_bytes() == b.read_bytes() and whole.voxel_count > 0
    assert len([k for k in report.tasks if k.startswith("block")]) > 2


def run_cli(*args, timeout=120):
    return subprocess.run([sys.executable, "-m", "octoreach.cli", *map(str, args)], capture_output=True, text=True,
                          timeout=timeout, env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})


def test_cli_build_many_on_the_cluster_address(cluster, reference, tmp_path):
    import yaml

    job = tmp_path / "job.yaml"
    job.write_text(yaml.safe_dump({**JOB, "out": "maps"}))
    r = run_cli("build-many", job, "--cluster", cluster.address, "--no-cache", "--quiet", timeout=600)
    assert r.returncode == 0, r.stderr
    assert "8 maps (8 built, 0 from the cache)" in r.stdout
    assert tree_bytes(tmp_path / "maps") == reference


def test_unreachable_cluster_fails_within_seconds(tmp_path):
    import socket

    with socket.socket() as s:  # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    job = tmp_path / "job.json"
    job.write_text(__import__("json").dumps(JOB))
    t0 = time.monotonic()
    r = run_cli("build-many", job, "--cluster", f"127.0.0.1:{port}", "--quiet")
    assert r.returncode == 2 and "cannot reach the Ray cluster" in r.stderr and time.monotonic() - t0 < 30
    t0 = time.monotonic()
    with pytest.raises(ConnectionError, match="cannot reach the Ray cluster at 10.255.255.1:6379 within 2 s"):
        octo_cluster._check_reachable("10.255.255.1:6379", timeout=2.0)  # no host, or something that is not Ray
    assert time.monotonic() - t0 < 10


def test_job_robot_without_arms_takes_its_default_arm(tmp_path):
    from octoreach import jobs

    job = tmp_path / "job.json"
    job.write_text(__import__("json").dumps({**JOB, "robots": ["test_arm"]}))
    caps = jobs.read_job(job).capability
    assert [c.arm.tip_link for c in caps] == ["tool0", "tool0"]  # its only arm, "arm", at both resolutions


@pytest.mark.parametrize("change, message", [
    ({"robots": ["no_such_robot"], "arms": ["arm"]}, "robots[0]: cannot load the robot"),
    ({"robots": [{"name": "test_arm", "arms": "arm"}]}, "robots[0]: 'arms' must list"),
    ({"robots": [{"name": "test_arm", "arms": ["no_arm"]}]}, "robots[0]: arms[0]"),
    ({"resolutions": [0.1, -1]}, "resolutions[1]"),
    ({"surfaces": [{"name": "t", "rectangle": {"size": [1, 1]}}]}, "surfaces[0]"),
    ({"surface": {"theta_binz": 4}}, "surface.theta_binz"),
    ({"capability": {"resolution": 0.1}}, "capability.resolution"),
    ({"colour": "red"}, "unknown key 'colour'"),
])
def test_job_file_errors_fail_before_any_work(tmp_path, change, message):
    job = tmp_path / "job.json"
    job.write_text(__import__("json").dumps({**JOB, **change}))
    r = run_cli("build-many", job, "--cluster", "127.0.0.1:1", "--quiet")  # checked before the cluster is asked
    assert r.returncode == 2 and message in r.stderr and "cannot reach" not in r.stderr, r.stderr
    assert not (tmp_path / "build_many_out").exists()


def test_design_study_example_runs_on_the_cluster(cluster, tmp_path):
    import json

    example = Path(__file__).resolve().parents[2] / "examples" / "design_study.py"
    r = subprocess.run([sys.executable, str(example), "--robot", "test_arm", "--arm", "base_link", "tool0",
                        "--table", "0.4", "0.3", "0.25", "--heights", "0", "0.1", "0.2", "--resolution", "0.2",
                        "--directions", "24", "--cluster", cluster.address, "--out", str(tmp_path), "--no-cache"],
                       capture_output=True, text=True, timeout=600,
                       env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    assert r.returncode == 0, r.stderr
    shares = json.loads((tmp_path / "share_vs_height.json").read_text())["shares"]
    assert list(shares) == ["0.0", "0.1", "0.2"] and all(0 <= v <= 1 for v in shares.values())
    assert (tmp_path / "share_vs_height.png").stat().st_size > 1000 and "best share" in r.stdout
