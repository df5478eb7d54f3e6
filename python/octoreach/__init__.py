"""octoreach: where a robot should stand and where it should look.

The compiled core lives in ``octoreach._core``; this package re-exports it with a thin Python layer (robots,
arms, rooms, the map cache, progress bars). The exploration loop, the viewer, the planner, the Ray cluster,
the plots and the test utilities are subpackages that load on first use (``octoreach.exploration``,
``octoreach.viewer``, ``octoreach.planning``, ``octoreach.cluster``, ``octoreach.plots``, ``octoreach.testing``),
so ``import octoreach`` imports neither matplotlib nor an optional extra.

Poses are 4x4 numpy arrays (homogeneous transforms) unless a docstring says (x, y, z, theta) rows. Units:
metres and radians; frames are right-handed, z up.
"""
from ._core import (  # noqa: F401
    AllowedCollisionOptions,
    Arm,
    ArmReport,
    CameraLink,
    CameraIntrinsics,
    Cancelled,
    CapabilityBlocks,
    CapabilityLookup,
    CapabilityMap,
    CapabilityMapOptions,
    CertifiedLookup,
    CertifiedLookupOptions,
    Chain,
    CostMap,
    DepthCamera,
    ExplorationMap,
    ExploreOptions,
    InversePointMap,
    MapRoom,
    MapWarning,
    NbvOptions,
    NbvResult,
    Obstacles,
    OrientationSet,
    PointMapOptions,
    PoseSampler,
    Robot,
    Scene,
    Shape,
    SelfCollisionOptions,
    SelfCollisionReport,
    Surface,
    SurfaceMap,
    ScoredView,
    ScoredViews,
    SurfaceMapOptions,
    ViewCandidate,
    ViewGains,
    ViewGainsResult,
    VoidCluster,
    __version__,
    arm_names,
    arm_report,
    base_pose,
    camera_link,
    default_reference,
    find_arms,
    find_camera_link,
    grasp_orientations,
    infer_approach_axis,
    link_roles,
    next_best_view,
    score_views,
    self_collision_report,
    set_progress_factory,
    view_gains,
    view_utility,
)
from . import arms, cache, limits, map_files, progress, robots, room_checks, rooms, surface_maps  # noqa: F401
from .rooms import Room  # noqa: F401

# How progress=True is drawn by the compiled builds: the core calls back into the package's progress bar.
set_progress_factory(progress.make_progress)

# Subpackages and names that load on first use: they import matplotlib or an optional extra.
_LAZY_MODULES = ("cluster", "experiments", "exploration", "jobs", "planning", "plots", "testing", "viewer")
_LAZY_NAMES = {"explore": "exploration"}


def __getattr__(name):
    import importlib

    if name in _LAZY_MODULES:
        return importlib.import_module(f".{name}", __name__)
    if name in _LAZY_NAMES:
        return getattr(importlib.import_module(f".{_LAZY_NAMES[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def view(*items, **kwargs):
    """Shows maps, samples and explorations in 3D in the browser (needs the viewer extra): octoreach.viewer.view,
    whose help lists the arguments (robot, q, joints, samples, html, png, serve, colour_by, ...); imported on the
    first call, so that importing octoreach does not import the viewer."""
    from .viewer import view as _view

    return _view(*items, **kwargs)


__all__ = [
    "MapRoom", "MapWarning", "ArmReport", "CameraLink",
    "SelfCollisionOptions", "SelfCollisionReport", "arm_report", "camera_link", "find_camera_link",
    "self_collision_report",
    "AllowedCollisionOptions", "Arm", "CameraIntrinsics", "Cancelled", "CapabilityBlocks", "CapabilityLookup",
    "CapabilityMap", "CapabilityMapOptions", "CertifiedLookup", "CertifiedLookupOptions",
    "Chain", "CostMap", "DepthCamera", "ExplorationMap", "ExploreOptions",
    "InversePointMap", "NbvOptions", "NbvResult", "Obstacles", "OrientationSet", "PointMapOptions", "PoseSampler",
    "Robot", "Room", "Scene", "ScoredView", "ScoredViews", "Shape", "Surface", "SurfaceMap", "SurfaceMapOptions",
    "ViewCandidate", "ViewGains", "ViewGainsResult", "VoidCluster", "__version__", "arm_names", "arms", "base_pose",
    "cache", "default_reference", "explore", "exploration", "find_arms", "grasp_orientations",
    "infer_approach_axis", "limits", "link_roles", "map_files", "next_best_view", "robots", "rooms", "score_views",
    "view", "view_gains", "view_utility",
]
