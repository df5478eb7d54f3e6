// Plain-KDL reference solvers, bound for benchmarks/ik.py: the yardstick octoreach's own IK and FK are
// measured against in the same process, on the same chain (bench::to_kdl, cpp/bench/kdl_chain) and the same targets.
//
// Private API (leading underscore): nothing in the library depends on it.
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>

#include "common.hpp"
#include "common/random_mix.hpp"
#include "kdl_chain.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::py_bindings {

namespace {

enum class KdlSolver { NrJl, Lma };

KdlSolver parse_solver(const std::string& s) {
  if (s == "nr_jl") return KdlSolver::NrJl;
  if (s == "lma") return KdlSolver::Lma;
  throw std::invalid_argument("KDL solver must be 'nr_jl' or 'lma', got '" + s + "'");
}

KDL::Frame to_frame(const Pose& T) {
  const auto& m = T.matrix();
  return KDL::Frame(KDL::Rotation(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)),
                    KDL::Vector(m(0, 3), m(1, 3), m(2, 3)));
}

// The acceptance test shared by both KDL solvers and identical to octoreach's own IK (Full mode): tip
// position within pos_tol (m), rotation angle within rot_tol (rad), measured with octoreach's
// Chain::fk, and the (wrapped) joint vector inside the limits. The solver's own return code is not
// trusted either way: NR_JL's eps is per twist component and LMA's is on a weighted norm.
bool accepted(const Chain& c, const Pose& target, const Eigen::VectorXd& q, double pos_tol, double rot_tol) {
  if (!q.allFinite() || !c.within_limits(q, 1e-9)) return false;
  Pose T = c.fk(q);
  if ((T.translation() - target.translation()).norm() >= pos_tol) return false;
  return Eigen::AngleAxisd(target.linear() * T.linear().transpose()).angle() < rot_tol;
}

void kdl_ik_batch(const Chain& c, const std::vector<Pose>& targets, KdlSolver which, int attempts,
                  int max_iterations, double eps, double pos_tol, double rot_tol, std::uint64_t rng_seed,
                  Eigen::MatrixXd& Q, std::vector<bool>& ok) {
  const int n = c.dof();
  Q = Eigen::MatrixXd::Constant(targets.size(), n, std::numeric_limits<double>::quiet_NaN());
  ok.assign(targets.size(), false);
  if (n == 0) return;
  const KDL::Chain kc = bench::to_kdl(c);

  // NR_JL clamps to its limits after every step; continuous joints get limits wide enough never to
  // bind (a clamp at +-pi would stall the solver on the seam) and are wrapped afterwards.
  KDL::JntArray q_min(n), q_max(n);
  for (int j = 0; j < n; ++j) {
    q_min(j) = c.continuous()[j] ? -1e6 : c.lower()[j];
    q_max(j) = c.continuous()[j] ? 1e6 : c.upper()[j];
  }
  KDL::ChainFkSolverPos_recursive fk(kc);
  KDL::ChainIkSolverVel_pinv vel(kc);
  std::unique_ptr<KDL::ChainIkSolverPos> solver;
  if (which == KdlSolver::NrJl) {
    solver = std::make_unique<KDL::ChainIkSolverPos_NR_JL>(kc, q_min, q_max, fk, vel,
                                                           static_cast<unsigned>(max_iterations), eps);
  } else {
    // LMA's default weights count a radian like 1 cm; 0.25 m per radian matches octoreach's own
    // weighting, so both minimise the same error. LMA knows no joint limits: a solution outside
    // them fails the acceptance test and the next restart runs, as a plain KDL user would do.
    Eigen::Matrix<double, 6, 1> L;
    L << 1, 1, 1, 0.25, 0.25, 0.25;
    solver = std::make_unique<KDL::ChainIkSolverPos_LMA>(kc, L, eps, max_iterations);
  }

  KDL::JntArray q_init(n), q_out(n);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    // Same stream splitter as Chain::ik_batch: target i gets its own stream whatever the batch is.
    std::mt19937_64 rng(detail::mix64(rng_seed, i));
    const KDL::Frame goal = to_frame(targets[i]);
    for (int a = 0; a < attempts; ++a) {
      q_init.data = c.random_configuration(rng);
      solver->CartToJnt(q_init, goal, q_out);  // return code ignored: see accepted()
      Eigen::VectorXd q = q_out.data;
      if (!q.allFinite()) continue;
      q = c.wrap(q);
      if (accepted(c, targets[i], q, pos_tol, rot_tol)) {
        Q.row(i) = q.transpose();
        ok[i] = true;
        break;
      }
    }
  }
}

}  // namespace

void wrap_kdl_reference(py::module_& m) {
  m.def("kdl_ik_batch",
        [](const Chain& c, const py::object& Ts, const std::string& solver, int attempts, const py::object& max_iter,
           double eps, double pos_tol, double rot_tol, std::uint64_t rng_seed) {
          KdlSolver which = parse_solver(solver);
          std::vector<Pose> targets = poses_from(Ts, "Ts");
          if (attempts < 1) throw std::invalid_argument("attempts must be >= 1, got " + std::to_string(attempts));
          int iters = max_iter.is_none() ? (which == KdlSolver::NrJl ? 100 : 500) : max_iter.cast<int>();
          if (iters < 1) throw std::invalid_argument("max_iterations must be >= 1, got " + std::to_string(iters));
          if (!(eps > 0)) throw std::invalid_argument("eps must be positive");
          if (!(pos_tol > 0) || !(rot_tol > 0)) throw std::invalid_argument("tolerances must be positive");
          Eigen::MatrixXd Q;
          std::vector<bool> ok;
          {
            py::gil_scoped_release release;
            kdl_ik_batch(c, targets, which, attempts, iters, eps, pos_tol, rot_tol, rng_seed, Q, ok);
          }
          py::array_t<bool> mask(static_cast<py::ssize_t>(ok.size()));
          auto w = mask.mutable_unchecked<1>();
          for (std::size_t i = 0; i < ok.size(); ++i) w(i) = ok[i];
          return py::make_tuple(Q, mask);
        },
        py::arg("chain"), py::arg("Ts"), py::arg("solver") = "nr_jl", py::arg("attempts") = 20,
        py::arg("max_iterations") = py::none(), py::arg("eps") = 1e-5, py::arg("position_tolerance") = 1e-4,
        py::arg("orientation_tolerance") = 1e-3, py::arg("rng_seed") = 0,
        "Reference IK with plain KDL on bench::to_kdl(chain), single-threaded: for benchmarks only.\n\n"
        "Solves the tip poses Ts (N, 4, 4, base link frame) with KDL::ChainIkSolverPos_NR_JL (solver='nr_jl',\n"
        "ChainIkSolverVel_pinv + ChainFkSolverPos_recursive, clamped to the chain's limits; continuous joints\n"
        "unbounded) or KDL::ChainIkSolverPos_LMA (solver='lma', task weights 1,1,1,0.25,0.25,0.25; no limits).\n"
        "Each target gets up to `attempts` starts drawn uniformly inside the chain's limits (continuous joints\n"
        "in [-pi, pi)) from a stream derived from rng_seed and the target's index, like Chain.ik_batch.\n"
        "max_iterations is per start (default: KDL's own, 100 for NR_JL and 500 for LMA); eps is KDL's stopping\n"
        "tolerance. Success is judged afterwards exactly as octoreach's own IK judges it (mode 'full'): the\n"
        "result, continuous joints wrapped, must be inside the limits and its tip pose by octoreach's Chain.fk\n"
        "within position_tolerance (m) and orientation_tolerance (rad) of the target; KDL's return code is\n"
        "ignored. Returns (Q (N, dof) with NaN rows where it failed, success mask (N,)). Releases the GIL.");

  m.def("kdl_fk_batch",
        [](const Chain& c, const py::object& Qobj) {
          RowMatrixXd M = matrix_from(Qobj, c.dof(), "Q");
          std::vector<Pose> out(M.rows());
          {
            py::gil_scoped_release release;
            const KDL::Chain kc = bench::to_kdl(c);
            KDL::ChainFkSolverPos_recursive fk(kc);
            KDL::JntArray q(c.dof());
            KDL::Frame F;
            for (Eigen::Index i = 0; i < M.rows(); ++i) {
              q.data = M.row(i).transpose();
              fk.JntToCart(q, F);
              Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
              for (int r = 0; r < 3; ++r) {
                for (int k = 0; k < 3; ++k) T(r, k) = F.M(r, k);
                T(r, 3) = F.p(r);
              }
              out[i].matrix() = T;
            }
          }
          return poses_to_array(out);
        },
        py::arg("chain"), py::arg("Q"),
        "Reference FK with plain KDL (ChainFkSolverPos_recursive on bench::to_kdl(chain)), single-threaded: tip poses\n"
        "(N, 4, 4) in the base link frame for joint rows Q (N, dof). For benchmarks only; releases the GIL.");
}

}  // namespace octoreach::py_bindings
