"""Seeded file-damage fuzzer over every file kind octoreach reads.

Seeds: a capability map (.orcm, with and without solutions), an inverse point map (.orpm), a surface
map (.orsm) and an exploration map written as OctoMap .bt, all of the test arm, built coarse. Each case
damages one seed (truncation, byte flips, a forged header with a recomputed checksum, a forged .bt
tree) or is a foreign file, and is loaded (and, when it loads, used) in a child process with a memory
cap; a map file is loaded by its kind's loader and by map_files.load (whichever kind its header names). A child that dies is a crash, one that stops making progress is a hang; the expected outcomes are
"loaded" or OSError (FileNotFoundError excluded), anything else is a wrong error.

Cases run in batches in one child (a crash or a hang is pinned on its case and the child restarted
after it), so a few hundred cases take seconds, not minutes.

    python tests/fuzz/file_fuzz.py --cases 3000 --seed 1     # prints counts per category
"""
from __future__ import annotations

import argparse
import json
import os
import random
import select
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from collections import Counter, defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from robust_util import MAGIC, bt_file, read_map, write_map  # noqa: E402

MEM_CAP = 2 << 30
CASE_TIMEOUT = 20.0

# ---- seeds ----


def make_seeds(out: Path) -> dict[str, Path]:
    import numpy as np

    import octoreach as o

    robot = o.robots.test_arm()
    chain = robot.chain("base_link", "tool0")
    cap = o.CapabilityMap.build(chain, resolution=0.2, directions=16, progress=False, seed=1)
    seeds = {}
    seeds["orcm_sol"] = out / "cap_sol.orcm"
    cap.save(str(seeds["orcm_sol"]), with_solutions=True)
    seeds["orcm"] = out / "cap.orcm"
    cap.save(str(seeds["orcm"]), with_solutions=False)
    pm = o.InversePointMap.build(robot, cap, theta_bins=8, progress=False)
    seeds["orpm"] = out / "point.orpm"
    pm.save(str(seeds["orpm"]))
    table = o.Surface.rectangle(0.6, 0.4, 0.4, x=0.55)
    sm = o.SurfaceMap.build(robot, cap, table, resolution=0.2, theta_bins=8, z_range=(0, 0), progress=False)
    seeds["orsm"] = out / "surf.orsm"
    sm.save(str(seeds["orsm"]))
    m = o.ExplorationMap(resolution=0.1)
    m.insert(np.random.default_rng(0).uniform([1, -0.5, 0], [1.6, 0.5, 0.6], (1500, 3)), [0, 0, 0.3])
    seeds["bt"] = out / "explore.bt"
    m.write_bt(str(seeds["bt"]))
    return seeds


# ---- damage ----

def truncate(data: bytes, rng: random.Random) -> bytes:
    return data[: rng.randrange(0, len(data))]


def flip_bytes(data: bytes, rng: random.Random) -> bytes:
    b = bytearray(data)
    for _ in range(rng.choice((1, 1, 2, 4, 16))):
        i = rng.randrange(len(b))
        b[i] = rng.randrange(256) if rng.random() < 0.5 else b[i] ^ (1 << rng.randrange(8))
    return bytes(b)


_ABSURD_VALUES = ["0", "-1", "nan", "inf", "-inf", "1e308", "1e-308", "4294967297", "9223372036854775807",
                  "18446744073709551616", "-9223372036854775808", "", "x", "0 0 0", "nan nan nan", "1 2",
                  "\u00e9\u00e8", "1e2x", " 5", "0x10"]


def forge_header(path: Path, rng: random.Random) -> bytes:
    """One to three header values replaced (or entries dropped/added), payload possibly re-encoded
    with a size field changed, checksum recomputed: only the content checks can catch it."""
    m = read_map(path)
    keys = list(m.header)
    for _ in range(rng.choice((1, 1, 2, 3))):
        r = rng.random()
        if r < 0.75:
            m.header[rng.choice(keys)] = rng.choice(_ABSURD_VALUES)
        elif r < 0.9:
            m.header.pop(rng.choice(keys), None)
        else:
            m.header[rng.choice(["extra", "x" * 50])] = rng.choice(_ABSURD_VALUES)
    payload = None
    if rng.random() < 0.3:  # damage the payload too, but keep it decompressible and checksummed
        raw = bytearray(m.payload())
        if raw:
            for _ in range(rng.choice((1, 4, 32))):
                i = rng.randrange(len(raw))
                raw[i] = rng.randrange(256)
            if rng.random() < 0.3:
                raw = raw[: rng.randrange(len(raw))]
        payload = bytes(raw)
    with tempfile.NamedTemporaryFile(delete=False) as f:
        tmp = f.name
    try:
        write_map(tmp, m, payload)
        return open(tmp, "rb").read()
    finally:
        os.unlink(tmp)


def forge_kind(path: Path, rng: random.Random) -> bytes:
    m = read_map(path)
    m.kind = rng.choice([b"", b"\xff\xfe\x80", b"capability", b"point", b"surface", bytes(rng.randrange(256) for _ in range(8))])
    with tempfile.NamedTemporaryFile(delete=False) as f:
        tmp = f.name
    try:
        write_map(tmp, m)
        return open(tmp, "rb").read()
    finally:
        os.unlink(tmp)


def forge_sizes(path: Path, rng: random.Random) -> bytes:
    """The raw / compressed size fields or the header length set to absurd values (checksum intact)."""
    data = bytearray(open(path, "rb").read())
    m = read_map(path)
    text = "".join(f"{k}={v}\n" for k, v in m.header.items()).encode()
    pos_hlen = len(MAGIC) + 8 + len(m.kind)
    pos_sizes = pos_hlen + 4 + len(text)
    which = rng.randrange(3)
    value = rng.choice([0, 1, 2**31, 2**32 - 1, 2**33, 2**40, 2**63, 2**64 - 1])
    if which == 0:
        data[pos_hlen:pos_hlen + 4] = struct.pack("<I", value & 0xFFFFFFFF)
    else:
        off = pos_sizes + (0 if which == 1 else 8)
        data[off:off + 8] = struct.pack("<Q", value & (2**64 - 1))
    return bytes(data)


def absurd_tree(rng: random.Random) -> bytes:
    """OctoMap .bt files with absurd trees: huge pruned leaves, deep chains, wrong sizes, bad resolution."""
    kind = rng.randrange(5)
    res = rng.choice(["0.1", "0.05", "1", "1e-9", "nan", "-0.1", "1e30", "0"])
    if kind == 0:  # 8 occupied leaves at depth 1: 2^48 cells
        return bt_file([b"\xaa\xaa"], size=9, res=float(res) if res not in ("nan",) else 0.1)
    if kind == 1:  # a chain of inner nodes ending in a pruned leaf at a random depth
        depth = rng.randrange(1, 17)
        nodes = [b"\x03\x00"] * depth + [b"\xaa\xaa"]
        return bt_file(nodes, size=depth + 1 + 8).replace(b"res 0.1", b"res " + res.encode())
    if kind == 2:  # random node bytes
        n = rng.randrange(1, 200)
        return bt_file([bytes(rng.randrange(256) for _ in range(2 * n))], size=rng.randrange(0, 10**6))
    if kind == 3:  # header fields absurd
        return (f"# Octomap OcTree binary file\nid {rng.choice(['OcTree', 'ColorOcTree', 'x'])}\n"
                f"size {rng.choice(['-1', '999999999999', 'nan', '1'])}\nres {res}\ndata\n").encode() + b"\xaa\xaa"
    return bt_file([b"\xaa\xaa"] * rng.randrange(1, 50), size=9).replace(b"res 0.1", b"res " + res.encode())


def foreign(rng: random.Random) -> bytes:
    return rng.choice([
        b"",
        b"\x00" * rng.randrange(1, 5000),
        bytes(rng.randrange(256) for _ in range(rng.randrange(1, 3000))),
        b"<robot name='x'></robot>",
        b"\x89PNG\r\n\x1a\n" + bytes(100),
        MAGIC,
        MAGIC + struct.pack("<I", 1),
        b"# Octomap OcTree binary file\n",
        "é".encode("latin-1") * 100,
    ])


# The loaders: the file kinds and what the child does with each.
KINDS = ["orcm", "orpm", "orsm", "bt"]
SEED_OF = {"orcm": ["orcm", "orcm_sol"], "orpm": ["orpm"], "orsm": ["orsm"], "bt": ["bt"]}


def make_cases(seeds: dict[str, Path], n: int, seed: int, out: Path) -> list[dict]:
    rng = random.Random(seed)
    cases = []
    categories = []
    for kind in KINDS:
        if kind == "bt":
            categories += [(kind, c) for c in ("truncate", "flip", "absurd_tree", "foreign")]
        else:
            categories += [(kind, c) for c in ("truncate", "flip", "forged_header", "forged_kind", "forged_sizes",
                                               "foreign")]
    for i in range(n):
        kind, cat = categories[i % len(categories)]
        src = seeds[rng.choice(SEED_OF[kind])]
        data = open(src, "rb").read()
        if cat == "truncate":
            blob = truncate(data, rng)
        elif cat == "flip":
            blob = flip_bytes(data, rng)
        elif cat == "forged_header":
            blob = forge_header(src, rng)
        elif cat == "forged_kind":
            blob = forge_kind(src, rng)
        elif cat == "forged_sizes":
            blob = forge_sizes(src, rng)
        elif cat == "absurd_tree":
            blob = absurd_tree(rng)
        else:
            blob = foreign(rng)
        p = out / f"case{i:05d}.{kind}"
        p.write_bytes(blob)
        cases.append({"i": i, "kind": kind, "category": f"{kind}/{cat}", "path": str(p)})
    return cases


# ---- the child ----

CHILD = r"""
import json, resource, sys
cap = int(sys.argv[1])
if cap:
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
import numpy as np, octoreach as o
rng = np.random.default_rng(0)
robot = o.robots.test_arm()

def use(kind, path):
    if kind in ('orcm', 'orpm', 'orsm'):
        try:  # whichever kind the file names (the registry of map kinds): a map or OSError, nothing else
            repr(o.map_files.load(path))
        except OSError:
            pass
    if kind == 'orcm':
        m = o.CapabilityMap.load(path)
        m.reachability(rng.uniform(-1, 1, (20, 3))); m.voxels(); repr(m)
        if m.voxel_count:
            o.InversePointMap.build(robot, m, theta_bins=4, progress=False)
    elif kind == 'orpm':
        m = o.InversePointMap.load(path)
        m.reachability(np.column_stack([rng.uniform(-1, 1, (20, 3)), rng.uniform(-3, 3, 20)])); m.voxels(); repr(m)
    elif kind == 'orsm':
        m = o.SurfaceMap.load(path)
        m.reachability(np.column_stack([rng.uniform(-1, 1, (20, 3)), rng.uniform(-3, 3, 20)])); m.voxels(); repr(m)
        if m.voxel_count:
            o.PoseSampler(m, seed=1, max_draws=2000).sample(2) if m.max_reachability > 0 else None
    else:
        # a quarter of the default cell limit: a valid tree right at the default limit (2^24 cells) loads
        # in over a minute on a loaded 2-core machine, which the per-case hang timeout would call a hang;
        # past this limit the loader must refuse before expanding, which is what the fuzzer checks
        m = o.ExplorationMap.from_file(path, max_cells=1 << 22)
        m.snapshot(); m.frontier_voids(); m.cells('occupied')
        s = o.Scene(); s.load_octomap(path); s.raycast([0, 0, 0.3], [1, 0, 0])
        ob = o.Obstacles(); ob.add_octree_file(path); ob.collides_box([0.1, 0.1, 0.1], np.eye(4))

for line in sys.stdin:
    c = json.loads(line)
    print('START', c['i'], flush=True)
    try:
        use(c['kind'], c['path'])
        outcome = 'loaded'
    except FileNotFoundError as e:
        outcome = 'wrong:FileNotFoundError'
    except OSError as e:
        outcome = 'oserror'
    except RuntimeError as e:
        # a sampler that finds nothing in a damaged but valid map says so; anything else is wrong
        outcome = 'loaded' if 'no valid base pose' in str(e) else 'wrong:RuntimeError:' + str(e)[:200]
    except ValueError as e:
        # a map that loads but does not fit the robot (forged links or dof) is refused on use
        outcome = 'refused_on_use' if 'capability map' in str(e) or 'robot' in str(e) else 'wrong:ValueError:' + str(e)[:200]
    except BaseException as e:
        outcome = 'wrong:' + type(e).__name__ + ':' + str(e)[:200]
    print('END', c['i'], outcome, flush=True)
"""


def run_cases(cases: list[dict], mem_cap: int = MEM_CAP, timeout: float = CASE_TIMEOUT, child_code: str = CHILD,
              startup: float = 60.0) -> list[dict]:
    """Runs the cases in batched children of `child_code` (reads JSON cases from stdin, prints START i / END i
    outcome); returns each case with its 'outcome' ("hang" when a case makes no progress within `timeout`
    seconds, "crash:<rc>" when it kills the child). The cases are fed from a file and the child's stderr goes to
    one, so neither pipe can fill up and block a batch."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    if "asan" in env.get("LD_PRELOAD", ""):
        mem_cap = 0  # AddressSanitizer reserves terabytes of address space: no RLIMIT_AS under it
    results = {}
    pending = list(cases)
    while pending:
        with tempfile.TemporaryFile("w+") as feed, tempfile.TemporaryFile("w+") as errors:
            feed.writelines(json.dumps(c) + "\n" for c in pending)
            feed.seek(0)
            child = subprocess.Popen([sys.executable, "-c", child_code, str(mem_cap)], stdin=feed,
                                     stdout=subprocess.PIPE, stderr=errors, env=env, text=True, bufsize=1)
            current = None
            last = time.monotonic()
            while True:  # startup: importing octoreach (slow under sanitizers)
                limit = (startup if current is None and not results else timeout) - (time.monotonic() - last)
                r, _, _ = select.select([child.stdout], [], [], max(0.0, limit))
                if not r:
                    child.kill()
                    child.wait()
                    if current is None:
                        errors.seek(0)
                        raise RuntimeError("the fuzz child did not start: " + errors.read()[-2000:])
                    results[current] = "hang"
                    break
                line = child.stdout.readline()
                if not line:
                    rc = child.wait()
                    if current is not None:
                        results[current] = f"crash:{rc}"
                    elif rc != 0 and len(results) < len(cases):
                        errors.seek(0)
                        raise RuntimeError("the fuzz child failed: " + errors.read()[-2000:])
                    break
                last = time.monotonic()
                parts = line.split(maxsplit=2)
                if parts[0] == "START":
                    current = int(parts[1])
                elif parts[0] == "END":
                    results[int(parts[1])] = parts[2].strip()
                    current = None
            if child.poll() is None:
                child.kill()
            child.wait()
            child.stdout.close()
        pending = [c for c in pending if c["i"] not in results]
    return [dict(c, outcome=results[c["i"]]) for c in cases]


def tally(results: list[dict], classify) -> dict:
    """Counts per category and in total of each case's classify(outcome), with "cases"."""
    per = defaultdict(Counter)
    for r in results:
        per[r["category"]]["cases"] += 1
        per[r["category"]][classify(r["outcome"])] += 1
    total = Counter()
    for c in per.values():
        total.update(c)
    return {"categories": {k: dict(v) for k, v in sorted(per.items())}, "total": dict(total)}


def summarize(results: list[dict]) -> dict:
    return tally(results, lambda o: "crash" if o.startswith("crash") else "hang" if o == "hang" else
                 "wrong_error" if o.startswith("wrong") else o)


def fuzz(n: int, seed: int, workdir: Path) -> tuple[list[dict], dict]:
    seeds = make_seeds(workdir)
    cases = make_cases(seeds, n, seed, workdir)
    results = run_cases(cases)
    return results, summarize(results)


def run_main(doc: str, fuzz_function, bad: tuple, default_cases: int, line=None) -> int:
    """The command line of a fuzzer: --cases, --seed; prints the summary as JSON (and line(total) when given);
    status 1 when an outcome starts with one of `bad`."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", type=int, default=default_cases)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory() as d:
        results, summary = fuzz_function(args.cases, args.seed, Path(d))
    summary["seconds"] = round(time.monotonic() - t0, 1)
    summary["seed"] = args.seed
    failed = [r for r in results if r["outcome"].startswith(bad)]
    summary["failures"] = [{k: r[k] for k in ("i", "category", "outcome")} for r in failed[:50]]
    print(json.dumps(summary, indent=1))
    if line is not None:
        print(line(summary["total"]))
    return 1 if failed else 0


def main() -> int:
    return run_main(__doc__, fuzz, ("crash", "hang", "wrong"), 3000)


if __name__ == "__main__":
    sys.exit(main())
