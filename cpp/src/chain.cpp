// A serial chain cut from a robot's tree: its construction (Robot::chain), FK, Jacobian, limits and
// joint wrapping. The IK solver is in ik.cpp.
#include <algorithm>
#include <cmath>

#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"
#include "chain_checks.hpp"

namespace octoreach {

using detail::check_joint_vector;

namespace {

inline double wrap_pi(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace

Chain Robot::chain(const std::string& base_link, const std::string& tip_link) const {
  int base = link_index(base_link), tip = link_index(tip_link);
  std::vector<int> path;  // joints from tip up to base
  int cur = tip;
  while (cur != base) {
    int pj = links_[cur].parent_joint;
    if (pj < 0)
      throw std::invalid_argument("no chain from '" + base_link + "' to '" + tip_link + "': '" + base_link +
                                  "' is not an ancestor of '" + tip_link + "'");
    path.push_back(pj);
    cur = joints_[pj].parent_link;
  }
  std::reverse(path.begin(), path.end());
  Chain c;
  c.robot_ = shared_from_this();
  c.base_link_ = base_link;
  c.tip_link_ = tip_link;
  std::vector<double> lo, hi;
  Pose pending = Pose::Identity();
  for (int ji : path) {
    const Joint& j = joints_[ji];
    if (j.type == JointType::Fixed || j.mimic >= 0) {
      if (j.mimic >= 0)
        throw std::invalid_argument("chain '" + base_link + "' -> '" + tip_link + "' passes mimic joint '" + j.name +
                                    "' (mimic joints are left out of chains)");
      pending = pending * j.origin;
      continue;
    }
    Chain::Segment s;
    s.origin = pending * j.origin;
    s.type = j.type;
    s.axis = j.axis;
    s.robot_joint = ji;
    pending = Pose::Identity();
    c.segments_.push_back(s);
    c.joint_names_.push_back(j.name);
    c.robot_indices_.push_back(j.index);
    lo.push_back(j.lower);
    hi.push_back(j.upper);
    c.continuous_.push_back(j.type == JointType::Continuous);
  }
  c.tip_offset_ = pending;
  if (c.segments_.size() > 64)
    throw std::invalid_argument("chains of more than 64 moving joints are not supported");
  // Which chain joints move each link: a link below chain joint i moves with it.
  c.link_masks_.assign(links_.size(), 0);
  for (std::size_t li = 0; li < links_.size(); ++li) {
    int cur = static_cast<int>(li);
    while (links_[cur].parent_joint >= 0) {
      int pj = links_[cur].parent_joint;
      for (std::size_t i = 0; i < c.segments_.size(); ++i)
        if (c.segments_[i].robot_joint == pj) c.link_masks_[li] |= (1ULL << i);
      cur = joints_[pj].parent_link;
    }
  }
  c.lower_ = Eigen::Map<Eigen::VectorXd>(lo.data(), lo.size());
  c.upper_ = Eigen::Map<Eigen::VectorXd>(hi.data(), hi.size());
  return c;
}


Pose Chain::fk(const Eigen::VectorXd& q) const {
  check_joint_vector(*this, q);
  Pose T = Pose::Identity();
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    T = T * s.origin;
    if (s.type == JointType::Prismatic) T.translate(s.axis * q[i]);
    else T.rotate(Eigen::AngleAxisd(q[i], s.axis));
  }
  return T * tip_offset_;
}

std::vector<Pose> Chain::fk_batch(const Eigen::MatrixXd& q_rows) const {
  if (q_rows.cols() != dof())
    throw std::invalid_argument("joint rows have " + std::to_string(q_rows.cols()) + " columns, chain '" +
                                base_link_ + "' -> '" + tip_link_ + "' has " + std::to_string(dof()) + " joints");
  std::vector<Pose> out(q_rows.rows());
  for (Eigen::Index i = 0; i < q_rows.rows(); ++i) out[i] = fk(q_rows.row(i).transpose());
  return out;
}

Pose Chain::fk_jacobian(const Eigen::VectorXd& q, Eigen::Matrix<double, 6, Eigen::Dynamic>& J) const {
  check_joint_vector(*this, q);
  const int n = dof();
  J.resize(6, n);
  thread_local std::vector<Eigen::Vector3d> origins, axes;
  origins.resize(n);
  axes.resize(n);
  Pose T = Pose::Identity();
  for (int i = 0; i < n; ++i) {
    const Segment& s = segments_[i];
    T = T * s.origin;
    origins[i] = T.translation();
    axes[i] = T.linear() * s.axis;
    if (s.type == JointType::Prismatic) T.translate(s.axis * q[i]);
    else T.rotate(Eigen::AngleAxisd(q[i], s.axis));
  }
  T = T * tip_offset_;
  const Eigen::Vector3d p = T.translation();
  for (int i = 0; i < n; ++i) {
    if (segments_[i].type == JointType::Prismatic) {
      J.col(i).head<3>() = axes[i];
      J.col(i).tail<3>().setZero();
    } else {
      J.col(i).head<3>() = axes[i].cross(p - origins[i]);
      J.col(i).tail<3>() = axes[i];
    }
  }
  return T;
}

bool Chain::within_limits(const Eigen::VectorXd& q, double tol) const {
  if (q.size() != dof() || !q.allFinite()) return false;
  for (int i = 0; i < dof(); ++i)
    if (!continuous_[i] && (q[i] < lower_[i] - tol || q[i] > upper_[i] + tol)) return false;
  return true;
}

Eigen::VectorXd Chain::wrap(const Eigen::VectorXd& q_in) const {
  check_joint_vector(*this, q_in);
  Eigen::VectorXd q = q_in;
  for (int i = 0; i < dof(); ++i) {
    if (continuous_[i]) {
      q[i] = wrap_pi(q[i]);
    } else if (segments_[i].type == JointType::Revolute) {
      // Shift by whole turns toward the limits; leave it outside if no turn fits. The turn count is
      // computed, not looped for, so the work does not grow with |q| (non-finite values stay as they are).
      q[i] = detail::shift_by_turns(q[i], lower_[i], upper_[i], 1e-12);
    }
  }
  return q;
}

Eigen::VectorXd Chain::to_robot_configuration(const Eigen::VectorXd& q, const Eigen::VectorXd& reference) const {
  check_joint_vector(*this, q);
  Eigen::VectorXd full = reference.size() == 0 ? robot_->home() : reference;
  if (full.size() != robot_->dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(full.size()) +
                                " entries, the robot has " + std::to_string(robot_->dof()));
  for (int i = 0; i < dof(); ++i) full[robot_indices_[i]] = q[i];
  return full;
}

void Chain::split_collision_pairs(std::vector<std::pair<int, int>>& moving,
                                  std::vector<std::pair<int, int>>& fixed) const {
  moving.clear();
  fixed.clear();
  for (const auto& p : robot_->checked_pairs())
    (link_masks_[p.first] != link_masks_[p.second] ? moving : fixed).push_back(p);
}

}  // namespace octoreach
