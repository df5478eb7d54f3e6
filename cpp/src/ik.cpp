// Chain IK: damped least squares (Levenberg-Marquardt) with random restarts, solutions checked
// against limits, self-collision and obstacles; ik_batch runs it on the thread pool.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "octoreach/chain.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "chain_checks.hpp"
#include "common/cancel.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {
namespace {

// Rotation vector (axis * angle) of R, robust near 0 and pi.
Eigen::Vector3d log_so3(const Eigen::Matrix3d& R) {
  Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

void check_ik_request(const Chain& c, const Pose& target, const IkOptions& o, const Eigen::VectorXd* seed) {
  if (!target.matrix().allFinite()) throw std::invalid_argument("IK target pose must be finite");
  if (!(o.position_tolerance > 0) || !(o.orientation_tolerance > 0))
    throw std::invalid_argument("IK tolerances must be positive");
  if (o.attempts < 1 || o.max_iterations < 1)
    throw std::invalid_argument("IK needs at least one attempt and one iteration");
  if (seed) {
    detail::check_joint_vector(c, *seed);
    if (!seed->allFinite()) throw std::invalid_argument("IK seed must be finite");
  }
  if (o.reference.size() != 0 && o.reference.size() != c.robot().dof())
    throw std::invalid_argument("IK reference configuration has " + std::to_string(o.reference.size()) +
                                " entries, the robot has " + std::to_string(c.robot().dof()));
}

// A chain without moving joints reaches only its own pose.
std::optional<Eigen::VectorXd> rigid_chain_ik(const Chain& c, const Pose& target, const IkOptions& o) {
  Pose T = c.fk(Eigen::VectorXd());
  bool pos_ok = (T.translation() - target.translation()).norm() < o.position_tolerance;
  double rot = o.mode == IkMode::Position ? 0.0
               : o.mode == IkMode::Full   ? Eigen::AngleAxisd(target.linear() * T.linear().transpose()).angle()
                                          : std::acos(std::min(1.0, (T.linear() * o.approach_axis.normalized())
                                                                        .dot(target.linear() * o.approach_axis.normalized())));
  if (pos_ok && rot < o.orientation_tolerance) return Eigen::VectorXd();
  return std::nullopt;
}

// One IK call: Levenberg-Marquardt descents from the seed and from random restarts. Matrices have
// a fixed upper size (no heap traffic in the loop); MaxDof = Eigen::Dynamic serves longer chains.
// A solver is the per-call workspace: built, solved once, dropped.
template <int MaxDof>
class LmIk {
 public:
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaxDof, 1>;
  using Jac = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, MaxDof>;
  using Sq = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxDof, MaxDof>;
  using Res = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  using ResJac = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, MaxDof>;

  LmIk(const Chain& chain, const Pose& target, const IkOptions& o)
      : c_(chain), target_(target), o_(o), n_(chain.dof()), rng_(o.seed), J_(6, n_), q_(n_), q_new_(n_), dq_(n_),
        g_(n_), A_(n_, n_) {
    approach_tip_ = o.approach_axis.normalized();
    approach_goal_ = target.linear() * approach_tip_;
    need_full_ = o.check_self_collision || o.obstacles;
    if (need_full_) reference_ = o.reference.size() ? o.reference : c_.robot().home();
    if (o.check_self_collision) c_.split_collision_pairs(moving_pairs_, fixed_pairs_);
    fixed_state_ = o.check_fixed_pairs ? -1 : 0;
  }

  std::optional<Eigen::VectorXd> solve(const Eigen::VectorXd* seed) {
    for (int attempt = 0; attempt < o_.attempts; ++attempt) {
      detail::poll_cancel("IK cancelled");
      if (attempt == 0 && seed) {
        q_ = *seed;
        clamp(q_);
      } else {
        q_ = c_.random_configuration(rng_);
      }
      if (descend()) {
        Eigen::VectorXd sol = c_.wrap(q_);
        if (accept(sol)) return sol;
      }
    }
    return std::nullopt;
  }

 private:
  // Orientation error is weighted so that one radian counts like this many metres.
  static constexpr double kRotWeight = 0.25;

  // Error vector (3 or 6 rows) and, when asked, the matching Jacobian rows; plus convergence test.
  void residual(const Pose& T, bool with_jacobian, Res& err, bool& converged) {
    Eigen::Vector3d ep = target_.translation() - T.translation();
    if (o_.mode == IkMode::Position) {
      err = ep;
      if (with_jacobian) Jr_ = J_.template topRows<3>();
      converged = ep.norm() < o_.position_tolerance;
      return;
    }
    Eigen::Vector3d er;
    double rot_err;
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
    if (o_.mode == IkMode::Full) {
      er = log_so3(target_.linear() * T.linear().transpose());
      rot_err = er.norm();
    } else {
      Eigen::Vector3d a = T.linear() * approach_tip_;
      Eigen::Vector3d c = a.cross(approach_goal_);
      double s = c.norm(), cs = a.dot(approach_goal_);
      rot_err = std::atan2(s, cs);
      if (s > 1e-12) er = c / s * rot_err;
      else if (cs < 0) er = a.unitOrthogonal() * kPi;  // opposite: any perpendicular axis
      else er.setZero();
      P -= a * a.transpose();  // roll about the approach axis does not matter
    }
    err.resize(6);
    err.template head<3>() = ep;
    err.template tail<3>() = kRotWeight * er;
    if (with_jacobian) {
      Jr_.resize(6, n_);
      Jr_.template topRows<3>() = J_.template topRows<3>();
      Jr_.template bottomRows<3>() = kRotWeight * (P * J_.template bottomRows<3>());
    }
    converged = ep.norm() < o_.position_tolerance && rot_err < o_.orientation_tolerance;
  }

  // Revolute joints shifted by whole turns toward their limits, then every bounded joint clamped.
  void clamp(Vec& v) const {
    const auto& lower = c_.lower();
    const auto& upper = c_.upper();
    for (int i = 0; i < n_; ++i) {
      if (c_.continuous()[i]) continue;
      if (c_.segments()[i].type == JointType::Revolute) v[i] = detail::shift_by_turns(v[i], lower[i], upper[i], 0.0);
      v[i] = std::min(std::max(v[i], lower[i]), upper[i]);
    }
  }

  // One descent from q_; true when it converged (q_ then holds the solution).
  bool descend() {
    // Errors this small are left to finish; above it, slow progress means a local minimum.
    const double tol2 = o_.position_tolerance * o_.position_tolerance;
    bool converged = false;
    Pose T = c_.fk_jacobian(q_, Jfull_);
    J_ = Jfull_;
    residual(T, true, e_, converged);
    double err = e_.squaredNorm();
    double lambda = 1e-3;
    int slow = 0;
    for (int it = 0; it < o_.max_iterations && !converged; ++it) {
      // Levenberg-Marquardt step: (J^T J + lambda (I + diag J^T J)) dq = J^T e
      A_.noalias() = Jr_.transpose() * Jr_;
      g_.noalias() = Jr_.transpose() * e_;
      A_.diagonal().array() += lambda * (1.0 + A_.diagonal().array());
      dq_ = A_.llt().solve(g_);  // A is symmetric positive definite
      q_new_ = q_ + dq_;
      clamp(q_new_);
      bool conv_new = false;
      Pose T_new = c_.fk_jacobian(q_new_, Jfull_);
      J_ = Jfull_;
      residual(T_new, false, e_new_, conv_new);
      double err_new = e_new_.squaredNorm();
      if (err_new < err) {
        slow = (err - err_new < 0.01 * err && err_new > 100 * tol2) ? slow + 1 : 0;
        q_ = q_new_;
        err = err_new;
        residual(T_new, true, e_, converged);
        lambda = std::max(lambda * 0.3, 1e-9);
        if (slow >= 4) break;  // crawling far from the target: a local minimum or a limit
      } else {
        lambda *= 10.0;
        if (lambda > 1e6) break;  // stuck: restart
        // Jr and e still describe q, so the next step needs no new kinematics.
      }
    }
    return converged;
  }

  // Limits, obstacles and self-collision of a converged (wrapped) solution. The pairs the chain
  // never moves are checked once per call, at the first solution that gets this far.
  bool accept(const Eigen::VectorXd& sol) {
    if (!c_.within_limits(sol, 1e-9)) return false;
    if (!need_full_) return true;
    const Robot& robot = c_.robot();
    Eigen::VectorXd full = c_.to_robot_configuration(sol, reference_);
    robot.link_poses(full, poses_);
    if (o_.obstacles && robot.links_in_collision(poses_, *o_.obstacles, o_.base_pose,
                                                 o_.obstacle_links.empty() ? nullptr : &o_.obstacle_links))
      return false;
    if (o_.check_self_collision) {
      if (fixed_state_ < 0) fixed_state_ = robot.in_self_collision_poses(poses_, fixed_pairs_) ? 1 : 0;
      if (fixed_state_ == 1) return false;
      if (robot.in_self_collision_poses(poses_, moving_pairs_)) return false;
    }
    return true;
  }

  const Chain& c_;
  const Pose& target_;
  const IkOptions& o_;
  const int n_;
  Eigen::Vector3d approach_tip_, approach_goal_;
  std::mt19937_64 rng_;
  Jac J_;  // Jacobian at the latest evaluated configuration
  Vec q_, q_new_, dq_, g_;
  Sq A_;
  Res e_, e_new_;
  ResJac Jr_;
  Eigen::Matrix<double, 6, Eigen::Dynamic> Jfull_;
  Eigen::VectorXd reference_;
  bool need_full_ = false;
  std::vector<std::pair<int, int>> moving_pairs_, fixed_pairs_;
  int fixed_state_ = -1;  // fixed pairs: -1 unknown, 0 free, 1 colliding
  std::vector<Pose> poses_;
};

}  // namespace

std::optional<Eigen::VectorXd> Chain::ik(const Pose& target, const IkOptions& o, const Eigen::VectorXd* seed) const {
  check_ik_request(*this, target, o, seed);
  detail::CancellableScope cancellable;
  if (dof() == 0) return rigid_chain_ik(*this, target, o);
  if (dof() <= 12) return LmIk<12>(*this, target, o).solve(seed);
  return LmIk<Eigen::Dynamic>(*this, target, o).solve(seed);
}

void Chain::ik_batch(const std::vector<Pose>& targets, const IkOptions& options, Eigen::MatrixXd& solutions,
                     std::vector<bool>& ok, const Eigen::MatrixXd* seeds, int threads) const {
  if (seeds && (seeds->rows() != static_cast<Eigen::Index>(targets.size()) || seeds->cols() != dof()))
    throw std::invalid_argument("seeds must have shape (" + std::to_string(targets.size()) + ", " +
                                std::to_string(dof()) + ")");
  detail::CancellableScope cancellable;
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

}  // namespace octoreach
