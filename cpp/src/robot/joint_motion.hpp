#pragma once
// Internal: a joint's value in a robot configuration and the motion it makes there, shared by the robot's link
// poses (robot.cpp) and IK's placing of the links a chain moves (ik.cpp).
#include <vector>

#include <Eigen/Geometry>

#include "octoreach/robot.hpp"

namespace octoreach::detail {

/// Joint j's value in the robot configuration q: its own entry, a mimic joint's from its source's, 0 when fixed.
inline double joint_value(const std::vector<Joint>& joints, const Joint& j, const Eigen::VectorXd& q) {
  if (j.index >= 0) return q[j.index];
  if (j.mimic >= 0) return q[joints[j.mimic].index] * j.mimic_multiplier + j.mimic_offset;
  return 0.0;
}

/// Joint j's motion at the value v (after its origin): a turn about its axis or a shift along it.
inline Pose joint_motion(const Joint& j, double v) {
  Pose m = Pose::Identity();
  if (j.type == JointType::Prismatic) m.translation() = j.axis * v;
  else if (j.type == JointType::Revolute || j.type == JointType::Continuous)
    m.linear() = Eigen::AngleAxisd(v, j.axis).toRotationMatrix();
  return m;
}

}  // namespace octoreach::detail
