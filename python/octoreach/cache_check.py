"""What a map cache entry must agree with before it is used: the inputs of its key.

An entry's file is the map file itself, and its header records what the map was built from. A hit is used
only when that header names the key's robot (model hash), arm (links, approach axis) and every build
option the header records (resolution, directions, rolls, symmetry, seed, tolerances, self-collision,
exhaustive, block size, FK samples when given, solutions kept; for a surface map also its polygon, base
height, grasp height and set, reference frame, checks, resolution and theta bins). A capability map's
content must agree with its header too: a few stored joint solutions, put through the arm's forward
kinematics, must land on their voxel centres with their cells' approach directions (a header relabelled to
another resolution or arm, with its checksum recomputed, fails here). Options a map header does not record
(the reference posture, exhaustive_attempts) are covered by the key alone.

Each function returns None when the entry agrees, else the first disagreement in words. Cost: well under a
millisecond per hit (a header read and a handful of FK calls; no walk over the voxels).
"""
from __future__ import annotations

import math

import numpy as np

from ._core import OrientationSet

_PROBES = 4  # grid points per axis inside the map's bounds, of which the best few are checked by FK
_CHECKED = 3  # stored solutions checked by FK


def _differs(name: str, found, expected) -> str | None:
    """None when header value `found` (a string, or None when absent) means `expected`, else the difference."""
    if found is None:
        return f"the map has no {name!r}"
    try:
        if isinstance(expected, bool):
            same = found in ("1", "0") and (found == "1") == expected
        elif isinstance(expected, int):
            same = int(found) == expected
        elif isinstance(expected, float):
            same = math.isclose(float(found), expected, rel_tol=1e-12, abs_tol=1e-12)
        elif isinstance(expected, (list, tuple, np.ndarray)):
            values = [float(v) for v in str(found).split()]
            same = len(values) == len(expected) and all(math.isclose(a, float(b), rel_tol=1e-9, abs_tol=1e-9)
                                                        for a, b in zip(values, expected))
        else:
            same = str(found) == str(expected)
    except ValueError:
        same = False
    if same:
        return None
    shown = found if len(str(found)) <= 60 else str(found)[:57] + "..."
    return f"{name} is {shown} in the map, the key asks for {expected}"


def _first(checks: dict, header: dict) -> str | None:
    for name, expected in checks.items():
        problem = _differs(name, header.get(name), expected)
        if problem:
            return problem
    return None


def capability_mismatch(m, fields: dict, robot=None) -> str | None:
    """How a loaded capability map disagrees with its key fields (cache.capability_key_fields), or None; with
    `robot`, also its content (stored solutions through forward kinematics)."""
    header = m.parameters
    arm, options = fields["arm"], fields["options"]
    checks = {"model_hash": int(fields["model_hash"]), "robot": fields["robot"], "base_link": arm["base_link"],
              "tip_link": arm["tip_link"], "approach_axis": list(arm["approach_axis"])}
    for name, value in options.items():
        if name in header and value is not None and not (name == "fk_samples" and value == 0):
            checks[name] = value
    if isinstance(options.get("directions"), int):  # the sphere's count may exceed the one asked for (50 -> 52)
        checks["directions"] = OrientationSet.sphere_directions(options["directions"], options.get("symmetry", 4),
                                                                bool(options.get("poles", False)))
    if "poles" in options:  # recorded only when on
        checks["poles"] = bool(options["poles"])
        header = {**header, "poles": header.get("poles", "0")}
    problem = _first(checks, header)
    if problem is None and bool(options.get("keep_solutions", True)) != bool(m.has_solutions):
        problem = f"the map {'has' if m.has_solutions else 'lacks'} joint solutions, the key asks otherwise"
    if problem is None and robot is not None and m.has_solutions and m.stats["reachable_cells"]:
        problem = _solutions_mismatch(m, robot)
    return problem


def _probe_points(m) -> np.ndarray:
    """Reachable points of the map with the highest reachability among a small grid over its bounds."""
    lo, hi = (np.asarray(v, float) for v in m.bounds)
    t = (np.arange(_PROBES) + 0.5) / _PROBES
    grid = np.stack(np.meshgrid(t, t, t, indexing="ij"), axis=-1).reshape(-1, 3)
    points = lo + grid * (hi - lo)
    d = np.asarray(m.reachability(points), float)
    order = np.argsort(-d, kind="stable")
    best = points[order[d[order] > 0]][:_CHECKED]
    if len(best):
        return best
    centres, values = m.voxels()  # an odd shape the grid missed: the slow way, once
    return np.asarray(centres, float)[np.argsort(-np.asarray(values), kind="stable")[:_CHECKED]]


def _solutions_mismatch(m, robot) -> str | None:
    """None when stored solutions of a few cells, through FK of the header's chain, land on their voxel
    centres (within twice the position tolerance) with the cells' approach directions (twice the
    orientation tolerance); else the disagreement."""
    if not (robot.has_link(m.base_link) and robot.has_link(m.tip_link)):
        return f"the robot has no chain {m.base_link} -> {m.tip_link}"
    chain = robot.chain(m.base_link, m.tip_link)
    header = m.parameters
    res = float(m.resolution)
    pos_tol = 2 * float(header.get("position_tolerance", 1e-3)) + 1e-9
    ang_tol = 2 * float(header.get("orientation_tolerance", 1e-2)) + 1e-9
    axis = np.asarray(m.approach_axis, float)
    orientations = m.orientations
    count = len(orientations)
    checked = 0
    for point in _probe_points(m):
        centre = (np.floor(point / res) + 0.5) * res
        for k in range(min(count, 256)):
            q = m.solution(point, k)
            if q is None:
                continue
            T = np.asarray(chain.fk(np.asarray(q, float)))
            off = float(np.linalg.norm(T[:3, 3] - centre))
            if off > pos_tol:
                return (f"a stored joint solution reaches {np.round(T[:3, 3], 3).tolist()}, {off:.3f} m from its voxel "
                        f"centre {np.round(centre, 3).tolist()}: the header does not describe this map's content")
            want = np.asarray(orientations.rotation(k, axis), float) @ axis
            angle = math.acos(max(-1.0, min(1.0, float((T[:3, :3] @ axis) @ want))))
            if angle > ang_tol:
                return (f"a stored joint solution approaches {angle:.3f} rad off its cell's direction: the header "
                        "does not describe this map's content")
            checked += 1
            break
    return None if checked else "no stored joint solution could be checked"


def surface_mismatch(m, fields: dict, polygon) -> str | None:
    """How a loaded surface map disagrees with its key fields (the build-many surface fields: capability fields,
    height, options) and the surface's polygon (N, 3), or None."""
    from ._core import SurfaceMapOptions

    cap, options = fields["capability"], fields.get("options", {})
    arm = cap["arm"]
    defaults = SurfaceMapOptions()
    header = dict(m.parameters)
    header["resolution"], header["theta_bins"] = repr(float(m.resolution)), str(int(m.theta_bins))
    header["checks"] = str(header.get("checks", "")).split(" (room:")[0]  # the room's obstacle count follows
    resolution = options.get("resolution") or cap["options"]["resolution"]
    grasps = options.get("grasps", defaults.grasps)
    checks = {"model_hash": int(cap["model_hash"]), "robot": cap["robot"],
              "arms": f"{arm['base_link']}->{arm['tip_link']}", "approach_axes": list(arm["approach_axis"]),
              "z_min": float(fields["height"]), "z_max": float(fields["height"]),
              "polygon": np.asarray(polygon, float).reshape(-1).tolist(),
              "grasp_height": float(options.get("grasp_height", defaults.grasp_height)),
              "resolution": float(resolution), "theta_bins": int(options.get("theta_bins", defaults.theta_bins)),
              "checks": "+".join(n for n, on in (("body", options.get("check_body", defaults.check_body)),
                                                 ("arm", options.get("check_arm", defaults.check_arm))) if on)}
    if isinstance(grasps, str):
        checks["grasp_set"] = grasps
    if options.get("reference_frame"):
        checks["reference_frame"] = options["reference_frame"]
    return _first(checks, header)
