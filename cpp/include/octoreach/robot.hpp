#pragma once
/// \file robot.hpp
/// \brief Robot model built from a URDF (urdfdom): links, joints, SRDF groups and collision checking.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "octoreach/chain.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

namespace detail {
struct RobotBuilder;  // fills a Robot while from_urdf builds it (urdf.cpp, srdf.cpp)
}  // namespace detail

/// \brief One URDF joint.
struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parent_link = -1;                         ///< index into Robot::links()
  int child_link = -1;                          ///< index into Robot::links()
  Pose origin = Pose::Identity();               ///< parent link frame -> joint frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< in the joint frame, unit length
  double lower = 0.0;                           ///< lower limit (-inf for continuous)
  double upper = 0.0;                           ///< upper limit (+inf for continuous)
  int index = -1;     ///< position in the robot's configuration vector; -1 for fixed and mimic joints
  int mimic = -1;     ///< index of the joint it mimics (into Robot::joints()), -1 if none
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;
};

/// \brief One URDF `<visual>` element: what a viewer draws of a link.
struct Visual {
  /// The shape in the link frame, without collision geometry (drawn, never checked); a mesh's file is resolved
  /// as a collision mesh's is, and mesh_path is "" when it could not be found (mesh_uri says which it was).
  Shape shape;
  std::string mesh_uri;                          ///< the URDF's mesh filename ("" for other shapes)
  std::string material;                          ///< material name ("" when none)
  std::optional<std::array<double, 4>> rgba;     ///< colour (red, green, blue, alpha in [0, 1]) when given
};

/// \brief One URDF link: its collision shapes and its visuals.
struct Link {
  std::string name;
  int parent_joint = -1;          ///< index into Robot::joints(), -1 for the root
  std::vector<int> child_joints;  ///< indices into Robot::joints()
  std::vector<Shape> shapes;      ///< collision shapes (empty if the link has none)
  std::vector<Visual> visuals;    ///< visual elements (empty if the link has none)
};

/// \brief Where a robot came from: what Robot::from_urdf read.
struct RobotSource {
  std::string urdf;                       ///< URDF file (absolute path); "" when given as XML text
  std::vector<std::string> package_dirs;  ///< folders package:// mesh URIs were resolved against
  std::string srdf;                       ///< SRDF file (absolute path); "" when none or given as XML text
};

/// \brief A chain group declared in an SRDF (for example the PR2's "right_arm").
struct ChainGroup {
  std::string name, base_link, tip_link;
};

/// \brief Any SRDF group as written: chains, joint lists, link lists and subgroups (names checked
/// against the URDF when the robot is built).
struct SrdfGroup {
  std::string name;
  std::vector<std::pair<std::string, std::string>> chains;  ///< (base_link, tip_link)
  std::vector<std::string> joints, links, subgroups;
};

/// \brief An SRDF end effector: the gripper group `group` attached at `parent_link` (of the arm
/// group `parent_group`, which may be empty).
struct EndEffector {
  std::string name, parent_link, group, parent_group;
};

/// \brief How the allowed-collision matrix is sampled (MoveIt setup assistant's method): pairs never
/// in collision over `samples` random configurations, pairs always in collision, and pairs in
/// collision at the home posture are allowed; adjacent pairs always are.
struct AllowedCollisionOptions {
  int samples = 5000;       ///< random configurations (MoveIt's default is 10,000)
  std::uint64_t seed = 0;   ///< sample i uses the stream mix64(seed, i): the result never depends on threads
  int threads = 0;          ///< 0 = every core
  bool default_posture = true;  ///< also allow pairs in collision at home() (MoveIt's "Default")
  /// Folder of the on-disk cache (keyed by model_hash, samples and seed); "" = $OCTOREACH_CACHE_DIR,
  /// else $XDG_CACHE_HOME/octoreach, else ~/.cache/octoreach; "none" = no cache.
  std::string cache_dir;
};

/// \brief Why a link pair is allowed to touch: the reasons MoveIt's setup assistant writes, and where the pair
/// came from (Robot::allowed_sources()).
enum class AllowedSource {
  kAdjacent,        ///< a link and its nearest ancestor with geometry
  kSrdf,            ///< a `<disable_collisions>` entry of the SRDF
  kNever,           ///< sampled: never in collision over the random configurations
  kAlways,          ///< sampled: always in collision over them
  kDefaultPosture,  ///< sampled: in collision at home()
  kGiven,           ///< added by Robot::with_allowed_collisions
};

/// \brief "adjacent", "SRDF", "never in collision", "always in collision", "in collision at home", "given".
const char* allowed_source_name(AllowedSource source);

/// \brief Pairs added by sampling, by the reason MoveIt's setup assistant gives them.
struct SampledCollisions {
  std::vector<std::pair<int, int>> never, always, default_posture;
  bool from_cache = false;  ///< read from the on-disk cache instead of sampled
  std::string cache_file;   ///< the cache file read or written ("" without cache)
};

/// \brief What Robot::from_urdf does with SRDF groups and end effectors that name links, joints or groups the
/// URDF lacks (an SRDF of another variant of the robot): an error naming them, or leave those entries out (as
/// MoveIt's srdfdom does, which warns), keeping the rest; Robot::srdf_left_out() says what was left out.
enum class SrdfMismatch { kError, kLeaveOut };

/// \brief Robot model: links, joints, collision shapes, allowed-collision pairs.
///
/// Build it with Robot::from_urdf. A Robot never changes once built (every member function is
/// const), so one robot serves any number of threads and chains at once. A different
/// allowed-collision matrix makes a new robot (with_allowed_collisions), with its own model_hash().
class Robot : public std::enable_shared_from_this<Robot> {
 public:
  /// \brief Parses a URDF (file path or XML string); resolves package:// and file:// mesh URIs
  /// through `package_dirs`; reads chain groups and disabled collision pairs from an SRDF
  /// (file path or XML string, may be empty); `mismatch` says what to do with SRDF entries the URDF does not fit.
  /// \throws std::invalid_argument on malformed input, std::runtime_error on unreadable files
  static std::shared_ptr<Robot> from_urdf(const std::string& urdf, const std::vector<std::string>& package_dirs = {},
                                          const std::string& srdf = "", SrdfMismatch mismatch = SrdfMismatch::kError);

  /// \brief The URDF's robot name.
  const std::string& name() const { return name_; }
  /// \brief The URDF and SRDF files and package folders the robot was read from.
  const RobotSource& source() const { return source_; }
  /// \brief 64-bit FNV-1a hash of the URDF text (the same for robots that differ only in their
  /// allowed-collision matrix; see model_hash()).
  std::uint64_t urdf_hash() const { return urdf_hash_; }
  /// \brief Hash of the model as maps depend on it: the URDF text and the allowed-collision matrix
  /// (two robots from one URDF with different allowed pairs have different model hashes).
  std::uint64_t model_hash() const;
  /// \brief Links, parents before children (breadth-first from the root).
  const std::vector<Link>& links() const { return links_; }
  /// \brief Joints, in the order of their child links.
  const std::vector<Joint>& joints() const { return joints_; }
  /// \brief Index of the root link (0).
  int root_link() const { return root_link_; }
  /// \brief Index of a link by name; throws std::invalid_argument naming the link and the nearest
  /// names the robot has if absent.
  int link_index(const std::string& name) const;
  /// \brief Index of a joint by name; throws std::invalid_argument if absent.
  int joint_index(const std::string& name) const;
  /// \brief True when the robot has a link of that name.
  bool has_link(const std::string& name) const { return link_by_name_.count(name) > 0; }

  /// \brief Number of entries of a configuration vector (moving, non-mimic joints).
  int dof() const { return static_cast<int>(active_joints_.size()); }
  /// \brief Names of the configuration vector's joints, in order.
  std::vector<std::string> joint_names() const;
  /// \brief Lower limits of the configuration vector (-inf for continuous joints).
  Eigen::VectorXd lower() const;
  /// \brief Upper limits of the configuration vector (+inf for continuous joints).
  Eigen::VectorXd upper() const;
  /// \brief Zero configuration moved into the joint limits.
  Eigen::VectorXd home() const;
  /// \brief Mimic joints found in the URDF (reported, left out of chains and of the configuration).
  std::vector<std::string> mimic_joints() const;
  /// \brief Chain groups from the SRDF.
  const std::vector<ChainGroup>& groups() const { return groups_; }
  /// \brief Every SRDF group as written (chains, joint lists, link lists, subgroups), in file order.
  const std::vector<SrdfGroup>& srdf_groups() const { return srdf_groups_; }
  /// \brief SRDF end effectors, in file order.
  const std::vector<EndEffector>& end_effectors() const { return end_effectors_; }
  /// \brief SRDF groups and end effectors left out by SrdfMismatch::kLeaveOut, each with what it names that the
  /// URDF lacks ("group 'r_leg': link 'r_foot' (did you mean ...)"); empty when everything was read.
  const std::vector<std::string>& srdf_left_out() const { return srdf_left_out_; }
  /// \brief Moving joints (indices into joints()) of an SRDF group: its chains, joints, the parent
  /// joints of its links and its subgroups, in tree order; throws naming an unknown group.
  std::vector<int> group_joints(const std::string& group) const;
  /// \brief Named joint values from the SRDF's group states (for example the PR2's "tuck_left_arm").
  const std::map<std::string, std::map<std::string, double>>& named_states() const { return named_states_; }
  /// \brief Configuration with values from a name -> value map, the rest from home().
  Eigen::VectorXd configuration(const std::map<std::string, double>& values) const;

  /// \brief Kinematic chain from base_link to tip_link; throws std::invalid_argument if absent
  /// or if base_link is not an ancestor of tip_link.
  Chain chain(const std::string& base_link, const std::string& tip_link) const;

  /// \brief Poses of every link in the root link frame, indexed like links().
  std::vector<Pose> link_poses(const Eigen::VectorXd& q) const;
  /// \brief Same as link_poses(q), into `out` (reused storage).
  void link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out) const;
  /// \brief The joints (indices into joints(), in the order link_poses evaluates them) between the
  /// root link and `links` (indices into links()): what link_poses(q, out, joints) evaluates.
  std::vector<int> joints_placing(const std::vector<int>& links) const;
  /// \brief link_poses(q, out) for the links `joints` place only: the same poses for those links and
  /// the root, far less work for a few links of a large robot; the other entries of `out` are left as
  /// they were. `joints` must be what joints_placing gave (every joint between the root and a placed
  /// link, ascending): a joint whose parent link is not placed reads that link's stale entry.
  /// \throws std::invalid_argument for indices that do not ascend, std::out_of_range for a bad index.
  void link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out, const std::vector<int>& joints) const;

  /// \brief True when two links not allowed to touch are in collision at q.
  bool in_self_collision(const Eigen::VectorXd& q) const;
  /// \brief True when any link (or any of `only_links`, by index) touches an obstacle; the robot's
  /// root sits at `base_pose` (world frame). `check_self` also checks the robot against itself.
  bool in_collision(const Eigen::VectorXd& q, const Obstacles& obstacles, const Pose& base_pose = Pose::Identity(),
                    bool check_self = false, const std::vector<int>* only_links = nullptr) const;
  /// \brief True when a link (the `only_links` indices, or every collision link) at the given link
  /// poses (root link frame) touches an obstacle, with the root at `base_pose` (world frame).
  bool links_in_collision(const std::vector<Pose>& link_poses, const Obstacles& obstacles,
                          const Pose& base_pose, const std::vector<int>* only_links = nullptr) const;
  /// \brief Lowest point (world z) of the robot's collision geometry at the given link poses (root link
  /// frame) with the root at `base_pose`, over every link with geometry or the `only_links` indices: mesh
  /// vertices and box corners exactly, other shapes by their bounding box; `link` gets the index of the
  /// link that holds it (-1 when there is no geometry, and the result is +inf).
  double lowest_point(const std::vector<Pose>& link_poses, const Pose& base_pose, int* link = nullptr,
                      const std::vector<int>* only_links = nullptr) const;
  /// \brief Self-collision of the checked pairs at the given link poses (root link frame).
  bool in_self_collision_poses(const std::vector<Pose>& link_poses) const;
  /// \brief Self-collision over the given link pairs only.
  bool in_self_collision_poses(const std::vector<Pose>& link_poses, const std::vector<std::pair<int, int>>& pairs) const;

  /// \brief Pairs of links whose collisions are ignored (sorted link indices, i < j).
  const std::vector<std::pair<int, int>>& allowed_pairs() const { return allowed_; }
  /// \brief Why each pair of allowed_pairs() is allowed (same order); the first reason a pair got is kept
  /// (adjacency before the SRDF's word). Not part of model_hash(): maps depend on the pairs only.
  const std::vector<AllowedSource>& allowed_sources() const { return allowed_sources_; }
  /// \brief Pairs of links checked for self-collision.
  const std::vector<std::pair<int, int>>& checked_pairs() const { return checked_; }
  /// \brief A new robot, the same as this one with `pairs` (link indices, either order) added to
  /// the allowed-collision matrix; pairs of a link with itself and pairs already allowed change
  /// nothing. This robot is left as it is. `source` is recorded as the new pairs' reason.
  /// \throws std::invalid_argument for a link index outside links()
  std::shared_ptr<Robot> with_allowed_collisions(const std::vector<std::pair<int, int>>& pairs,
                                                 AllowedSource source = AllowedSource::kGiven) const;
  /// \brief Same as with_allowed_collisions, with links by name.
  /// \throws std::invalid_argument naming a link the robot does not have
  std::shared_ptr<Robot> with_allowed_collisions(const std::vector<std::pair<std::string, std::string>>& pairs) const;
  /// \brief Samples `samples` random configurations (deterministic for `seed`) and returns the
  /// checked pairs never or always in collision over them (as MoveIt's setup assistant finds them),
  /// sorted: the pairs to pass to with_allowed_collisions. Empty when there is nothing to add.
  /// \throws std::invalid_argument if samples < 1, Cancelled when `progress` returns false
  std::vector<std::pair<int, int>> compute_allowed_collisions(int samples = 2000, std::uint64_t seed = 0,
                                                              const ProgressCallback& progress = nullptr) const;
  /// \brief MoveIt-style set-up of the allowed-collision matrix (allowed_collisions.cpp): among the
  /// checked pairs, those never or always in collision over options.samples random configurations
  /// and those in collision at home(); read from / written to the on-disk cache when it is enabled.
  /// \throws std::invalid_argument if samples < 1, Cancelled when `progress` returns false
  SampledCollisions sample_allowed_collisions(const AllowedCollisionOptions& options = {},
                                              const ProgressCallback& progress = nullptr) const;
  /// \brief This robot with sample_allowed_collisions() added to its allowed pairs.
  std::shared_ptr<Robot> with_sampled_collisions(const AllowedCollisionOptions& options = {},
                                                 const ProgressCallback& progress = nullptr) const;
  /// \brief Checked pairs in collision at the link poses (at most `limit`), to name them in errors.
  std::vector<std::pair<int, int>> colliding_pairs(const std::vector<Pose>& link_poses,
                                                   const std::vector<std::pair<int, int>>& pairs,
                                                   std::size_t limit = 8) const;
  /// \brief SRDF text of the model: its groups, end effectors, group states and every allowed pair
  /// as `<disable_collisions>` with MoveIt's reason words ("Adjacent", "Never", "Always", "Default", "User";
  /// "Allowed" for the pairs read from an SRDF).
  std::string srdf_text() const;
  /// \brief srdf_text() written atomically to `path`.
  void write_srdf(const std::string& path) const;

  /// \brief Links with collision geometry.
  const std::vector<int>& collision_links() const { return collision_links_; }

 private:
  friend struct detail::RobotBuilder;
  Robot() = default;
  Robot(const Robot&) = default;
  /// Sets the allowed pairs (i < j) with their reasons and derives the checked pairs from them.
  void set_allowed_pairs_(const std::map<std::pair<int, int>, AllowedSource>& allowed);
  std::string name_;
  RobotSource source_;
  std::uint64_t urdf_hash_ = 0;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<int> active_joints_;  // joint indices, in configuration order
  int root_link_ = 0;
  std::map<std::string, int> link_by_name_, joint_by_name_;
  std::vector<ChainGroup> groups_;
  std::vector<SrdfGroup> srdf_groups_;
  std::vector<EndEffector> end_effectors_;
  std::vector<std::string> srdf_left_out_;
  std::map<std::string, std::map<std::string, double>> named_states_;
  std::vector<std::pair<int, int>> allowed_, checked_;
  std::vector<AllowedSource> allowed_sources_;
  std::vector<int> collision_links_;
};

}  // namespace octoreach
