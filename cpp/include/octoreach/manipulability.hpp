#pragma once
/// \file manipulability.hpp
/// \brief Quality of an arm configuration: Yoshikawa's manipulability and a joint-limit penalty.

#include <cstdint>

#include <Eigen/Core>

#include "octoreach/chain.hpp"

namespace octoreach {

/// \brief Generic rank of the chain's 6 x dof geometric Jacobian: its largest numerical rank over random
/// configurations (6 for an arm of six or more independent joints, 5 for a five-joint arm); deterministic.
int jacobian_rank(const Chain& chain);

/// \brief Yoshikawa's manipulability of configuration q: sqrt(det(J J^T)) of the 6 x dof geometric Jacobian
/// (base frame, rows linear then angular, at the tip), i.e. the product of its singular values. For a chain whose
/// generic rank r (jacobian_rank) is below 6, the product of its r largest singular values: the volume of the
/// manipulability ellipsoid in the directions the arm can move at all (sqrt(det(J J^T)) would be 0 everywhere).
/// \throws std::invalid_argument for q of the wrong size or not finite, or rank outside [1, 6].
double manipulability(const Chain& chain, const Eigen::VectorXd& q, int rank = 6);

/// \brief Joint-limit penalty of q in [0, 1] (Tsai's penalty, used by Vahrenkamp et al. for their
/// manipulability index): 1 - exp(-k prod_i (q_i - l_i)(u_i - q_i) / (u_i - l_i)^2) over the bounded joints, with
/// k = 4^n for n bounded joints, so that a configuration in the middle of every range scores 1 - 1/e whatever the
/// number of joints, and one at or past any limit scores 0. Continuous joints do not count; with none bounded it is 1.
/// \throws std::invalid_argument for q of the wrong size or not finite.
double joint_limit_penalty(const Chain& chain, const Eigen::VectorXd& q);

}  // namespace octoreach
