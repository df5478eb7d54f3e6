#pragma once
/// \file robot.hpp
/// \brief Robot model built from a URDF (urdfdom): links, joints, SRDF groups and collision checking.

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
  /// \brief Hash of the model as maps depend on it: the URDF text and the allowed-collision matrix
  /// (two robots from one URDF with different allowed pairs have different model hashes).
  std::uint64_t model_hash() const;
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

}  // namespace octoreach
