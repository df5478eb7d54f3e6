// The robot model's queries: names, limits, configurations, link poses, the model hash.
// Building is in urdf.cpp and srdf.cpp, collision checks in robot_collision.cpp, chains in chain.cpp.
#include "octoreach/robot.hpp"

#include <cmath>

#include "common/random_mix.hpp"

namespace octoreach {

int Robot::link_index(const std::string& name) const {
  auto it = link_by_name_.find(name);
  if (it == link_by_name_.end())
    throw std::invalid_argument("robot '" + name_ + "' has no link named '" + name + "'");
  return it->second;
}

int Robot::joint_index(const std::string& name) const {
  auto it = joint_by_name_.find(name);
  if (it == joint_by_name_.end())
    throw std::invalid_argument("robot '" + name_ + "' has no joint named '" + name + "'");
  return it->second;
}

std::vector<std::string> Robot::joint_names() const {
  std::vector<std::string> out;
  for (int j : active_joints_) out.push_back(joints_[j].name);
  return out;
}

Eigen::VectorXd Robot::lower() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints_[active_joints_[i]].lower;
  return v;
}

Eigen::VectorXd Robot::upper() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints_[active_joints_[i]].upper;
  return v;
}

Eigen::VectorXd Robot::home() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(dof());
  for (int i = 0; i < dof(); ++i) {
    const Joint& j = joints_[active_joints_[i]];
    q[i] = std::min(std::max(0.0, j.lower), j.upper);
  }
  return q;
}

std::vector<std::string> Robot::mimic_joints() const {
  std::vector<std::string> out;
  for (const auto& j : joints_)
    if (j.mimic >= 0) out.push_back(j.name);
  return out;
}

Eigen::VectorXd Robot::configuration(const std::map<std::string, double>& values) const {
  Eigen::VectorXd q = home();
  for (const auto& [name, value] : values) {
    const Joint& j = joints_[joint_index(name)];
    if (j.index < 0) throw std::invalid_argument("joint '" + name + "' is fixed or a mimic joint");
    if (!std::isfinite(value)) throw std::invalid_argument("joint '" + name + "' value must be finite");
    if (value < j.lower - 1e-9 || value > j.upper + 1e-9)
      throw std::invalid_argument("joint '" + name + "' value " + std::to_string(value) + " is outside its limits [" +
                                  std::to_string(j.lower) + ", " + std::to_string(j.upper) + "]");
    q[j.index] = value;
  }
  return q;
}

namespace {
inline Pose joint_motion(const Joint& j, double q) {
  Pose m = Pose::Identity();
  if (j.type == JointType::Prismatic) m.translation() = j.axis * q;
  else if (j.type == JointType::Revolute || j.type == JointType::Continuous)
    m.linear() = Eigen::AngleAxisd(q, j.axis).toRotationMatrix();
  return m;
}
}  // namespace

void Robot::link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out) const {
  if (q.size() != dof())
    throw std::invalid_argument("configuration has " + std::to_string(q.size()) + " entries, robot '" + name_ +
                                "' expects " + std::to_string(dof()));
  out.resize(links_.size());
  out[root_link_] = Pose::Identity();
  // joints_ are stored in breadth-first order of their child links: parents first.
  for (const Joint& j : joints_) {
    double v = 0.0;
    if (j.index >= 0) v = q[j.index];
    else if (j.mimic >= 0) v = q[joints_[j.mimic].index] * j.mimic_multiplier + j.mimic_offset;
    out[j.child_link] = out[j.parent_link] * j.origin * joint_motion(j, v);
  }
}

std::vector<Pose> Robot::link_poses(const Eigen::VectorXd& q) const {
  std::vector<Pose> out;
  link_poses(q, out);
  return out;
}

std::uint64_t Robot::model_hash() const {
  std::uint64_t h = urdf_hash_;
  for (const auto& [a, b] : allowed_) h = detail::mix64(h, (std::uint64_t(a) << 32) | std::uint64_t(b));
  return h;
}

}  // namespace octoreach
