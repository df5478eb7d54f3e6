"""Fuzzing a shared map cache: entries swapped between keys, headers forged with their checksum recomputed
(half of them with the entry's note rewritten to record the forged bytes, so that the header and content
checks are what must catch them), and symbolic links planted at every name a build writes (entry, note,
lock, marker, temporary files). The rule: no planted file or forged entry changes any file outside the cache
or any answer; an entry is either rebuilt (with a warning) or gives the honest map's answers. Each run is a
child process with a memory cap and a timeout; OCTOREACH_FUZZ_CACHE_CASES sets the number of forgeries
(`make fuzz` runs more)."""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from robust_util import run_python  # noqa: E402

FORGERIES = r"""
import json, random, shutil, sys, warnings
from pathlib import Path
import numpy as np
sys.path.insert(0, {util!r})
from robust_util import read_map, reseal, write_map
import octoreach as o
from octoreach import arms
from octoreach.cache import MapCache, capability_key_fields, capability_options, key_of

robot = o.robots.test_arm()
ARM = ("base_link", "tool0")
VARIANTS = [dict(resolution=0.2, directions=16, seed=1), dict(resolution=0.3, directions=16, seed=1),
            dict(resolution=0.2, directions=24, seed=1), dict(resolution=0.2, directions=16, seed=2),
            dict(resolution=0.25, directions=16, seed=1, block_size=2)]
work = Path({work!r})
cache = MapCache(work / "cache")
a = o.Arm.resolve(robot, ARM)
paths = []
honest = []
probe = np.random.default_rng(0).uniform(-0.9, 0.9, (300, 3))
for v in VARIANTS:
    m = arms.capability_map(robot, ARM, cache=cache, progress=False, **v)
    paths.append(cache.path("capability", key_of(capability_key_fields(robot, a, capability_options(None, **v)))))
    honest.append((m.voxel_count, m.reachability(probe).tolist(), m.resolution))
originals = [(p.read_bytes(), p.with_suffix(".json").read_bytes()) for p in paths]
VALUES = ["0", "-1", "nan", "inf", "1e308", "0.1", "0.10000000000000001", "0.2", "0.30000000000000004", "16", "24",
          "1", "2", "4", "0 0 1", "1 0 0", "0 1 0", "base_link", "wrist_3_link", "tool0", "shoulder_link", "", "x",
          "3529531254582503403", "1234", "0.001", "0.5", "99999999999999999999"]
rng = random.Random({seed})
results = []
for case in range({cases}):
    for p, (data, note) in zip(paths, originals):
        p.write_bytes(data)
        p.with_suffix(".json").write_bytes(note)
    target = rng.randrange(len(paths))
    source = rng.randrange(len(paths))
    m = read_map(paths[source])
    for _ in range(rng.choice((0, 1, 1, 2, 3))):
        m.header[rng.choice(list(m.header))] = rng.choice(VALUES)
    write_map(paths[target], m)
    changed = paths[target].read_bytes() != originals[target][0]
    resealed = rng.random() < 0.5
    if resealed:
        reseal(paths[target])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = arms.capability_map(robot, ARM, cache=cache, progress=False, **VARIANTS[target])
    answer = (got.voxel_count, got.reachability(probe).tolist(), got.resolution)
    rebuilt = any("deleting and rebuilding" in str(w.message) for w in caught)
    # A map of seed 1 whose header says seed 2, its note rewritten to match, is a whole, consistent map of the
    # arm: nothing short of building it again tells the two apart (the seed only steers the sampling). Counted,
    # not failed. Without the rewritten note the digest catches it.
    s, t = VARIANTS[source], VARIANTS[target]
    relabel = resealed and m.header.get("seed") == str(t["seed"]) and answer == honest[source] and \
        {{k: v for k, v in s.items() if k != "seed"}} == {{k: v for k, v in t.items() if k != "seed"}}
    results.append({{"case": case, "source": source, "target": target, "rebuilt": rebuilt, "resealed": resealed,
                     "changed": changed, "honest": answer == honest[target], "seed_relabel": relabel}})
print("RESULTS", json.dumps(results))
"""

PLANTED = r"""
import os, warnings
from pathlib import Path
warnings.simplefilter("ignore")
import octoreach as o
from octoreach import arms
from octoreach.cache import MapCache, capability_key_fields, capability_options, key_of
work = Path({work!r})
victim = work / "victim"
victim.write_text("mine")
robot = o.robots.test_arm()
cache = MapCache(work / "cache")
cache.directory.mkdir()
a = o.Arm.resolve(robot, ("base_link", "tool0"))
opts = dict(resolution=0.2, directions=16, seed=1)
key = key_of(capability_key_fields(robot, a, capability_options(None, **opts)))
entry = cache.path("capability", key)
names = [".octoreach-cache", entry.name, entry.with_suffix(".json").name, key + ".lock"]
names += [entry.name + ".tmp." + s for s in ("0", str(os.getpid()) + ".0", str(os.getpid() + 1) + ".0", "abcdef")]
for name in names:
    (cache.directory / name).symlink_to(victim)
m = arms.capability_map(robot, ("base_link", "tool0"), cache=cache, progress=False, **opts)
again = arms.capability_map(robot, ("base_link", "tool0"), cache=cache, progress=False, **opts)
print("VICTIM", victim.read_text(), m.voxel_count == again.voxel_count > 0)
"""


def test_swapped_and_forged_entries_never_change_an_answer(tmp_path):
    cases = int(os.environ.get("OCTOREACH_FUZZ_CACHE_CASES", "40"))
    util = str(Path(__file__).resolve().parent.parent / "python")
    child = run_python(FORGERIES.format(util=util, work=str(tmp_path), seed=7, cases=cases), timeout=60 + 5 * cases,
                       mem_bytes=3 << 30)
    assert not child.hung and child.returncode == 0, child.stderr[-3000:]
    results = json.loads(child.stdout.split("RESULTS", 1)[1])
    assert len(results) == cases
    wrong = [r for r in results if not r["honest"] and not r["seed_relabel"]]
    assert not wrong, wrong[:10]
    swapped = [r for r in results if r["source"] != r["target"] and not r["seed_relabel"]]
    assert swapped and all(r["rebuilt"] for r in swapped)
    assert all(r["rebuilt"] for r in results if r["changed"] and not r["resealed"])  # the digest catches those
    print(f"{cases} forgeries: {sum(r['rebuilt'] for r in results)} rebuilt, "
          f"{sum(r['honest'] and not r['rebuilt'] for r in results)} used with the honest answers, "
          f"{sum(r['seed_relabel'] for r in results)} seed relabels of a whole map with a rewritten note "
          f"(not detectable); {sum(r['resealed'] for r in results)} with the note rewritten")


def test_links_planted_at_every_name_a_build_writes_redirect_nothing(tmp_path):
    child = run_python(PLANTED.format(work=str(tmp_path)), timeout=300)
    assert not child.hung and child.returncode == 0, child.stderr[-3000:]
    assert "VICTIM mine True" in child.stdout, child.stdout
