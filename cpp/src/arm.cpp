#include "octoreach/arm.hpp"

#include <algorithm>
#include <set>

#include "octoreach/capability_map.hpp"
#include "octoreach/orientation_set.hpp"

namespace octoreach {
namespace {

struct KnownArm {
  const char* robot;
  const char* name;
  const char* base_link;
  const char* tip_link;
  Eigen::Vector3d approach_axis;
};

// The arms whose SRDF groups end where a capability map should not: the PR2's SRDF arm groups end
// at the wrist, its gripper tool frames approach along +x. Kept small on purpose: the one place
// named arms are defined until they are inferred from the model.
const std::vector<KnownArm>& known_arms() {
  static const std::vector<KnownArm> table = {
      {"pr2", "right_arm", "torso_lift_link", "r_gripper_tool_frame", Eigen::Vector3d::UnitX()},
      {"pr2", "left_arm", "torso_lift_link", "l_gripper_tool_frame", Eigen::Vector3d::UnitX()},
  };
  return table;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

}  // namespace

Arm Arm::named(const Robot& robot, const std::string& name) {
  for (const KnownArm& k : known_arms())
    if (robot.name() == k.robot && name == k.name) return Arm{k.base_link, k.tip_link, k.approach_axis};
  for (const ChainGroup& g : robot.groups())
    if (g.name == name) return Arm{g.base_link, g.tip_link, Eigen::Vector3d::UnitZ()};
  std::string known;
  for (const std::string& n : arm_names(robot)) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("robot " + quoted(robot.name()) + " has no arm " + quoted(name) + "; known: " +
                              (known.empty() ? "none (pass (base, tip))" : known));
}

Arm Arm::from_links(const Robot& robot, const std::string& base_link, const std::string& tip_link,
                    const Eigen::Vector3d& approach_axis) {
  for (const std::string* link : {&base_link, &tip_link})
    if (!robot.has_link(*link))
      throw std::invalid_argument("robot " + quoted(robot.name()) + " has no link named " + quoted(*link));
  return Arm{base_link, tip_link, approach_axis};
}

std::vector<std::string> arm_names(const Robot& robot) {
  std::set<std::string> names;
  for (const KnownArm& k : known_arms())
    if (robot.name() == k.robot) names.insert(k.name);
  for (const ChainGroup& g : robot.groups()) names.insert(g.name);
  return {names.begin(), names.end()};
}

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
  if (capability.robot_name() != robot.name() || capability.urdf_hash() != robot.urdf_hash())
    throw std::invalid_argument("the capability map was built for robot '" + capability.robot_name() +
                                "' (another URDF), not for '" + robot.name() + "'");
  // Self-collision decided which cells are reachable: the allowed-collision matrix must match too.
  if (capability.model_hash() != 0 && capability.model_hash() != robot.model_hash())
    throw std::invalid_argument("the capability map was built for robot '" + capability.robot_name() +
                                "' with another allowed-collision matrix (model_hash differs)");
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
