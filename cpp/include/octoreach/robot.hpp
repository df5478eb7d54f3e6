#pragma once
/// \file robot.hpp
/// \brief Robot model built from a URDF (urdfdom), kinematic chains, and collision checking.

#include <map>
#include <memory>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "octoreach/collision.hpp"
#include "octoreach/types.hpp"

namespace KDL {
class Chain;
}

namespace octoreach {

/// \brief Joint kinds understood by octoreach (URDF planar and floating joints are kept fixed).
enum class JointType { Fixed, Revolute, Continuous, Prismatic };

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

/// \brief One URDF link and its collision shapes.
struct Link {
  std::string name;
  int parent_joint = -1;          ///< index into Robot::joints(), -1 for the root
  std::vector<int> child_joints;  ///< indices into Robot::joints()
  std::vector<Shape> shapes;      ///< collision shapes (empty if the link has none)
};

class Robot;
struct IkOptions;

/// \brief A serial chain between two links of a robot, with FK, Jacobian and IK.
///
/// Immutable and cheap to copy; safe to share between threads.
class Chain {
 public:
  /// \brief One moving or fixed step of the chain.
  struct Segment {
    Pose origin = Pose::Identity();  ///< previous frame -> joint frame
    JointType type = JointType::Fixed;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    int robot_joint = -1;  ///< index into Robot::joints()
  };

  const std::string& base_link() const { return base_link_; }
  const std::string& tip_link() const { return tip_link_; }
  /// \brief Number of moving joints.
  int dof() const { return static_cast<int>(joint_names_.size()); }
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  /// \brief Positions of the chain's joints in the robot configuration vector.
  const std::vector<int>& robot_indices() const { return robot_indices_; }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }
  /// \brief True for continuous (unbounded, wrapped) joints.
  const std::vector<bool>& continuous() const { return continuous_; }
  const std::vector<Segment>& segments() const { return segments_; }
  const Robot& robot() const { return *robot_; }
  std::shared_ptr<const Robot> robot_ptr() const { return robot_; }

  /// \brief Pose of the tip link in the base link frame.
  Pose fk(const Eigen::VectorXd& q) const;
  /// \brief Pose of the tip and its 6 x dof geometric Jacobian (rows: linear, angular), base frame.
  Pose fk_jacobian(const Eigen::VectorXd& q, Eigen::Matrix<double, 6, Eigen::Dynamic>& jacobian) const;
  /// \brief True when q has dof entries, all finite and inside the limits (continuous joints excepted).
  bool within_limits(const Eigen::VectorXd& q, double tolerance = 1e-9) const;
  /// \brief Wraps continuous joints into [-pi, pi) and revolute joints by 2 pi into their limits where possible.
  Eigen::VectorXd wrap(const Eigen::VectorXd& q) const;
  /// \brief Uniform random configuration inside the limits (continuous joints in [-pi, pi)).
  template <class Rng>
  Eigen::VectorXd random_configuration(Rng& rng) const;

  /// \brief Inverse kinematics of the tip pose `target` (base frame); returns q or nothing.
  std::optional<Eigen::VectorXd> ik(const Pose& target, const IkOptions& options,
                                    const Eigen::VectorXd* seed = nullptr) const;
  /// \brief IK of many poses on every core; row i of the result solves targets[i] where ok[i].
  void ik_batch(const std::vector<Pose>& targets, const IkOptions& options, Eigen::MatrixXd& solutions,
                std::vector<bool>& ok, const Eigen::MatrixXd* seeds = nullptr, int threads = 0) const;

  /// \brief Full robot configuration with this chain's joints set to q and the rest from `reference`.
  Eigen::VectorXd to_robot_configuration(const Eigen::VectorXd& q, const Eigen::VectorXd& reference) const;

  /// \brief The same chain as a KDL::Chain (built by octoreach, not by kdl_parser).
  KDL::Chain to_kdl() const;

  /// \brief Bit i set when chain joint i moves robot link `link` (0: the chain does not move it;
  /// all dof bits: rigidly attached to the tip, e.g. a gripper).
  std::uint64_t link_mask(int link) const { return link_masks_.at(link); }

  /// \brief Splits the robot's checked self-collision pairs into those whose relative pose this
  /// chain's joints change (`moving`) and those it never changes (`fixed`).
  void split_collision_pairs(std::vector<std::pair<int, int>>& moving, std::vector<std::pair<int, int>>& fixed) const;

 private:
  friend class Robot;
  template <int MaxDof>
  std::optional<Eigen::VectorXd> ik_impl_(const Pose& target, const IkOptions& options,
                                          const Eigen::VectorXd* seed) const;
  std::shared_ptr<const Robot> robot_;
  std::string base_link_, tip_link_;
  std::vector<Segment> segments_;
  Pose tip_offset_ = Pose::Identity();
  std::vector<std::string> joint_names_;
  std::vector<int> robot_indices_;
  Eigen::VectorXd lower_, upper_;
  std::vector<bool> continuous_;
  std::vector<std::uint64_t> link_masks_;  // per robot link: bit i set if chain joint i moves it
};

/// \brief A chain group declared in an SRDF (for example the PR2's "right_arm").
struct ChainGroup {
  std::string name, base_link, tip_link;
};

/// \brief Robot model: links, joints, collision shapes, allowed-collision pairs.
///
/// Build it with Robot::from_urdf. The model is immutable except for the
/// allowed-collision matrix, which may be extended once after construction.
class Robot : public std::enable_shared_from_this<Robot> {
 public:
  /// \brief Parses a URDF (file path or XML string); resolves package:// and file:// mesh URIs
  /// through `package_dirs`; reads chain groups and disabled collision pairs from an SRDF
  /// (file path or XML string, may be empty).
  /// \throws std::invalid_argument on malformed input, std::runtime_error on unreadable files
  static std::shared_ptr<Robot> from_urdf(const std::string& urdf, const std::vector<std::string>& package_dirs = {},
                                          const std::string& srdf = "");

  const std::string& name() const { return name_; }
  /// \brief SHA-256-free content hash (FNV-1a, 64 bit) of the URDF text, to tie maps to a robot.
  std::uint64_t urdf_hash() const { return urdf_hash_; }
  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  int root_link() const { return root_link_; }
  /// \brief Index of a link by name; throws std::invalid_argument naming the link if absent.
  int link_index(const std::string& name) const;
  /// \brief Index of a joint by name; throws std::invalid_argument if absent.
  int joint_index(const std::string& name) const;
  bool has_link(const std::string& name) const { return link_by_name_.count(name) > 0; }

  /// \brief Number of entries of a configuration vector (moving, non-mimic joints).
  int dof() const { return static_cast<int>(active_joints_.size()); }
  /// \brief Names of the configuration vector's joints, in order.
  std::vector<std::string> joint_names() const;
  Eigen::VectorXd lower() const;
  Eigen::VectorXd upper() const;
  /// \brief Zero configuration moved into the joint limits.
  Eigen::VectorXd home() const;
  /// \brief Mimic joints found in the URDF (reported, left out of chains and of the configuration).
  std::vector<std::string> mimic_joints() const;
  /// \brief Chain groups from the SRDF.
  const std::vector<ChainGroup>& groups() const { return groups_; }
  /// \brief Named joint values from the SRDF's group states (for example the PR2's "tuck_left_arm").
  const std::map<std::string, std::map<std::string, double>>& named_states() const { return named_states_; }
  /// \brief Configuration with values from a name -> value map, the rest from home().
  Eigen::VectorXd configuration(const std::map<std::string, double>& values) const;

  /// \brief Kinematic chain from base_link to tip_link; throws std::invalid_argument if absent
  /// or if base_link is not an ancestor of tip_link.
  Chain chain(const std::string& base_link, const std::string& tip_link) const;

  /// \brief Poses of every link in the root link frame, indexed like links().
  std::vector<Pose> link_poses(const Eigen::VectorXd& q) const;
  void link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out) const;

  /// \brief True when two links not allowed to touch are in collision at q.
  bool in_self_collision(const Eigen::VectorXd& q) const;
  /// \brief True when any link touches an obstacle; the robot's root sits at `base_pose` (world frame).
  bool in_collision(const Eigen::VectorXd& q, const Obstacles& obstacles, const Pose& base_pose = Pose::Identity(),
                    bool check_self = false) const;
  /// \brief Same as in_collision, restricted to the given links (by index).
  bool links_in_collision(const std::vector<Pose>& link_poses, const Obstacles& obstacles,
                          const Pose& base_pose, const std::vector<int>* only_links = nullptr) const;
  bool in_self_collision_poses(const std::vector<Pose>& link_poses) const;
  /// \brief Self-collision over the given link pairs only.
  bool in_self_collision_poses(const std::vector<Pose>& link_poses, const std::vector<std::pair<int, int>>& pairs) const;

  /// \brief Pairs of links whose collisions are ignored (sorted link indices, i < j).
  const std::vector<std::pair<int, int>>& allowed_pairs() const { return allowed_; }
  /// \brief Pairs of links checked for self-collision.
  const std::vector<std::pair<int, int>>& checked_pairs() const { return checked_; }
  /// \brief Adds a pair of links to the allowed-collision matrix.
  void allow_collision(const std::string& link_a, const std::string& link_b);
  /// \brief Samples random configurations and allows the pairs never or always in collision
  /// (as MoveIt's setup assistant does); returns the number of pairs added.
  std::size_t compute_allowed_collisions(int samples = 2000, std::uint64_t seed = 0,
                                         const ProgressCallback& progress = nullptr);

  /// \brief Links with collision geometry.
  const std::vector<int>& collision_links() const { return collision_links_; }

 private:
  Robot() = default;
  void finalize_();
  void rebuild_checked_();
  std::string name_;
  std::uint64_t urdf_hash_ = 0;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<int> active_joints_;  // joint indices, in configuration order
  std::vector<int> joint_order_;    // joints in topological order
  int root_link_ = 0;
  std::map<std::string, int> link_by_name_, joint_by_name_;
  std::vector<ChainGroup> groups_;
  std::map<std::string, std::map<std::string, double>> named_states_;
  std::vector<std::pair<int, int>> allowed_, checked_;
  std::vector<int> collision_links_;
};

template <class Rng>
Eigen::VectorXd Chain::random_configuration(Rng& rng) const {
  Eigen::VectorXd q(dof());
  for (int i = 0; i < dof(); ++i) {
    double lo = continuous_[i] ? -M_PI : lower_[i];
    double hi = continuous_[i] ? M_PI : upper_[i];
    std::uniform_real_distribution<double> u(lo, hi);
    q[i] = u(rng);
  }
  return q;
}

}  // namespace octoreach
