"""octoreach: where a robot should stand and where it should look.

The compiled core lives in ``octoreach._core``; this package re-exports it with a
thin Python layer (robots, progress bars, plots, command line).

Poses are 4x4 numpy arrays (homogeneous transforms) unless a docstring says
(x, y, z, theta) rows. Units: metres and radians; frames are right-handed, z up.
"""
from ._core import (  # noqa: F401
    AllowedCollisionOptions,
    Arm,
    Cancelled,
    CapabilityBlocks,
    CapabilityLookup,
    CapabilityMap,
    CapabilityMapOptions,
    Chain,
    CostMap,
    InversePointMap,
    Obstacles,
    OrientationSet,
    PointMapOptions,
    PoseSampler,
    Robot,
    Surface,
    SurfaceMap,
    SurfaceMapOptions,
    __version__,
    arm_names,
    base_pose,
    default_reference,
    find_arms,
    grasp_orientations,
    infer_approach_axis,
    link_roles,
)
from . import progress as _progress
from ._core import set_progress_factory as _set_progress_factory

_set_progress_factory(_progress.make_progress)  # how progress=True is drawn by the compiled builds

from . import robots  # noqa: F401
from . import arms, map_files, surface_maps  # noqa: F401
from . import rooms  # noqa: F401
from . import cache  # noqa: F401  (octoreach.cluster and octoreach.jobs load on use: Ray is optional)
from .rooms import Room  # noqa: F401
from ._core import (  # noqa: F401
    CameraIntrinsics,
    DepthCamera,
    ExplorationMap,
    NbvOptions,
    Scene,
    VoidCluster,
    next_best_view,
    score_views,
    view_gains,
    view_utility,
)
from . import exploration  # noqa: F401
from .exploration import explore  # noqa: F401



def view(*items, **kwargs):
    """Shows maps, samples and explorations in 3D in the browser (octoreach.viewer.view; needs the viewer
    extra)."""
    from .viewer import view as _view

    return _view(*items, **kwargs)


__all__ = ["Arm", "Cancelled", "CapabilityBlocks", "CapabilityLookup", "CapabilityMap", "CapabilityMapOptions", "Chain", "CostMap", "InversePointMap",
           "PointMapOptions", "PoseSampler", "Surface", "SurfaceMap", "SurfaceMapOptions", "arms", "OrientationSet",
           "Obstacles", "Robot", "robots", "__version__", "arm_names", "base_pose", "default_reference",
           "grasp_orientations", "link_roles", "AllowedCollisionOptions", "find_arms", "infer_approach_axis",
           "rooms", "Room", "map_files", "cache"]
__all__ += ["CameraIntrinsics", "DepthCamera", "ExplorationMap", "NbvOptions", "Scene", "VoidCluster", "next_best_view", "view_utility",
            "score_views", "view_gains", "exploration", "explore", "view"]
