// An arm's joints as map builds see them (arm_report.hpp): the chain's joints, the ones upstream of the
// arm's base that the builds hold at the reference posture, and the arm's self-collision share.
#include "octoreach/arm_report.hpp"

namespace octoreach {

ArmReport arm_report(const Robot& robot, const Arm& arm, const SelfCollisionOptions& options,
                     const ProgressCallback& progress) {
  const Chain chain = robot.chain(arm.base_link, arm.tip_link);
  const Eigen::VectorXd reference = default_reference(robot, chain);
  ArmReport report;
  report.moving = chain.joint_names();
  for (int j : robot.joints_placing({robot.link_index(arm.base_link)})) {
    const Joint& joint = robot.joints()[j];
    if (joint.index < 0) continue;  // fixed and mimic joints are not the build's to move
    if (report.held.empty()) report.base_to_include_held = robot.links()[joint.parent_link].name;
    report.held.push_back({joint.name, reference[joint.index]});
  }
  SelfCollisionOptions o = options;
  o.joints = chain.joint_names();
  o.reference = reference;
  o.links.clear();
  report.with_body = self_collision_report(robot, o, progress);
  const LinkRoles roles = link_roles(robot, chain);
  for (const auto& part : {roles.arm, roles.tool})
    for (int l : part) o.links.push_back(robot.links()[l].name);
  report.self_collision = self_collision_report(robot, o, progress);
  return report;
}

}  // namespace octoreach
