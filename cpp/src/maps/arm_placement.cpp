#include "octoreach/arm.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "octoreach/capability_map.hpp"
#include "octoreach/orientation_set.hpp"

namespace octoreach {
Eigen::VectorXd default_reference(const Robot& robot, const Chain& chain) {
  const std::vector<std::string>& moved = chain.joint_names();
  std::map<std::string, double> values;
  for (const auto& [name, joints] : robot.named_states()) {  // sorted by name: later states win ties
    if (name.rfind("tuck", 0) != 0) continue;
    bool moves_arm = false;
    for (const auto& entry : joints)
      moves_arm = moves_arm || std::find(moved.begin(), moved.end(), entry.first) != moved.end();
    if (moves_arm) continue;
    for (const auto& [joint, value] : joints) values[joint] = value;
  }
  return robot.configuration(values);
}

Eigen::VectorXd reference_or_default(const Robot& robot, const Chain& chain, const Eigen::VectorXd& reference) {
  Eigen::VectorXd q = reference.size() ? reference : default_reference(robot, chain);
  if (q.size() != robot.dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(q.size()) + " entries, the robot has " +
                                std::to_string(robot.dof()));
  for (int i = 0; i < q.size(); ++i)
    if (!std::isfinite(q[i]))
      throw std::invalid_argument("reference configuration entry " + std::to_string(i) + " is not finite (NaN or inf)");
  return q;
}

Pose base_pose(double x, double y, double z, double theta) {
  // AngleAxis, as every C++ user of base poses computed it (bit-identical maps and samples).
  Pose B = Pose::Identity();
  B.translation() = Eigen::Vector3d(x, y, z);
  B.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return B;
}

LinkRoles link_roles(const Robot& robot, const Chain& chain) {
  const std::uint64_t full = chain.dof() >= 64 ? ~0ULL : ((1ULL << chain.dof()) - 1);
  LinkRoles roles;
  for (int li : robot.collision_links()) {
    std::uint64_t mask = chain.link_mask(li);
    (mask == 0 ? roles.body : mask == full ? roles.tool : roles.arm).push_back(li);
  }
  return roles;
}

std::vector<int> grasp_orientations(const OrientationSet& set, const std::vector<int>& directions) {
  std::vector<int> out;
  for (int d : directions) {
    if (d < 0 || d >= set.directions())
      throw std::invalid_argument("grasp direction index " + std::to_string(d) + " out of range [0, " +
                                  std::to_string(set.directions()) + ")");
    for (int r = 0; r < set.rolls(); ++r) out.push_back(d * set.rolls() + r);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

GraspSet GraspSet::make(const OrientationSet& set, const std::vector<int>& directions, const std::string& subset) {
  std::vector<int> dirs = directions.empty() ? set.subset(subset) : directions;
  if (dirs.empty()) throw std::invalid_argument("the grasp set is empty");
  return GraspSet{directions.empty() ? subset : "custom", grasp_orientations(set, dirs)};
}

void check_map_robot(const Robot& robot, const CapabilityMap& capability) {
  if (capability.robot_name() != robot.name())
    throw std::invalid_argument("the capability map was built for robot '" + capability.robot_name() + "', not for '" +
                                robot.name() + "': pass the robot the map was built for, or build a map for this one");
  if (capability.urdf_hash() != robot.urdf_hash())
    throw std::invalid_argument("the capability map was built for robot '" + capability.robot_name() +
                                "' from another URDF than this '" + robot.name() +
                                "' (URDF hashes differ): pass the robot the map was built for, or build a map for "
                                "this one");
  // Self-collision decided which cells are reachable: the allowed-collision matrix must match too.
  if (capability.model_hash() != 0 && capability.model_hash() != robot.model_hash())
    throw std::invalid_argument("the capability map was built for robot '" + capability.robot_name() +
                                "' with another allowed-collision matrix (model_hash differs): load the robot the way the map was built "
                                "(same SRDF; from the command line, --allowed-collisions srdf keeps the URDF/SRDF pairs "
                                "and auto adds the sampled ones) or rebuild the capability map");
  // A header edited after the build: the chain it names must exist here and move as many joints as it stores.
  if (!robot.has_link(capability.base_link()) || !robot.has_link(capability.tip_link()) ||
      robot.chain(capability.base_link(), capability.tip_link()).dof() != capability.dof())
    throw std::invalid_argument("the capability map's chain '" + capability.base_link() + "' -> '" +
                                capability.tip_link() + "' with " + std::to_string(capability.dof()) +
                                " joints does not match robot '" + robot.name() + "'");
}

ArmPlacement ArmPlacement::make(const Robot& robot, const CapabilityMap& cap, const std::string& reference_frame,
                                const Eigen::VectorXd& reference, const std::vector<int>& grasp_directions,
                                const std::string& grasp_subset) {
  check_map_robot(robot, cap);
  ArmPlacement p;
  p.reference_frame = reference_frame.empty() ? robot.links()[robot.root_link()].name : reference_frame;
  p.grasps = GraspSet::make(cap.orientations(), grasp_directions, grasp_subset);
  const Chain chain = robot.chain(cap.base_link(), cap.tip_link());
  p.reference = reference_or_default(robot, chain, reference);
  p.link_poses = robot.link_poses(p.reference);
  p.root_in_reference = p.link_poses[robot.link_index(p.reference_frame)].inverse();
  p.reference_to_arm = p.root_in_reference * p.link_poses[robot.link_index(cap.base_link())];
  p.roles = link_roles(robot, chain);
  return p;
}

}  // namespace octoreach
