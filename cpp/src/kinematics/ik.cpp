// Chain IK: damped least squares (Levenberg-Marquardt) with random restarts, solutions checked
// against limits, self-collision and obstacles; ik_batch runs it on the thread pool.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "octoreach/chain.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "kinematics/chain_checks.hpp"
#include "collision/detail.hpp"
#include "kinematics/chain_self_check.hpp"
#include "common/cancel.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "robot/joint_motion.hpp"

namespace octoreach {
namespace {

// Rotation vector (axis * angle) of R, robust near 0 and pi.
Eigen::Vector3d log_so3(const Eigen::Matrix3d& R) {
  Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

void check_ik_request(const Chain& c, const Pose& target, const IkOptions& o, const Eigen::VectorXd* seed) {
  check_rigid(target, "IK target pose");
  check_rigid(o.base_pose, "IK base_pose");
  if (!(o.position_tolerance > 0) || !std::isfinite(o.position_tolerance))
    throw std::invalid_argument("IK position_tolerance must be a positive finite number of metres, got " +
                                std::to_string(o.position_tolerance));
  if (!(o.orientation_tolerance > 0) || !std::isfinite(o.orientation_tolerance))
    throw std::invalid_argument("IK orientation_tolerance must be a positive finite number of radians, got " +
                                std::to_string(o.orientation_tolerance));
  if (!o.approach_axis.allFinite() || o.approach_axis.norm() < 1e-9)
    throw std::invalid_argument("IK approach_axis must be a finite non-zero vector");
  if (!(o.approach_cone >= 0) || !(o.approach_cone < kPi))
    throw std::invalid_argument("IK approach_cone must be a number of radians in [0, pi), got " +
                                std::to_string(o.approach_cone));
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
  const Eigen::Vector3d a = o.approach_axis.normalized();
  const double off = std::acos(std::min(1.0, (T.linear() * a).dot(target.linear() * a)));
  double rot = o.mode == IkMode::Position ? 0.0
               : o.mode == IkMode::Full   ? Eigen::AngleAxisd(target.linear() * T.linear().transpose()).angle()
                                          : std::max(0.0, off - o.approach_cone);
  if (pos_ok && rot < o.orientation_tolerance) return Eigen::VectorXd();
  return std::nullopt;
}

// What IK needs to check its solutions of one chain at one reference posture for collisions: the
// robot's checked pairs split into those the chain moves and those it never moves, and the link
// poses at the reference and the check of the moving pairs (chain_self_check.hpp). Per thread, the set-ups
// of the last four robot, chain and reference combinations are kept and reused by the next call for
// the same robot, chain and reference (keyed by the robot's control block through a weak_ptr, so a
// robot built at the address of a freed one never matches). Checking a solution then recomputes
// only the links the chain moves that the check reads (the joints in `moved`, parents first).
struct CollisionSetup {
  std::weak_ptr<const Robot> robot;
  std::string base, tip;
  Eigen::VectorXd reference;
  std::vector<std::pair<int, int>> moving_pairs, fixed_pairs;
  std::vector<int> moved;  // joints whose child link the chain moves and a check reads, parents first
  // Per joint in `moved`: whether the chain sets its value (its own or, for a mimic joint, its source's), and if
  // not, its origin times its motion at the reference, which no solution changes.
  std::vector<char> turns;
  std::vector<Pose> still;
  std::vector<Pose> poses;
  detail::ChainSelfCheck self;  // the moving pairs, flat: boxes, hinge certificates, witnesses
  Eigen::VectorXd full;         // scratch: the robot configuration of the solution checked

  const Robot* address = nullptr;  // the robot's, compared while `robot` lives (no other live robot has it)

  // Compared without copying the chain's shared_ptr: its count is one cache line every IK thread would write.
  bool matches(const Chain& c, const Eigen::VectorXd& ref) const {
    return address == &c.robot() && !robot.expired() && base == c.base_link() && tip == c.tip_link() &&
           reference.size() == ref.size() && reference == ref;
  }

  // The set-up of the reference IK options `o` check at (their reference, else the robot's home).
  static CollisionSetup& of(const Chain& c, const IkOptions& o) {
    return of(c, o.reference.size() ? o.reference : c.robot().home());
  }

  static CollisionSetup& of(const Chain& c, const Eigen::VectorXd& reference) {
    // The last few set-ups of this thread, so that a caller alternating between arms keeps what their
    // hinge pairs measured; the least recently used one makes room.
    thread_local std::array<CollisionSetup, 4> cache;
    thread_local std::array<std::uint64_t, 4> used{};
    thread_local std::uint64_t clock = 0;
    std::size_t pick = 0;
    for (std::size_t i = 0; i < cache.size(); ++i) {
      if (cache[i].matches(c, reference)) {
        used[i] = ++clock;
        return cache[i];
      }
      if (used[i] < used[pick]) pick = i;
    }
    used[pick] = ++clock;
    const std::shared_ptr<const Robot> r = c.robot_ptr();
    CollisionSetup& s = cache[pick];
    s.robot = r;
    s.address = r.get();
    s.base = c.base_link();
    s.tip = c.tip_link();
    s.reference = reference;
    c.split_collision_pairs(s.moving_pairs, s.fixed_pairs);
    // The moved links a check reads: those with collision shapes and the links above them (a gripper's frames
    // without geometry, a camera frame, are never placed).
    std::vector<char> read(r->links().size(), 0);
    for (std::size_t j = r->joints().size(); j-- > 0;) {
      const Joint& joint = r->joints()[j];
      if (!r->links()[joint.child_link].shapes.empty()) read[joint.child_link] = 1;
      if (read[joint.child_link]) read[joint.parent_link] = 1;
    }
    s.moved.clear();
    for (std::size_t j = 0; j < r->joints().size(); ++j)
      if (c.link_mask(r->joints()[j].child_link) != 0 && read[r->joints()[j].child_link])
        s.moved.push_back(static_cast<int>(j));
    std::vector<char> in_chain(r->dof(), 0);
    for (int i = 0; i < c.dof(); ++i) in_chain[c.robot_indices()[i]] = 1;
    s.turns.clear();
    s.still.clear();
    for (int ji : s.moved) {
      const Joint& j = r->joints()[ji];
      const int source = detail::joint_source(r->joints(), j);
      s.turns.push_back(source >= 0 && in_chain[source]);
      s.still.push_back(j.origin * detail::joint_motion(j, detail::joint_value(r->joints(), j, reference)));
    }
    r->link_poses(reference, s.poses);
    s.self = detail::ChainSelfCheck(c, s.moving_pairs, s.poses, reference);
    s.full = reference;
    return s;
  }

  // Obstacles and self-collision of a solution of chain `c` (its joint vector `sol`), as IK checks them.
  // `fixed_state` caches the pairs the chain never moves: -1 unknown (checked here), 0 free, 1 colliding.
  bool collides(const Chain& c, const Eigen::VectorXd& sol, const IkOptions& o, int& fixed_state) {
    const Robot& r = c.robot();
    for (int i = 0; i < c.dof(); ++i) full[c.robot_indices()[i]] = sol[i];  // the rest stays at the reference
    place(r, full);
    if (o.obstacles &&
        r.links_in_collision(poses, *o.obstacles, o.base_pose, o.obstacle_links.empty() ? nullptr : &o.obstacle_links))
      return true;
    if (!o.check_self_collision) return false;
    if (fixed_state < 0) fixed_state = r.in_self_collision_poses(poses, fixed_pairs) ? 1 : 0;
    return fixed_state == 1 || self.collides(r, poses, full);
  }

  // Link poses at the robot configuration `full`, which differs from the reference only in the chain.
  void place(const Robot& robot, const Eigen::VectorXd& full) {
    for (std::size_t k = 0; k < moved.size(); ++k) {
      const Joint& j = robot.joints()[moved[k]];
      Pose& child = poses[j.child_link];
      if (!turns[k]) {
        child = poses[j.parent_link] * still[k];
        continue;
      }
      // parent * origin * motion, the motion applied to the product's columns
      const double v = detail::joint_value(robot.joints(), j, full);
      child = poses[j.parent_link] * j.origin;
      if (j.type == JointType::Prismatic) child.translation() += child.linear() * (j.axis * v);
      else if (j.type == JointType::Revolute || j.type == JointType::Continuous)
        child.linear() = child.linear() * detail::axis_rotation(j.axis, v);
    }
  }
};

// One IK call: Levenberg-Marquardt descents from the seed and from random restarts. N is the
// chain's dof when it is known at compile time (1 to 8: fixed-size matrices, no heap traffic and
// unrolled products), else Eigen::Dynamic with at most MaxDof columns (MaxDof Dynamic: any chain).
// A solver is the per-call workspace: built, solved once, dropped.
template <int N, int MaxDof = N>
class LmIk {
 public:
  using Vec = Eigen::Matrix<double, N, 1, 0, MaxDof, 1>;
  using Jac = Eigen::Matrix<double, 6, N, 0, 6, MaxDof>;
  using Sq = Eigen::Matrix<double, N, N, 0, MaxDof, MaxDof>;
  using Res = Eigen::Matrix<double, 6, 1>;

  LmIk(const Chain& chain, const Pose& target, const IkOptions& o)
      : c_(chain), target_(target), o_(o), n_(chain.dof()), J_(6, n_), J_new_(6, n_), Jr_(6, n_),
        q_(n_), q_new_(n_), dq_(n_), g_(n_), A_(n_, n_) {
    approach_tip_ = o.approach_axis.normalized();
    approach_goal_ = target.linear() * approach_tip_;
    need_full_ = o.check_self_collision || o.obstacles;
    if (need_full_) setup_ = &CollisionSetup::of(c_, o);
    fixed_state_ = o.check_fixed_pairs ? -1 : 0;
  }

  std::optional<Eigen::VectorXd> solve(const Eigen::VectorXd* seed) {
    for (int attempt = 0; attempt < o_.attempts; ++attempt) {
      detail::poll_cancel("IK cancelled");
      if (attempt == 0 && seed) {
        q_ = *seed;
        clamp(q_);
      } else {
        q_ = c_.random_configuration(rng());
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
  static constexpr int kMaxWindow = 16;

  // Error vector (6 rows; the rotation rows are zero in Position mode) and, when asked, the
  // matching rows of the Jacobian J_ in Jr_ (weighted_jacobian); plus the convergence test.
  void residual(const Pose& T, bool with_jacobian, Res& err, bool& converged) {
    Eigen::Vector3d ep = target_.translation() - T.translation();
    err.template head<3>() = ep;
    if (o_.mode == IkMode::Position) {
      err.template tail<3>().setZero();
      if (with_jacobian) weighted_jacobian();
      converged = ep.norm() < o_.position_tolerance;
      return;
    }
    Eigen::Vector3d er;
    double rot_err;
    Eigen::Matrix3d& P = P_;  // kept: weighted_jacobian() of this pose needs it
    P.setIdentity();
    if (o_.mode == IkMode::Full) {
      er = log_so3(target_.linear() * T.linear().transpose());
      rot_err = er.norm();
    } else {
      Eigen::Vector3d a = T.linear() * approach_tip_;
      Eigen::Vector3d c = a.cross(approach_goal_);
      double s = c.norm(), cs = a.dot(approach_goal_);
      rot_err = std::max(0.0, std::atan2(s, cs) - o_.approach_cone);  // inside the cone: reached
      if (s > 1e-12) er = c / s * rot_err;
      else if (cs < 0) er = a.unitOrthogonal() * rot_err;  // opposite: any perpendicular axis
      else er.setZero();
      P -= a * a.transpose();  // roll about the approach axis does not matter
    }
    err.template tail<3>() = kRotWeight * er;
    if (with_jacobian) weighted_jacobian();
    converged = ep.norm() < o_.position_tolerance && rot_err < o_.orientation_tolerance;
  }

  // Jr_ from J_, weighted as the residual of the pose residual() saw last.
  void weighted_jacobian() {
    Jr_.template topRows<3>() = J_.template topRows<3>();
    if (o_.mode == IkMode::Position) Jr_.template bottomRows<3>().setZero();
    else Jr_.template bottomRows<3>().noalias() = kRotWeight * (P_ * J_.template bottomRows<3>());
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

  // A joint sitting on a limit that the step dq_ would push past it is held there: its row and
  // column leave the system (A_, g_), so the next solve gives the other joints the whole step.
  // (Clamping alone leaves them a share of a step planned with the held joint moving: the descent
  // then crawls, with linear convergence.) True when a joint was held.
  bool hold_limits() {
    bool held = false;
    for (int i = 0; i < n_; ++i) {
      if (c_.continuous()[i]) continue;
      if ((q_[i] <= c_.lower()[i] && dq_[i] < 0) || (q_[i] >= c_.upper()[i] && dq_[i] > 0)) {
        A_.row(i).setZero();
        A_.col(i).setZero();
        A_(i, i) = 1.0;
        g_[i] = 0.0;
        held = true;
      }
    }
    return held;
  }

  // One descent from q_; true when it converged (q_ then holds the solution).
  bool descend() {
    // Errors this small are left to finish; above it, slow progress means a local minimum.
    const double tol2 = o_.position_tolerance * o_.position_tolerance;
    bool converged = false;
    Pose T = c_.fk_jacobian(q_.data(), J_.data());
    residual(T, true, e_, converged);
    double err = e_.squaredNorm();
    double lambda = 1e-3;
    int slow = 0;
    // err at the last stall_window iterations (ring); a stalled descent is stopped.
    double history[kMaxWindow];
    const int window = std::min(o_.stall_window, kMaxWindow);
    for (int it = 0; it < o_.max_iterations && !converged; ++it) {
      if (window > 0) {
        if (it >= window && err > 4 * tol2 && err > 0.9 * history[it % window]) break;  // stalled
        history[it % window] = err;
      }
      // Levenberg-Marquardt step: (J^T J + lambda (I + diag J^T J)) dq = J^T e
      A_.noalias() = Jr_.transpose().lazyProduct(Jr_);
      g_.noalias() = Jr_.transpose() * e_;
      A_.diagonal().array() += lambda * (1.0 + A_.diagonal().array());
      dq_ = A_.llt().solve(g_);  // A is symmetric positive definite
      if (hold_limits()) dq_ = A_.llt().solve(g_);
      q_new_ = q_ + dq_;
      clamp(q_new_);
      bool conv_new = false;
      Pose T_new = c_.fk_jacobian(q_new_.data(), J_new_.data());
      residual(T_new, false, e_new_, conv_new);
      double err_new = e_new_.squaredNorm();
      if (err_new < err) {
        slow = (err - err_new < 0.01 * err && err_new > 100 * tol2) ? slow + 1 : 0;
        q_ = q_new_;
        J_.swap(J_new_);
        err = err_new;
        // The residual at T_new is e_new_ (the same computation): only the Jacobian rows are new.
        e_ = e_new_;
        converged = conv_new;
        weighted_jacobian();
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
    return !need_full_ || !setup_->collides(c_, sol, o_, fixed_state_);
  }

  const Chain& c_;
  const Pose& target_;
  const IkOptions& o_;
  const int n_;
  Eigen::Vector3d approach_tip_, approach_goal_;
  // The restarts' generator, seeded at the first restart: a seeded single-attempt call (the capability
  // map's flood) never draws from it, and seeding a Mersenne twister costs more than a descent step.
  std::optional<std::mt19937_64> rng_;
  std::mt19937_64& rng() {
    if (!rng_) rng_.emplace(o_.seed);
    return *rng_;
  }
  Jac J_, J_new_, Jr_;  // Jacobian at q_ and at q_new_; rows weighted as the residual
  Vec q_, q_new_, dq_, g_;
  Sq A_;
  Res e_, e_new_;
  Eigen::Matrix3d P_ = Eigen::Matrix3d::Identity();  // residual(): projection of the rotation rows (Approach mode)
  CollisionSetup* setup_ = nullptr;  // this thread's, while the call lasts
  bool need_full_ = false;
  int fixed_state_ = -1;  // fixed pairs: -1 unknown, 0 free, 1 colliding
};

}  // namespace

namespace detail {

bool ik_solution_collides(const Chain& c, const Eigen::VectorXd& sol, const IkOptions& o) {
  if (!o.check_self_collision && !o.obstacles) return false;
  int fixed_state = o.check_fixed_pairs ? -1 : 0;
  return CollisionSetup::of(c, o).collides(c, sol, o, fixed_state);
}

}  // namespace detail

std::optional<Eigen::VectorXd> Chain::ik(const Pose& target, const IkOptions& o, const Eigen::VectorXd* seed) const {
  check_ik_request(*this, target, o, seed);
  return detail::ik_checked(*this, target, o, seed);
}

std::optional<Eigen::VectorXd> detail::ik_checked(const Chain& c, const Pose& target, const IkOptions& o,
                                                  const Eigen::VectorXd* seed) {
  detail::CancellableScope cancellable;
  if (c.dof() == 0) return rigid_chain_ik(c, target, o);
  // Fixed-size solvers for the chains of heads, arms and arms on a rail (up to 8 joints): the descent's products
  // and factorisations unrolled, with no run-time sizes. Longer chains share a solver of dynamic size.
  switch (c.dof()) {
    case 1: return LmIk<1>(c, target, o).solve(seed);
    case 2: return LmIk<2>(c, target, o).solve(seed);
    case 3: return LmIk<3>(c, target, o).solve(seed);
    case 4: return LmIk<4>(c, target, o).solve(seed);
    case 5: return LmIk<5>(c, target, o).solve(seed);
    case 6: return LmIk<6>(c, target, o).solve(seed);
    case 7: return LmIk<7>(c, target, o).solve(seed);
    case 8: return LmIk<8>(c, target, o).solve(seed);
    default: break;
  }
  if (c.dof() <= 12) return LmIk<Eigen::Dynamic, 12>(c, target, o).solve(seed);
  return LmIk<Eigen::Dynamic, Eigen::Dynamic>(c, target, o).solve(seed);
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
