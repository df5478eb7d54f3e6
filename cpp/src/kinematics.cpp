#include <cmath>
#include <random>

#include <kdl/chain.hpp>

#include "octoreach/ik.hpp"
#include "octoreach/robot.hpp"
#include "parallel.hpp"

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

std::uint64_t mix(std::uint64_t seed, std::uint64_t i) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (i + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
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

std::optional<Eigen::VectorXd> Chain::ik(const Pose& target, const IkOptions& o, const Eigen::VectorXd* seed) const {
  if (!target.matrix().allFinite()) throw std::invalid_argument("IK target pose must be finite");
  if (!(o.position_tolerance > 0) || !(o.orientation_tolerance > 0))
    throw std::invalid_argument("IK tolerances must be positive");
  if (o.attempts < 1 || o.max_iterations < 1)
    throw std::invalid_argument("IK needs at least one attempt and one iteration");
  if (seed) check_q(*this, *seed);
  if (o.reference.size() != 0 && o.reference.size() != robot_->dof())
    throw std::invalid_argument("IK reference configuration has " + std::to_string(o.reference.size()) +
                                " entries, the robot has " + std::to_string(robot_->dof()));
  const int n = dof();
  if (n == 0) return std::nullopt;
  const Eigen::Vector3d approach_tip = o.approach_axis.normalized();
  const Eigen::Vector3d approach_goal = target.linear() * approach_tip;
  // Orientation error is weighted so that one radian counts like this many metres.
  const double w_rot = 0.25;
  std::mt19937_64 rng(o.seed);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, n);
  Eigen::VectorXd q, q_new, reference;
  bool need_full = o.check_self_collision || o.obstacles;
  if (need_full) reference = o.reference.size() ? o.reference : robot_->home();

  // Error vector (up to 6 rows) and the matching Jacobian rows, plus convergence test.
  auto residual = [&](const Pose& T, const Eigen::Matrix<double, 6, Eigen::Dynamic>* Jin, Eigen::VectorXd& e,
                      Eigen::MatrixXd* Jout, bool& converged) {
    Eigen::Vector3d ep = target.translation() - T.translation();
    if (o.mode == IkMode::Position) {
      e = ep;
      if (Jout) *Jout = Jin->topRows<3>();
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
      er = s > 1e-12 ? Eigen::Vector3d(c / s * rot_err) : Eigen::Vector3d::Zero();
      if (s <= 1e-12 && cs < 0) {  // opposite: any perpendicular axis
        Eigen::Vector3d perp = a.unitOrthogonal();
        er = perp * M_PI;
      }
      P -= a * a.transpose();  // roll about the approach axis does not matter
    }
    e.resize(6);
    e.head<3>() = ep;
    e.tail<3>() = w_rot * er;
    if (Jout) {
      Jout->resize(6, n);
      Jout->topRows<3>() = Jin->topRows<3>();
      Jout->bottomRows<3>() = w_rot * (P * Jin->bottomRows<3>());
    }
    converged = ep.norm() < o.position_tolerance && rot_err < o.orientation_tolerance;
  };

  auto accept = [&](const Eigen::VectorXd& sol) -> bool {
    if (!within_limits(sol, 1e-9)) return false;
    if (!need_full) return true;
    Eigen::VectorXd full = to_robot_configuration(sol, reference);
    if (o.obstacles && robot_->in_collision(full, *o.obstacles, o.base_pose, false)) return false;
    if (o.check_self_collision && robot_->in_self_collision(full)) return false;
    return true;
  };

  auto clamp = [&](Eigen::VectorXd& v) {
    for (int i = 0; i < n; ++i) {
      if (continuous_[i]) continue;
      if (segments_[i].type == JointType::Revolute) {
        while (v[i] > upper_[i] && v[i] - 2 * M_PI >= lower_[i]) v[i] -= 2 * M_PI;
        while (v[i] < lower_[i] && v[i] + 2 * M_PI <= upper_[i]) v[i] += 2 * M_PI;
      }
      v[i] = std::min(std::max(v[i], lower_[i]), upper_[i]);
    }
  };

  Eigen::VectorXd e, e_new;
  Eigen::MatrixXd Jr;
  for (int attempt = 0; attempt < o.attempts; ++attempt) {
    if (attempt == 0 && seed) {
      q = *seed;
      clamp(q);
    } else {
      q = random_configuration(rng);
    }
    bool converged = false;
    Pose T = fk_jacobian(q, J);
    residual(T, &J, e, &Jr, converged);
    double err = e.squaredNorm();
    double lambda = 1e-3;
    for (int it = 0; it < o.max_iterations && !converged; ++it) {
      // Levenberg-Marquardt step: (J^T J + lambda diag) dq = J^T e
      Eigen::MatrixXd A = Jr.transpose() * Jr;
      Eigen::VectorXd g = Jr.transpose() * e;
      A.diagonal().array() += lambda * (1.0 + A.diagonal().array());
      Eigen::VectorXd dq = A.ldlt().solve(g);
      q_new = q + dq;
      clamp(q_new);
      bool conv_new = false;
      Pose T_new = fk_jacobian(q_new, J);
      residual(T_new, &J, e_new, nullptr, conv_new);
      double err_new = e_new.squaredNorm();
      if (err_new < err) {
        q = q_new;
        e = e_new;
        err = err_new;
        residual(T_new, &J, e, &Jr, converged);
        lambda = std::max(lambda * 0.3, 1e-9);
      } else {
        lambda *= 10.0;
        if (lambda > 1e6) break;  // stuck in a local minimum or at a limit: restart
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
    o.seed = mix(options.seed, i);  // per-item streams: the result does not depend on the thread count
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

KDL::Chain Chain::to_kdl() const {
  auto frame = [](const Pose& T) {
    KDL::Rotation R(T(0, 0), T(0, 1), T(0, 2), T(1, 0), T(1, 1), T(1, 2), T(2, 0), T(2, 1), T(2, 2));
    return KDL::Frame(R, KDL::Vector(T(0, 3), T(1, 3), T(2, 3)));
  };
  KDL::Chain chain;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    KDL::Frame F = frame(s.origin);
    KDL::Vector axis = F.M * KDL::Vector(s.axis.x(), s.axis.y(), s.axis.z());
    KDL::Joint::JointType type =
        s.type == JointType::Prismatic ? KDL::Joint::TransAxis : KDL::Joint::RotAxis;
    const std::string& name = robot_->joints()[s.robot_joint].name;
    chain.addSegment(KDL::Segment(robot_->links()[robot_->joints()[s.robot_joint].child_link].name,
                                  KDL::Joint(name, F.p, axis, type), F));
  }
  if (!tip_offset_.matrix().isIdentity(1e-12) || segments_.empty())
    chain.addSegment(KDL::Segment(tip_link_ + "_fixed", KDL::Joint(KDL::Joint::None), frame(tip_offset_)));
  return chain;
}

}  // namespace octoreach
