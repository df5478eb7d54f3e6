"""
octoreach compiled core: robot model, IK, collision, reachability maps, exploration
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import types
import typing
__all__: list[str] = ['AllowedCollisionOptions', 'Arm', 'ArmReport', 'CameraIntrinsics', 'CameraLink', 'Cancelled', 'CapabilityBlocks', 'CapabilityLookup', 'CapabilityMap', 'CapabilityMapOptions', 'CertifiedLookup', 'CertifiedLookupOptions', 'Chain', 'ChoiceMemory', 'CostMap', 'DepthCamera', 'ExplorationMap', 'ExploreOptions', 'ExplorerCore', 'HeldJoint', 'InversePointMap', 'MapProvenance', 'MapRoom', 'MapWarning', 'NbvOptions', 'NbvResult', 'NextView', 'Obstacles', 'OrientationSet', 'PairHits', 'PointMapOptions', 'PoseSampler', 'Robot', 'RobotSource', 'Scene', 'ScoredView', 'ScoredViews', 'SelfCollisionOptions', 'SelfCollisionReport', 'Shape', 'Surface', 'SurfaceMap', 'SurfaceMapOptions', 'ViewCandidate', 'ViewChoice', 'ViewGains', 'ViewGainsResult', 'Visual', 'VoidCluster', 'accumulate_utility', 'arm_names', 'arm_report', 'base_pose', 'camera_link', 'choose_view', 'default_reference', 'expect_view', 'exposed_cells', 'find_arms', 'find_camera_link', 'grasp_orientations', 'infer_approach_axis', 'limits', 'link_roles', 'load_any', 'look_at', 'map_format_version', 'map_kind', 'map_kinds', 'missed_cells', 'next_best_view', 'ranks_before', 'score_views', 'self_collision_report', 'set_progress_factory', 'view_gains', 'view_utility', 'visibility_curve', 'void_enclosure']
class Cancelled(KeyboardInterrupt):
    pass
class Shape:
    """
    A solid with its pose: a box, cylinder (along its local z), sphere, triangle mesh or OctoMap. The one shape
    description of the library: a robot link's collision and visual shapes (pose in the link frame), Obstacles,
    Scene and rooms (pose in the world frame). Build one with the static methods; metres, 4x4 poses.
    """
    @staticmethod
    def box(size: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], pose: typing.Any = None) -> Shape:
        """
        A box of extents `size` (x, y, z) centred at `pose`.
        """
    @staticmethod
    def cylinder(radius: typing.SupportsFloat | typing.SupportsIndex, length: typing.SupportsFloat | typing.SupportsIndex, pose: typing.Any = None) -> Shape:
        """
        A cylinder along the local z axis of `pose`, centred there.
        """
    @staticmethod
    def mesh_file(path: str, pose: typing.Any = None, scale: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ...) -> Shape:
        """
        A mesh file (STL, DAE, OBJ ... read by assimp), scaled per axis (OSError if it cannot be read).
        """
    @staticmethod
    def octree_file(path: str, pose: typing.Any = None) -> Shape:
        """
        The occupied cells of an OctoMap file (.bt, or .ot holding an OcTree).
        """
    @staticmethod
    def sphere(radius: typing.SupportsFloat | typing.SupportsIndex, pose: typing.Any = None) -> Shape:
        ...
    @staticmethod
    def triangle_mesh(vertices: typing.Any, triangles: typing.Any, pose: typing.Any = None) -> Shape:
        """
        A triangle mesh: vertices (N, 3) and triangles (M, 3) of vertex indices, in the frame of `pose`.
        """
    def __repr__(self) -> str:
        ...
    def mesh_triangles(self) -> tuple:
        """
        (vertices (N, 3), triangles (M, 3)) of a mesh shape in its own frame (before `pose`); ValueError for
        other kinds.
        """
    def octree_cells(self) -> tuple:
        """
        (centres (N, 3), edges (N,)) of an OctoMap shape's occupied cells in its own frame (before `pose`);
        ValueError for other kinds.
        """
    @property
    def kind(self) -> str:
        """
        'box', 'cylinder', 'sphere', 'mesh' or 'octree'.
        """
    @property
    def length(self) -> float:
        """
        Cylinder length.
        """
    @property
    def mesh_path(self) -> str:
        """
        Mesh file ('' for triangles given in memory, or a robot's visual mesh not found).
        """
    @property
    def pose(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        4x4 pose in the parent frame (a link's frame, or the world).
        """
    @property
    def radius(self) -> float:
        """
        Cylinder or sphere radius.
        """
    @property
    def scale(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Mesh scale, per axis.
        """
    @property
    def size(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Box extents (x, y, z).
        """
class Obstacles:
    """
    Environment objects in the world frame (boxes, spheres, cylinders, meshes, OctoMaps).
    """
    def __init__(self) -> None:
        ...
    def __len__(self) -> int:
        ...
    def add(self, other: Obstacles) -> None:
        """
        Adds every obstacle of `other` (the objects are shared; the two sets stay independent).
        """
    def add_box(self, size: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], pose: typing.Any = None, name: str = '') -> None:
        """
        Adds a box of extents `size` (x, y, z) centred at `pose` (4x4, world frame).
        """
    def add_cylinder(self, radius: typing.SupportsFloat | typing.SupportsIndex, length: typing.SupportsFloat | typing.SupportsIndex, pose: typing.Any = None, name: str = '') -> None:
        """
        Adds a cylinder along the local z axis of `pose`.
        """
    def add_mesh(self, path: str, pose: typing.Any = None, scale: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ..., name: str = '') -> None:
        """
        Adds a mesh file (STL, DAE, OBJ ... read by assimp).
        """
    def add_octree_file(self, path: str, pose: typing.Any = None, name: str = '') -> None:
        """
        Adds the occupied cells of an OctoMap file (.bt or .ot).
        """
    def add_points(self, points: typing.Any, resolution: typing.SupportsFloat | typing.SupportsIndex, name: str = '') -> None:
        """
        Adds occupied cells at the given points (N, 3) as an OctoMap of the given resolution.
        """
    def add_shape(self, shape: Shape, name: str = '') -> None:
        """
        Adds a Shape (world frame).
        """
    def add_sphere(self, radius: typing.SupportsFloat | typing.SupportsIndex, pose: typing.Any = None, name: str = '') -> None:
        ...
    def add_triangles(self, vertices: typing.Any, triangles: typing.Any, pose: typing.Any = None, name: str = '') -> None:
        """
        Adds a triangle mesh from arrays: vertices (N, 3) and triangles (M, 3) of vertex indices.
        """
    def collides_box(self, size: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], pose: typing.Any) -> bool:
        """
        True when a box of extents `size` at `pose` touches an obstacle.
        """
    @property
    def names(self) -> list[str]:
        ...
    @property
    def shapes(self) -> list[Shape]:
        """
        The obstacles' Shapes (world frame), in the order added.
        """
class Chain:
    """
    Serial chain between two links: FK, Jacobian and IK (poses in the base link frame).
    """
    def __repr__(self) -> str:
        ...
    def aim(self, target: typing.Any, axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ..., tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.001, attempts: typing.SupportsInt | typing.SupportsIndex = 6, max_iterations: typing.SupportsInt | typing.SupportsIndex = 60, rng_seed: typing.SupportsInt | typing.SupportsIndex = 0, seed: typing.Any = None) -> typing.Any:
        """
        Joints (inside the limits) that point the tip's `axis` (a camera's optical axis) at `target` (a point,
        base link frame) within `tolerance` radians, the tip's position following from the chain (look-at IK for
        a pan/tilt head); None when the chain cannot aim there (aim_error tells by how much it misses).
        """
    def aim_error(self, q: typing.Any, target: typing.Any, axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ...) -> float:
        """
        Radians between the tip's `axis` at joints q and the ray from the tip's origin to `target` (base link frame).
        """
    def fk(self, q: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        Pose (4x4) of the tip link in the base link frame.
        """
    def fk_batch(self, Q: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        Tip poses (N, 4, 4) in the base link frame for joint rows Q (N, dof).
        """
    def ik(self, T: typing.Any, seed: typing.Any = None, mode: str = 'full', position_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, orientation_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.001, attempts: typing.SupportsInt | typing.SupportsIndex = 20, max_iterations: typing.SupportsInt | typing.SupportsIndex = 100, rng_seed: typing.SupportsInt | typing.SupportsIndex = 0, approach_axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ..., approach_cone: typing.SupportsFloat | typing.SupportsIndex = 0.0, self_collision: bool = False, obstacles: Obstacles = None, base_pose: typing.Any = None, reference: typing.Any = None, obstacle_links: typing.Any = None) -> typing.Any:
        """
        Joint vector reaching the 4x4 tip pose T (base link frame), or None.
        
        mode: 'full' (position and orientation), 'position', or 'approach' (position and the tip's
        approach_axis within approach_cone radians, any roll about it). Random restarts inside the limits;
        deterministic for rng_seed. self_collision / obstacles reject colliding solutions (obstacles in the
        world frame, the robot's root at base_pose; obstacle_links restricts that check to the named links);
        joints outside the chain take their values from `reference` (default robot.home()).
        """
    def ik_batch(self, Ts: typing.Any, seeds: typing.Any = None, mode: str = 'full', position_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, orientation_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.001, attempts: typing.SupportsInt | typing.SupportsIndex = 20, max_iterations: typing.SupportsInt | typing.SupportsIndex = 100, rng_seed: typing.SupportsInt | typing.SupportsIndex = 0, approach_axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ..., approach_cone: typing.SupportsFloat | typing.SupportsIndex = 0.0, self_collision: bool = False, obstacles: Obstacles = None, base_pose: typing.Any = None, reference: typing.Any = None, obstacle_links: typing.Any = None, threads: typing.SupportsInt | typing.SupportsIndex = 0) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"], numpy.typing.NDArray[numpy.bool]]:
        """
        IK of poses Ts (N, 4, 4) on every core. Returns (Q of shape (N, dof) with NaN rows where it failed,
        success mask (N,)). Item i uses a random stream derived from rng_seed and i.
        """
    def jacobian(self, q: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        Geometric Jacobian (6, dof), rows vx vy vz wx wy wz, in the base link frame.
        """
    def link_mask(self, link: str) -> int:
        """
        Bit i set when chain joint i moves `link`: 0 for links the chain does not move, all bits for links
        rigid with the tip (a gripper).
        """
    def random_configuration(self, seed: typing.SupportsInt | typing.SupportsIndex = 0) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        One uniform random configuration inside the limits (continuous joints in [-pi, pi)).
        """
    def random_configurations(self, n: typing.SupportsInt | typing.SupportsIndex, seed: typing.SupportsInt | typing.SupportsIndex = 0) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (n, dof) uniform random configurations inside the limits (continuous joints in [-pi, pi)), one per row;
        row 0 equals random_configuration(seed).
        """
    def to_robot_configuration(self, q: typing.Any, reference: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Full robot configuration with this chain's joints set to q, the rest from `reference` (default home).
        """
    def within_limits(self, arg0: typing.Any) -> bool:
        ...
    def wrap(self, arg0: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Continuous joints wrapped into [-pi, pi), revolute joints shifted by 2 pi into their limits where possible.
        """
    @property
    def base_link(self) -> str:
        ...
    @property
    def continuous(self) -> list[bool]:
        ...
    @property
    def dof(self) -> int:
        ...
    @property
    def joint_axes(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (dof, 3): each joint's axis in its own frame (unit vectors).
        """
    @property
    def joint_names(self) -> list[str]:
        ...
    @property
    def joint_origins(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (dof, 4, 4): joint i's frame in joint i-1's frame (the base link's for joint 0), fixed joints
        folded in. With joint_axes, prismatic, the limits and tip_offset: the chain's description.
        """
    @property
    def lower(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Lower joint limits (-inf for continuous joints).
        """
    @property
    def moved_links(self) -> list[str]:
        """
        The robot's collision links that this chain's joints move (its arm links and what they carry), in
        Robot.collision_links order.
        """
    @property
    def prismatic(self) -> list[bool]:
        """
        True for prismatic joints (the others rotate about their axis).
        """
    @property
    def robot_indices(self) -> list[int]:
        """
        Positions of this chain's joints in the robot configuration vector.
        """
    @property
    def tip_link(self) -> str:
        ...
    @property
    def tip_offset(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        Fixed transform (4x4) from the last joint's frame to the tip link.
        """
    @property
    def upper(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Upper joint limits (+inf for continuous joints).
        """
    @property
    def jacobian_rank(self) -> int:
        """
        Generic rank of the 6 x dof Jacobian (6 for six or more independent joints).
        """
    def joint_limit_penalty(self, q: typing.Any) -> float:
        """
        Joint-limit penalty of q in [0, 1] (Tsai; Vahrenkamp et al.): 1 - exp(-4^n prod (q - l)(u - q) / (u - l)^2)
        over the n bounded joints; 1 - 1/e in the middle of every range, 0 at a limit.
        """
    def manipulability(self, q: typing.Any, rank: typing.Any = None) -> float:
        """
        Yoshikawa's manipulability of q: sqrt(det(J J^T)), the product of the Jacobian's singular values; for a chain
        of Jacobian rank r < 6 (rank None: jacobian_rank) the product of its r largest.
        """
class AllowedCollisionOptions:
    """
    How the allowed-collision matrix is sampled (MoveIt setup assistant's method; defaults defined once, in C++).
    """
    def __init__(self) -> None:
        ...
    @property
    def cache_dir(self) -> str:
        """
        '' = $OCTOREACH_CACHE_DIR, else $XDG_CACHE_HOME/octoreach, else ~/.cache/octoreach; 'none' = no cache.
        """
    @cache_dir.setter
    def cache_dir(self, arg0: str) -> None:
        ...
    @property
    def default_posture(self) -> bool:
        """
        Also allow pairs in collision at home().
        """
    @default_posture.setter
    def default_posture(self, arg0: bool) -> None:
        ...
    @property
    def samples(self) -> int:
        """
        Random configurations (MoveIt's default: 10,000).
        """
    @samples.setter
    def samples(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        ...
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def threads(self) -> int:
        """
        0: every core.
        """
    @threads.setter
    def threads(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class Robot:
    """
    Robot model from a URDF: links, joints, collision shapes. Never changes once built.
    """
    @staticmethod
    def from_urdf(urdf: typing.Any, package_dirs: typing.Any = None, srdf: typing.Any = None, srdf_mismatch: typing.Any = None) -> Robot:
        """
        Robot from a URDF file path (str or os.PathLike) or XML string. package:// and file:// mesh URIs are resolved through
        package_dirs. srdf (path or XML) adds chain groups and disabled collision pairs. srdf_mismatch: SRDF
        groups and end effectors that name links, joints or groups the URDF lacks are an error ('error', the
        default) or left out ('leave_out', as MoveIt does; srdf_left_out says which).
        """
    def __repr__(self) -> str:
        ...
    def chain(self, base_link: str, tip_link: str) -> Chain:
        ...
    def compute_allowed_collisions(self, samples: typing.SupportsInt | typing.SupportsIndex = 2000, seed: typing.SupportsInt | typing.SupportsIndex = 0, progress: typing.Any = None) -> list[tuple[str, str]]:
        """
        Link pairs (link_a, link_b) never or always in collision over `samples` random configurations
        (deterministic for seed), among the pairs checked now: pass them to with_allowed_collisions.
        Empty when there is nothing to add. with_sampled_collisions() does it all (and caches).
        """
    def configuration(self, values: collections.abc.Mapping[str, typing.SupportsFloat | typing.SupportsIndex]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Configuration vector from a {joint name: value} dict, the rest from home().
        """
    def group_joints(self, group: str) -> list[str]:
        """
        Moving joints of an SRDF group (chains, joints, links' parent joints, subgroups).
        """
    def has_link(self, arg0: str) -> bool:
        ...
    def home(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Zero configuration moved into the joint limits.
        """
    def in_collision(self, q: typing.Any, obstacles: Obstacles, base_pose: typing.Any = None, self_collision: bool = False, links: typing.Any = None) -> bool:
        """
        True when a link (all, or the named `links`) touches an obstacle (world frame) with the root link at
        base_pose (4x4); self_collision also checks the robot against itself.
        """
    def in_self_collision(self, q: typing.Any) -> bool:
        """
        True when two links that are not allowed to touch collide at q.
        """
    def link_poses(self, q: typing.Any) -> dict:
        """
        {link name: 4x4 pose in the root link frame}.
        """
    def lowest_point(self, q: typing.Any) -> tuple[float, typing.Any]:
        """
        (z, link): the lowest point of the collision geometry at q in the root link frame and the link holding it
        ((inf, None) without geometry). A surface map refuses a robot that would stand in the floor.
        """
    def sample_allowed_collisions(self, options: typing.Any = None, progress: typing.Any = False, **kwargs) -> dict:
        """
        MoveIt setup-assistant pairs among the checked ones: {'never', 'always', 'default': [(a, b)], 'from_cache',
        'cache_file'}; keywords set AllowedCollisionOptions fields (samples, seed, threads, default_posture, cache_dir).
        """
    def self_collisions(self, q: typing.Any) -> list[tuple[str, str]]:
        """
        Checked link pairs (link_a, link_b) in collision at q.
        """
    def srdf_text(self) -> str:
        """
        SRDF of the model: groups, end effectors, group states, every allowed pair.
        """
    def with_allowed_collisions(self, pairs: collections.abc.Sequence[tuple[str, str]]) -> Robot:
        """
        A new Robot, this one with the (link_a, link_b) pairs added to its allowed collisions (its own
        model_hash); this robot is left as it is.
        """
    def with_sampled_collisions(self, options: typing.Any = None, progress: typing.Any = False, **kwargs) -> Robot:
        """
        A new Robot with the sampled allowed-collision pairs added (cached on disk by model hash); keywords set
        AllowedCollisionOptions fields.
        """
    def write_srdf(self, path: str) -> None:
        """
        Writes srdf_text() atomically to path.
        """
    @property
    def allowed_collisions(self) -> list[tuple[str, str]]:
        """
        Link pairs whose contacts are ignored (adjacent, SRDF, sampled).
        """
    @property
    def checked_pairs(self) -> int:
        """
        Number of link pairs checked for self-collision.
        """
    @property
    def collision_links(self) -> list[str]:
        ...
    @property
    def collision_shapes(self) -> dict:
        """
        {link name: [Shape]} of the links with collision shapes (link frame).
        """
    @property
    def dof(self) -> int:
        ...
    @property
    def end_effectors(self) -> list:
        """
        SRDF end effectors: [{'name', 'parent_link', 'group', 'parent_group'}].
        """
    @property
    def groups(self) -> dict:
        """
        SRDF chain groups: name -> (base_link, tip_link).
        """
    @property
    def joint_names(self) -> list[str]:
        """
        Joints of the configuration vector, in order.
        """
    @property
    def link_names(self) -> list[str]:
        ...
    @property
    def lower(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def mimic_joints(self) -> list[str]:
        ...
    @property
    def model_hash(self) -> int:
        """
        64-bit hash of the URDF text and the allowed-collision pairs: what maps depend on.
        """
    @property
    def name(self) -> str:
        ...
    @property
    def named_states(self) -> dict[str, dict[str, float]]:
        """
        SRDF group states: name -> {joint: value} (for example 'tuck_left_arm').
        """
    @property
    def root_link(self) -> str:
        ...
    @property
    def source(self) -> RobotSource:
        """
        The URDF, SRDF and package folders the robot was read from.
        """
    @property
    def srdf_groups(self) -> dict:
        """
        Every SRDF group: name -> {'chains': [(base, tip)], 'joints': [...], 'links': [...], 'subgroups': [...]}.
        """
    @property
    def srdf_left_out(self) -> list[str]:
        """
        SRDF groups and end effectors left out (srdf_mismatch='leave_out'), each with what it names
        that the URDF lacks.
        """
    @property
    def upper(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def urdf_hash(self) -> int:
        """
        64-bit FNV-1a hash of the URDF text (the same for robots that differ only in their
        allowed collisions; see model_hash).
        """
    @property
    def visuals(self) -> dict:
        """
        {link name: [Visual]} of the links with <visual> elements.
        """
    @property
    def allowed_collision_sources(self) -> list:
        """
        (link_a, link_b, reason) of every allowed pair, in the order of allowed_collisions; reason: 'adjacent',
        'SRDF', 'never in collision', 'always in collision', 'in collision at home' (sampled) or 'given'.
        """
class Visual:
    """
    One URDF <visual> of a link: its Shape (link frame) and colour.
    """
    def __repr__(self) -> str:
        ...
    @property
    def material(self) -> str:
        ...
    @property
    def mesh_uri(self) -> str:
        """
        The URDF's mesh filename.
        """
    @property
    def rgba(self) -> typing.Any:
        """
        (red, green, blue, alpha) in [0, 1], or None when the URDF gives no colour.
        """
    @property
    def shape(self) -> Shape:
        """
        The Shape (a mesh's mesh_path is '' when its file was not found).
        """
class RobotSource:
    """
    The files a Robot was read from (absolute paths).
    """
    @property
    def package_dirs(self) -> list[str]:
        ...
    @property
    def srdf(self) -> str:
        """
        SRDF file ('' when none or given as XML text).
        """
    @property
    def urdf(self) -> str:
        """
        URDF file ('' when the URDF was given as XML text).
        """
class OrientationSet:
    """
    Evenly spread approach directions on the sphere, times rolls about each (index = direction * rolls + roll).
    """
    @staticmethod
    def sphere(count: typing.SupportsInt | typing.SupportsIndex = 200, rolls: typing.SupportsInt | typing.SupportsIndex = 1, symmetry: typing.SupportsInt | typing.SupportsIndex = 4, poles: bool = False) -> OrientationSet:
        ...
    @staticmethod
    def sphere_directions(count: typing.SupportsInt | typing.SupportsIndex, symmetry: typing.SupportsInt | typing.SupportsIndex = 4, poles: bool = False) -> int:
        """
        Number of directions sphere(count, ..., symmetry, poles) holds.
        """
    def __len__(self) -> int:
        ...
    def nearest_direction(self, d: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> int:
        ...
    def rotation(self, index: typing.SupportsInt | typing.SupportsIndex, approach_axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ...) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        Tool rotation (3x3) of orientation `index` for a tool whose approach axis is `approach_axis`.
        """
    def subset(self, name: str) -> list[int]:
        """
        Direction indices of 'all', 'upper_hemisphere' (d_z <= 0: gripper above the object), 'top', 'side', 'lower_hemisphere'.
        """
    @property
    def directions(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (K, 3) unit approach directions.
        """
    @property
    def poles(self) -> bool:
        """
        True when the set holds the directions along +z and -z.
        """
    @property
    def rolls(self) -> int:
        ...
    @property
    def symmetry(self) -> int:
        ...
class Arm:
    """
    An arm: base link, tip (tool) link, the tool's approach axis and why (reason), its name and where it
    was found (source). Arm.named / Arm.from_links / find_arms find them; the reference posture of the
    joints it does not move is default_reference(robot, robot.chain(arm.base_link, arm.tip_link)).
    """
    NOT_FOUND: typing.ClassVar[str]  # why find_arms finds no arm on a robot, as the errors that say so put it
    @staticmethod
    def from_links(robot: Robot, base_link: str, tip_link: str, approach_axis: typing.Any = None) -> Arm:
        """
        The arm base_link -> tip_link; the approach axis inferred from the gripper unless given.
        """
    @staticmethod
    def named(robot: Robot, name: str) -> Arm:
        """
        The arm called `name` (find_arms, else a serial SRDF group); ValueError listing the arms otherwise.
        """
    @staticmethod
    def resolve(robot: Robot, arm: typing.Any, approach_axis: typing.Any = None) -> Arm:
        """
        The arm of a name or of a (base_link, tip_link[, approach_axis]) tuple; approach_axis overrides the
        inferred axis. ValueError listing the arms that exist, or naming a missing link and the nearest names.
        """
    def __init__(self, base_link: str, tip_link: str, approach_axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def with_approach_axis(self, approach_axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> Arm:
        ...
    @property
    def approach_axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def base_link(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def reason(self) -> str:
        """
        Why this approach axis (inferred from the gripper, or 'given').
        """
    @property
    def source(self) -> str:
        """
        Where the arm was found (SRDF group, end effector, kinematic tree, links).
        """
    @property
    def tip_link(self) -> str:
        ...
class MapProvenance:
    """
    The robot a map was built for, as its file records it.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: MapProvenance) -> bool:
        ...
    def __ne__(self, arg0: MapProvenance) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def matches(self, robot: Robot) -> bool:
        """
        True when `robot` is the one recorded (name and URDF; the model hash where it is known).
        """
    @property
    def model_hash(self) -> int:
        """
        Robot.model_hash of the robot built for (URDF and allowed collisions); 0: unknown.
        """
    @property
    def robot_name(self) -> str:
        ...
    @property
    def urdf_hash(self) -> int:
        ...
class CapabilityMapOptions:
    """
    Build parameters of a capability map (defaults defined once, in C++).
    """
    def __init__(self) -> None:
        ...
    @property
    def approach_axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Tool axis that approaches the object (tool frame).
        """
    @approach_axis.setter
    def approach_axis(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def block_size(self) -> int:
        """
        0: one flood over the whole box; n: blocks of n voxels per edge, each flooded on its own
        (CapabilityBlocks: built anywhere, merged into the same bytes).
        """
    @block_size.setter
    def block_size(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def directions(self) -> int:
        """
        Approach directions on the sphere, rounded to the nearest multiple of the symmetry
        (4: 50 gives 52; with poles the spiral takes two fewer and the poles come on top: 200 gives 202).
        """
    @directions.setter
    def directions(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def exhaustive(self) -> bool:
        """
        Also run random-restart IK on every cell sampling did not reach.
        """
    @exhaustive.setter
    def exhaustive(self, arg0: bool) -> None:
        ...
    @property
    def exhaustive_attempts(self) -> int:
        ...
    @exhaustive_attempts.setter
    def exhaustive_attempts(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def fk_samples(self) -> int:
        """
        Forward-kinematics samples (0: 40 per voxel of the bounding box).
        """
    @fk_samples.setter
    def fk_samples(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def keep_solutions(self) -> bool:
        """
        Keep one joint solution per reachable cell.
        """
    @keep_solutions.setter
    def keep_solutions(self, arg0: bool) -> None:
        ...
    @property
    def orientation_tolerance(self) -> float:
        """
        IK tolerance (rad).
        """
    @orientation_tolerance.setter
    def orientation_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def poles(self) -> bool:
        """
        Also the directions straight up and down (+z, -z of the base link): for a tool held vertical
        (a SCARA's), which no direction of the spiral points along exactly. Recorded in files.
        """
    @poles.setter
    def poles(self, arg0: bool) -> None:
        ...
    @property
    def position_tolerance(self) -> float:
        """
        IK tolerance at the voxel centre (m).
        """
    @position_tolerance.setter
    def position_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def reference(self) -> typing.Any:
        """
        Robot configuration off the chain; None: default_reference(robot, chain).
        """
    @reference.setter
    def reference(self, arg1: typing.Any) -> None:
        ...
    @property
    def resolution(self) -> float:
        """
        Voxel edge (m).
        """
    @resolution.setter
    def resolution(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rolls(self) -> int:
        """
        Rolls per direction (1: any roll).
        """
    @rolls.setter
    def rolls(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        ...
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def self_collision(self) -> bool:
        """
        Solutions must be free of self-collision.
        """
    @self_collision.setter
    def self_collision(self, arg0: bool) -> None:
        ...
    @property
    def symmetry(self) -> int:
        """
        z symmetry of the direction set.
        """
    @symmetry.setter
    def symmetry(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def threads(self) -> int:
        """
        0: every core.
        """
    @threads.setter
    def threads(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class CapabilityLookup:
    """
    How CapabilityMap.reachable answers a pose from the cells. nearest_cell: the voxel holding the position.
    vote: the 8 voxel centres around the position weighted trilinearly; reachable when the reachable ones
    weigh at least one half (equal to nearest_cell at voxel centres). any: reachable when any of those 8
    is; no only where every cell around the pose says no (for pruning ahead of IK).
    """
    any: typing.ClassVar[CapabilityLookup]
    nearest_cell: typing.ClassVar[CapabilityLookup]
    vote: typing.ClassVar[CapabilityLookup]
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class CertifiedLookupOptions:
    """
    Options of CertifiedLookup (defaults defined once, in C++).
    """
    def __init__(self) -> None:
        ...
    @property
    def branch_seeds(self) -> int:
        """
        Configurations of other IK branches tried at most when the seeds fail (0: none), from the cells
        around the corners, each more than 1 rad from every configuration tried in some joint.
        """
    @branch_seeds.setter
    def branch_seeds(self, arg0: int) -> None:
        ...
    @property
    def collided_branch_seeds(self) -> int:
        """
        Configurations of other branches tried at most (instead of branch_seeds) once a descent reached
        the pose in self-collision: another branch often reaches it free.
        """
    @collided_branch_seeds.setter
    def collided_branch_seeds(self, arg0: int) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        """
        Iterations per descent.
        """
    @max_iterations.setter
    def max_iterations(self, arg0: int) -> None:
        ...
    @property
    def seeds(self) -> int:
        """
        Stored configurations IK starts from at most, nearest cells first.
        """
    @seeds.setter
    def seeds(self, arg0: int) -> None:
        ...
class CertifiedLookup:
    """
    Reachability of tool poses from a capability map where the cells around a pose agree, and from IK at the
    exact pose where they do not (the pose lies where the reachable set ends between the cells, or in a mixed
    cell; where the descents from the cells' configurations fail, configurations of other IK branches stored
    around them are tried too: branch_seeds; collided_branch_seeds once a descent reached the pose in
    self-collision). Needs a map built with solutions by this version; keeps the map
    alive.
    """
    def __init__(self, map: CapabilityMap, robot: Robot, reference: typing.Any = None, options: typing.Any = None, **kwargs) -> None:
        ...
    def certain(self, poses: typing.Any) -> numpy.ndarray:
        ...
    def reachable(self, poses: typing.Any, threads: int = 0) -> typing.Any:
        ...
    def solution(self, pose: typing.Any) -> typing.Any:
        ...
    @property
    def chain(self) -> Chain:
        ...
    @property
    def options(self) -> CertifiedLookupOptions:
        """
        A copy of the options (fixed when the lookup is made).
        """
    @property
    def reference(self) -> numpy.ndarray:
        ...
class CapabilityMap:
    """
    Capability map of an arm: for each voxel around the chain's base link, the reachable orientations.
    """
    extension: typing.ClassVar[str] = '.orcm'
    format_version: typing.ClassVar[int] = 3
    kind: typing.ClassVar[str] = 'capability'
    DEFAULT_LOOKUP: typing.ClassVar[CapabilityLookup]
    @staticmethod
    def build(chain: Chain, options: typing.Any = None, progress: typing.Any = True, **kwargs) -> CapabilityMap:
        """
        Builds the map of `chain` (positions in its base link frame); keyword arguments set CapabilityMapOptions
        fields. A cell (voxel, orientation) is reachable when IK finds a solution inside the limits, free of
        self-collision (joints off the chain at `reference`, default default_reference(robot, chain)), for the voxel
        centre. Forward-kinematics sampling proposes cells and IK seeds; a flood fill over neighbouring cells
        settles the rest; exhaustive=True also tries every other cell.
        progress: True draws a bar, False is silent, or a callable (done, total).
        """
    @staticmethod
    def build_for_arm(robot: Robot, arm: typing.Any, options: typing.Any = None, progress: typing.Any = True, **kwargs) -> CapabilityMap:
        """
        Builds the map of an arm (a name, an Arm or a (base_link, tip_link[, approach_axis]) tuple) with the arm's
        approach axis (inferred from the gripper unless given; approach_axis=(x, y, z) overrides it); other
        keyword arguments set CapabilityMapOptions fields.
        """
    @staticmethod
    def load(path: str) -> CapabilityMap:
        ...
    def __repr__(self) -> str:
        ...
    def export_octovis(self, path: str) -> None:
        """
        Writes a ColorOcTree (.ot) for octovis, red (low D) to blue (high D).
        """
    def reachability(self, points: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        Reachability index D (N,) of points (N, 3) in the base link frame; 0 outside.
        """
    def reachable(self, poses: typing.Any, lookup: CapabilityLookup | str | None = None) -> numpy.typing.NDArray[numpy.bool]:
        """
        True (N,) where tool pose (N, 4, 4) (base link frame) is reachable: the orientation nearest the pose's,
        the position by `lookup` (CapabilityLookup or its name; None: CapabilityMap.DEFAULT_LOOKUP, the vote).
        """
    def reachable_cell(self, point: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], orientation: typing.SupportsInt | typing.SupportsIndex) -> bool:
        """
        The stored cell: orientation index `orientation` reachable in the voxel holding `point` (the
        nearest_cell rule; reachable(poses) gives the map's answer for poses).
        """
    def save(self, path: str, with_solutions: bool = False) -> None:
        """
        Writes the map atomically; with_solutions also stores one joint solution per reachable cell.
        """
    def solution(self, point: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], orientation: typing.SupportsInt | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"] | None:
        """
        Stored joint solution of a reachable cell, or None when the cell is not reachable; ValueError on a
        map without solutions (has_solutions False).
        """
    def voxels(self) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]]:
        """
        (centres (M, 3), D (M,)) of the voxels with D > 0, base link frame.
        """
    @property
    def approach_axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def base_link(self) -> str:
        ...
    @property
    def bounds(self) -> tuple:
        """
        (min corner, max corner) of the reachable voxels.
        """
    @property
    def has_solutions(self) -> bool:
        """
        True when the map keeps joint solutions (built with keep_solutions, saved with them),
        also where no cell is reachable.
        """
    @property
    def model_hash(self) -> int:
        """
        Robot.model_hash of the robot built for (URDF and allowed collisions); 0: unknown.
        """
    @property
    def orientations(self) -> OrientationSet:
        ...
    @property
    def parameters(self) -> dict:
        ...
    @property
    def provenance(self) -> MapProvenance:
        """
        The robot the map was built for.
        """
    @property
    def resolution(self) -> float:
        ...
    @property
    def robot_name(self) -> str:
        ...
    @property
    def stats(self) -> dict:
        ...
    @property
    def tip_link(self) -> str:
        ...
    @property
    def urdf_hash(self) -> int:
        ...
    @property
    def voxel_count(self) -> int:
        ...
    @property
    def warning(self) -> str:
        """
        One line when the map looks suspicious, with what to try; '' otherwise: no reachable voxel
        (a reach thinner than a cell), a best voxel reaching few approach directions (something
        blocks the wrist), or more than MIXED_PER_REACHABLE mixed cells per reachable one (the plain
        lookups miss much of the reach). Builds emit it as a MapWarning.
        """
    @property
    def has_cell_data(self) -> bool:
        """
        True when the map marks its mixed cells (format 2; CertifiedLookup needs it).
        """
    @property
    def has_quality(self) -> bool:
        """
        True when the map keeps a quality per reachable cell (built with solutions).
        """
    @property
    def jacobian_rank(self) -> int:
        """
        Jacobian rank the manipulability was computed with (0: unknown).
        """
    @property
    def max_quality(self) -> float:
        """
        Largest cell quality of the map (0: none).
        """
    @property
    def reference(self) -> typing.Any:
        """
        Robot configuration the map was built at (None for older files).
        """
    def mixed_cell(self, point: typing.Any, orientation: typing.SupportsInt | typing.SupportsIndex) -> bool:
        """
        True when cell (point, orientation) is mixed: IK at its centre fails but a configuration reaches a pose
        inside it.
        """
    def quality(self, point: typing.Any, orientation: typing.SupportsInt | typing.SupportsIndex) -> typing.Any:
        """
        (manipulability, joint-limit penalty) of the stored solution of reachable cell (point, orientation), or
        None when the cell is not reachable; their product is the cell's quality. ValueError (saying how to
        rebuild) for a map without quality.
        """
    def voxel_quality(self, how: str = 'mean', relative: bool = False) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Per voxel of voxels() (D > 0): the mean or the largest quality (manipulability x penalty) of its reachable
        cells; relative=True divides by the map's best cell (values in [0, 1]). ValueError (saying how to rebuild)
        for a map without quality.
        """
class CapabilityBlocks:
    """
    The block build of a capability map (block_size voxels per block edge, default 16): one FK sampling
    of the whole workspace box, then each block's IK waves, flood fill and retry pass on its own cells,
    then a merge. A block's result depends on its seeds alone, so blocks built on any machine merge into
    the bytes CapabilityMap.build gives for the same options (block_size included). Seeds and results are
    bytes that carry a fingerprint of the plan; every machine must run the same octoreach build.
    """
    @staticmethod
    def seed_count(seeds: bytes) -> int:
        """
        Seeds in a seed list (the work of its block).
        """
    def __init__(self, robot: Robot, arm: typing.Any, options: typing.Any = None, **kwargs) -> None:
        """
        Plans the block build of an arm (name, Arm or (base, tip[, approach_axis]) tuple); keywords set
        CapabilityMapOptions fields (block_size 0 becomes 16).
        """
    def __repr__(self) -> str:
        ...
    def build(self, progress: typing.Any = True) -> CapabilityMap:
        """
        The three steps in this process (as CapabilityMap.build with block_size).
        """
    def build_block(self, block: typing.SupportsInt | typing.SupportsIndex, seeds: bytes, progress: typing.Any = False) -> bytes:
        """
        Step 2: block `block` from its seed list; its reachable cells and solutions (bytes).
        """
    def merge(self, results: typing.Any) -> CapabilityMap:
        """
        Step 3: the CapabilityMap from every block's result, in block order.
        """
    def sample(self, progress: typing.Any = False) -> list:
        """
        Step 1: the FK sampling of the whole box as one seed list (bytes) per block.
        """
    @property
    def block_size(self) -> int:
        """
        Voxels per block edge.
        """
    @property
    def count(self) -> int:
        """
        Number of blocks.
        """
    @property
    def fingerprint(self) -> int:
        """
        Fingerprint of the plan (robot model, options, reference posture, box).
        """
    @property
    def options(self) -> CapabilityMapOptions:
        """
        Options of the map built (block_size set).
        """
class PointMapOptions:
    """
    Build parameters of an inverse point map (defaults defined once, in C++).
    """
    def __init__(self) -> None:
        ...
    @property
    def grasps(self) -> typing.Any:
        """
        Grasp set: a subset name ('upper_hemisphere', 'top', 'side', 'all') or a list of direction indices.
        """
    @grasps.setter
    def grasps(self, arg1: typing.Any) -> None:
        ...
    @property
    def reference(self) -> typing.Any:
        """
        Robot configuration fixing the joints between reference frame and arm; None: the default.
        """
    @reference.setter
    def reference(self, arg1: typing.Any) -> None:
        ...
    @property
    def reference_frame(self) -> str:
        """
        Link whose pose is mapped ('': the root link).
        """
    @reference_frame.setter
    def reference_frame(self, arg0: str) -> None:
        ...
    @property
    def resolution(self) -> float:
        """
        Voxel edge (m); 0 or None: the capability map's resolution.
        """
    @resolution.setter
    def resolution(self, arg1: typing.Any) -> None:
        ...
    @property
    def theta_bins(self) -> int:
        ...
    @theta_bins.setter
    def theta_bins(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def threads(self) -> int:
        """
        0: every core.
        """
    @threads.setter
    def threads(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def use_symmetry(self) -> bool:
        """
        Derive the theta bins the grasp set's z symmetry determines by rotating the grid.
        """
    @use_symmetry.setter
    def use_symmetry(self, arg0: bool) -> None:
        ...
    @property
    def z_max(self) -> float:
        ...
    @z_max.setter
    def z_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def z_min(self) -> float:
        ...
    @z_min.setter
    def z_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def z_range(self) -> tuple[float, float]:
        """
        (min, max) base heights in metres; None: unbounded.
        """
    @z_range.setter
    def z_range(self, arg1: typing.Any) -> None:
        ...
    @property
    def quality_weight(self) -> bool:
        """
        R_P weights each reachable grasp by its cell's quality relative to the capability map's best
        cell (needs a map with quality); False: the paper's R_P, each grasp counts 1.
        """
    @quality_weight.setter
    def quality_weight(self, arg0: bool) -> None:
        ...
class InversePointMap:
    """
    Inverse point map: R_P of base poses (x, y, z, theta) of a reference frame around a target at the origin.
    """
    extension: typing.ClassVar[str] = '.orpm'
    format_version: typing.ClassVar[int] = 1
    kind: typing.ClassVar[str] = 'point'
    @staticmethod
    def build(robot: Robot, capability_map: CapabilityMap, options: typing.Any = None, progress: typing.Any = True, **kwargs) -> InversePointMap:
        """
        Inverts a capability map; keyword arguments set PointMapOptions fields. reference_frame: the link whose
        pose is mapped (default the root link, e.g. base_footprint). grasps: a subset name ('upper_hemisphere',
        'top', 'side', 'all') or a list of direction indices; a direction d means the tool approaches the target
        along d (world frame). reference: robot configuration fixing the joints between reference frame and arm
        (e.g. the torso). z_range: (min, max) base z relative to the target. theta bins that the grasp set's z
        symmetry determines are derived by rotating the grid instead of being recomputed.
        """
    @staticmethod
    def direct_reachability(capability_map: CapabilityMap, reference_to_arm: typing.Any, orientations: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex], poses: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        R_P computed straight from the capability map at continuous poses (N, 4), for checks.
        """
    @staticmethod
    def load(path: str) -> InversePointMap:
        ...
    def __repr__(self) -> str:
        ...
    def export_octovis(self, path: str) -> None:
        ...
    def reachability(self, poses: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        R_P (N,) of base poses (N, 4) as x, y, z, theta relative to the target; 0 outside.
        """
    def save(self, path: str) -> None:
        ...
    def voxels(self) -> tuple:
        """
        (centres (M, 3), values (M, theta_bins)) of the voxels with a non-zero value.
        """
    @property
    def approach_axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Approach axis of the arm's tool frame.
        """
    @property
    def arm_base_link(self) -> str:
        ...
    @property
    def arm_tip_link(self) -> str:
        ...
    @property
    def bounds(self) -> tuple:
        ...
    @property
    def build_seconds(self) -> float:
        ...
    @property
    def grasp_orientations(self) -> list[int]:
        ...
    @property
    def model_hash(self) -> int:
        """
        Robot.model_hash of the robot built for (URDF and allowed collisions); 0: unknown.
        """
    @property
    def parameters(self) -> dict:
        ...
    @property
    def provenance(self) -> MapProvenance:
        """
        The robot the map was built for.
        """
    @property
    def pose_count(self) -> int:
        """
        Number of (voxel, theta) poses with R_P > 0.
        """
    @property
    def reference_frame(self) -> str:
        ...
    @property
    def reference_to_arm(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def resolution(self) -> float:
        ...
    @property
    def robot_name(self) -> str:
        ...
    @property
    def theta_bins(self) -> int:
        ...
    @property
    def urdf_hash(self) -> int:
        ...
    @property
    def used_symmetry(self) -> bool:
        ...
    @property
    def voxel_count(self) -> int:
        ...
    @property
    def weight(self) -> str:
        """
        'quality' when R_P weights grasps by their cells' quality, else ''.
        """
class Surface:
    """
    A flat working surface: a planar polygon (3D vertices, world frame, convex or not, any height and tilt)
    with a thickness below its top face, plus obstacle boxes (legs, walls).
    """
    @staticmethod
    def rectangle(size_x: typing.SupportsFloat | typing.SupportsIndex, size_y: typing.SupportsFloat | typing.SupportsIndex, height: typing.SupportsFloat | typing.SupportsIndex, x: typing.SupportsFloat | typing.SupportsIndex = 0.0, y: typing.SupportsFloat | typing.SupportsIndex = 0.0, yaw: typing.SupportsFloat | typing.SupportsIndex = 0.0, thickness: typing.SupportsFloat | typing.SupportsIndex = 0.03) -> Surface:
        """
        A rectangular table top of size_x by size_y centred at (x, y), top face at `height`.
        """
    def __init__(self, vertices: typing.Any, thickness: typing.SupportsFloat | typing.SupportsIndex = 0.03) -> None:
        ...
    def add_box(self, size: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], pose: typing.Any) -> None:
        """
        Adds an obstacle box (extents, 4x4 centre pose in the world frame).
        """
    def add_legs(self, width: typing.SupportsFloat | typing.SupportsIndex = 0.05) -> None:
        """
        Adds a leg under each vertex down to the floor: a box `width` by `width` across, its sides
        along the world axes, its centre `width` from the vertex towards the polygon's centre.
        """
    def contains(self, points: typing.Any) -> numpy.typing.NDArray[numpy.bool]:
        """
        True where a point's projection on the plane lies inside the polygon.
        """
    def obstacles(self) -> Obstacles:
        """
        The surface slab and its boxes as Obstacles (for collision checks).
        """
    def points(self, resolution: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        Grid points (M, 3) inside the polygon, as used to build surface maps.
        """
    @property
    def area(self) -> float:
        ...
    @property
    def boxes(self) -> list:
        """
        The obstacle boxes as (size (3,), pose (4, 4)) pairs.
        """
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def triangles(self) -> numpy.typing.NDArray[numpy.int64]:
        """
        The polygon's triangles (M, 3) as indices into vertices (ear clipping; any simple polygon), wound
        counter-clockwise seen from the normal; their areas add up to area.
        """
    @property
    def thickness(self) -> float:
        ...
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
class SurfaceMapOptions:
    """
    Build parameters of a surface map (defaults defined once, in C++).
    """
    def __init__(self) -> None:
        ...
    @property
    def check_arm(self) -> bool:
        """
        Reject grasps whose arm passes below the surface inside its outline or touches a box or obstacle.
        """
    @check_arm.setter
    def check_arm(self, arg0: bool) -> None:
        ...
    @property
    def check_body(self) -> bool:
        """
        Reject base poses where the body touches the surface, boxes or obstacles.
        """
    @check_body.setter
    def check_body(self, arg0: bool) -> None:
        ...
    @property
    def grasp_height(self) -> float:
        """
        Grasp points lie this far above the surface (m).
        """
    @grasp_height.setter
    def grasp_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def grasps(self) -> typing.Any:
        """
        Grasp set: a subset name ('upper_hemisphere', 'top', 'side', 'all') or a list of direction indices.
        """
    @grasps.setter
    def grasps(self, arg1: typing.Any) -> None:
        ...
    @property
    def obstacles(self) -> Obstacles:
        """
        The rest of the room (Obstacles, world frame) or None: checked against the body and the arm.
        """
    @obstacles.setter
    def obstacles(self, arg1: typing.Any) -> None:
        ...
    @property
    def reference(self) -> typing.Any:
        """
        Robot configuration off the arm (torso, other arm); None: default_reference of the arm.
        """
    @reference.setter
    def reference(self, arg1: typing.Any) -> None:
        ...
    @property
    def reference_frame(self) -> str:
        """
        Link whose pose is mapped ('': the root link).
        """
    @reference_frame.setter
    def reference_frame(self, arg0: str) -> None:
        ...
    @property
    def resolution(self) -> float:
        """
        Voxel edge (m); 0 or None: the capability map's resolution.
        """
    @resolution.setter
    def resolution(self, arg1: typing.Any) -> None:
        ...
    @property
    def theta_bins(self) -> int:
        ...
    @theta_bins.setter
    def theta_bins(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def threads(self) -> int:
        """
        0: every core.
        """
    @threads.setter
    def threads(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def z_max(self) -> float:
        ...
    @z_max.setter
    def z_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def z_min(self) -> float:
        ...
    @z_min.setter
    def z_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def z_range(self) -> tuple[float, float]:
        """
        (min, max) base heights in metres; None: unbounded.
        """
    @z_range.setter
    def z_range(self, arg1: typing.Any) -> None:
        ...
    @property
    def quality_weight(self) -> bool:
        """
        R_P weights each valid grasp by its cell's quality relative to the capability map's best cell, so
        R_S and the sampler prefer base poses reached away from joint limits and singularities (needs a
        map with quality); False: the paper's R_S, each grasp counts 1.
        """
    @quality_weight.setter
    def quality_weight(self, arg0: bool) -> None:
        ...
class SurfaceMap:
    """
    Surface inverse reachability map: R_S of base poses (x, y, z, theta) of the reference frame, world frame.
    """
    extension: typing.ClassVar[str] = '.orsm'
    format_version: typing.ClassVar[int] = 2
    kind: typing.ClassVar[str] = 'surface'
    @staticmethod
    def build(robot: Robot, arm: typing.Any, surface: Surface, options: typing.Any = None, progress: typing.Any = True, **kwargs) -> SurfaceMap:
        """
        Surface map of `arm`: a CapabilityMap with solutions, or an arm name or (base, tip[, approach_axis])
        tuple whose capability map is built first (keywords directions, poles and seed; at `resolution`,
        default CapabilityMapOptions().resolution; a given map fixes its directions and seed, and directions=, seed= or
        poles= asking for others raise). Other keywords set SurfaceMapOptions fields. Base poses (x, y, z,
        theta) are of `reference_frame` (default the root link, e.g. base_footprint), world frame.
        The robot stands on the floor (z_range (0, 0), the default); give z_range=(lo, hi) for a floating base.
        `obstacles` (Obstacles: walls, other surfaces, meshes, OctoMaps) are checked against body and arm. `reference` fixes the joints off the arm
        (default: default_reference, the other arm tucked). Grasp points lie `grasp_height` above the surface.
        """
    @staticmethod
    def combine(maps: collections.abc.Sequence[SurfaceMap], mode: str = 'max') -> SurfaceMap:
        """
        Per-pose max ('max': any arm reaches) or min ('min': both arms reach) of maps of one robot, frame,
        resolution and theta bins; ValueError otherwise.
        """
    @staticmethod
    def load(path: str) -> SurfaceMap:
        ...
    def __repr__(self) -> str:
        ...
    def export_octovis(self, path: str) -> None:
        """
        ColorOcTree (.ot) for octovis: each voxel coloured by its best theta, red low, blue high.
        """
    def reachability(self, poses: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        R_S (N,) of base poses (N, 4) as x, y, z, theta (world frame); 0 outside the map. The condition attachment.
        """
    def save(self, path: str) -> None:
        """
        Writes the map atomically.
        """
    def voxels(self) -> tuple:
        """
        (centres (M, 3), R_S (M, theta_bins)) of the voxels with R_S > 0.
        """
    @property
    def approach_axes(self) -> str:
        """
        Approach axis (tip frame) of each arm's capability map, as in arms.
        """
    @property
    def arms(self) -> str:
        ...
    @property
    def bounds(self) -> tuple:
        """
        (min corner, max corner) of the voxels with R_S > 0.
        """
    @property
    def empty_reason(self) -> str:
        ...
    @property
    def max_reachability(self) -> float:
        ...
    @property
    def model_hash(self) -> int:
        """
        Robot.model_hash of the robot built for (URDF and allowed collisions); 0: unknown.
        """
    @property
    def parameters(self) -> dict:
        ...
    @property
    def provenance(self) -> MapProvenance:
        """
        The robot the map was built for.
        """
    @property
    def room(self) -> MapRoom:
        """
        The room the map was built with (MapRoom: obstacles and body); empty (room.empty) for files written before
        maps recorded their room.
        """
    @property
    def polygon(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def reference_frame(self) -> str:
        ...
    @property
    def resolution(self) -> float:
        ...
    @property
    def robot_name(self) -> str:
        ...
    @property
    def stats(self) -> dict:
        ...
    @property
    def theta_bins(self) -> int:
        ...
    @property
    def urdf_hash(self) -> int:
        ...
    @property
    def voxel_count(self) -> int:
        ...
    @property
    def z_range(self) -> tuple[float, float]:
        ...
    @property
    def warning(self) -> str:
        """
        One line when the build looks suspicious (the surface at the edge of the arm's reach), with
        what to try; '' otherwise and for a loaded map. Builds emit it as a MapWarning.
        """
    @property
    def weight(self) -> str:
        """
        'quality' when R_P weights grasps by their cells' quality, else ''.
        """
class CostMap:
    """
    2D navigation cost map: grid[row, col] covers x in [ox + col r, ...), y in [oy + row r, ...);
    free where the cost is below threshold; outside the grid is not free.
    """
    def __init__(self, grid: typing.Annotated[numpy.typing.ArrayLike, numpy.float32, "[m, n]"], origin: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], resolution: typing.SupportsFloat | typing.SupportsIndex, threshold: typing.SupportsFloat | typing.SupportsIndex = 0.5) -> None:
        ...
    def is_free(self, x: typing.SupportsFloat | typing.SupportsIndex, y: typing.SupportsFloat | typing.SupportsIndex) -> bool:
        ...
class PoseSampler:
    """
    Samples good, well spread base poses (x, y, z, theta) from a surface map: the grounding attachment.
    """
    def __init__(self, surface_map: SurfaceMap, candidates: typing.SupportsInt | typing.SupportsIndex = 40, discount_sigma: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[4, 1]"] = ..., seed: typing.SupportsInt | typing.SupportsIndex = 0, is_free: typing.Any = None, in_collision: typing.Any = None, max_draws: typing.SupportsInt | typing.SupportsIndex = 0, room_check: bool = True) -> None:
        """
        candidates: valid candidates per sample (best R_S x w wins). discount_sigma: S of eq. (3).
        is_free: a CostMap or a callable (pose (4,) as x, y, z, theta) -> bool. By default the body is checked against
        the room the map was built with (SurfaceMap.room); in_collision replaces that check: an Obstacles (the map's
        body against them), a tuple (robot, obstacles[, reference configuration]) checked with FCL in C++, or a
        callable (pose (4,)) -> bool (True = in collision). room_check=False turns the room check off.
        """
    def discount(self, pose: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[4, 1]"]) -> float:
        """
        w of eq. (3) for a pose against the history.
        """
    def reset(self) -> None:
        """
        Forgets the history and restarts the random stream.
        """
    def sample(self, k: typing.Any = None) -> typing.Any:
        """
        One base pose (4,) as x, y, z, theta, or k poses (k, 4); each is discounted against all earlier ones.
        """
    @property
    def history(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        Poses returned so far (K, 4).
        """
    @property
    def checks_room(self) -> bool:
        """
        True when the map's body is checked against a room (its own, or in_collision's Obstacles).
        """
    @property
    def last_counts(self) -> dict:
        ...
class MapRoom:
    """
    The room a surface map was built with (SurfaceMap.room): its obstacles (world frame) and the robot's body as
    the build checked it (in the map's reference frame). Saved in the map file.
    """
    def __repr__(self) -> str:
        ...
    def body_collides(self, poses: typing.Any, obstacles: Obstacles | None = None) -> numpy.typing.NDArray[numpy.bool_]:
        """
        (N,) bools: whether the body at base poses (N, 4) touches `obstacles` (default: the recorded ones).
        """
    def differences(self, obstacles: Obstacles, tolerance: typing.SupportsFloat = 0.0001) -> list[str]:
        """
        How `obstacles` differ from the recorded ones: a line per obstacle in only one of them.
        """
    def touched(self, poses: typing.Any, obstacles: Obstacles | None = None) -> list[str]:
        """
        Per base pose (N, 4), the name of the first obstacle the body touches there ('' when none).
        """
    @property
    def body(self) -> list[Shape]:
        ...
    @property
    def body_links(self) -> list[str]:
        ...
    @property
    def empty(self) -> bool:
        ...
    @property
    def obstacles(self) -> Obstacles:
        ...
    @property
    def surface_count(self) -> int:
        ...
class Scene:
    """
    Simulated world: Shapes (boxes with any pose, cylinders, spheres, meshes, OctoMaps), crates, closed
    boxes with an opening, boards. Whatever it holds is seen by the DepthCamera and is an obstacle
    (obstacles()). Metres, world frame.
    """
    def __init__(self) -> None:
        ...
    def add_board(self, lo: typing.Any, hi: typing.Any) -> None:
        ...
    def add_box(self, lo: typing.Any, hi: typing.Any) -> None:
        """
        Solid box (a board is a thin box).
        """
    def add_closed_box(self, lo: typing.Any, hi: typing.Any, thickness: typing.SupportsFloat | typing.SupportsIndex = 0.02, face: str = '-x', opening_width: typing.SupportsFloat | typing.SupportsIndex = 0.1, opening_height: typing.SupportsFloat | typing.SupportsIndex = 0.1) -> None:
        """
        Closed box with one opening centred in face '+x', '-x', '+y', '-y' or '+z'; its inside is an interior.
        """
    def add_crate(self, lo: typing.Any, hi: typing.Any, thickness: typing.SupportsFloat | typing.SupportsIndex = 0.02) -> None:
        """
        Open-topped crate; its inside is an interior.
        """
    def add_interior(self, lo: typing.Any, hi: typing.Any) -> None:
        """
        Records a region of interest for coverage figures.
        """
    def add_mesh(self, vertices: typing.Any, triangles: typing.Any) -> None:
        ...
    def add_obstacles(self, obstacles: Obstacles) -> None:
        """
        Adds every shape of an Obstacles set (a Room's, a Surface's).
        """
    def add_shape(self, shape: Shape) -> None:
        """
        Adds a Shape (world frame).
        """
    def bounds(self) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]]:
        ...
    def load_octomap(self, path: str) -> None:
        """
        Adds the occupied cells of an OctoMap .bt file to the world (OSError if it cannot be read).
        """
    def obstacles(self) -> Obstacles:
        """
        The scene's shapes as Obstacles (for collision checks).
        """
    def raycast(self, origin: typing.Any, direction: typing.Any, max_range: typing.SupportsFloat | typing.SupportsIndex = 4.0, normal: bool = False) -> typing.Any:
        """
        Distance to the first surface along the ray (direction: any non-zero length), or None; with
        normal=True (distance, unit surface normal facing the ray).
        """
    def solid(self, points: typing.Any) -> numpy.typing.NDArray[numpy.bool]:
        """
        True for points inside a solid box, sphere or cylinder.
        """
    @property
    def boxes(self) -> list:
        """
        Axis-aligned solid boxes as (lo, hi) pairs (rotated boxes are in shapes).
        """
    @property
    def interiors(self) -> list:
        """
        Regions of interest (insides of crates and closed boxes) as (lo, hi) pairs.
        """
    @property
    def shapes(self) -> list[Shape]:
        """
        Every Shape of the scene (world frame), in the order added.
        """
    @property
    def triangle_count(self) -> int:
        """
        Triangles of every mesh.
        """
class CameraIntrinsics:
    """
    Pinhole depth sensor: image size, horizontal fov (rad), range (m).
    """
    def __init__(self, width: typing.SupportsInt | typing.SupportsIndex = 640, height: typing.SupportsInt | typing.SupportsIndex = 480, fov: typing.SupportsFloat | typing.SupportsIndex = 1.0123, max_range: typing.SupportsFloat | typing.SupportsIndex = 4.0) -> None:
        ...
    @property
    def fov(self) -> float:
        ...
    @property
    def height(self) -> int:
        ...
    @property
    def max_range(self) -> float:
        ...
    @property
    def width(self) -> int:
        ...
class DepthCamera:
    """
    Simulated depth camera. It looks along its +z axis (+x right, +y down in the image, as
    ROS optical frames); poses are 4x4 camera -> world transforms. noise: depth standard
    deviation at 1 m, growing with depth^2. max_incidence (radians, (0, pi/2]): pixels whose
    ray meets the surface at a larger angle to its normal give no return (pi/2: never);
    noisy depths beyond max_range give none either.
    """
    def __init__(self, width: typing.SupportsInt | typing.SupportsIndex = 640, height: typing.SupportsInt | typing.SupportsIndex = 480, fov: typing.SupportsFloat | typing.SupportsIndex = 1.0123, max_range: typing.SupportsFloat | typing.SupportsIndex = 4.0, noise: typing.SupportsFloat | typing.SupportsIndex = 0.0, seed: typing.SupportsInt | typing.SupportsIndex = 0, max_incidence: typing.SupportsFloat | typing.SupportsIndex = 1.5707963267948966) -> None:
        ...
    def capture(self, scene: Scene, camera_pose: typing.Any, threads: typing.SupportsInt | typing.SupportsIndex = 0) -> numpy.typing.NDArray[numpy.float64]:
        """
        Points (N, 3), world frame, seen from camera_pose (4x4 camera -> world).
        """
    @property
    def fov(self) -> float:
        ...
    @property
    def height(self) -> int:
        ...
    @property
    def intrinsics(self) -> CameraIntrinsics:
        ...
    @property
    def max_incidence(self) -> float:
        ...
    @property
    def max_range(self) -> float:
        ...
    @property
    def noise(self) -> float:
        ...
    @property
    def width(self) -> int:
        ...
class VoidCluster:
    """
    Ellipsoidal cluster of void cells (map frame, metres): centroid, axes (columns e1..e3),
    eigenvalues (m^2, decreasing), semi_axes sqrt(5 lambda), fit score of eq. (2), cells.
    """
    def __repr__(self) -> str:
        ...
    @property
    def axes(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        ...
    @property
    def centroid(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def eigenvalues(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def keys(self) -> numpy.typing.NDArray[numpy.uint64]:
        ...
    @property
    def score(self) -> float:
        ...
    @property
    def semi_axes(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def size(self) -> int:
        ...
class ExplorationMap:
    """
    OctoMap occupancy map with incremental frontiers (free cells with an unknown 6-neighbour,
    clustered by 26-connectivity) and voids (unknown cells inside the convex hull of the
    occupied cells), clustered into ellipsoids. Map frame, metres.
    """
    @staticmethod
    def from_file(path: str, void_fit_threshold: typing.SupportsFloat | typing.SupportsIndex = 0.6, seed: typing.SupportsInt | typing.SupportsIndex = 0, max_cells: typing.SupportsInt | typing.SupportsIndex = 16777216, search_space: typing.Any = None) -> ExplorationMap:
        """
        Map from an OctoMap .bt file: FileNotFoundError if it does not exist, OSError if it cannot be read,
        states a resolution outside [1e-4, 1e4] m, covers more than max_cells finest-resolution cells, or
        its occupied cells span a box (clipped to search_space) too large to look for voids in.
        """
    def __init__(self, resolution: typing.SupportsFloat | typing.SupportsIndex = 0.025, void_fit_threshold: typing.SupportsFloat | typing.SupportsIndex = 0.6, seed: typing.SupportsInt | typing.SupportsIndex = 0, threads: typing.SupportsInt | typing.SupportsIndex = 0, track_voids: bool = True, search_space: typing.Any = None) -> None:
        """
        search_space: (2, 3) box (lo, hi) of the paper's search space S; voids are only looked for inside it.
        """
    def cells(self, which: str) -> numpy.typing.NDArray[numpy.float64]:
        """
        Centres (N, 3) of the frontier, void, occupied or free cells.
        """
    def center(self, key: typing.SupportsInt | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Centre (metres) of a cell key.
        """
    def centers(self, keys: typing.Annotated[numpy.typing.ArrayLike, numpy.uint64]) -> numpy.typing.NDArray[numpy.float64]:
        ...
    def changed_keys(self) -> numpy.typing.NDArray[numpy.uint64]:
        """
        Keys of the cells whose class the last insert changed.
        """
    def count_known(self, lo: typing.Any, hi: typing.Any) -> tuple[int, int]:
        """
        (known, unknown) cell counts in an axis-aligned box.
        """
    def frontier_clusters(self) -> list:
        """
        Frontier clusters as a list of (N, 3) cell centres.
        """
    def frontier_keys(self) -> numpy.typing.NDArray[numpy.uint64]:
        ...
    def frontier_voids(self) -> list:
        """
        Void clusters with the frontier clusters touching them: dicts with void_index, frontier_clusters,
        frontier_cells (touching frontier cells, (K, 3)) and utility (void volume, m^3).
        """
    def hull_vertices(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    def insert(self, points: typing.Any, sensor_origin: typing.Any, max_range: typing.SupportsFloat | typing.SupportsIndex = -1.0) -> dict:
        """
        Integrates points (N, 3) seen from sensor_origin (map frame); returns statistics and timings.
        Same occupancy as OctoMap insertPointCloud. Rows with NaN/inf are dropped; an empty cloud is a
        no-op; max_range <= 0 means unlimited. ValueError for a wrong shape, a non-finite origin or an
        origin outside the map bounds.
        """
    def inside_hull(self, arg0: typing.Any) -> bool:
        ...
    def key_of(self, arg0: typing.Any) -> int:
        ...
    def occupancy_digest(self) -> dict:
        """
        Counts and an order-independent hash of the finest-resolution occupancy (to compare trees).
        """
    def ray_statistics(self) -> dict:
        """
        What the rays of all inserts did to cells that were unknown (distinct cells that became free or
        occupied; all unknown cells and void cells alone) and the pass probabilities learned from it.
        """
    def recompute_from_scratch(self) -> dict:
        """
        The same, recomputed from the occupancy and hull alone.
        """
    def snapshot(self) -> dict:
        """
        Incrementally maintained frontier cells, clusters and void cells (keys).
        """
    def state(self, points: typing.Any) -> numpy.typing.NDArray[numpy.uint8]:
        """
        Class of the cell of each point (N, 3): 0 unknown, 1 free, 2 occupied.
        """
    def void_cluster_cells(self, cluster: VoidCluster) -> numpy.typing.NDArray[numpy.float64]:
        """
        Centres (N, 3) of a void cluster's cells.
        """
    def void_clusters(self) -> list[VoidCluster]:
        """
        Void clusters (ellipsoid region growing, deterministic for the map's seed).
        """
    def void_clusters_from_scratch(self) -> list[VoidCluster]:
        """
        Void clusters computed from scratch from the current void cells (void_clusters() equals them).
        """
    def void_keys(self) -> numpy.typing.NDArray[numpy.uint64]:
        ...
    def write_bt(self, path: str) -> None:
        """
        Writes an OctoMap .bt file (octovis can open it).
        """
    @property
    def frontier_cell_count(self) -> int:
        ...
    @property
    def pass_probability(self) -> float:
        """
        p of the next-best-view visibility model for unknown cells outside the voids, learned
        from the inserts so far.
        """
    @property
    def resolution(self) -> float:
        ...
    @property
    def void_cell_count(self) -> int:
        ...
    @property
    def void_pass_probability(self) -> float:
        """
        p of the visibility model for void cells (prior: pass_probability).
        """
    @property
    def sealed_void_cell_count(self) -> int:
        """
        void cells no view can reveal (their void component touches only occupied cells)
        """
class NbvOptions:
    """
    Options of next_best_view (defaults of the C++ struct); every attribute is also a
    keyword argument of next_best_view.
    """
    arm_collisions: bool
    capability_orientations: bool
    @staticmethod
    def exploration_loop() -> NbvOptions:
        """
        The exploration loop's search: 100 valid poses from the best 800 candidate cells, the best
        16 by a coarse score scored in full (rescore_best), the camera 5 cm clear of surfaces,
        enclosed voids and the exposed faces of voids first, the ground an obstacle for the arm
        (docs/design/next_best_view.md says why).
        """
    def __init__(self) -> None:
        ...
    @property
    def capability_base(self) -> typing.Any:
        """
        4x4 capability map base link -> map (None: identity).
        """
    @capability_base.setter
    def capability_base(self, arg1: typing.Any) -> None:
        ...
    @property
    def capability_map(self) -> CapabilityMap:
        """
        CapabilityMap of the arm carrying the camera, or None.
        """
    @capability_map.setter
    def capability_map(self, arg1: CapabilityMap) -> None:
        ...
    @property
    def chain(self) -> Chain:
        """
        Chain carrying the camera (its tip is the camera frame, +z forward), or None.
        """
    @chain.setter
    def chain(self, arg1: Chain) -> None:
        ...
    @property
    def chain_base(self) -> typing.Any:
        """
        4x4 chain base -> map (None: identity).
        """
    @chain_base.setter
    def chain_base(self, arg1: typing.Any) -> None:
        ...
    @property
    def reference(self) -> typing.Any:
        """
        The robot's configuration for the joints off the chain (robot.dof values, e.g.
        robot.configuration({...})) in the arm's collision checks; None: home.
        """
    @reference.setter
    def reference(self, arg1: typing.Any) -> None:
        ...
    @property
    def enclosure_power(self) -> float:
        """
        gain 'frontier_void': each void cell also counts with e^power in the ranking and the voids'
        utility, e its enclosure (share of the six axis directions that meet a surface before free
        space within enclosure_range); 0: the paper's plain count
        """
    @enclosure_power.setter
    def enclosure_power(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def enclosure_range(self) -> float:
        """
        metres walked from a void cell per direction for its enclosure
        """
    @enclosure_range.setter
    def enclosure_range(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gain(self) -> str:
        """
        what views are ranked by: 'frontier_void' (expected void cells), 'frontiers' (expected
        frontier cells) or 'unknown' (expected unknown cells, as nbvplanner)
        """
    @gain.setter
    def gain(self, arg1: str) -> None:
        ...
    @property
    def aiming(self) -> str:
        """
        how a chain's camera is placed: 'auto' (the default: 'look_at' for a chain of fewer than 5
        joints, such as a pan/tilt head, else 'pose'), 'pose' (IK of each candidate's position and
        optical axis) or 'look_at' (the chain aims the optical axis at void or frontier cells; the
        position follows)
        """
    @aiming.setter
    def aiming(self, arg1: str) -> None:
        ...
    @property
    def ground_is_obstacle(self) -> bool:
        """
        with a chain: the ground is an obstacle for the links the chain moves, at the lower of the
        robot's root link and the map's search space floor (on in exploration_loop())
        """
    @ground_is_obstacle.setter
    def ground_is_obstacle(self, arg0: bool) -> None:
        ...
    @property
    def look_at_tolerance(self) -> float:
        """
        aiming 'look_at': radians an aimed optical axis may miss its target by
        """
    @look_at_tolerance.setter
    def look_at_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ik_attempts(self) -> int:
        ...
    @ik_attempts.setter
    def ik_attempts(self, arg1: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def ik_orientation_tolerance(self) -> float:
        ...
    @ik_orientation_tolerance.setter
    def ik_orientation_tolerance(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ik_position_tolerance(self) -> float:
        ...
    @ik_position_tolerance.setter
    def ik_position_tolerance(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_candidate_cells(self) -> int:
        ...
    @max_candidate_cells.setter
    def max_candidate_cells(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_valid_poses(self) -> int:
        """
        N of the paper: stop after this many valid poses
        """
    @max_valid_poses.setter
    def max_valid_poses(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def min_distance(self) -> float:
        """
        metres from the camera to the nearest point of any occupied cell
        """
    @min_distance.setter
    def min_distance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def min_reachability(self) -> float:
        ...
    @min_reachability.setter
    def min_reachability(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def orientation_spread(self) -> float:
        """
        radians around the mean utility direction
        """
    @orientation_spread.setter
    def orientation_spread(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def orientations_per_cell(self) -> int:
        ...
    @orientations_per_cell.setter
    def orientations_per_cell(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def rescore_best(self) -> int:
        """
        n > 0: next_best_view (and the loop's aimed looks) score valid poses with a grid half as fine
        across and down first, and only the n best by each ranking key with the full grid (ranked
        holds those); the aimed looks rank more than 16 n poses with every fourth ray first and go
        on in chunks of 16 n; 0: every one in full. A camera that only aims, score_views and the
        baselines always score in full; views beyond the voids rank as the aimed looks, at most 2 in full.
        """
    @rescore_best.setter
    def rescore_best(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def score_height(self) -> int:
        ...
    @score_height.setter
    def score_height(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def score_width(self) -> int:
        ...
    @score_width.setter
    def score_width(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seeds the orientation samples and the IK restarts
        """
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def threads(self) -> int:
        ...
    @threads.setter
    def threads(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def unexposed_weight(self) -> float:
        """
        gain 'frontier_void': a void cell with no observed free cell among its 26 neighbours counts
        with this factor in [0, 1] in the ranking and the voids' utility (1: none)
        """
    @unexposed_weight.setter
    def unexposed_weight(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def unknown_is_obstacle(self) -> bool:
        """
        safe views: unknown cells of the map's search space are obstacles for the arm and the camera
        """
    @unknown_is_obstacle.setter
    def unknown_is_obstacle(self, arg0: bool) -> None:
        ...
    @property
    def unknown_margin(self) -> float:
        """
        metres around the camera with no unknown cell of the search space (unknown_is_obstacle)
        """
    @unknown_margin.setter
    def unknown_margin(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def unknown_pass_probability(self) -> typing.Any:
        """
        p of the visibility model (chance that an unknown cell lets a ray through); None: learned by the map
        """
    @unknown_pass_probability.setter
    def unknown_pass_probability(self, arg1: typing.Any) -> None:
        ...
    @property
    def workspace(self) -> typing.Any:
        """
        Callable taking positions (N, 3) (candidate cell centres, aimed eyes) and returning (N,) bools, each
        judged on its own (a search may call it several times), or None.
        """
    @workspace.setter
    def workspace(self, arg1: typing.Any) -> None:
        ...
    @property
    def workspace_box(self) -> typing.Any:
        """
        Sensor positions inside this box ((2, 3): lo, hi rows; map frame), or None.
        """
    @workspace_box.setter
    def workspace_box(self, arg1: typing.Any) -> None:
        ...
    @property
    def workspace_sphere(self) -> typing.Any:
        """
        Sensor positions within (center, radius) of a point (map frame), or None.
        """
    @workspace_sphere.setter
    def workspace_sphere(self, arg1: typing.Any) -> None:
        ...
class ExploreOptions:
    """
    Settings of the exploration loop (explore(); defaults of the C++ struct, docs/design/next_best_view.md
    says why each value): its search, budget and stopping rule, and how it chooses a view beyond the search.
    """
    @staticmethod
    def benchmark() -> ExploreOptions:
        """
        The exploration benchmark's settings: its stated stopping rule (min_utility 10 expected void
        cells for patience 3 views in a row).
        """
    def __copy__(self) -> ExploreOptions:
        ...
    def __deepcopy__(self, memo: dict) -> ExploreOptions:
        ...
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        ValueError naming the first bad setting (the search's: by the search).
        """
    @property
    def aimed_distance(self) -> tuple[float, float]:
        """
        (min, max) metres from an aimed eye to its void cell
        """
    @aimed_distance.setter
    def aimed_distance(self, arg0: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def aimed_poses(self) -> int:
        """
        second look: poses aimed at void cells, per base
        """
    @aimed_poses.setter
    def aimed_poses(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def beyond_voids(self) -> bool:
        """
        frontier_void: a view beyond the voids (toward the search space's unknown cells outside the hull of the occupied cells) where it expects more unknown cells of the search space (voids included) than frontier-void's view expects void cells, and where frontier-void's choice would end the loop
        """
    @beyond_voids.setter
    def beyond_voids(self, arg0: bool) -> None:
        ...
    @property
    def failed_view_radius(self) -> float:
        """
        metres: no view is chosen this near the camera of a view not taken
        """
    @failed_view_radius.setter
    def failed_view_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def last_directions(self) -> int:
        """
        last chance (the choice would end the loop): rays out of each void cell, half of them through the voids' gates (observed-free cells with a void cell across a face)
        """
    @last_directions.setter
    def last_directions(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def last_distance(self) -> tuple[float, float]:
        """
        (min, max) metres from a last-chance eye to its void cell
        """
    @last_distance.setter
    def last_distance(self, arg0: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def last_poses(self) -> int:
        """
        last chance: poses kept from those rays
        """
    @last_poses.setter
    def last_poses(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def learn_misses(self) -> bool:
        """
        announce each view before its insert (expect_view)
        """
    @learn_misses.setter
    def learn_misses(self, arg0: bool) -> None:
        ...
    @property
    def low_aimed_poses(self) -> int:
        """
        before a low view is taken: this many more poses, aimed at any void cell
        """
    @low_aimed_poses.setter
    def low_aimed_poses(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_ray_cells(self) -> int:
        """
        last chance: void cells the rays leave from, and gates they pass, each at most
        """
    @max_ray_cells.setter
    def max_ray_cells(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_views(self) -> int:
        """
        view budget
        """
    @max_views.setter
    def max_views(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def min_camera_height(self) -> float:
        """
        metres: sampled and aimed cameras stay above this
        """
    @min_camera_height.setter
    def min_camera_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def min_utility(self) -> float:
        """
        stop when the chosen view's utility has been <= this for `patience` views in a row (0: the
        paper's rule, utility 0)
        """
    @min_utility.setter
    def min_utility(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def patience(self) -> int:
        """
        chosen views in a row at or below min_utility before the loop stops
        """
    @patience.setter
    def patience(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def physical_check(self) -> bool:
        """
        with a robot: a view whose arm touches the scene's true geometry is not taken
        """
    @physical_check.setter
    def physical_check(self, arg0: bool) -> None:
        ...
    @property
    def sampled_poses(self) -> int:
        """
        baselines: camera poses sampled per view and base
        """
    @sampled_poses.setter
    def sampled_poses(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def search(self) -> NbvOptions:
        """
        NbvOptions of every view's search (default NbvOptions.exploration_loop()); its seed is the
        run's: the map's, and view k searches with seed + k
        """
    @search.setter
    def search(self, arg0: NbvOptions) -> None:
        ...
    @property
    def second_look(self) -> bool:
        """
        frontier_void: poses aimed at void cells are scored on every view too, the better view taken
        """
    @second_look.setter
    def second_look(self, arg0: bool) -> None:
        ...
    @property
    def unexposed_share(self) -> float:
        """
        share of the void cells with no observed free neighbour among the aimed poses' targets
        """
    @unexposed_share.setter
    def unexposed_share(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @staticmethod
    def paper_stop() -> ExploreOptions:
        """
        The paper's stop rule: the first chosen view with utility 0 (min_utility 0,
        patience 1).
        """
    def stop_threshold(self, camera: typing.Any, resolution: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        min_utility, or when it is None the void cells a view must be expected to see to be worth taking:
        score_width x score_height x resolution / camera.max_range (the cells its score rays would meet if one
        cell in every max_range / resolution cells along them were void).
        """
class ViewGains:
    """
    What a camera pose is expected to see (the visibility model of next_best_view).
    """
    def to_dict(self) -> dict:
        """
        Every field as a dict (views inside as dicts too).
        """
    @property
    def expected_enclosed_void(self) -> float:
        """
        expected_void with each void cell weighted by enclosure_power and unexposed_weight
        """
    @property
    def expected_frontier(self) -> float:
        """
        frontier cells weighted likewise
        """
    @property
    def expected_unknown(self) -> float:
        """
        unknown cells of the search space weighted likewise, each outside the voids also by the chance that its ray returns at or behind it (1 when it ends on an occupied cell)
        """
    @property
    def expected_void(self) -> float:
        """
        void cells weighted by their expected visibility
        """
    @property
    def frontier_cells(self) -> int:
        """
        distinct frontier cells met (raw)
        """
    @property
    def unknown_cells(self) -> int:
        """
        distinct unknown cells of the search space met (void cells included; raw)
        """
    @property
    def void_cells(self) -> int:
        """
        distinct void cells met before the first occupied cell (raw)
        """
class ViewGainsResult(ViewGains):
    """
    view_gains' answer: the gains and the p it used.
    """
    @property
    def pass_probability(self) -> float:
        """
        p for unknown cells outside the voids
        """
    @property
    def void_pass_probability(self) -> float:
        """
        p for void cells
        """
class ViewCandidate(ViewGains):
    """
    A scored camera pose (a view of next_best_view).
    """
    @property
    def cell_utility(self) -> float:
        """
        accumulated utility at the pose's candidate cell (m^3; 0 for given poses)
        """
    @property
    def expected_gain(self) -> float:
        """
        the expected gain of `gain` (the ranking key)
        """
    @property
    def pose(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        4x4 camera -> map
        """
    @property
    def q(self) -> typing.Any:
        """
        arm joints (with a chain and an IK solution), else None
        """
    @property
    def utility_dm3(self) -> float:
        """
        expected_void as a volume, dm^3
        """
class ScoredView(ViewCandidate):
    """
    One pose scored by score_views, with its status.
    """
    @property
    def status(self) -> str:
        """
        'valid', 'outside_workspace', 'not_reachable', 'camera_not_clear', 'no_ik' or 'arm_collision'
        """
    @property
    def valid(self) -> bool:
        """
        status == 'valid'
        """
class ScoredViews:
    """
    score_views' answer: per-pose arrays (the fields of ScoredView), and the poses one by one
    (len, [i], iteration); `best_by` picks the first valid view in the ranking order.
    """
    def __getitem__(self, index: typing.SupportsInt | typing.SupportsIndex) -> ScoredView:
        ...
    def __iter__(self) -> collections.abc.Iterator[ScoredView]:
        ...
    def __len__(self) -> int:
        ...
    def best_by(self, by: str = 'expected_gain') -> typing.Any:
        """
        The first valid view in the ranking order by `by` ('expected_gain' or 'expected_void'), then expected
        unknown cells; None when no view is valid.
        """
    def to_dict(self) -> dict:
        """
        Every field as a dict (views inside as dicts too).
        """
    @property
    def expected_enclosed_void(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def expected_frontier(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def expected_gain(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N,) the expected gain of `gain` (NaN for invalid poses with score_invalid=False)
        """
    @property
    def expected_unknown(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def expected_void(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def frontier_cells(self) -> numpy.typing.NDArray[numpy.int64]:
        ...
    @property
    def gain(self) -> str:
        """
        the gain expected_gain is of
        """
    @property
    def pass_probability(self) -> float:
        """
        p the model used for unknown cells outside the voids
        """
    @property
    def pose(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, 4, 4): the pose the arm reaches when IK succeeds, else the given one
        """
    @property
    def q(self) -> typing.Any:
        """
        (N, dof) joints, NaN rows without a solution; None without a chain
        """
    @property
    def status(self) -> list:
        """
        list of 'valid', 'outside_workspace', 'not_reachable', 'camera_not_clear', 'no_ik', 'arm_collision'
        """
    @property
    def unknown_cells(self) -> numpy.typing.NDArray[numpy.int64]:
        ...
    @property
    def utility_dm3(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def valid(self) -> numpy.typing.NDArray[numpy.bool]:
        ...
    @property
    def void_cells(self) -> numpy.typing.NDArray[numpy.int64]:
        ...
    @property
    def void_pass_probability(self) -> float:
        """
        p it used for void cells
        """
class NbvResult:
    """
    next_best_view's answer: the valid poses ranked (best first), the best one's figures and the
    search's statistics.
    """
    def best_by(self, by: str = 'expected_gain') -> typing.Any:
        """
        The first ranked view by `by` ('expected_gain': `best`; 'expected_void': the most expected void
        cells), then expected unknown cells; None when there is none.
        """
    def to_dict(self) -> dict:
        """
        Every field as a dict (views inside as dicts too).
        """
    @property
    def arm_collisions(self) -> int:
        """
        IK solutions whose arm touches an occupied (or unknown) cell
        """
    @property
    def best(self) -> typing.Any:
        """
        the best view, or None
        """
    @property
    def best_pose(self) -> typing.Any:
        """
        4x4 camera -> map of the best view, or None
        """
    @property
    def camera_not_clear(self) -> int:
        """
        cells whose camera is not in observed-free space
        """
    @property
    def candidate_cells(self) -> int:
        """
        after workspace and capability-map pruning
        """
    @property
    def capability_pruned(self) -> int:
        """
        cells the capability map removed
        """
    @property
    def capability_rejected(self) -> int:
        """
        sampled poses the capability map ruled out
        """
    @property
    def expected_enclosed_void(self) -> float:
        """
        of the best view
        """
    @property
    def expected_frontier(self) -> float:
        """
        of the best view
        """
    @property
    def expected_gain(self) -> float:
        """
        of the best view: its expected gain of `gain`
        """
    @property
    def expected_unknown(self) -> float:
        """
        of the best view
        """
    @property
    def expected_void(self) -> float:
        """
        of the best view
        """
    @property
    def frontier_cells(self) -> int:
        """
        of the best view
        """
    @property
    def gain(self) -> str:
        """
        the gain the views are ranked by
        """
    @property
    def ik_failures(self) -> int:
        ...
    @property
    def pass_probability(self) -> float:
        """
        p the model used for unknown cells outside the voids
        """
    @property
    def poses_scored(self) -> int:
        ...
    @property
    def ranked(self) -> list[ViewCandidate]:
        """
        valid views (ViewCandidate), best first (with rescore_best: those scored in full)
        """
    @property
    def seconds(self) -> float:
        ...
    @property
    def seconds_prune(self) -> float:
        """
        step 3
        """
    @property
    def seconds_score(self) -> float:
        """
        step 4
        """
    @property
    def seconds_vectors(self) -> float:
        """
        steps 1-2
        """
    @property
    def unknown_cells(self) -> int:
        """
        of the best view
        """
    @property
    def utility_cells(self) -> int:
        """
        cells with utility > 0 in the workspace's box and sphere
        """
    @property
    def utility_dm3(self) -> float:
        """
        of the best view: expected_void as dm^3
        """
    @property
    def utility_vectors(self) -> int:
        ...
    @property
    def void_cells(self) -> int:
        """
        of the best view
        """
    @property
    def void_pass_probability(self) -> float:
        """
        p it used for void cells
        """
def accumulate_utility(map: ExplorationMap, sensor_range: typing.SupportsFloat | typing.SupportsIndex) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
    """
    Algorithm 1: (cell centres (N, 3), accumulated utility (N,), m^3) before workspace pruning.
    """
def arm_names(robot: Robot) -> list[str]:
    """
    Names of find_arms(robot), sorted.
    """
def base_pose(pose: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[4, 1]"]) -> numpy.typing.NDArray[numpy.float64]:
    """
    4x4 pose (world frame) of a frame at base pose (x, y, z, theta): yaw about z, then translation.
    """
def default_reference(robot: Robot, chain: Chain) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    Reference posture (robot configuration) for the joints off `chain`: home with every SRDF 'tuck*' state
    applied that does not move the chain (the other arm tucked). Builds use it when given no reference.
    """
def expect_view(map: ExplorationMap, camera: typing.Any, camera_pose: typing.Any, options: typing.Any = None, **kwargs) -> None:
    """
    Announces the view (4x4 camera -> map) the map's next insert comes from: the unknown cells it is
    expected to see (score_width x score_height rays, unknown_pass_probability as in next_best_view)
    are recorded with their ray weights w, and the next insert multiplies the seeability of each one it
    leaves unknown by (1 - w). Later view scores count unknown cells with w * seeability; a void cell
    its rays still meet after the insert with no surface behind it within range (they ended on nothing)
    counts 0 in views from an eye within the angle one cell spans from this one and no nearer.
    """
def exposed_cells(map: ExplorationMap, keys: numpy.typing.ArrayLike) -> numpy.typing.NDArray[numpy.bool_]:
    """
    (N,) bools: each cell (keys (N,) uint64) has an observed free cell among its 26 neighbours (the
    exposure NbvOptions.unexposed_weight weighs).
    """
def find_arms(robot: Robot) -> list[Arm]:
    """
    The robot's arms: serial SRDF groups (tips moved to their tool frames), else branches of the kinematic
    tree that end in a gripper-like tip.
    """
def grasp_orientations(orientations: OrientationSet, directions: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> list[int]:
    """
    Orientation indices (d * rolls + r, sorted) of an OrientationSet for direction indices, all rolls of each.
    """
def infer_approach_axis(robot: Robot, base_link: str, tip_link: str) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], str]:
    """
    (axis, reason): the approach axis of the tool frame tip_link inferred from the gripper; ValueError saying
    how to give it when it cannot be inferred.
    """
def link_roles(robot: Robot, chain: Chain) -> dict:
    """
    Collision links by role: 'body' (not moved by the chain), 'arm' (moved by it), 'tool' (rigid with the tip).
    """
def load_any(path: str, kind: str = '') -> CapabilityMap | InversePointMap | SurfaceMap:
    """
    The map stored at `path` (CapabilityMap, InversePointMap or SurfaceMap), of the kind its header names;
    with `kind` the file must hold that kind. OSError naming the file and the problem (not a map file, an
    unknown or unexpected kind, damage); ValueError for a `kind` that is not a map kind.
    """
def look_at(eye: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], target: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], roll: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> numpy.typing.NDArray[numpy.float64]:
    """
    Camera pose (4x4 camera -> world) at `eye` looking at `target` (world frame), rolled by `roll` radians
    about the optical axis (+z); at roll 0 the image +y points down.
    """
limits: types.MappingProxyType[str, int | float]
"""The numeric limits octoreach checks its inputs against (cpp/include/octoreach/limits.hpp), read-only."""
def map_format_version() -> int:
    """
    The newest map file format version this library writes and reads (part of a map cache key); older
    versions are read too, and each map kind writes its own (SurfaceMap.format_version).
    """
def map_kind(path: str) -> str:
    """
    The kind tag a map file's header names ('capability', 'point', 'surface'), without loading the map.
    OSError naming the file when it is not an octoreach map file.
    """
def map_kinds() -> dict[str, str]:
    """
    The map kinds a file can hold: {kind tag: usual file extension}.
    """
def missed_cells(map: ExplorationMap) -> int:
    """
    Unknown cells whose seeability a missed view (expect_view) has lowered.
    """
def next_best_view(map: ExplorationMap, camera: typing.Any, options: typing.Any = None, **kwargs) -> NbvResult:
    """
    Next best view (Algorithm 1 + frustum scoring). Options: an NbvOptions and/or its attributes as
    keyword arguments. Returns an NbvResult: ranked (the valid views, best first, as ViewCandidate;
    with rescore_best, those scored in full), best and best_pose (4x4 camera -> map, or None), the best
    view's gains, expected_gain (of `gain`) and utility_dm3, the pass probabilities used and the
    search's statistics. The workspace is
    workspace_box ((2, 3): lo, hi), workspace_sphere ((center, radius)) and/or workspace, a callable
    taking cell centres (N, 3) and returning (N,) bools. With chain (its tip is the camera frame,
    +z forward) and chain_base (4x4 chain base -> map), a pose counts only if IK reaches it.
    capability_map (a CapabilityMap of that arm) with capability_base (4x4 map base link -> map) prunes
    candidate cells where each of the 8 voxels around them has reachability index <= min_reachability before
    any IK, and with capability_orientations skips IK for sampled poses whose optical axis none of the 8 cells
    around them reaches (CapabilityLookup.any: the map says no only where it is sure).
    arm_collisions (with chain): IK solutions whose links touch an occupied cell are rejected.
    """
def ranks_before(a: ViewCandidate, b: ViewCandidate, by: str = 'expected_gain') -> bool:
    """
    True when view a ranks before view b in the one order of views: more of `by` ('expected_gain' or
    'expected_void'), then more expected unknown cells (next_best_view's ranking, best_by's choice).
    """
def score_views(map: ExplorationMap, camera: typing.Any, poses: typing.Any, options: typing.Any = None, *, score_invalid: bool = True, **kwargs) -> ScoredViews:
    """
    Gains and validity of given camera poses (N, 4, 4) (camera -> map) with the checks and ray casting
    of next_best_view (same options: workspace_*, capability_map, chain, chain_base, arm_collisions,
    min_distance, unknown_is_obstacle, unknown_margin, gain, unknown_pass_probability, score_*).
    A chain that can only aim its camera (aiming 'look_at', or 'auto' and fewer than 5 joints: a pan/tilt
    head) aims it at the point half the camera's range along each pose's optical axis, and the checks and
    gains are of the pose it reaches, which pose and q hold whenever the aim succeeds (status no_ik when
    it cannot aim there).
    Returns ScoredViews: per-pose arrays valid, status, pose (the pose the arm reaches when IK succeeds,
    else the given one), q, the gains and expected_gain (of `gain`), and the poses one by one as
    ScoredView. score_invalid=False: poses that fail a check are not ray cast (cell counts 0, expected
    gains NaN), far less work when most fail.
    """
def set_progress_factory(factory: typing.Any) -> None:
    """
    Registers factory(progress, label) -> callable (done, total) or None, used for progress=True and
    callables; octoreach/__init__.py registers octoreach.progress.make_progress. None unregisters.
    """
def visibility_curve(map: ExplorationMap) -> dict:
    """
    The visibility curve the map learned from the views announced with expect_view: per unknown depth d
    (index; the last holds deeper cells), for unknown cells outside the voids ('unknown_*') and void cells
    ('void_*'), the cells views expected (weighted by seeability), the cells their inserts turned known and
    the learned non-increasing share.
    """
def void_enclosure(map: ExplorationMap, range: typing.SupportsFloat | typing.SupportsIndex = 0.5) -> tuple[numpy.typing.NDArray[numpy.uint64], numpy.typing.NDArray[numpy.float64]]:
    """
    How enclosed each void cell is, as next_best_view's enclosure_power weighs it: (keys (N,) uint64
    sorted as map.void_keys(), enclosure (N,) in [0, 1]): the share of the six axis directions that, walking
    from the cell through unknown cells up to `range` metres, meet an occupied cell (1) rather than a
    free one (0; unknown all the way: 1/2).
    """
__version__: str = '0.2.0'

def view_gains(map: ExplorationMap, camera: typing.Any, camera_pose: typing.Any, score_width: typing.SupportsInt | typing.SupportsIndex = 48, score_height: typing.SupportsInt | typing.SupportsIndex = 36, pass_probability: typing.Any = None) -> ViewGainsResult:
    """
    What a camera at camera_pose (4x4) is expected to see under the visibility model (a ray's weight
    starts at 1 and is multiplied by pass_probability after each unknown cell, and a cell counts with
    the chance that its ray returns at or behind it: 1 in front of an occupied cell, else 1 minus the
    product of the pass probabilities of the unknown cells from there on; None: the map's learned
    values, void_pass_probability for void cells and pass_probability for the others, and its visibility
    curve learned from the views announced with expect_view): a ViewGainsResult (the raw distinct
    void_cells, unknown_cells, frontier_cells, their visibility-weighted expected_void, expected_unknown,
    expected_frontier, expected_enclosed_void, and the pass probabilities used).
    """
def view_utility(map: ExplorationMap, camera: typing.Any, camera_pose: typing.Any, score_width: typing.SupportsInt | typing.SupportsIndex = 48, score_height: typing.SupportsInt | typing.SupportsIndex = 36) -> tuple[int, int]:
    """
    (void cells, unknown cells) a camera at camera_pose (4x4) sees before the first occupied cell,
    casting a score_width x score_height grid of rays.
    """
__version__: str = '0.2.0'
class SelfCollisionOptions:
    """
    What self_collision_report samples (defaults defined once, in C++).
    """
    def __init__(self) -> None:
        ...
    @property
    def joints(self) -> list[str]:
        """
        Joints drawn at random (names; empty: every joint).
        """
    @joints.setter
    def joints(self, arg0: collections.abc.Sequence[str]) -> None:
        ...
    @property
    def links(self) -> list[str]:
        """
        Only the checked pairs of two of these links count (empty: every pair).
        """
    @links.setter
    def links(self, arg0: collections.abc.Sequence[str]) -> None:
        ...
    @property
    def reference(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Values of the joints not drawn (empty: home()).
        """
    @reference.setter
    def reference(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def samples(self) -> int:
        """
        Random configurations.
        """
    @samples.setter
    def samples(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        ...
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def threads(self) -> int:
        """
        0: every core.
        """
    @threads.setter
    def threads(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class PairHits:
    """
    A checked link pair and the sampled configurations that put it in collision.
    """
    def __repr__(self) -> str:
        ...
    @property
    def hits(self) -> int:
        ...
    @property
    def link_a(self) -> str:
        ...
    @property
    def link_b(self) -> str:
        ...
class SelfCollisionReport:
    """
    Random configurations free of self-collision and the pairs that collide, most often first.
    """
    FREE_SHARE_HINT: typing.ClassVar[float] = 0.75
    def __repr__(self) -> str:
        ...
    @property
    def free(self) -> int:
        ...
    @property
    def free_share(self) -> float:
        ...
    @property
    def pairs(self) -> list[PairHits]:
        ...
    @property
    def samples(self) -> int:
        ...
    @property
    def suspicious(self) -> bool:
        """
        free_share below FREE_SHARE_HINT: the collision model likely blocks the joints.
        """
class CameraLink:
    """
    A robot's camera link and why it was chosen.
    """
    def __repr__(self) -> str:
        ...
    @property
    def link(self) -> str:
        ...
    @property
    def reason(self) -> str:
        """
        'given', or how find_camera_link found it.
        """
class HeldJoint:
    """
    A moving joint a map build holds still, at its reference value (rad or m).
    """
    def __repr__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> float:
        ...
class ArmReport:
    """
    An arm's joints as map builds see them.
    """
    @property
    def base_to_include_held(self) -> str:
        """
        The link to give as the chain's base (--base LINK) to include every held joint; '' when none.
        """
    @property
    def held(self) -> list[HeldJoint]:
        """
        Moving joints between the root and the arm's base link, held at default_reference().
        """
    @property
    def moving(self) -> list[str]:
        """
        The chain's moving joints, base to tip.
        """
    @property
    def self_collision(self) -> SelfCollisionReport:
        """
        The arm's joints drawn at random, the rest of the robot at default_reference(); only pairs of two
        links the arm moves count (its collision model fighting its joints).
        """
    @property
    def with_body(self) -> SelfCollisionReport:
        """
        The same draws with every checked pair (the body too).
        """
class MapWarning(UserWarning):
    """
    A map build whose result looks suspicious (a capability map whose best voxel reaches few directions, a
    surface at the edge of the arm's reach): the message says why and what to try.
    """
def arm_report(robot: Robot, arm: typing.Any, options: typing.Any = None, progress: typing.Any = False, **kwargs) -> ArmReport:
    """
    The ArmReport of an arm (a name, an Arm or a (base_link, tip_link) tuple); keywords set SelfCollisionOptions
    fields of the arm's self-collision sampling (samples, seed, threads).
    """
def camera_link(robot: Robot, given: typing.Any = None) -> CameraLink:
    """
    `given` checked against the robot's links (reason 'given'), or find_camera_link(robot) when it is None.
    """
def find_camera_link(robot: Robot) -> CameraLink:
    """
    The robot's head camera link: the links named like a camera on one rigid body (on the head when they are
    on several), else the end of the head; ValueError naming the candidates and asking for the link otherwise.
    The planner's inspect actions use its position. Its axes are the URDF's: a camera link often looks along +x,
    so an exploration chain ends at the camera's optical frame (+z forward), named as in the URDF.
    """
def self_collision_report(robot: Robot, options: typing.Any = None, progress: typing.Any = False, **kwargs) -> SelfCollisionReport:
    """
    How often configurations drawn uniformly inside the joint limits are free of self-collision, and how often
    each checked pair collides; keywords set SelfCollisionOptions fields (samples, seed, joints, reference).
    """
class ChoiceMemory:
    """
    What the exploration loop remembers between choices of a view (plain data, copyable).
    """
    def __copy__(self) -> ChoiceMemory:
        ...
    def __init__(self) -> None:
        ...
    @property
    def beyond_misses(self) -> int:
        """
        frontier_void: views beyond the voids in a row that saw no more than the stop threshold of the search space's unknown cells; at patience none is chosen until a view sees more
        """
    @beyond_misses.setter
    def beyond_misses(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def choices(self) -> int:
        """
        views chosen so far
        """
    @choices.setter
    def choices(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def failed_views(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, 3) cameras of views chosen and not taken: no view is chosen near them again
        """
    @failed_views.setter
    def failed_views(self, arg1: typing.Any) -> None:
        ...
    @property
    def last_beyond(self) -> bool:
        """
        the last choice was a view beyond the voids
        """
    @last_beyond.setter
    def last_beyond(self, arg0: bool) -> None:
        ...
    @property
    def last_space_seen(self) -> int | None:
        """
        unknown cells of the search space the last view taken made known (InsertStats space_known; Explorer sets it) or None: see beyond_misses (cleared by the next choice)
        """
    @last_space_seen.setter
    def last_space_seen(self, arg0: typing.SupportsInt | typing.SupportsIndex | None) -> None:
        ...
    @property
    def last_void_seen(self) -> int | None:
        """
        void cells the last view taken took off the void set (InsertStats void_removed; Explorer sets it) or None: for frontier_void and random, a low view that saw more than the stop threshold breaks the row of low views (cleared by the next choice)
        """
    @last_void_seen.setter
    def last_void_seen(self, arg0: typing.SupportsInt | typing.SupportsIndex | None) -> None:
        ...
    @property
    def low_views(self) -> int:
        """
        choices in a row with utility <= min_utility (frontier-void's utility, also where a view beyond the voids was taken instead)
        """
    @low_views.setter
    def low_views(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class ViewChoice:
    """
    choose_view's answer: the view, its utility and the stop decision.
    """
    @property
    def aimed(self) -> bool:
        """
        found by a look aimed at void cells
        """
    @property
    def base(self) -> int:
        """
        index of the base the view is taken from
        """
    @property
    def beyond(self) -> bool:
        """
        frontier_void (beyond_voids): a view beyond the voids, expecting the most unknown cells of the search space (its expected_unknown is the utility): more than frontier-void's view expects void cells, or where frontier-void's own choice would end the loop
        """
    @property
    def candidates(self) -> int:
        """
        poses scored
        """
    @property
    def found(self) -> bool:
        """
        a valid view was found
        """
    @property
    def harder(self) -> bool:
        """
        found by the looks before a low view
        """
    @property
    def search(self) -> NbvResult:
        """
        frontier_void: next_best_view's answer from the chosen base
        """
    @property
    def stop(self) -> bool:
        """
        the loop ends here
        """
    @property
    def stop_reason(self) -> str:
        """
        why it ends ('' when it goes on)
        """
    @property
    def utility(self) -> float:
        """
        the gain the stop rule looks at
        """
    @property
    def valid(self) -> int:
        """
        of them valid (with rescore_best, of those an aimed look checked)
        """
    @property
    def view(self) -> typing.Any:
        """
        the view (ViewCandidate: pose, q, gains) or None
        """
class NextView:
    """
    Explorer.next_view()'s answer: the view to take next, or why to stop.
    """
    @property
    def base(self) -> int:
        """
        index of the base pose to drive to
        """
    @property
    def base_pose(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def camera_pose(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        4x4 camera -> map
        """
    @property
    def choice(self) -> ViewChoice:
        """
        choose_view's whole answer (ViewChoice)
        """
    @property
    def expected_gain(self) -> float:
        """
        what the stop rule looks at (expected void cells)
        """
    @property
    def q(self) -> typing.Any:
        """
        chain joints, or None
        """
    @property
    def stop(self) -> bool:
        ...
    @property
    def stop_reason(self) -> str:
        ...
class ExplorerCore:
    """
    An exploration session (octoreach.exploration.Explorer wraps it): the map, the loop's memory,
    integrate clouds or depth images, ask for the next view.
    """
    def __init__(self, camera: typing.Any, search_space: typing.Any, bases: typing.Any = None, reach: typing.SupportsFloat | typing.SupportsIndex = 0.0, resolution: typing.Any = None, void_fit_threshold: typing.Any = None, options: typing.Any = None, strategy: str = 'frontier_void') -> None:
        ...
    def integrate(self, points: typing.Any, camera_pose: typing.Any) -> dict:
        ...
    def integrate_depth(self, depth: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], camera_pose: typing.Any) -> dict:
        ...
    def next_view(self) -> NextView:
        ...
    def view_failed(self) -> None:
        ...
    @property
    def current_base(self) -> int:
        ...
    @property
    def map(self) -> ExplorationMap:
        ...
    @property
    def memory(self) -> ChoiceMemory:
        ...
    @property
    def views(self) -> int:
        ...
def choose_view(map: ExplorationMap, camera: typing.Any, bases: typing.Any, current: typing.SupportsInt | typing.SupportsIndex, options: ExploreOptions, memory: ChoiceMemory, strategy: str = 'frontier_void', reach: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> ViewChoice:
    """
    The exploration loop's whole choice of the next view from any of `bases` ((N, 4, 4) chain base -> map;
    the current one first): the search, the second looks, the last chance and the stop decision, with
    options (ExploreOptions; its search's chain carries the camera). `reach` (m, with a chain and no
    workspace): the camera stays that near each base. Updates `memory` (ChoiceMemory). Returns ViewChoice.
    """
