#pragma once
// Internal: a joint's value in a robot configuration and the motion it makes there, shared by the robot's link
// poses (robot.cpp) and IK's placing of the links a chain moves (ik.cpp).
#include <vector>

#include <Eigen/Geometry>

#include "octoreach/robot.hpp"
#include "common/sin_cos.hpp"

namespace octoreach::detail {

/// The robot configuration entry joint j's value comes from: its own, a mimic joint's source's; -1 when fixed.
inline int joint_source(const std::vector<Joint>& joints, const Joint& j) {
  return j.index >= 0 ? j.index : j.mimic >= 0 ? joints[j.mimic].index : -1;
}

/// Joint j's value in the robot configuration q: its own entry, a mimic joint's from its source's, 0 when fixed.
inline double joint_value(const std::vector<Joint>& joints, const Joint& j, const Eigen::VectorXd& q) {
  const int source = joint_source(joints, j);
  if (source < 0) return 0.0;
  return j.index >= 0 ? q[source] : q[source] * j.mimic_multiplier + j.mimic_offset;
}

/// The rotation by angle v about the unit axis a (Rodrigues' formula; sine and cosine from sin_cos).
inline Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& a, double v) {
  double s, c;
  sin_cos(v, s, c);
  Eigen::Matrix3d r = (1.0 - c) * a * a.transpose();
  r.diagonal().array() += c;
  const Eigen::Vector3d sa = s * a;
  r(0, 1) -= sa.z();
  r(1, 0) += sa.z();
  r(0, 2) += sa.y();
  r(2, 0) -= sa.y();
  r(1, 2) -= sa.x();
  r(2, 1) += sa.x();
  return r;
}

/// Joint j's motion at the value v (after its origin): a turn about its axis or a shift along it.
inline Pose joint_motion(const Joint& j, double v) {
  Pose m = Pose::Identity();
  if (j.type == JointType::Prismatic) m.translation() = j.axis * v;
  else if (j.type == JointType::Revolute || j.type == JointType::Continuous)
    m.linear() = axis_rotation(j.axis, v);
  return m;
}

}  // namespace octoreach::detail
