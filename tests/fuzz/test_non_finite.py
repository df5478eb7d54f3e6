"""NaN and infinity, API-wide: every public callable of octoreach._core is called with NaN, +inf and -inf
in each of its number arguments in turn (a scalar, or one entry of an array, list or mapping of numbers;
the other arguments valid) and must raise ValueError naming the argument, never answer. Likewise every
number field of the options classes, given as a keyword to the builds and searches that take them.

Signatures and valid values come from the wrong-types sweep (test_wrong_types.py), so a function added
later is swept without editing this file."""
from __future__ import annotations

import math

import numpy as np
import pytest

import octoreach as o
from octoreach import _core
from test_wrong_types import ALIASES, _required, swept_signatures, sweep, valid_value  # noqa: F401

BAD = (math.nan, math.inf, -math.inf)

# Sensor data, not a query: a depth cloud marks pixels without a return with NaN, and insert drops those rows
# (as OctoMap's insertPointCloud does); max_range <= 0 or infinite means unlimited. Both documented.
ALLOWED = {("ExplorationMap.insert", "points"), ("ExplorationMap.insert", "max_range")}

# Valid values the wrong-types sweep does not need (it passes a wrong type there, never a number).
VALID = {
    ("PoseSampler.discount", "pose"): np.array([0.5, 0.0, 0.0, 0.0]),
    ("base_pose", "pose"): np.array([0.5, 0.0, 0.0, 0.0]),
    ("CostMap.__init__", "grid"): np.zeros((4, 4), dtype=np.float32),
    ("CostMap.__init__", "origin"): np.array([0.0, 0.0]),
    ("Scene.add_closed_box", "face"): "-x",
    ("Chain.ik", "seed"): "zeros",
    ("choose_view", "bases"): np.eye(4)[None],
    ("choose_view", "current"): 0,
    ("choose_view", "options"): o.ExploreOptions(),
    ("choose_view", "memory"): _core.ChoiceMemory(),
    ("choose_view", "strategy"): "frontier_void",
    ("ExplorerCore.__init__", "strategy"): "frontier_void",
    ("ExplorerCore.__init__", "search_space"): np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]),
}


def _valid(world, label, pname, ann):
    v = VALID.get((label, pname))
    if isinstance(v, str) and v == "zeros":
        return np.zeros(world["by_name"]["chain"].dof)
    if v is not None:
        return v
    if label == "Robot.configuration" and pname == "values":
        return {world["instances"]["Robot"].joint_names[0]: 0.0}
    if label in ("Obstacles.add_mesh", "Shape.mesh_file") and pname == "path":
        return str(world["dir"] / "tetra.stl")
    return valid_value(world, label, pname, ann)


def bad_variants(v, bad):
    """`v` with `bad` in its first number (nothing when `v` holds no float)."""
    if isinstance(v, (bool, np.bool_)) or isinstance(v, (int, np.integer)):
        return []
    if isinstance(v, float):
        return [bad]
    if isinstance(v, np.ndarray):
        if v.dtype.kind != "f" or v.size == 0:
            return []
        a = v.copy()
        a.flat[0] = bad
        return [a]
    if isinstance(v, dict) and v and all(isinstance(x, float) for x in v.values()):
        return [{k: bad for k in v}]
    if isinstance(v, (list, tuple)) and v:
        if all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
            return [[bad] + list(v[1:])]
        if all(isinstance(x, (list, tuple)) for x in v):
            return [[[bad] + list(v[0][1:])] + [list(x) for x in v[1:]]]
    return []


def names_the_argument(pname: str, msg: str) -> bool:
    return pname.startswith("arg") or pname in msg or pname.rstrip("s") in msg or ALIASES.get(pname, "@") in msg


def _outcome(f):
    try:
        f()
        return None
    except BaseException as e:  # noqa: BLE001 - anything but a ValueError naming the argument is a finding
        return e


def _findings(results):
    accepted, wrong, n = [], [], 0
    for label, pname, bad, err in results:
        n += 1
        if err is None:
            if (label, pname) not in ALLOWED:
                accepted.append(f"{label}({pname}={bad})")
        elif not isinstance(err, ValueError):
            wrong.append(f"{label}({pname}={bad}): {type(err).__name__}: {str(err)[:160]}")
        elif not names_the_argument(pname, str(err)):
            wrong.append(f"{label}({pname}={bad}): the ValueError does not name '{pname}': {str(err)[:160]}")
    return n, accepted, wrong


@pytest.fixture(scope="module")
def world(sweep):  # noqa: F811 - the wrong-types sweep's fixture, reused
    # a tetrahedron mesh file for Obstacles.add_mesh
    (sweep["dir"] / "tetra.stl").write_text(
        "solid t\n" + "".join(
            f"facet normal 0 0 0\nouter loop\nvertex {a}\nvertex {b}\nvertex {c}\nendloop\nendfacet\n"
            for a, b, c in (("0 0 0", "1 0 0", "0 1 0"), ("0 0 0", "0 0 1", "1 0 0"),
                            ("0 0 0", "0 1 0", "0 0 1"), ("1 0 0", "0 0 1", "0 1 0"))) + "endsolid t\n")
    return sweep


def sweep_core(world):
    """(label, argument, bad value, exception or None) for every number argument of every callable."""
    for label, target, params in swept_signatures(world):
        n = _required(params)
        for i, (pname, ann, _) in enumerate(params):
            if "int" in ann.lower() and "float" not in ann.lower():
                continue  # integer arguments (keys, indices): NaN is a wrong type there, swept by test_wrong_types
            base = [_valid(world, label, qn, qa) for (qn, qa, _) in params[: max(i + 1, n)]]
            for bad in BAD:
                for v in bad_variants(base[i], bad):
                    args = list(base)
                    args[i] = v
                    yield label, pname, bad, _outcome(lambda: target(*args))


def test_every_number_argument_rejects_nan_and_infinity(world):
    n, accepted, wrong = _findings(sweep_core(world))
    print(f"swept {n} calls")
    assert n > 150
    assert not accepted, "NaN or inf accepted:\n" + "\n".join(accepted)
    assert not wrong, "\n".join(wrong)


# Builds and searches that take `options=None, **kwargs`: each number field of the options class as a keyword.
def _option_calls(world):
    bn = world["by_name"]
    m = bn["map"]
    cam = o.DepthCamera(16, 12, 1.0, 3.0)
    return {
        "CapabilityMap.build": ("CapabilityMapOptions", lambda **k: _core.CapabilityMap.build(
            bn["chain"], progress=False, resolution=k.pop("resolution", 0.3), directions=k.pop("directions", 8), **k)),
        "InversePointMap.build": ("PointMapOptions", lambda **k: _core.InversePointMap.build(
            bn["robot"], bn["capability_map"], progress=False, **k)),
        "SurfaceMap.build": ("SurfaceMapOptions", lambda **k: _core.SurfaceMap.build(
            bn["robot"], bn["capability_map"], bn["surface"], progress=False, **k)),
        "next_best_view": ("NbvOptions", lambda **k: _core.next_best_view(m, cam, **k)),
        "score_views": ("NbvOptions", lambda **k: _core.score_views(m, cam, np.eye(4)[None], **k)),
    }


def test_every_number_option_rejects_nan_and_infinity(world):
    def results():
        for label, (opts, call) in _option_calls(world).items():
            defaults = getattr(_core, opts)()
            for field, prop in vars(getattr(_core, opts)).items():
                if not isinstance(prop, property) or prop.fset is None:
                    continue
                v = getattr(defaults, field)
                if isinstance(v, (bool, int)) or not isinstance(v, (float, np.ndarray, list, tuple)):
                    continue
                for bad in BAD:
                    for w in bad_variants(v if not isinstance(v, tuple) else list(v), bad):
                        yield label, field, bad, _outcome(lambda: call(**{field: w}))
    n, accepted, wrong = _findings(results())
    print(f"swept {n} keywords")
    assert n > 40
    assert not accepted, "NaN or inf accepted:\n" + "\n".join(accepted)
    assert not wrong, "\n".join(wrong)
