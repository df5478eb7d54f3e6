"""Structure-aware fuzzer of the files users write: room files, job files (build-many) and polygon files.

Each case starts from a valid file of its kind (tables, polygons, shelves, boxes; a job of the test arm) and
breaks it one way, the way of its category: wrong types, NaN/inf, huge, tiny or negative values, deep
nesting, YAML aliases (bombs, recursive anchors, many aliases), duplicate keys, colliding or unsafe names
(paths, NUL, control characters, overlong), special files (the file itself, or a mesh, OctoMap, URDF or
room path inside it, is a FIFO, /dev/zero, a folder, a link to a device, or too large), counts past the
limits, or damaged text. The file is written as JSON or YAML and read in a child process with a memory
cap (Room.load, every surface's obstacles and the room's Scene, each asked a collision check, a ray and a
small depth image; surface_from_file; jobs.read_job).

Outcomes: accepted; a clean error (ValueError, TypeError or OSError with a message of one paragraph:
at most 2,000 characters); a traceback (any other exception); a memory blow-up (MemoryError); a crash
(the child died); a hang (no answer within the case timeout).

    python tests/fuzz/input_fuzz.py --cases 2000 --seed 1     # prints counts per category
"""
from __future__ import annotations

import copy
import json
import math
import os
import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from file_fuzz import run_cases, run_main, tally  # noqa: E402

MEM_CAP = 2 << 30
CASE_TIMEOUT = 60.0  # wall seconds: a hang never ends; a slow case on a loaded 2-core machine does
KINDS = ("room", "job", "polygon")
CATEGORIES = ("valid", "wrong_type", "nonfinite", "magnitude", "nesting", "aliases", "duplicate_keys", "names",
              "special_file", "paths", "counts", "damaged_text")

# ---- valid files ----


def _table(rng: random.Random, name: str) -> dict:
    entry = {"name": name, "rectangle": {"size": [round(rng.uniform(0.3, 2), 3), round(rng.uniform(0.3, 1.2), 3)],
                                         "height": round(rng.uniform(0.3, 1.1), 3), "x": round(rng.uniform(-3, 3), 3),
                                         "y": round(rng.uniform(-3, 3), 3), "yaw": round(rng.uniform(-3, 3), 3)}}
    if rng.random() < 0.5:
        entry["legs"] = 0.05
    if rng.random() < 0.3:
        entry["boxes"] = [{"name": f"{name}_cup", "size": [0.08, 0.08, 0.1], "xyz": [0, 0, 0.8]}]
    return entry


def _polygon(rng: random.Random, n: int | None = None) -> list:
    n = n or rng.randrange(3, 12)
    z = round(rng.uniform(0.3, 1.0), 3)
    r = rng.uniform(0.3, 1.0)
    return [[round(r * math.cos(2 * math.pi * i / n), 4), round(r * math.sin(2 * math.pi * i / n), 4), z]
            for i in range(n)]


def valid_room(rng: random.Random) -> dict:
    room = {"surfaces": [_table(rng, f"table_{i}") for i in range(rng.randrange(1, 4))]}
    if rng.random() < 0.5:
        room["surfaces"].append({"name": "poly", "vertices": _polygon(rng), "thickness": 0.03})
    if rng.random() < 0.5:
        room["shelves"] = [{"name": "shelf", "size": [0.8, 0.35], "boards": [0.4, 0.8, 1.2], "x": -2, "y": 1}]
    if rng.random() < 0.5:
        room["boxes"] = [{"name": "wall", "size": [0.05, 2, 2], "xyz": [4, 0, 1]}]
    if rng.random() < 0.4:
        room["cylinders"] = [{"name": "bin", "radius": round(rng.uniform(0.05, 0.3), 3),
                              "length": round(rng.uniform(0.2, 1.0), 3), "xyz": [-3, -2, 0.4],
                              "rpy": [0, round(rng.uniform(-1, 1), 3), 0]}]
    if rng.random() < 0.4:
        room["spheres"] = [{"name": "ball", "radius": round(rng.uniform(0.05, 0.3), 3), "xyz": [3, -2, 0.2]}]
    return room


def valid_job(rng: random.Random, room_file: str) -> dict:
    job = {"robots": [{"name": "test_arm", "arms": [["base_link", "tool0"]]}],
           "resolutions": [rng.choice([0.2, 0.3])], "capability": {"directions": 16, "seed": rng.randrange(5)},
           "surfaces": [{"name": "t", "rectangle": {"size": [0.4, 0.3], "height": 0.3, "x": 0.4}}],
           "base_heights": [0.0], "surface": {"theta_bins": 8}, "out": "out"}
    if rng.random() < 0.4:
        job["surfaces"].append({"room": room_file})
    return job


def valid_polygon(rng: random.Random):
    if rng.random() < 0.4:
        return _polygon(rng)
    out = {"vertices": _polygon(rng), "thickness": 0.03}
    if rng.random() < 0.5:
        out["legs"] = 0.05
    return out


# ---- breaking one thing ----

WRONG = [None, True, False, "x", "", "0.5", [], {}, [1, 2], {"a": 1}, [[[]]], 1, -1, 0, 1.5, "é" * 300,
         {"name": "t"}, ["a", "b", "c"], [None, None, None], "../../../etc/passwd", 10 ** 400]
NONFINITE = [float("nan"), float("inf"), float("-inf")]
MAGNITUDE = [1e300, -1e300, 1e-300, -1.0, 0.0, -0.0, 1e9, -1e9, 4e18, 10 ** 30, 10 ** 400, -(10 ** 400), 2 ** 63,
             1e-12, 123456789.123]


def _slots(data, path=()):
    """Every (path) of a node in the data (dict keys and list indices)."""
    yield path
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _slots(v, path + (k,))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _slots(v, path + (i,))


def _set(data, path, value):
    if not path:
        return value
    node = data
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    return data


def replace_some(data, rng: random.Random, pool, leaves_only: bool = False, count: int | None = None):
    data = copy.deepcopy(data)
    for _ in range(count or rng.choice((1, 1, 2, 3))):
        slots = [p for p in _slots(data) if p]
        if leaves_only:
            slots = [p for p in slots if not isinstance(_get(data, p), (dict, list))] or slots
        data = _set(data, rng.choice(slots), copy.deepcopy(rng.choice(pool)))
    return data


def _get(data, path):
    for k in path:
        data = data[k]
    return data


def dump(data, rng: random.Random, yaml_share: float = 0.5) -> str:
    import yaml

    if rng.random() < yaml_share:
        try:
            return yaml.safe_dump(data, sort_keys=False, width=1 << 20)
        except (yaml.YAMLError, ValueError, OverflowError):
            pass
    return json.dumps(data)


def nested(rng: random.Random, valid: dict, key: str) -> str:
    """A field nested deep: lists or mappings 10 to 100,000 levels, in JSON or YAML flow or block style."""
    depth = rng.choice([10, 40, 63, 65, 100, 999, 1001, 5000, 100000])
    style = rng.randrange(4)
    if style == 0:
        inner = "[" * depth + "1" + "]" * depth
    elif style == 1:
        inner = '{"a": ' * depth + "1" + "}" * depth
    elif style == 2:  # YAML block nesting: "- - - 1" is a list in a list in a list
        return f"{key}:\n  " + "- " * min(depth, 5000) + "1\n"
    else:  # unclosed
        inner = "[" * depth
    body = json.dumps({k: v for k, v in valid.items() if k != key})[1:-1]
    return "{" + (body + ", " if body else "") + json.dumps(key) + ": " + inner + "}"


def alias_text(rng: random.Random, valid, kind: str) -> str:
    """YAML with anchors: a bomb of `levels` levels of `width` aliases in a field that the checks reach, a
    recursive anchor, or thousands of small aliases."""
    style = rng.randrange(3)
    levels, width = rng.choice([(3, 3), (6, 8), (9, 9), (12, 10), (20, 2), (30, 3)])
    if style == 0:
        chain = ["&a0 [" + ", ".join(['"lol"'] * width) + "]"]
        for i in range(1, levels):
            chain.append(f"&a{i} [" + ", ".join([f"*a{i - 1}"] * width) + "]")
        bomb = "[" + ", ".join(chain) + "]"
        field = {"room": "surfaces", "job": "resolutions", "polygon": "vertices"}[kind]
        use = rng.choice([f"*a{levels - 1}", "[*a%d]" % (levels - 1), "{name: t, rectangle: {size: *a%d, height: 1}}"
                          % (levels - 1)])
        if kind == "polygon":
            return f"thickness: 0.03\nholder: {bomb}\nvertices: {use}\n" if rng.random() < 0.5 else \
                f"vertices: [{bomb}, {use}]\n"
        if kind == "job":
            return (f"robots: [{{name: test_arm, arms: [[base_link, tool0]], package_dirs: {bomb}}}]\n"
                    f"resolutions: {use}\ncapability: {{seed: *a{levels - 1}}}\n")
        return f"boxes: {bomb}\n{field}: {use}\n" if rng.random() < 0.5 else f"{field}: [{bomb}, {use}]\n"
    if style == 1:
        recursive = rng.choice(["&r [*r]", "&r {a: *r}", "&r [1, [2, *r]]"])
        field = {"room": "surfaces", "job": "surfaces", "polygon": "vertices"}[kind]
        return f"{field}: {recursive}\n"
    n = rng.choice([100, 5000, 20000])
    items = ", ".join(["*v"] * n)
    field = {"room": "surfaces", "job": "base_heights", "polygon": "vertices"}[kind]
    value = {"room": "&v {name: t, rectangle: {size: [1, 1], height: 1}}", "job": "&v 0.1",
             "polygon": "&v [0, 0, 1]"}[kind]
    return f"{field}: [{value}, {items}]\n"


def duplicate_text(rng: random.Random, valid, kind: str) -> str:
    if kind == "polygon" and isinstance(valid, list):
        valid = {"vertices": valid}
    keys = list(valid)
    key = rng.choice(keys)
    if rng.random() < 0.5:
        body = json.dumps(valid)[:-1]
        return body + ", " + json.dumps(key) + ": " + json.dumps(valid[key]) + "}"
    import yaml

    text = yaml.safe_dump(valid, sort_keys=False)
    return text + yaml.safe_dump({key: valid[key]}, sort_keys=False)


NAMES = ["a/b", "a_b", "s/0", "s_0", "S_0", "a\x00b", "a\nb", "a\\b", ".", "..", "", " ", "x" * 300, "x" * 200,
         "tab\tle", "é" * 50, "\u202e", "con", "a?b", "a b", "a*b", "/abs", "~", "$HOME", 5, None, ["n"]]


def named(rng: random.Random, valid, kind: str):
    data = copy.deepcopy(valid)
    if kind == "polygon":
        data = {"vertices": data} if isinstance(data, list) else data
        data["boxes"] = [{"name": rng.choice(NAMES), "size": [0.1, 0.1, 0.1]} for _ in range(2)]
        return data
    surfaces = data.setdefault("surfaces", [])
    if kind == "room" and rng.random() < 0.3:
        data["shelves"] = [{"name": rng.choice(["s", "a"]), "size": [0.8, 0.35], "boards": [0.4, 0.8]}]
    for _ in range(rng.choice((1, 2, 3))):
        surfaces.append({"name": rng.choice(NAMES), "rectangle": {"size": [0.4, 0.3], "height": 0.3, "x": 0.4}})
    if kind == "job":
        roll = rng.random()
        if roll < 0.3:
            data["resolutions"] = rng.choice([[0.2, 0.2000001], [0.2, 0.2], [0.3, 0.30000000000000004]])
        elif roll < 0.6:
            data["base_heights"] = rng.choice([[0.1, 0.1000001], [0.0, -0.0], [0.1, 0.1]])
        else:
            data["robots"] = [{"name": rng.choice(NAMES), "arms": [["base_link", "tool0"]]}]
    return data


def counts(rng: random.Random, valid, kind: str):
    n = rng.choice([101, 1001, 2000, 20001])
    if kind == "polygon":
        return _polygon(rng, min(n, 2000))  # the polygon size limit and its cost are the compiled library's
    data = copy.deepcopy(valid)
    roll = rng.random()
    if kind == "room":
        if roll < 0.4:
            data["surfaces"] = [{"name": f"t{i}", "rectangle": {"size": [0.5, 0.5], "height": 0.7, "x": 3.0 * i}}
                                for i in range(min(n, 1200))]
        elif roll < 0.7:
            data["shelves"] = [{"name": "s", "size": [0.8, 0.35], "boards": [0.1 * i for i in range(1, n)]}]
        else:
            key, entry = rng.choice([("boxes", {"size": [0.1, 0.1, 0.1]}), ("cylinders", {"radius": 0.1, "length": 0.2}),
                                     ("spheres", {"radius": 0.1})])
            data[key] = [{"name": f"o{i}", **entry, "xyz": [i, 0, 0]} for i in range(n + 20000)]
        return data
    if roll < 0.5:
        data["resolutions"] = [0.2 + 1e-6 * i for i in range(n)]
        data["base_heights"] = [0.01 * i for i in range(n)]
    else:
        data["surfaces"] = [{"name": f"t{i}", "rectangle": {"size": [0.4, 0.3], "height": 0.3, "x": 0.4}}
                            for i in range(min(n, 2000))]
    return data


def special_paths(workdir: Path) -> list[str]:
    fifo = workdir / "fifo"
    if not fifo.exists():
        os.mkfifo(fifo)
    folder = workdir / "folder"
    folder.mkdir(exist_ok=True)
    link = workdir / "link_to_zero"
    if not link.exists():
        link.symlink_to("/dev/zero")
    big = workdir / "big.json"
    if not big.exists():
        with open(big, "wb") as f:
            f.truncate(64 << 20)  # sparse: a 64 MB file of zeros
    return [str(fifo), "/dev/zero", "/dev/null", "/dev/urandom", str(folder), str(link), str(big), "/proc/self/mem",
            str(workdir / "missing.json"), "/etc/shadow"]


def with_paths(rng: random.Random, valid, kind: str, specials: list[str]):
    data = copy.deepcopy(valid)
    target = rng.choice(specials + ["", "x\x00y", 123, None, ["a"]])
    if kind == "room":
        key = rng.choice(["meshes", "octomaps"])
        data[key] = [{"name": "thing", "path": target}]
    elif kind == "polygon":
        data = {"vertices": data} if isinstance(data, list) else data
        data["meshes"] = [{"name": "thing", "path": target}]
    else:
        roll = rng.random()
        if roll < 0.3:
            data["robots"] = [{"urdf": target, "arms": [["base_link", "tool0"]]}]
        elif roll < 0.5:
            data["robots"][0]["package_dirs"] = rng.choice([5, "x", [target], None])
        elif roll < 0.8:
            data["surfaces"] = [{"room": target}]
        else:
            data["out"] = target
    return data


def damaged(rng: random.Random, text: str) -> str:
    roll = rng.random()
    if roll < 0.3:
        return text[: rng.randrange(len(text) + 1)]
    if roll < 0.6:
        chars = list(text)
        for _ in range(rng.choice((1, 2, 5))):
            chars[rng.randrange(len(chars))] = rng.choice("{}[]:,\"'&*!|>-#%@`\x00\t\n\\ 9e.")
        return "".join(chars)
    if roll < 0.8:
        return rng.choice(["", "null", "[]", "{}", "0", '"x"', "---\n...\n", "!!python/object:os.system x",
                           "!!binary aGVsbG8=", "a: !!set {x, y}", "a: 2001-12-14", "%YAML 9.9\n---\na: 1",
                           "- &a x\n- *b", "{a: 1}\n---\n{b: 2}", "\ufeff{}", "a: " + "9" * 5000])
    return "".join(chr(rng.randrange(1, 0x3000)) for _ in range(rng.randrange(1, 400)))


# ---- cases ----


def make_case(kind: str, category: str, rng: random.Random, workdir: Path, i: int, specials: list[str]) -> dict:
    room_file = workdir / f"room{i:05d}.json"
    room_file.write_text(json.dumps(valid_room(rng)))
    valid = {"room": valid_room, "polygon": valid_polygon}.get(kind, lambda r: valid_job(r, str(room_file)))(rng)
    path = workdir / f"case{i:05d}.{kind}"
    text = None
    if category == "valid":
        data = valid
    elif category == "wrong_type":
        data = replace_some(valid, rng, WRONG)
    elif category == "nonfinite":
        data = replace_some(valid, rng, NONFINITE, leaves_only=True)
    elif category == "magnitude":
        data = replace_some(valid, rng, MAGNITUDE, leaves_only=True)
    elif category == "nesting":
        key = rng.choice(list(valid) if isinstance(valid, dict) else ["vertices"])
        text = nested(rng, valid if isinstance(valid, dict) else {"vertices": valid}, key)
    elif category == "aliases":
        text = alias_text(rng, valid, kind)
    elif category == "duplicate_keys":
        text = duplicate_text(rng, valid, kind)
    elif category == "names":
        data = named(rng, valid, kind)
    elif category == "paths":
        data = with_paths(rng, valid, kind, specials)
    elif category == "counts":
        data = counts(rng, valid, kind)
    elif category == "damaged_text":
        text = damaged(rng, dump(valid, rng))
    else:  # special_file: the file itself
        return {"i": i, "kind": kind, "category": f"{kind}/{category}", "path": rng.choice(specials)}
    if text is None:
        text = dump(data, rng)
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    return {"i": i, "kind": kind, "category": f"{kind}/{category}", "path": str(path)}


def make_cases(n: int, seed: int, workdir: Path) -> list[dict]:
    rng = random.Random(seed)
    specials = special_paths(workdir)
    pairs = [(k, c) for k in KINDS for c in CATEGORIES]
    return [make_case(*pairs[i % len(pairs)], rng, workdir, i, specials) for i in range(n)]


CHILD = r"""
import json, os, resource, sys, warnings
cap = int(sys.argv[1])
if cap:
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
warnings.simplefilter("ignore")
import numpy as np
from octoreach import DepthCamera, _core, jobs, rooms
from octoreach.cli.build import output_stems

CAMERA = DepthCamera(16, 12, 1.0, 8.0)
LOOK = _core.look_at([0.0, -4.0, 1.5], [0.0, 0.0, 0.5])

def query(obstacles, scene=None):  # what a map build and a simulated camera ask of the room's shapes
    obstacles.collides_box([0.2, 0.2, 0.2], np.eye(4))
    if scene is not None:
        scene.raycast([0.0, 0.0, 3.0], [0.0, 0.0, -1.0], max_range=10.0)
        CAMERA.capture(scene, LOOK)

def use(kind, path):
    if kind == "room":
        room = rooms.Room.load(path)
        for name in room.surfaces:
            room.obstacles(without=name)
        json.dumps(room.description)
        repr(room)
        output_stems(list(room.surfaces), "room")
        query(room.obstacles(), room.scene())
    elif kind == "polygon":
        surface, obstacles = rooms.surface_from_file(path)
        surface.area
        surface.contains([[0.0, 0.0, 0.0]])
        len(obstacles)
        query(obstacles)
    else:
        job = jobs.read_job(path, out=os.path.dirname(path) + "/out")
        len(job)

for line in sys.stdin:
    c = json.loads(line)
    print("START", c["i"], flush=True)
    try:
        use(c["kind"], c["path"])
        outcome = "accepted"
    except (ValueError, TypeError, OSError) as e:
        message = str(e)
        outcome = "clean" if message.strip() and len(message) <= 2000 else "long_message:" + message[:100]
    except MemoryError as e:
        outcome = "memory"
    except BaseException as e:
        outcome = "traceback:" + type(e).__name__ + ":" + str(e)[:200]
    print("END", c["i"], " ".join(outcome.split()), flush=True)
"""


def summarize(results: list[dict]) -> dict:
    return tally(results, lambda o: o if o in ("hang", "memory") else o.split(":", 1)[0])


BAD = ("hang", "crash", "traceback", "long_message", "memory")


def fuzz(n: int, seed: int, workdir: Path) -> tuple[list[dict], dict]:
    cases = make_cases(n, seed, workdir)
    results = run_cases(cases, mem_cap=MEM_CAP, timeout=CASE_TIMEOUT, child_code=CHILD)
    return results, summarize(results)


def line(t: dict) -> str:
    return (f"input fuzz: {t.get('cases', 0)} cases: {t.get('accepted', 0)} accepted, {t.get('clean', 0)} clean "
            f"errors, {t.get('traceback', 0)} tracebacks, {t.get('hang', 0)} hangs, {t.get('memory', 0)} memory "
            f"blow-ups, {t.get('crash', 0)} crashes, {t.get('long_message', 0)} overlong messages")


def main() -> int:
    return run_main(__doc__, fuzz, BAD, 2000, line)


if __name__ == "__main__":
    sys.exit(main())
