"""CPU time of the Python layers on valid input: room, polygon and job files read and checked, the rest of a room
built per surface, and a map cache hit with its key check (octoreach.cache_check) and its digest check (the
SHA-256 of the entry's bytes against its note). Medians of process CPU
seconds (not wall time: the machine is shared), printed as JSON in milliseconds.

    python benchmarks/python_layers.py
"""
from __future__ import annotations

import json
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

import octoreach as o
from octoreach import arms, jobs, rooms
from octoreach.cache import MapCache, capability_key_fields, capability_options, key_of


def cpu_ms(fn, n: int) -> float:
    times = []
    for _ in range(n):
        t = time.process_time()
        fn()
        times.append(time.process_time() - t)
    return round(statistics.median(times) * 1e3, 3)


def files(d: Path) -> dict:
    room = rooms.Room()
    for i in range(60):
        room.add_table(f"t{i}", 1.2, 0.8, 0.75, x=3.0 * (i % 8), y=3.0 * (i // 8))
    room.add_shelf("shelf", 0.8, 0.35, [0.4, 0.8, 1.2], x=-2)
    for i in range(40):
        room.add_box(f"w{i}", [0.05, 2, 2], [i, -3, 1])
    room.save(d / "room.json")
    room.save(d / "room.yaml")
    ring = np.linspace(0, 6.2, 5000)
    (d / "poly.json").write_text(json.dumps({"vertices": [[float(np.cos(t)), float(np.sin(t)), 0.7] for t in ring]}))
    job = {"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}], "resolutions": [0.2, 0.3],
           "capability": {"directions": 16}, "surfaces": [{"room": str(d / "room.yaml")}], "base_heights": [0.0, 0.1],
           "out": str(d / "out")}
    (d / "job.json").write_text(json.dumps(job))
    return {"room_json_load": cpu_ms(lambda: rooms.Room.load(d / "room.json"), 20),
            "room_yaml_load": cpu_ms(lambda: rooms.Room.load(d / "room.yaml"), 10),
            "polygon_5000_vertices_json": cpu_ms(lambda: rooms.surface_from_file(d / "poly.json"), 10),
            "read_job_2x2x64_maps": cpu_ms(lambda: jobs.read_job(d / "job.json"), 5),
            "room_obstacles_per_surface_all": cpu_ms(lambda: [room.obstacles(without=n) for n in room.surfaces], 5)}


def digest_check(cache: MapCache, fields: dict) -> None:
    """What a hit adds for the digest: the entry's bytes hashed through its descriptor, its note read and compared."""
    import os

    from octoreach.cache_files import fd_digest, note_disagrees, read_note

    key = key_of(fields)
    path = cache.path("capability", key)
    fd = os.open(path, os.O_RDONLY)
    try:
        found, _ = fd_digest(fd)
    finally:
        os.close(fd)
    assert note_disagrees(read_note(path.with_suffix(".json"), "capability", key), found) is None


def cache_hits() -> dict:
    from octoreach import cache_check

    out = {}
    for name, robot, arm, kw in [("test_arm 0.2 m, 16 directions", o.robots.test_arm(), ("base_link", "tool0"),
                                  dict(resolution=0.2, directions=16)),
                                 ("test_arm 0.05 m, 50 directions", o.robots.test_arm(), ("base_link", "tool0"),
                                  dict(resolution=0.05, directions=50)),
                                 ("pr2 right_arm 0.1 m, 50 directions", o.robots.pr2(), "right_arm",
                                  dict(resolution=0.1, directions=50))]:
        cache = MapCache(tempfile.mkdtemp())
        m = arms.capability_map(robot, arm, cache=cache, progress=False, **kw)
        fields = capability_key_fields(robot, o.Arm.resolve(robot, arm), capability_options(None, **kw))
        out[name] = {"voxels": m.voxel_count, "entry_bytes": cache.path("capability", key_of(fields)).stat().st_size,
                     "key_check_ms": cpu_ms(lambda: cache_check.capability_mismatch(m, fields, robot), 300),
                     "digest_check_ms": cpu_ms(lambda: digest_check(cache, fields), 300),
                     "hit_ms": cpu_ms(lambda: arms.capability_map(robot, arm, cache=cache, progress=False, **kw), 20)}
    return out


def main() -> None:
    with tempfile.TemporaryDirectory() as d:
        result = {"files": files(Path(d)), "cache_hits": cache_hits(), "unit": "CPU milliseconds, medians"}
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
