#pragma once
/// \file kdl_solvers.hpp
/// \brief Benchmark and test support (not part of the octoreach library): plain-KDL IK and FK on a chain
/// given as arrays, the yardstick octoreach's own IK and FK are measured against in the same process.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kdl_chain.hpp"

namespace octoreach::bench {

enum class KdlSolver { NrJl, Lma };

/// \brief "nr_jl" or "lma". \throws std::invalid_argument naming any other value.
KdlSolver parse_solver(const std::string& name);

/// \brief What kdl_ik_batch does: solver, starts per target, iterations per start (KDL's own default
/// when 0: 100 for NR_JL, 500 for LMA), KDL's stopping tolerance, the acceptance tolerances, the seed.
struct KdlIkOptions {
  KdlSolver solver = KdlSolver::NrJl;
  int attempts = 20;
  int max_iterations = 0;
  double eps = 1e-5;
  double position_tolerance = 1e-4;     ///< m
  double orientation_tolerance = 1e-3;  ///< rad
  std::uint64_t seed = 0;
};

/// \brief IK of every target (tip poses in the base frame) with KDL::ChainIkSolverPos_NR_JL (clamped to
/// the limits; continuous joints unbounded) or KDL::ChainIkSolverPos_LMA (weights 1,1,1,0.25,0.25,0.25; no
/// limits), single-threaded. Target i draws its starts uniformly inside the limits (continuous joints in
/// [-pi, pi)) from std::mt19937_64(mix64(seed, i)), as Chain::ik_batch does. A result is accepted as
/// octoreach's own IK accepts one (mode full): wrapped into the limits, tip within the tolerances (by KDL's
/// FK); KDL's return code is ignored. Row i of `solutions` is NaN where ok[i] is false.
/// \throws std::invalid_argument for bad options or a chain whose arrays disagree.
void kdl_ik_batch(const ChainArrays& chain, const std::vector<Pose>& targets, const KdlIkOptions& options,
                  Eigen::MatrixXd& solutions, std::vector<bool>& ok);

/// \brief Tip poses (base frame) for the joint rows of `q_rows` (N x dof), by KDL::ChainFkSolverPos_recursive.
std::vector<Pose> kdl_fk_batch(const ChainArrays& chain, const Eigen::MatrixXd& q_rows);

}  // namespace octoreach::bench
