// A serial chain cut from a robot's tree: its construction (Robot::chain), FK, Jacobian, limits and
// joint wrapping. The IK solver is in ik.cpp.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"
#include "common/sin_cos.hpp"
#include "kinematics/chain_checks.hpp"
#include "robot/joint_motion.hpp"

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
  for (const Chain::Segment& s : c.segments_) {
    std::int8_t kind = -1;
    for (int k = 0; k < 3; ++k) {
      if (s.axis == Eigen::Vector3d::Unit(k)) kind = static_cast<std::int8_t>(k);
      if (s.axis == -Eigen::Vector3d::Unit(k)) kind = static_cast<std::int8_t>(3 + k);
    }
    c.axis_kind_.push_back(kind);
    c.turned_origin_.push_back(!s.origin.linear().isIdentity(0.0));
  }
  c.lower_ = Eigen::Map<Eigen::VectorXd>(lo.data(), lo.size());
  c.upper_ = Eigen::Map<Eigen::VectorXd>(hi.data(), hi.size());
  return c;
}


namespace {

// R <- R * Rot(axis, angle) for a joint axis along a frame axis (kind 0-5, see axis_kind_): two
// columns of R mix; any other axis takes the general rotation.
inline void rotate_about(Eigen::Matrix3d& R, int kind, const Eigen::Vector3d& axis, double angle) {
  if (kind < 0) {
    R = R * detail::axis_rotation(axis, angle);
    return;
  }
  const int k = kind % 3;
  double s, c;
  detail::sin_cos(angle, s, c);
  if (kind >= 3) s = -s;
  const int a = (k + 1) % 3, b = (k + 2) % 3;  // Rot(e_k, t): e_a -> c e_a + s e_b, e_b -> -s e_a + c e_b
  const Eigen::Vector3d ca = R.col(a), cb = R.col(b);
  R.col(a) = c * ca + s * cb;
  R.col(b) = c * cb - s * ca;
}

}  // namespace

Pose Chain::fk_jacobian(const double* q, double* jacobian) const {
  const int n = dof();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  // Joint origins and axes (base frame) for the Jacobian: a short chain keeps them on the stack.
  constexpr int kStack = 16;
  Eigen::Vector3d o_stack[kStack], a_stack[kStack];
  std::vector<Eigen::Vector3d> o_heap, a_heap;
  Eigen::Vector3d* origins = o_stack;
  Eigen::Vector3d* axes = a_stack;
  if (jacobian && n > kStack) {
    o_heap.resize(n);
    a_heap.resize(n);
    origins = o_heap.data();
    axes = a_heap.data();
  }
  for (int i = 0; i < n; ++i) {
    const Segment& s = segments_[i];
    p += R * s.origin.translation();
    if (turned_origin_[i]) R = R * s.origin.linear();  // most URDF joint frames are not turned: no product
    const int kind = axis_kind_[i];
    if (jacobian) {
      origins[i] = p;
      axes[i] = kind < 0 ? Eigen::Vector3d(R * s.axis) : kind < 3 ? Eigen::Vector3d(R.col(kind)) : Eigen::Vector3d(-R.col(kind - 3));
    }
    if (s.type == JointType::Prismatic) p += R * (s.axis * q[i]);
    else rotate_about(R, kind, s.axis, q[i]);
  }
  Pose T = Pose::Identity();
  T.translation() = p + R * tip_offset_.translation();
  T.linear() = R * tip_offset_.linear();
  if (jacobian) {
    const Eigen::Vector3d tip = T.translation();
    for (int i = 0; i < n; ++i) {
      Eigen::Map<Eigen::Matrix<double, 6, 1>> col(jacobian + 6 * i);
      if (segments_[i].type == JointType::Prismatic) {
        col.head<3>() = axes[i];
        col.tail<3>().setZero();
      } else {
        col.head<3>() = axes[i].cross(tip - origins[i]);
        col.tail<3>() = axes[i];
      }
    }
  }
  return T;
}

Pose Chain::fk(const Eigen::VectorXd& q) const {
  check_joint_vector(*this, q);
  return fk_jacobian(q.data(), nullptr);
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
  J.resize(6, dof());
  return fk_jacobian(q.data(), J.data());
}

bool Chain::within_limits(const Eigen::VectorXd& q, double tol) const {
  if (q.size() != dof() || !q.allFinite()) return false;
  for (int i = 0; i < dof(); ++i)
    if (!continuous_[i] && (q[i] < lower_[i] - tol || q[i] > upper_[i] + tol)) return false;
  return true;
}

Eigen::MatrixXd Chain::random_configurations(int n, std::uint64_t seed) const {
  if (n < 0) throw std::invalid_argument("random_configurations: n must be >= 0 (got " + std::to_string(n) + ")");
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd out(n, dof());
  for (int r = 0; r < n; ++r) out.row(r) = random_configuration(rng).transpose();
  return out;
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

std::vector<int> Chain::moved_collision_links() const {
  std::vector<int> out;
  for (int li : robot_->collision_links())
    if (link_masks_[li]) out.push_back(li);
  return out;
}

void Chain::split_collision_pairs(std::vector<std::pair<int, int>>& moving,
                                  std::vector<std::pair<int, int>>& fixed) const {
  moving.clear();
  fixed.clear();
  for (const auto& p : robot_->checked_pairs())
    (link_masks_[p.first] != link_masks_[p.second] ? moving : fixed).push_back(p);
}

}  // namespace octoreach
