#pragma once
/// \file arm.hpp
/// \brief Where an arm sits on its robot for a map build: reference posture, link roles, grasp set, base
/// poses; the set-up shared by every map built from a capability map (point maps, surface maps) and by the
/// Python layer, so nothing re-derives it. The arms themselves: arm_discovery.hpp.

#include <string>
#include <vector>

#include "octoreach/arm_discovery.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

class CapabilityMap;
class OrientationSet;

/// \brief The reference posture of the joints off an arm: home() with every SRDF state whose name
/// starts with "tuck" applied, unless it moves a joint of `chain` (the PR2's other arm tucked).
/// Every build that is given no reference configuration uses it.
Eigen::VectorXd default_reference(const Robot& robot, const Chain& chain);

/// \brief `reference` when it is set, else default_reference(robot, chain); throws
/// std::invalid_argument when its size is not the robot's dof.
Eigen::VectorXd reference_or_default(const Robot& robot, const Chain& chain, const Eigen::VectorXd& reference);

/// \brief Pose (world frame) of a frame at base pose (x, y, z, theta): yaw theta about z, then the
/// translation (x, y, z).
Pose base_pose(double x, double y, double z, double theta);

/// \brief Collision links of a robot by what an arm does to them.
struct LinkRoles {
  std::vector<int> body;  ///< not moved by the arm
  std::vector<int> arm;   ///< moved by some but not all of the arm's joints
  std::vector<int> tool;  ///< moved by every joint (rigid with the tip: the gripper, may touch the object)
};

/// \brief Splits robot.collision_links() by Chain::link_mask (indices into robot.links()).
LinkRoles link_roles(const Robot& robot, const Chain& chain);

/// \brief Orientation indices (d * rolls + r, sorted, unique) of a set for direction indices, all
/// rolls of each; throws std::invalid_argument for an index out of range.
std::vector<int> grasp_orientations(const OrientationSet& set, const std::vector<int>& directions);

/// \brief Grasp set of a build: explicit direction indices, or else the named subset of the set.
struct GraspSet {
  std::string name;               ///< the subset name, or "custom" for explicit indices
  std::vector<int> orientations;  ///< orientation indices (d * rolls + r)
  /// \brief Resolves `directions` (non-empty) or else `subset`; throws when the set is empty.
  static GraspSet make(const OrientationSet& set, const std::vector<int>& directions, const std::string& subset);
};

/// \brief Throws std::invalid_argument unless `capability` was built for `robot`: name, URDF and (when the
/// map records it) Robot::model_hash(), which covers the allowed-collision matrix.
void check_map_robot(const Robot& robot, const CapabilityMap& capability);

/// \brief Where an arm sits on the robot for a map build: the robot check, the reference posture,
/// the reference frame and the pose of the arm's base link in it, the grasp set and the link roles.
struct ArmPlacement {
  std::string reference_frame;      ///< link whose base pose (x, y, z, theta) maps index
  Eigen::VectorXd reference;        ///< robot configuration (joints off the arm)
  std::vector<Pose> link_poses;     ///< every link at `reference`, root link frame
  Pose root_in_reference = Pose::Identity();  ///< root link in the reference frame
  Pose reference_to_arm = Pose::Identity();   ///< arm base link in the reference frame
  GraspSet grasps;
  LinkRoles roles;

  /// \brief Checks that `capability` belongs to `robot` and sets the placement up; an empty
  /// `reference_frame` is the root link, an empty `reference` default_reference().
  static ArmPlacement make(const Robot& robot, const CapabilityMap& capability, const std::string& reference_frame,
                           const Eigen::VectorXd& reference, const std::vector<int>& grasp_directions,
                           const std::string& grasp_subset);
  /// \brief Pose (world frame) of the robot's root link when the reference frame is at (x, y, z, theta).
  Pose root_pose(double x, double y, double z, double theta) const {
    return base_pose(x, y, z, theta) * root_in_reference;
  }
};

/// \brief Offset added to targets expressed in the arm frame: a target exactly on a capability-voxel
/// boundary (common: grid centres line up with them) would be assigned by rounding noise; a fixed
/// offset far below any resolution makes the assignment the same however the pose was computed.
inline Eigen::Vector3d target_offset() { return Eigen::Vector3d(1.3e-7, 0.7e-7, 0.3e-7); }

}  // namespace octoreach
