"""Wrong types, API-wide: every public bound class and function of octoreach._core and every public
Python entry point (robots, arms, surface_maps, rooms) is called with a wrong-typed value in each of its
arguments (the others valid) and must raise TypeError or ValueError whose message names the argument;
no pybind11 cast message ("Unable to cast ...", "C++ type '?'") may reach a user.

pybind11's own message for a call that matches no signature ("incompatible function arguments. The
following argument types are supported: 1. (self, k: int) -> ... Invoked with: ...") is kept: it lists
every argument by name and type, which is what a user needs. Signatures are read from the docstrings
pybind11 writes, so a function added later is swept without editing this file."""
from __future__ import annotations

import inspect
import re

import numpy as np
import pytest

import octoreach as o
from octoreach import _core

CAST_MESSAGES = ("Unable to cast", "C++ type", "'?'", "cast Python instance")
OVERLOAD_MESSAGES = ("incompatible function arguments", "incompatible constructor arguments")
# Arguments whose message names the field of the description they become (Room.add_table(size_x=...) ->
# "surfaces[0] ('t').rectangle: 'size' must be a list of 2 numbers").
ALIASES = {"size_x": "size", "size_y": "size", "width": "size", "depth": "size", "description": "room"}


class Wrong:
    """A value no octoreach argument accepts."""

    def __repr__(self):
        return "<Wrong>"


WRONG = Wrong()


# ---- a valid world: one instance of each class, and valid values by argument name ----

@pytest.fixture(scope="module")
def sweep(world, tmp_path_factory):
    d = tmp_path_factory.mktemp("wrong_types")
    robot, chain, cap, surface, sm, pm, m, scene, obs = (world[k] for k in ("robot", "chain", "cap", "surface", "sm",
                                                                            "pm", "m", "scene", "obs"))
    m.write_bt(str(d / "m.bt"))
    cap.save(str(d / "cap.orcm"))
    cam = o.DepthCamera(16, 12, 1.0, 3.0)
    arm = o.Arm.from_links(robot, "base_link", "tool0")
    clusters = m.void_clusters()
    instances = {
        "Robot": robot, "Chain": chain, "CapabilityMap": cap, "Surface": surface, "SurfaceMap": sm,
        "InversePointMap": pm, "ExplorationMap": m, "Scene": scene, "Obstacles": obs, "DepthCamera": cam,
        "Arm": arm, "OrientationSet": o.OrientationSet.sphere(16), "PoseSampler": o.PoseSampler(sm, seed=1),
        "CameraIntrinsics": cam.intrinsics, "CostMap": None, "VoidCluster": clusters[0] if clusters else None,
        "CapabilityMapOptions": o.CapabilityMapOptions(), "PointMapOptions": o.PointMapOptions(),
        "SurfaceMapOptions": o.SurfaceMapOptions(), "NbvOptions": o.NbvOptions(),
        "AllowedCollisionOptions": o.AllowedCollisionOptions(), "ExploreOptions": o.ExploreOptions(),
        "NbvResult": o.next_best_view(m, cam, max_valid_poses=2),
        "ScoredViews": o.score_views(m, cam, np.repeat(np.eye(4)[None], 2, axis=0)),
        "CertifiedLookup": o.CertifiedLookup(cap, robot),
    }
    by_name = {
        "robot": robot, "chain": chain, "capability_map": cap, "surface": surface, "surface_map": sm,
        "scene": scene, "obstacles": obs, "map": m, "camera": cam, "arm": arm,
        "q": np.zeros(chain.dof), "Q": np.zeros((2, chain.dof)), "seed": 0, "seeds": None,
        "T": chain.fk(np.zeros(chain.dof)), "Ts": chain.fk_batch(np.zeros((2, chain.dof))),
        "pose": np.eye(4), "camera_pose": o._core.look_at([0, 0, 0.5], [1, 0, 0.5]), "base_pose": np.eye(4),
        "points": np.zeros((2, 3)), "lo": [1.0, -0.5, 0.0], "hi": [1.5, 0.5, 0.5],
        "vertices": np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), "triangles": np.array([[0, 1, 2]]),
        "size": [0.1, 0.1, 0.1], "radius": 0.1, "length": 0.2, "resolution": 0.1, "thickness": 0.02,
        "path": str(d / "m.bt"), "urdf": str(o.robots.project_urdf("test_arm")),
        "base_link": "base_link", "tip_link": "tool0", "link": "tool0", "name": "x", "names": [],
        "origin": [0, 0, 0.5], "direction": [1, 0, 0], "sensor_origin": [0, 0, 0.3], "eye": [0, 0, 0.5],
        "target": [1, 0, 0.5], "up": [0, 0, 1], "count": 16, "k": 1, "width": 16, "height": 12, "fov": 1.0,
        "max_range": 3.0, "kind": "free", "mode": "full", "poses": None, "reference_to_arm": np.eye(4),
        "orientations": [0, 1], "maps": [sm], "with_solutions": False, "key": 0, "keys": [0], "indices": [0],
        "factory": None, "cell": (0, 0, 0),
    }
    return dict(instances=instances, by_name=by_name, dir=d)


# ---- signatures from pybind11 docstrings ----

_SIG = re.compile(r"^(?:\d+\. )?(\w+)\((.*)\) -> ")


def _split_top(s: str) -> list[str]:
    out, depth, cur = [], 0, ""
    for ch in s:
        if ch in "[(" or ch == "{":
            depth += 1
        elif ch in "])" or ch == "}":
            depth -= 1
        if ch == "," and depth == 0:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur.strip())
    return out


def signatures(f) -> list[list[tuple[str, str, bool]]]:
    """Each overload of a pybind11 callable as [(name, annotation, has_default)], self and **kwargs left out."""
    sigs = []
    name = getattr(f, "__name__", "")
    for line in (f.__doc__ or "").splitlines():
        mt = _SIG.match(line.strip())
        if not mt or mt.group(1) != name:
            continue
        params = []
        for p in _split_top(mt.group(2)):
            if p.startswith("*"):
                continue
            pname, _, rest = p.partition(":")
            ann, eq, _ = rest.partition("=")
            params.append((pname.strip(), ann.strip(), bool(eq)))
        if params and params[0][0] == "self":
            params = params[1:]
        sigs.append(params)
    return sigs


def public_callables():
    """(label, owner class or None, attribute name) of every public callable of _core."""
    for cname in sorted(dir(_core)):
        if cname.startswith("_") or cname in ("set_progress_factory", "Cancelled"):
            continue
        obj = getattr(_core, cname)
        if inspect.isclass(obj):
            for attr, v in vars(obj).items():
                if attr.startswith("_") and attr != "__init__":
                    continue
                if isinstance(v, property):
                    continue
                yield f"{cname}.{attr}", obj, attr
        else:
            yield cname, None, cname


# ---- values ----

def valid_value(sweep, fname: str, pname: str, ann: str):
    bn = sweep["by_name"]
    inst = sweep["instances"]
    for cls, v in inst.items():
        if ann == cls or ann.endswith("." + cls):
            return v
    if fname.startswith(("Robot.", "Chain.to_robot_configuration")) and pname in ("q", "reference"):
        return inst["Robot"].home()
    if fname.startswith("Chain.") and pname == "arg0":
        return np.zeros(bn["chain"].dof)
    if fname in ("ExplorationMap.inside_hull", "ExplorationMap.key_of") and pname == "arg0":
        return [1.2, 0.0, 0.3]
    if fname.startswith("SurfaceMap.reachability") or fname.startswith("InversePointMap.reachability"):
        if pname == "poses":
            return np.zeros((2, 4))
    if fname in ("CapabilityMap.reachable", "score_views", "CertifiedLookup.reachable",
                 "CertifiedLookup.certain") and pname == "poses":
        return np.repeat(np.eye(4)[None], 2, axis=0)
    if fname == "InversePointMap.direct_reachability" and pname == "poses":
        return np.zeros((2, 4))
    if pname in bn:
        return bn[pname]
    if "[3, 1]" in ann:
        return np.array([0.1, 0.2, 0.3])
    if "[4, 1]" in ann:
        return np.array([0.1, 0.2, 0.3, 0.4])
    if "SupportsFloat" in ann or ann == "float":
        return 0.5
    if "SupportsInt" in ann or ann == "int":
        return 1
    if ann == "bool":
        return False
    if ann == "str":
        return "x"
    if ann.startswith("collections.abc.Sequence") or ann.startswith("list"):
        return []
    return None


def wrong_values(ann: str):
    """What to pass: a value of no accepted type, and, where the argument is a container or untyped
    (converted inside the binding), containers holding one."""
    out = [WRONG]
    if ann in ("typing.Any", "object") or "Sequence" in ann or ann.startswith(("list", "tuple")):
        out += [[WRONG], (WRONG, WRONG), {"a": WRONG}]
    return out


def check_message(label: str, pname: str, ann: str, err: BaseException):
    msg = str(err)
    assert not any(c in msg for c in CAST_MESSAGES), f"{label}({pname}=...): pybind11 cast message: {msg}"
    assert isinstance(err, TypeError), f"{label}({pname}=...): {type(err).__name__}, not TypeError: {msg}"
    if any(m in msg for m in OVERLOAD_MESSAGES):
        return  # pybind11's list of signatures: every argument by name and type
    # our own TypeError names the argument (unnamed ones: what they are) and the type it expects
    assert "must be" in msg, f"{label}({pname}=...): TypeError does not say what is expected: {msg}"
    if not pname.startswith("arg"):
        assert pname in msg or pname.rstrip("s") in msg or ALIASES.get(pname, "@") in msg, f"{label}({pname}=...): TypeError does not name the argument: {msg}"


def _call(target, args, kwargs):
    return target(*args, **kwargs)


def _target(sweep, owner, attr):
    if owner is None:
        return getattr(_core, attr), False
    v = vars(owner)[attr]
    if attr == "__init__":
        return owner, False
    if isinstance(v, staticmethod) or type(v).__name__ == "builtin_function_or_method":
        return getattr(owner, attr), False
    inst = sweep["instances"].get(owner.__name__)
    if inst is None:
        return None, True
    return getattr(inst, attr), False


def swept_signatures(sweep):
    """(label, callable, params) for every signature of every public callable of _core there is something to
    call it on."""
    for label, owner, attr in public_callables():
        target, skip = _target(sweep, owner, attr)
        if skip or target is None:
            continue
        doc_owner = vars(owner)[attr] if owner is not None else target
        if isinstance(doc_owner, staticmethod):
            doc_owner = doc_owner.__func__
        for params in signatures(doc_owner):
            yield label, target, params


def sweep_core(sweep):
    """Yields (label, pname, ann, exception or None, wrong value) for every argument of every callable."""
    for label, target, params in swept_signatures(sweep):
        for i, (pname, ann, _) in enumerate(params):
            for w in wrong_values(ann):
                args = []
                for j, (qn, qa, qd) in enumerate(params[: max(i + 1, _required(params))]):
                    args.append(w if j == i else valid_value(sweep, label, qn, qa))
                try:
                    _call(target, args, {})
                    err = None
                except BaseException as e:  # noqa: BLE001 - anything but TypeError/ValueError is a finding
                    err = e
                yield label, pname, ann, err, w


def _required(params):
    return max([j + 1 for j, (_, _, d) in enumerate(params) if not d], default=0)


def _run(f):
    try:
        f()
        return None
    except BaseException as e:  # noqa: BLE001 - anything but TypeError is a finding
        return e


def _collect(results):
    findings, accepted, n = [], [], 0
    for label, pname, ann, err, w in results:
        n += 1
        if err is None:
            accepted.append(f"{label}({pname}={w!r})")
            continue
        try:
            check_message(label, pname, ann, err)
        except AssertionError as a:
            findings.append(str(a).splitlines()[0])
    return n, findings, accepted


def test_every_bound_argument_rejects_a_wrong_type(sweep):
    n, findings, accepted = _collect(sweep_core(sweep))
    print(f"swept {n} calls")
    assert n > 500
    assert not findings, "\n".join(findings[:40])
    assert not accepted, "wrong types accepted silently:\n" + "\n".join(accepted[:40])


# Builds that take `options=None, **kwargs`: each field of the options class as a keyword of the wrong type.
KWARG_OPTIONS = {
    ("CapabilityMap", "build"): ("CapabilityMapOptions", lambda w: (w["by_name"]["chain"],)),
    ("CapabilityMap", "build_for_arm"): ("CapabilityMapOptions", lambda w: (w["by_name"]["robot"], ("base_link", "tool0"))),
    ("InversePointMap", "build"): ("PointMapOptions", lambda w: (w["by_name"]["robot"], w["by_name"]["capability_map"])),
    ("SurfaceMap", "build"): ("SurfaceMapOptions", lambda w: (w["by_name"]["robot"], w["by_name"]["capability_map"],
                                                               w["by_name"]["surface"])),
    ("Robot", "with_sampled_collisions"): ("AllowedCollisionOptions", lambda w: ()),
    ("Robot", "sample_allowed_collisions"): ("AllowedCollisionOptions", lambda w: ()),
}


def test_every_options_keyword_and_field_rejects_a_wrong_type(sweep):
    def results():
        for (cls, fn), (opts, args) in KWARG_OPTIONS.items():
            target = getattr(sweep["instances"]["Robot"], fn) if cls == "Robot" else getattr(getattr(_core, cls), fn)
            fields = [k for k, v in vars(getattr(_core, opts)).items() if isinstance(v, property) and v.fset]
            assert fields, opts
            for field in fields:
                for w in (WRONG, [WRONG]):
                    yield f"{cls}.{fn}", field, "", _run(lambda: target(*args(sweep), progress=False, **{field: w})), w
        # the options classes themselves: every settable field
        for cname, obj in vars(_core).items():
            if not inspect.isclass(obj):
                continue
            inst = sweep["instances"].get(cname)
            for field, v in vars(obj).items():
                if isinstance(v, property) and v.fset is not None and inst is not None:
                    for w in (WRONG, [WRONG]):
                        yield f"{cname}.{field} = ", field, "", _run(lambda: setattr(inst, field, w)), w
    n, findings, accepted = _collect(results())
    print(f"swept {n} keywords and fields")
    assert n > 100
    assert not findings, "\n".join(findings[:40])
    assert not accepted, "wrong types accepted silently:\n" + "\n".join(accepted[:40])


# ---- the Python entry points ----

def python_entry_points(sweep):
    """(label, callable, [(name, valid value)]) of every public function of the Python modules users call."""
    robot, chain, cap, surface = (sweep["by_name"][k] for k in ("robot", "chain", "capability_map", "surface"))
    urdf = sweep["by_name"]["urdf"]
    valid = {"robot": robot, "arm": ("base_link", "tool0"), "chain": chain, "capability_map": cap, "surface": surface,
             "poses": np.zeros((1, 4)), "urdf": urdf, "package_dirs": [], "srdf": None, "allowed_collisions": "srdf",
             "srdf_given": True, "name": "t", "size_x": 1.0, "size_y": 0.8, "height": 0.7, "width": 1.0, "depth": 0.4,
             "vertices": [[0, 0, 0.7], [1, 0, 0.7], [0, 1, 0.7]], "size": [0.1, 0.1, 0.1], "xyz": [1.0, 0, 0],
             "rpy": [0, 0, 0], "boards": [0.5], "description": {}, "base_dir": ".", "path": urdf}
    yield "robots.load", o.robots.load, [("name", "test_arm"), ("srdf", True), ("allowed_collisions", "srdf")]
    yield "robots.pr2", o.robots.pr2, [("srdf", True)]
    yield "robots.project_urdf", o.robots.project_urdf, [("name", "test_arm")]
    yield "robots.from_urdf", o.robots.from_urdf, [(k, valid[k]) for k in ("urdf", "package_dirs", "srdf", "allowed_collisions")]
    yield "robots.complete_allowed_collisions", o.robots.complete_allowed_collisions, [("robot", robot), ("srdf_given", True)]
    yield "arms.resolve", o.arms.resolve, [("robot", robot), ("arm", valid["arm"]), ("approach_axis", None)]
    yield "arms.default_reference", o.arms.default_reference, [("robot", robot), ("arm", valid["arm"])]
    yield "arms.capability_map", lambda robot, arm, approach_axis: o.arms.capability_map(
        robot, arm, progress=False, approach_axis=approach_axis, resolution=0.3, directions=8), \
        [("robot", robot), ("arm", valid["arm"]), ("approach_axis", None)]
    yield "surface_maps.link_roles", o.surface_maps.link_roles, [("robot", robot), ("chain", chain)]
    yield "testing.direct_reachability", o.testing.direct_reachability, \
        [("robot", robot), ("capability_map", cap), ("surface", surface), ("poses", valid["poses"]),
         ("grasps", "upper_hemisphere"), ("resolution", 0.3), ("grasp_height", 0.05), ("attempts", 2), ("seed", 0),
         ("obstacles", None)]
    yield "atomic_write.write_atomically", o.atomic_write.write_atomically, \
        [("path", str(sweep["dir"] / "written.txt")), ("data", b"x")]
    yield "data_files.read_data", lambda path: o.data_files.read_data(path, "room file"), \
        [("path", sweep["dir"] / "room.json")]
    yield "rooms.Room", o.rooms.Room, [("description", None), ("base_dir", ".")]
    yield "rooms.Room.load", o.rooms.Room.load, [("path", sweep["dir"] / "room.json")]
    yield "rooms.surface_from_file", o.rooms.surface_from_file, [("path", sweep["dir"] / "room.json")]
    for meth, params in (("add_table", ["name", "size_x", "size_y", "height"]),
                         ("add_surface", ["name", "vertices"]),
                         ("add_shelf", ["name", "width", "depth", "boards"]),
                         ("add_box", ["name", "size", "xyz", "rpy"]),
                         ("save", ["path"]),
                         ("obstacles", [])):
        yield f"rooms.Room.{meth}", (lambda m: lambda **k: getattr(o.rooms.Room(), m)(**k))(meth), \
            [(p, valid[p] if p != "path" else str(sweep["dir"] / "saved.json")) for p in params]


def test_python_entry_points_reject_wrong_types(sweep):
    (sweep["dir"] / "room.json").write_text('{"surfaces": [{"name": "t", "rectangle": {"size": [1, 1]}, "height": 0.7}]}')

    def results():
        for label, f, params in python_entry_points(sweep):
            for i, (pname, _) in enumerate(params):
                for w in (WRONG, [WRONG]):
                    if w != WRONG and pname in ("package_dirs", "boards", "vertices", "size", "xyz", "rpy", "poses",
                                                "description"):
                        pass  # a list holding a wrong value: still wrong
                    elif w != WRONG:
                        continue
                    kwargs = {k: (w if j == i else v) for j, (k, v) in enumerate(params)}
                    yield label, pname, "", _run(lambda: f(**kwargs)), w
    n, findings, accepted = _collect(results())
    print(f"swept {n} calls")
    assert not findings, "\n".join(findings[:40])
    assert not accepted, "wrong types accepted silently:\n" + "\n".join(accepted[:40])
