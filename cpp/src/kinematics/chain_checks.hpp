#pragma once
// Internal: the joint-vector size check shared by the chain's kinematics (chain.cpp) and IK (ik.cpp), IK's
// collision check of a solution, and IK without the request's checks.

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "octoreach/chain.hpp"

namespace octoreach::detail {

/// Raises std::invalid_argument unless q has one entry per moving joint of the chain.
inline void check_joint_vector(const Chain& c, const Eigen::VectorXd& q) {
  if (q.size() != c.dof())
    throw std::invalid_argument("joint vector has " + std::to_string(q.size()) + " entries, chain '" + c.base_link() +
                                "' -> '" + c.tip_link() + "' has " + std::to_string(c.dof()) + " joints");
}

/// The value of q + 2 pi k for the integer k of smallest |k| that brings q into [lo, hi] from the side it
/// is on, as far as whole turns fit (within `eps` of the far limit). The turn count is computed, not looped
/// for, so the work does not grow with |q|; a non-finite q is returned as it is.
inline double shift_by_turns(double q, double lo, double hi, double eps) {
  const double turn = 2 * kPi;
  if (!std::isfinite(q)) return q;
  if (q > hi) {
    const double fit = std::floor((q - (lo - eps)) / turn);  // most turns that keep q >= lo
    const double need = std::ceil((q - hi) / turn);          // fewest turns that bring q <= hi
    return q - std::max(0.0, std::min(fit, need)) * turn;
  }
  if (q < lo) {
    const double fit = std::floor(((hi + eps) - q) / turn);
    const double need = std::ceil((lo - q) / turn);
    return q + std::max(0.0, std::min(fit, need)) * turn;
  }
  return q;
}

/// True when IK with options `o` would reject the solution `sol` (within the limits) for a collision: with
/// the obstacles, or (check_self_collision) with itself, the pairs the chain never moves included when
/// check_fixed_pairs. The same check and per-thread witnesses as Chain::ik: a caller that ran a single-attempt IK
/// without collision checks and checks its solution here gets IK's answer, and learns why it failed.
bool ik_solution_collides(const Chain& c, const Eigen::VectorXd& sol, const IkOptions& o);

/// Chain::ik without its checks of the request, for callers that build many requests from checked ones (the
/// capability map's build: its targets are voxel centres and rotations, its seeds the chain's own solutions).
std::optional<Eigen::VectorXd> ik_checked(const Chain& c, const Pose& target, const IkOptions& o,
                                          const Eigen::VectorXd* seed);

}  // namespace octoreach::detail
