// Look-at IK (aim.hpp): damped least squares on the aim error, projected onto the joint limits, with restarts.
#include "octoreach/aim.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <Eigen/Dense>

#include "kinematics/chain_checks.hpp"

namespace octoreach {

namespace {

constexpr double kMaxStep = 0.5;  // largest joint step of one iteration (rad or m): the aim error is not linear

// The tip's aimed axis a, the unit ray u to the target and the error vector u - a (base frame); false when
// the target is at the tip's origin (no ray).
struct AimState {
  Eigen::Vector3d a, u, d;
  double dist = 0;
  bool ok = false;
  double angle() const { return ok ? std::atan2(a.cross(u).norm(), a.dot(u)) : kPi; }
};

AimState state_at(const Pose& T, const Eigen::Vector3d& target, const Eigen::Vector3d& axis) {
  AimState s;
  s.a = T.linear() * axis;
  s.d = target - T.translation();
  s.dist = s.d.norm();
  s.ok = s.dist > 1e-9;
  s.u = s.ok ? Eigen::Vector3d(s.d / s.dist) : s.a;
  return s;
}

// Joints moved into the limits (continuous ones wrapped into [-pi, pi)).
void project(const Chain& c, Eigen::VectorXd& q) {
  for (int i = 0; i < c.dof(); ++i) {
    if (c.continuous()[std::size_t(i)]) q[i] = std::remainder(q[i], 2 * kPi);
    else q[i] = std::clamp(q[i], c.lower()[i], c.upper()[i]);
  }
}

// One descent from q (changed in place); returns its angle.
double descend(const Chain& c, const Eigen::Vector3d& target, const AimOptions& o, Eigen::VectorXd& q) {
  const int n = c.dof();
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, n);
  Eigen::Matrix<double, 3, Eigen::Dynamic> Je(3, n);
  const Eigen::MatrixXd damp = o.damping * o.damping * Eigen::MatrixXd::Identity(n, n);
  double angle = kPi;
  for (int it = 0; it < o.max_iterations; ++it) {
    const Pose T = c.fk_jacobian(q.data(), J.data());
    const AimState s = state_at(T, target, o.axis);
    angle = s.angle();
    if (!s.ok || angle <= o.tolerance) break;
    // d(u - a)/dq: the ray turns as the tip moves, the axis as the joints turn it
    const Eigen::Matrix3d P = (Eigen::Matrix3d::Identity() - s.u * s.u.transpose()) / s.dist;
    for (int j = 0; j < n; ++j)
      Je.col(j) = -P * J.block<3, 1>(0, j) - J.block<3, 1>(3, j).cross(s.a);
    Eigen::VectorXd dq = (Je.transpose() * Je + damp).ldlt().solve(-Je.transpose() * (s.u - s.a));
    const double big = dq.cwiseAbs().maxCoeff();
    if (!std::isfinite(big)) break;
    if (big > kMaxStep) dq *= kMaxStep / big;
    const Eigen::VectorXd before = q;
    q += dq;
    project(c, q);
    if ((q - before).cwiseAbs().maxCoeff() < 1e-10) break;  // pinned at a limit: no step left
  }
  return aim_error(c, q, target, o.axis);
}

}  // namespace

void AimOptions::validate() const {
  if (!axis.allFinite() || axis.norm() < 1e-9)
    throw std::invalid_argument("aim axis must be a finite non-zero vector");
  if (!(tolerance > 0) || !std::isfinite(tolerance))
    throw std::invalid_argument("aim tolerance must be a positive finite number of radians, got " +
                                std::to_string(tolerance));
  if (max_iterations < 1 || attempts < 1)
    throw std::invalid_argument("aim needs max_iterations >= 1 and attempts >= 1, got " +
                                std::to_string(max_iterations) + " and " + std::to_string(attempts));
  if (!(damping >= 0) || !std::isfinite(damping))
    throw std::invalid_argument("aim damping must be a finite number >= 0, got " + std::to_string(damping));
}

double aim_error(const Chain& chain, const Eigen::VectorXd& q, const Eigen::Vector3d& target,
                 const Eigen::Vector3d& axis) {
  detail::check_joint_vector(chain, q);
  if (!target.allFinite()) throw std::invalid_argument("aim target must be finite");
  if (!axis.allFinite() || axis.norm() < 1e-9) throw std::invalid_argument("aim axis must be a finite non-zero vector");
  return state_at(chain.fk(q), target, axis.normalized()).angle();
}

AimResult aim(const Chain& chain, const Eigen::Vector3d& target, const AimOptions& options,
              const Eigen::VectorXd* start) {
  options.validate();
  if (!target.allFinite()) throw std::invalid_argument("aim target must be finite");
  if (start) {
    detail::check_joint_vector(chain, *start);
    if (!start->allFinite()) throw std::invalid_argument("aim start must be finite");
  }
  AimOptions o = options;
  o.axis = options.axis.normalized();
  const int n = chain.dof();
  AimResult best;
  best.error = kPi + 1;
  std::mt19937_64 rng(o.seed);
  for (int attempt = 0; attempt < o.attempts; ++attempt) {
    Eigen::VectorXd q(n);
    if (attempt == 0 && start) {
      q = *start;
    } else if (attempt == 0) {
      for (int i = 0; i < n; ++i)
        q[i] = chain.continuous()[std::size_t(i)] ? 0.0 : 0.5 * (chain.lower()[i] + chain.upper()[i]);
    } else {
      q = chain.random_configuration(rng);
    }
    project(chain, q);
    const double e = n ? descend(chain, target, o, q) : aim_error(chain, q, target, o.axis);
    if (e < best.error) {
      best.error = e;
      best.q = q;
    }
    if (best.error <= o.tolerance) break;
  }
  best.reached = best.error <= o.tolerance;
  return best;
}

}  // namespace octoreach
