// The robot model's queries: names, limits, configurations, link poses, the model hash.
// Building is in urdf.cpp and srdf.cpp, collision checks in robot_collision.cpp, chains in chain.cpp.
#include "octoreach/robot.hpp"

#include <algorithm>
#include <cmath>

#include "common/nearest_names.hpp"
#include "common/random_mix.hpp"
#include "robot/joint_motion.hpp"

namespace octoreach {

int Robot::link_index(const std::string& name) const {
  auto it = link_by_name_.find(name);
  if (it == link_by_name_.end())
  {
    std::vector<std::string> names;
    for (const Link& l : links_) names.push_back(l.name);
    throw std::invalid_argument("robot '" + name_ + "' has no link named '" + name + "'" + detail::did_you_mean(name, names));
  }
  return it->second;
}

int Robot::joint_index(const std::string& name) const {
  auto it = joint_by_name_.find(name);
  if (it == joint_by_name_.end())
  {
    std::vector<std::string> names;
    for (const Joint& j : joints_) names.push_back(j.name);
    throw std::invalid_argument("robot '" + name_ + "' has no joint named '" + name + "'" + detail::did_you_mean(name, names));
  }
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
// The pose of joint j's child link from its parent's, at configuration q (one step of link_poses).
void place_child(const std::vector<Joint>& joints, const Joint& j, const Eigen::VectorXd& q, std::vector<Pose>& out) {
  out[j.child_link] = out[j.parent_link] * j.origin * detail::joint_motion(j, detail::joint_value(joints, j, q));
}

// `q` has one entry per degree of freedom of the robot `name`, else std::invalid_argument.
void check_configuration(const Eigen::VectorXd& q, int dof, const std::string& name) {
  if (q.size() != dof)
    throw std::invalid_argument("configuration has " + std::to_string(q.size()) + " entries, robot '" + name +
                                "' expects " + std::to_string(dof));
}
}  // namespace

void Robot::link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out) const {
  check_configuration(q, dof(), name_);
  out.resize(links_.size());
  out[root_link_] = Pose::Identity();
  // joints_ are stored in breadth-first order of their child links: parents first.
  for (const Joint& j : joints_) place_child(joints_, j, q, out);
}

std::vector<int> Robot::joints_placing(const std::vector<int>& links) const {
  std::vector<char> in(joints_.size(), 0);
  for (int l : links) {
    if (l < 0 || l >= static_cast<int>(links_.size()))
      throw std::out_of_range("link index " + std::to_string(l) + " out of range (robot '" + name_ + "' has " +
                              std::to_string(links_.size()) + " links)");
    for (int j = links_[l].parent_joint; j >= 0 && !in[j]; j = links_[joints_[j].parent_link].parent_joint) in[j] = 1;
  }
  std::vector<int> out;
  for (std::size_t j = 0; j < joints_.size(); ++j)
    if (in[j]) out.push_back(static_cast<int>(j));
  return out;
}

void Robot::link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out, const std::vector<int>& joints) const {
  check_configuration(q, dof(), name_);
  out.resize(links_.size());
  out[root_link_] = Pose::Identity();
  int last = -1;
  for (int j : joints) {  // ascending: parents first
    if (j <= last)
      throw std::invalid_argument("link_poses: joint indices must ascend (as joints_placing gives them), got " +
                                  std::to_string(j) + " after " + std::to_string(last));
    place_child(joints_, joints_.at(static_cast<std::size_t>(j)), q, out);
    last = j;
  }
}

std::vector<Pose> Robot::link_poses(const Eigen::VectorXd& q) const {
  std::vector<Pose> out;
  link_poses(q, out);
  return out;
}

std::vector<int> Robot::group_joints(const std::string& group) const {
  std::vector<char> in(joints_.size(), 0);
  std::vector<std::string> stack{group}, seen;
  while (!stack.empty()) {
    std::string name = stack.back();
    stack.pop_back();
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) continue;  // subgroup cycles
    seen.push_back(name);
    auto it = std::find_if(srdf_groups_.begin(), srdf_groups_.end(), [&](const SrdfGroup& g) { return g.name == name; });
    if (it == srdf_groups_.end()) {
      std::vector<std::string> names;
      for (const SrdfGroup& g : srdf_groups_) names.push_back(g.name);
      throw std::invalid_argument("robot '" + name_ + "' has no SRDF group '" + name + "'" + detail::did_you_mean(name, names));
    }
    for (const auto& [base, tip] : it->chains) {
      const int b = link_index(base);
      for (int l = link_index(tip); l != b && links_[l].parent_joint >= 0; l = joints_[links_[l].parent_joint].parent_link)
        in[links_[l].parent_joint] = 1;
    }
    for (const std::string& j : it->joints) in[joint_index(j)] = 1;
    for (const std::string& l : it->links)
      if (links_[link_index(l)].parent_joint >= 0) in[links_[link_index(l)].parent_joint] = 1;
    for (const std::string& g : it->subgroups) stack.push_back(g);
  }
  std::vector<int> out;
  for (std::size_t j = 0; j < joints_.size(); ++j)
    if (in[j] && joints_[j].type != JointType::Fixed) out.push_back(static_cast<int>(j));
  return out;
}

std::uint64_t Robot::model_hash() const {
  std::uint64_t h = urdf_hash_;
  for (const auto& [a, b] : allowed_) h = detail::mix64(h, (std::uint64_t(a) << 32) | std::uint64_t(b));
  return h;
}

}  // namespace octoreach
