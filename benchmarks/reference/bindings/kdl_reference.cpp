// Plain-KDL reference solvers, bound for benchmarks/ik.py and the tests: the yardstick octoreach's own IK and
// FK are measured against in the same process, on the same chain and the same targets. The chain arrives as
// any object with a Chain's description (octoreach.Chain: joint_origins, joint_axes, prismatic, continuous,
// lower, upper, tip_offset), read through Python: this module links no octoreach code.
#include "common.hpp"
#include "kdl_solvers.hpp"

namespace octoreach::py_bindings {

namespace {

std::vector<bool> bools_from(const py::handle& chain, const char* what, int dof) {
  auto v = cast_arg<std::vector<bool>>(chain.attr(what), what, "a list of booleans");
  if (static_cast<int>(v.size()) != dof)
    throw std::invalid_argument(std::string("chain.") + what + " must have " + std::to_string(dof) + " entries");
  return v;
}

bench::ChainArrays chain_from(const py::handle& chain) {
  bench::ChainArrays c;
  c.origins = poses_from(chain.attr("joint_origins"), "chain.joint_origins");
  const int dof = c.dof();
  RowMatrixXd axes = matrix_from(chain.attr("joint_axes"), 3, "chain.joint_axes");
  if (axes.rows() != dof) throw std::invalid_argument("chain.joint_axes must have one row per joint");
  for (int i = 0; i < dof; ++i) c.axes.push_back(axes.row(i).transpose());
  c.prismatic = bools_from(chain, "prismatic", dof);
  c.continuous = bools_from(chain, "continuous", dof);
  c.lower = cast_arg<Eigen::VectorXd>(chain.attr("lower"), "chain.lower", "a vector of joint limits");
  c.upper = cast_arg<Eigen::VectorXd>(chain.attr("upper"), "chain.upper", "a vector of joint limits");
  c.tip_offset = pose_from(chain.attr("tip_offset"), "chain.tip_offset");
  return c;
}

}  // namespace

void wrap_kdl_reference(py::module_& m) {
  m.def("kdl_ik_batch",
        [](const py::object& chain, const py::object& Ts, const std::string& solver, int attempts,
           const py::object& max_iter, double eps, double pos_tol, double rot_tol, std::uint64_t rng_seed) {
          bench::KdlIkOptions o;
          o.solver = bench::parse_solver(solver);
          const bench::ChainArrays c = chain_from(chain);
          std::vector<Pose> targets = poses_from(Ts, "Ts");
          o.attempts = attempts;
          if (!max_iter.is_none()) {
            o.max_iterations = cast_arg<int>(max_iter, "max_iterations", "an integer");
            if (o.max_iterations < 1)
              throw std::invalid_argument("max_iterations must be >= 1, got " + std::to_string(o.max_iterations));
          }
          o.eps = eps;
          o.position_tolerance = pos_tol;
          o.orientation_tolerance = rot_tol;
          o.seed = rng_seed;
          Eigen::MatrixXd Q;
          std::vector<bool> ok;
          {
            py::gil_scoped_release release;
            bench::kdl_ik_batch(c, targets, o, Q, ok);
          }
          py::array_t<bool> mask(static_cast<py::ssize_t>(ok.size()));
          auto w = mask.mutable_unchecked<1>();
          for (std::size_t i = 0; i < ok.size(); ++i) w(i) = ok[i];
          return py::make_tuple(Q, mask);
        },
        py::arg("chain"), py::arg("Ts"), py::arg("solver") = "nr_jl", py::arg("attempts") = 20,
        py::arg("max_iterations") = py::none(), py::arg("eps") = 1e-5, py::arg("position_tolerance") = 1e-4,
        py::arg("orientation_tolerance") = 1e-3, py::arg("rng_seed") = 0,
        "Reference IK with plain KDL on the chain's description, single-threaded: for benchmarks only.\n\n"
        "Solves the tip poses Ts (N, 4, 4, base link frame) with KDL::ChainIkSolverPos_NR_JL (solver='nr_jl',\n"
        "ChainIkSolverVel_pinv + ChainFkSolverPos_recursive, clamped to the chain's limits; continuous joints\n"
        "unbounded) or KDL::ChainIkSolverPos_LMA (solver='lma', task weights 1,1,1,0.25,0.25,0.25; no limits).\n"
        "Each target gets up to `attempts` starts drawn uniformly inside the chain's limits (continuous joints\n"
        "in [-pi, pi)) from a stream derived from rng_seed and the target's index, like Chain.ik_batch.\n"
        "max_iterations is per start (default: KDL's own, 100 for NR_JL and 500 for LMA); eps is KDL's stopping\n"
        "tolerance. Success is judged afterwards as octoreach's own IK judges it (mode 'full'): the result,\n"
        "wrapped, must be inside the limits and its tip pose (KDL's FK) within position_tolerance (m) and\n"
        "orientation_tolerance (rad) of the target; KDL's return code is ignored. Returns (Q (N, dof) with NaN\n"
        "rows where it failed, success mask (N,)). Releases the GIL.");

  m.def("kdl_fk_batch",
        [](const py::object& chain, const py::object& Qobj) {
          const bench::ChainArrays c = chain_from(chain);
          Eigen::MatrixXd M = matrix_from(Qobj, c.dof(), "Q");
          std::vector<Pose> out;
          {
            py::gil_scoped_release release;
            out = bench::kdl_fk_batch(c, M);
          }
          return poses_to_array(out);
        },
        py::arg("chain"), py::arg("Q"),
        "Reference FK with plain KDL (ChainFkSolverPos_recursive on the chain's description), single-threaded:\n"
        "tip poses (N, 4, 4) in the base link frame for joint rows Q (N, dof). For benchmarks only; releases the GIL.");
}

}  // namespace octoreach::py_bindings
