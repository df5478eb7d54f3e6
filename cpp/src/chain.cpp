#include <cmath>
#include <random>

#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {
namespace {

void check_q(const Chain& c, const Eigen::VectorXd& q) {
  if (q.size() != c.dof())
    throw std::invalid_argument("joint vector has " + std::to_string(q.size()) + " entries, chain '" + c.base_link() +
                                "' -> '" + c.tip_link() + "' has " + std::to_string(c.dof()) + " joints");
}

inline double wrap_pi(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0) a += 2.0 * M_PI;
  return a - M_PI;
}

// Rotation vector (axis * angle) of R, robust near 0 and pi.
Eigen::Vector3d log_so3(const Eigen::Matrix3d& R) {
  Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}


}  // namespace

Pose Chain::fk(const Eigen::VectorXd& q) const {
  check_q(*this, q);
  Pose T = Pose::Identity();
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    T = T * s.origin;
    if (s.type == JointType::Prismatic) T.translate(s.axis * q[i]);
    else T.rotate(Eigen::AngleAxisd(q[i], s.axis));
  }
  return T * tip_offset_;
}

Pose Chain::fk_jacobian(const Eigen::VectorXd& q, Eigen::Matrix<double, 6, Eigen::Dynamic>& J) const {
  check_q(*this, q);
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
  check_q(*this, q_in);
  Eigen::VectorXd q = q_in;
  for (int i = 0; i < dof(); ++i) {
    if (continuous_[i]) {
      q[i] = wrap_pi(q[i]);
    } else if (segments_[i].type == JointType::Revolute) {
      // Shift by whole turns toward the limits; leave it outside if no turn fits.
      while (q[i] > upper_[i] && q[i] - 2 * M_PI >= lower_[i] - 1e-12) q[i] -= 2 * M_PI;
      while (q[i] < lower_[i] && q[i] + 2 * M_PI <= upper_[i] + 1e-12) q[i] += 2 * M_PI;
    }
  }
  return q;
}

Eigen::VectorXd Chain::to_robot_configuration(const Eigen::VectorXd& q, const Eigen::VectorXd& reference) const {
  check_q(*this, q);
  Eigen::VectorXd full = reference.size() == 0 ? robot_->home() : reference;
  if (full.size() != robot_->dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(full.size()) +
                                " entries, the robot has " + std::to_string(robot_->dof()));
  for (int i = 0; i < dof(); ++i) full[robot_indices_[i]] = q[i];
  return full;
}

namespace {

// Levenberg-Marquardt IK core. Matrices have a fixed upper size (no heap traffic in the loop);
// MaxDof = Eigen::Dynamic serves longer chains.
template <int MaxDof>
struct LmSolver {
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaxDof, 1>;
  using Jac = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, MaxDof>;
  using Sq = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxDof, MaxDof>;
  using Res = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  using ResJac = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, MaxDof>;
};

}  // namespace

std::optional<Eigen::VectorXd> Chain::ik(const Pose& target, const IkOptions& o, const Eigen::VectorXd* seed) const {
  if (!target.matrix().allFinite()) throw std::invalid_argument("IK target pose must be finite");
  if (!(o.position_tolerance > 0) || !(o.orientation_tolerance > 0))
    throw std::invalid_argument("IK tolerances must be positive");
  if (o.attempts < 1 || o.max_iterations < 1)
    throw std::invalid_argument("IK needs at least one attempt and one iteration");
  if (seed) {
    check_q(*this, *seed);
    if (!seed->allFinite()) throw std::invalid_argument("IK seed must be finite");
  }
  if (o.reference.size() != 0 && o.reference.size() != robot_->dof())
    throw std::invalid_argument("IK reference configuration has " + std::to_string(o.reference.size()) +
                                " entries, the robot has " + std::to_string(robot_->dof()));
  if (dof() == 0) {  // a rigid chain reaches only its own pose
    Pose T = fk(Eigen::VectorXd());
    bool pos_ok = (T.translation() - target.translation()).norm() < o.position_tolerance;
    double rot = o.mode == IkMode::Position ? 0.0
                 : o.mode == IkMode::Full   ? Eigen::AngleAxisd(target.linear() * T.linear().transpose()).angle()
                                            : std::acos(std::min(1.0, (T.linear() * o.approach_axis.normalized())
                                                                          .dot(target.linear() * o.approach_axis.normalized())));
    if (pos_ok && rot < o.orientation_tolerance) return Eigen::VectorXd();
    return std::nullopt;
  }
  if (dof() <= 12) return ik_impl_<12>(target, o, seed);
  return ik_impl_<Eigen::Dynamic>(target, o, seed);
}

template <int MaxDof>
std::optional<Eigen::VectorXd> Chain::ik_impl_(const Pose& target, const IkOptions& o,
                                               const Eigen::VectorXd* seed) const {
  using S = LmSolver<MaxDof>;
  const int n = dof();
  const Eigen::Vector3d approach_tip = o.approach_axis.normalized();
  const Eigen::Vector3d approach_goal = target.linear() * approach_tip;
  // Orientation error is weighted so that one radian counts like this many metres.
  const double w_rot = 0.25;
  std::mt19937_64 rng(o.seed);
  typename S::Jac J(6, n);  // Jacobian at the latest evaluated configuration
  typename S::Vec q(n), q_new(n), dq(n), g(n);
  typename S::Sq A(n, n);
  typename S::Res e, e_new;
  typename S::ResJac Jr;
  Eigen::VectorXd reference;
  bool need_full = o.check_self_collision || o.obstacles;
  if (need_full) reference = o.reference.size() ? o.reference : robot_->home();

  // Error vector (3 or 6 rows) and, when asked, the matching Jacobian rows; plus convergence test.
  auto residual = [&](const Pose& T, bool with_jacobian, typename S::Res& err, bool& converged) {
    Eigen::Vector3d ep = target.translation() - T.translation();
    if (o.mode == IkMode::Position) {
      err = ep;
      if (with_jacobian) Jr = J.template topRows<3>();
      converged = ep.norm() < o.position_tolerance;
      return;
    }
    Eigen::Vector3d er;
    double rot_err;
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
    if (o.mode == IkMode::Full) {
      er = log_so3(target.linear() * T.linear().transpose());
      rot_err = er.norm();
    } else {
      Eigen::Vector3d a = T.linear() * approach_tip;
      Eigen::Vector3d c = a.cross(approach_goal);
      double s = c.norm(), cs = a.dot(approach_goal);
      rot_err = std::atan2(s, cs);
      if (s > 1e-12) er = c / s * rot_err;
      else if (cs < 0) er = a.unitOrthogonal() * M_PI;  // opposite: any perpendicular axis
      else er.setZero();
      P -= a * a.transpose();  // roll about the approach axis does not matter
    }
    err.resize(6);
    err.template head<3>() = ep;
    err.template tail<3>() = w_rot * er;
    if (with_jacobian) {
      Jr.resize(6, n);
      Jr.template topRows<3>() = J.template topRows<3>();
      Jr.template bottomRows<3>() = w_rot * (P * J.template bottomRows<3>());
    }
    converged = ep.norm() < o.position_tolerance && rot_err < o.orientation_tolerance;
  };

  std::vector<std::pair<int, int>> moving_pairs, fixed_pairs;
  if (o.check_self_collision) split_collision_pairs(moving_pairs, fixed_pairs);
  int fixed_state = o.check_fixed_pairs ? -1 : 0;  // -1 unknown, 0 free, 1 colliding
  std::vector<Pose> poses;
  auto accept = [&](const Eigen::VectorXd& sol) -> bool {
    if (!within_limits(sol, 1e-9)) return false;
    if (!need_full) return true;
    Eigen::VectorXd full = to_robot_configuration(sol, reference);
    robot_->link_poses(full, poses);
    if (o.obstacles && robot_->links_in_collision(poses, *o.obstacles, o.base_pose,
                                                  o.obstacle_links.empty() ? nullptr : &o.obstacle_links))
      return false;
    if (o.check_self_collision) {
      if (fixed_state < 0) fixed_state = robot_->in_self_collision_poses(poses, fixed_pairs) ? 1 : 0;
      if (fixed_state == 1) return false;
      if (robot_->in_self_collision_poses(poses, moving_pairs)) return false;
    }
    return true;
  };

  auto clamp = [&](auto& v) {
    for (int i = 0; i < n; ++i) {
      if (continuous_[i]) continue;
      if (segments_[i].type == JointType::Revolute) {
        while (v[i] > upper_[i] && v[i] - 2 * M_PI >= lower_[i]) v[i] -= 2 * M_PI;
        while (v[i] < lower_[i] && v[i] + 2 * M_PI <= upper_[i]) v[i] += 2 * M_PI;
      }
      v[i] = std::min(std::max(v[i], lower_[i]), upper_[i]);
    }
  };

  // Errors this small are left to finish; above it, slow progress means a local minimum.
  const double tol2 = o.position_tolerance * o.position_tolerance;
  Eigen::Matrix<double, 6, Eigen::Dynamic> Jfull;
  for (int attempt = 0; attempt < o.attempts; ++attempt) {
    if (attempt == 0 && seed) {
      q = *seed;
      clamp(q);
    } else {
      q = random_configuration(rng);
    }
    bool converged = false;
    Pose T = fk_jacobian(q, Jfull);
    J = Jfull;
    residual(T, true, e, converged);
    double err = e.squaredNorm();
    double lambda = 1e-3;
    int slow = 0;
    for (int it = 0; it < o.max_iterations && !converged; ++it) {
      // Levenberg-Marquardt step: (J^T J + lambda (I + diag J^T J)) dq = J^T e
      A.noalias() = Jr.transpose() * Jr;
      g.noalias() = Jr.transpose() * e;
      A.diagonal().array() += lambda * (1.0 + A.diagonal().array());
      dq = A.llt().solve(g);  // A is symmetric positive definite
      q_new = q + dq;
      clamp(q_new);
      bool conv_new = false;
      Pose T_new = fk_jacobian(q_new, Jfull);
      J = Jfull;
      residual(T_new, false, e_new, conv_new);
      double err_new = e_new.squaredNorm();
      if (err_new < err) {
        slow = (err - err_new < 0.01 * err && err_new > 100 * tol2) ? slow + 1 : 0;
        q = q_new;
        err = err_new;
        residual(T_new, true, e, converged);
        lambda = std::max(lambda * 0.3, 1e-9);
        if (slow >= 4) break;  // crawling far from the target: a local minimum or a limit
      } else {
        lambda *= 10.0;
        if (lambda > 1e6) break;  // stuck: restart
        // Jr and e still describe q, so the next step needs no new kinematics.
      }
    }
    if (converged) {
      Eigen::VectorXd sol = wrap(q);
      if (accept(sol)) return sol;
    }
  }
  return std::nullopt;
}

void Chain::ik_batch(const std::vector<Pose>& targets, const IkOptions& options, Eigen::MatrixXd& solutions,
                     std::vector<bool>& ok, const Eigen::MatrixXd* seeds, int threads) const {
  if (seeds && (seeds->rows() != static_cast<Eigen::Index>(targets.size()) || seeds->cols() != dof()))
    throw std::invalid_argument("seeds must have shape (" + std::to_string(targets.size()) + ", " +
                                std::to_string(dof()) + ")");
  solutions = Eigen::MatrixXd::Constant(targets.size(), dof(), std::numeric_limits<double>::quiet_NaN());
  std::vector<char> flags(targets.size(), 0);
  detail::parallel_for(targets.size(), threads, [&](std::size_t i, int) {
    IkOptions o = options;
    o.seed = detail::mix64(options.seed, i);  // per-item streams: the result does not depend on the thread count
    Eigen::VectorXd s;
    if (seeds) s = seeds->row(i).transpose();
    auto q = ik(targets[i], o, seeds ? &s : nullptr);
    if (q) {
      solutions.row(i) = q->transpose();
      flags[i] = 1;
    }
  }, 4);
  ok.assign(flags.begin(), flags.end());
}

void Chain::split_collision_pairs(std::vector<std::pair<int, int>>& moving,
                                  std::vector<std::pair<int, int>>& fixed) const {
  moving.clear();
  fixed.clear();
  for (const auto& p : robot_->checked_pairs())
    (link_masks_[p.first] != link_masks_[p.second] ? moving : fixed).push_back(p);
}

}  // namespace octoreach
