"""Exploration in the user's own loop: an Explorer takes the robot's clouds (or depth images) with the camera
pose they were taken from and answers the next view (camera pose, joints, base) or why to stop, with the
strategy and stop rule explore() uses (it drives one). The work is C++ (_core.ExplorerCore, explorer.hpp)."""
from __future__ import annotations

from typing import Optional

import numpy as np

from .. import _core
from .._checks import finite_pose, shown
from ._options import explore_options
from .robot import arm_base_pose, arm_reach, explorer_capability_map, explorer_robot
from .strategies import Choice, _choice_of, check_strategy, stop_message


def carrier(robot, chain, base_pose):
    """(robot, chain, base_pose) of the arm that carries the camera: `robot=True` is the explorer, another
    robot needs `chain` (a Chain, or with a robot its (base link, camera link) names or the camera link's name,
    from the robot's root link); a chain without a base pose stands at the origin; robot None when not given."""
    if isinstance(chain, (str, tuple, list)) and robot is not True:  # (robot=True: the explorer's own chain)
        if not isinstance(robot, _core.Robot):
            raise ValueError(f"chain={chain!r} names links: pass the robot too (robot=Robot.from_urdf(...)), or a "
                             "Chain (robot.chain(base_link, camera_link))")
        links = (robot.root_link, chain) if isinstance(chain, str) else tuple(chain)
        if len(links) != 2 or not all(isinstance(x, str) for x in links):
            raise ValueError("chain must be a Chain, a (base link, camera link) pair or a camera link name, "
                             f"got {chain!r}")
        chain = robot.chain(*links)
    elif chain is not None and robot is not True and not isinstance(chain, _core.Chain):
        raise TypeError(f"chain must be a Chain (robot.chain(base_link, camera_link)), a (base link, camera link) pair "
                        f"or a camera link name, got {type(chain).__name__}")
    rob = None
    if robot is True or (robot is not None and chain is None):
        rob, chain = explorer_robot() if robot is True else (robot, None)
        if chain is None:
            raise ValueError("pass chain= with a robot other than the explorer")
        base_pose = arm_base_pose(rob, chain, base_pose)
    elif robot is not None:
        rob = robot
    if chain is not None and base_pose is None:
        base_pose = np.eye(4)
    return rob, chain, base_pose


def base_list(chain, base_pose, base_moves) -> list:
    """The chain base poses the search may use: the current one first, then `base_moves` (None: a free camera)."""
    bases = [finite_pose(base_pose, "base_pose")] if chain is not None else [None]
    if base_moves is not None:
        if chain is None:
            raise ValueError("base_moves needs a chain (or robot=True)")
        bases += [finite_pose(b, f"base_moves[{i}] (chain base -> world)") for i, b in enumerate(base_moves)]
    return bases


def check_in_sight(bases, region, limit: float) -> None:
    """ValueError when the search space `region` ((2, 3) lo, hi) lies farther than `limit` metres (the arm's reach
    plus the camera's range) from every chain base: no view could see any of it (a box in millimetres, or in
    another frame)."""
    lo, hi = region[0], region[1]
    gaps = [float(np.linalg.norm(np.maximum(0.0, np.maximum(lo - b[:3, 3], b[:3, 3] - hi)))) for b in bases]
    if gaps and min(gaps) > limit:
        raise ValueError(f"search_space lies {min(gaps):.2f} m from the nearest chain base, beyond the arm's reach "
                         f"plus the camera's range ({limit:.2f} m): no view can see any of it (metres, in the "
                         f"world frame?); got {shown(region.tolist())}")


def capability(capability_map, chain):
    """`capability_map` itself, or the coarse explorer map for "auto"."""
    if isinstance(capability_map, str):
        if capability_map != "auto" or chain is None:
            raise ValueError(f"capability_map must be a CapabilityMap, None or 'auto' (with a chain), got {capability_map!r}")
        # a chain without a movable joint has no map to build: the Explorer refuses it by name
        capability_map = explorer_capability_map(chain) if chain.dof > 0 else None
    return capability_map


class Explorer:
    """An exploration session (see the module).

    `camera`: a DepthCamera or CameraIntrinsics. `search_space` ((2, 3) lo, hi): the region to explore. The camera
    is carried by `chain` (tip = camera frame, +z its optical axis; a Chain, or a (base link, camera link) pair or the
    camera link's name, from the root link, of the robot given) of `robot` (robot=True: urdf/explorer.urdf;
    any Robot, e.g. Robot.from_urdf(path)), whose base stands at `base_pose` (4x4 chain base -> map; with robot=True
    the pose of its base_footprint) and may drive to any of `base_moves`; without a chain it moves freely in the
    search's workspace. A chain of fewer than 5 joints (a pan/tilt head, a torso lift under it) cannot place its
    camera, so its views aim the optical axis at void cells (look-at; `aiming="pose"` or `"look_at"` decides
    for any chain). Every other keyword is an ExploreOptions field or one of its search's (as explore()'s); the
    stop rule is on by default.

    `integrate(points, camera_pose)` ((N, 3) map-frame points) or `integrate(depth=image, camera_pose=...)`
    ((height, width) metres along the optical axis, 0: no return); `next_view()` -> NextView (camera_pose, q,
    base, base_pose, expected_gain, stop, stop_reason; `Explorer.stop_message(view)` says why no view was valid);
    `view_failed()` when the proposed view could not be taken. Bad input (NaN/inf points, a pose that is not
    rigid, a depth image of the wrong size) raises ValueError naming it and leaves the explorer unchanged."""

    def __init__(self, camera, search_space, options: Optional[_core.ExploreOptions] = None, *, robot=None,
                 chain=None, base_pose=None, base_moves=None, capability_map=None, strategy: str = "frontier_void",
                 resolution: Optional[float] = None, void_fit_threshold: Optional[float] = None, **settings):
        opts = explore_options(options, **settings)
        check_strategy(strategy)
        self.robot, self.chain, base_pose = carrier(robot, chain, base_pose)
        self.bases = base_list(self.chain, base_pose, base_moves)
        search = opts.search
        if self.chain is not None and search.reference is not None:  # now, not at the first next_view()
            self.chain.to_robot_configuration(np.zeros(self.chain.dof), search.reference)
        search.chain, search.capability_map = self.chain, capability(capability_map, self.chain)
        free = search.workspace_sphere is None and search.workspace_box is None and search.workspace is None
        reach = arm_reach(self.chain, search.seed) if self.chain is not None and free else 0.0
        bases = np.array([np.eye(4) if b is None else b for b in self.bases])
        self.options, self.strategy, self.reach = opts, strategy, reach
        self._core = _core.ExplorerCore(camera, np.asarray(search_space, float), bases, reach, resolution,
                                        void_fit_threshold, opts, strategy)
        if reach > 0 and getattr(camera, "max_range", None):  # the core checked the search space's shape
            check_in_sight(bases, np.asarray(search_space, float), reach + float(camera.max_range))
        self._keep = (camera, search.chain, search.capability_map)  # the core holds plain pointers to them

    def integrate(self, points=None, camera_pose=None, *, depth=None) -> dict:
        """Integrates a cloud (map frame) or a depth image taken from `camera_pose`; the insert's statistics."""
        if camera_pose is None or (points is None) == (depth is None):
            raise ValueError("integrate needs camera_pose and either points or depth")
        if depth is not None:
            dtype = np.asarray(depth).dtype
            if dtype.kind != "f":  # a 16UC1 ROS image holds millimetres; read as metres it would clear the room
                raise ValueError(f"depth image must hold metres as floats, got dtype {dtype} "
                                 "(an integer image holds millimetres: pass depth / 1000.0)")
            return self._core.integrate_depth(depth, camera_pose)
        return self._core.integrate(points, camera_pose)

    def next_view(self):
        """The next view to take, or why to stop (NextView)."""
        return self._core.next_view()

    def view_failed(self) -> None:
        """The proposed view was not taken: no view near its camera is proposed again."""
        self._core.view_failed()

    @staticmethod
    def choice(view) -> Choice:
        """The loop's Choice of a NextView (its gains; stop and stop_reason the NextView's)."""
        c = _choice_of(view.choice)
        c.stop, c.stop_reason = view.stop, view.stop_reason
        return c

    @staticmethod
    def stop_message(view) -> str:
        """Why a NextView stops, with the search's counts per rejection status for "no valid view" ("" when it
        goes on): strategies.stop_message."""
        return stop_message(view)

    @property
    def map(self) -> _core.ExplorationMap:
        return self._core.map

    @property
    def views(self) -> int:
        return self._core.views

    @property
    def current_base(self) -> int:
        return self._core.current_base
