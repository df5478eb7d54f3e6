#include "kdl_solvers.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>

#include "common/random_mix.hpp"
#include "kinematics/chain_checks.hpp"

namespace octoreach::bench {

namespace {

KDL::Frame to_frame(const Pose& T) {
  const auto& m = T.matrix();
  return KDL::Frame(KDL::Rotation(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)),
                    KDL::Vector(m(0, 3), m(1, 3), m(2, 3)));
}

Pose to_pose(const KDL::Frame& F) {
  Pose T = Pose::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) T.matrix()(r, k) = F.M(r, k);
    T.matrix()(r, 3) = F.p(r);
  }
  return T;
}

// Octoreach's wrapping of a result: continuous joints into [-pi, pi), rotational joints by whole turns
// toward their limits (detail::shift_by_turns, the library's own header-only rule).
Eigen::VectorXd wrapped(const ChainArrays& c, Eigen::VectorXd q) {
  for (int i = 0; i < c.dof(); ++i) {
    if (c.continuous[i]) {
      double a = std::fmod(q[i] + kPi, 2.0 * kPi);
      q[i] = (a < 0 ? a + 2.0 * kPi : a) - kPi;
    } else if (!c.prismatic[i]) {
      q[i] = detail::shift_by_turns(q[i], c.lower[i], c.upper[i], 1e-12);
    }
  }
  return q;
}

// The acceptance test shared by both KDL solvers and identical to octoreach's own IK (Full mode): the
// wrapped joint vector inside the limits, tip position within pos_tol (m) and rotation angle within rot_tol
// (rad). The solver's own return code is not trusted either way: NR_JL's eps is per twist component and
// LMA's is on a weighted norm.
bool accepted(const ChainArrays& c, KDL::ChainFkSolverPos_recursive& fk, const Pose& target,
              const Eigen::VectorXd& q, double pos_tol, double rot_tol) {
  if (!q.allFinite()) return false;
  for (int i = 0; i < c.dof(); ++i)
    if (!c.continuous[i] && (q[i] < c.lower[i] - 1e-9 || q[i] > c.upper[i] + 1e-9)) return false;
  KDL::JntArray jq(c.dof());
  jq.data = q;
  KDL::Frame F;
  fk.JntToCart(jq, F);
  const Pose T = to_pose(F);
  if ((T.translation() - target.translation()).norm() >= pos_tol) return false;
  return Eigen::AngleAxisd(target.linear() * T.linear().transpose()).angle() < rot_tol;
}

// A uniform start inside the limits (continuous joints in [-pi, pi)), drawn as Chain::random_configuration.
Eigen::VectorXd random_start(const ChainArrays& c, std::mt19937_64& rng) {
  Eigen::VectorXd q(c.dof());
  for (int i = 0; i < c.dof(); ++i) {
    std::uniform_real_distribution<double> u(c.continuous[i] ? -kPi : c.lower[i], c.continuous[i] ? kPi : c.upper[i]);
    q[i] = u(rng);
  }
  return q;
}

}  // namespace

KdlSolver parse_solver(const std::string& s) {
  if (s == "nr_jl") return KdlSolver::NrJl;
  if (s == "lma") return KdlSolver::Lma;
  throw std::invalid_argument("KDL solver must be 'nr_jl' or 'lma', got '" + s + "'");
}

void kdl_ik_batch(const ChainArrays& c, const std::vector<Pose>& targets, const KdlIkOptions& o,
                  Eigen::MatrixXd& Q, std::vector<bool>& ok) {
  if (o.attempts < 1) throw std::invalid_argument("attempts must be >= 1, got " + std::to_string(o.attempts));
  if (o.max_iterations < 0)
    throw std::invalid_argument("max_iterations must be >= 1, got " + std::to_string(o.max_iterations));
  if (!(o.eps > 0)) throw std::invalid_argument("eps must be positive");
  if (!(o.position_tolerance > 0) || !(o.orientation_tolerance > 0))
    throw std::invalid_argument("tolerances must be positive");
  const KDL::Chain kc = to_kdl(c);
  const int n = c.dof();
  Q = Eigen::MatrixXd::Constant(targets.size(), n, std::numeric_limits<double>::quiet_NaN());
  ok.assign(targets.size(), false);
  if (n == 0) return;
  const int iters = o.max_iterations > 0 ? o.max_iterations : (o.solver == KdlSolver::NrJl ? 100 : 500);

  // NR_JL clamps to its limits after every step; continuous joints get limits wide enough never to
  // bind (a clamp at +-pi would stall the solver on the seam) and are wrapped afterwards.
  KDL::JntArray q_min(n), q_max(n);
  for (int j = 0; j < n; ++j) {
    q_min(j) = c.continuous[j] ? -1e6 : c.lower[j];
    q_max(j) = c.continuous[j] ? 1e6 : c.upper[j];
  }
  KDL::ChainFkSolverPos_recursive fk(kc);
  KDL::ChainIkSolverVel_pinv vel(kc);
  std::unique_ptr<KDL::ChainIkSolverPos> solver;
  if (o.solver == KdlSolver::NrJl) {
    solver = std::make_unique<KDL::ChainIkSolverPos_NR_JL>(kc, q_min, q_max, fk, vel, static_cast<unsigned>(iters),
                                                           o.eps);
  } else {
    // LMA's default weights count a radian like 1 cm; 0.25 m per radian matches octoreach's own
    // weighting, so both minimise the same error. LMA knows no joint limits: a solution outside
    // them fails the acceptance test and the next restart runs, as a plain KDL user would do.
    Eigen::Matrix<double, 6, 1> L;
    L << 1, 1, 1, 0.25, 0.25, 0.25;
    solver = std::make_unique<KDL::ChainIkSolverPos_LMA>(kc, L, o.eps, iters);
  }

  KDL::JntArray q_init(n), q_out(n);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    // Same stream splitter as Chain::ik_batch: target i gets its own stream whatever the batch is.
    std::mt19937_64 rng(detail::mix64(o.seed, i));
    const KDL::Frame goal = to_frame(targets[i]);
    for (int a = 0; a < o.attempts; ++a) {
      q_init.data = random_start(c, rng);
      solver->CartToJnt(q_init, goal, q_out);  // return code ignored: see accepted()
      if (!q_out.data.allFinite()) continue;
      const Eigen::VectorXd q = wrapped(c, q_out.data);
      if (accepted(c, fk, targets[i], q, o.position_tolerance, o.orientation_tolerance)) {
        Q.row(i) = q.transpose();
        ok[i] = true;
        break;
      }
    }
  }
}

std::vector<Pose> kdl_fk_batch(const ChainArrays& c, const Eigen::MatrixXd& q_rows) {
  if (q_rows.cols() != c.dof())
    throw std::invalid_argument("Q must have " + std::to_string(c.dof()) + " columns (the chain's dof), got " +
                                std::to_string(q_rows.cols()));
  const KDL::Chain kc = to_kdl(c);
  KDL::ChainFkSolverPos_recursive fk(kc);
  KDL::JntArray q(c.dof());
  KDL::Frame F;
  std::vector<Pose> out(q_rows.rows());
  for (Eigen::Index i = 0; i < q_rows.rows(); ++i) {
    q.data = q_rows.row(i).transpose();
    fk.JntToCart(q, F);
    out[i] = to_pose(F);
  }
  return out;
}

}  // namespace octoreach::bench
