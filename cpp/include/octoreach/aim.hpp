#pragma once
/// \file aim.hpp
/// \brief Look-at IK: the joints of a chain that point an axis of its tip frame (a camera's optical axis)
/// at a target point; the tip's position is whatever the chain gives. For cameras on chains that cannot
/// place them freely (a pan/tilt head, a torso lift under it).

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "octoreach/chain.hpp"

namespace octoreach {

/// \brief Options of aim(): damped least squares on the aim error with random restarts.
struct AimOptions {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< tip-frame axis to aim (a camera's optical axis)
  double tolerance = 1e-3;   ///< radians between the axis and the ray from the tip to the target
  int max_iterations = 60;   ///< per attempt
  int attempts = 6;          ///< the start (or the middle of the limits) plus random restarts
  double damping = 0.05;     ///< lambda of (J^T J + lambda^2 I) dq = -J^T e
  std::uint64_t seed = 0;    ///< random restarts are deterministic for a seed
  /// \brief \throws std::invalid_argument naming the first bad value.
  void validate() const;
};

/// \brief What aim() found: the best joints of all attempts and the angle they leave.
struct AimResult {
  bool reached = false;  ///< error <= AimOptions::tolerance
  Eigen::VectorXd q;     ///< the joints (inside the limits) with the smallest error found
  double error = 0.0;    ///< radians between the aimed axis and the ray from the tip to the target
};

/// \brief Joints of `chain` (within its limits) that point its tip's `options.axis` at `target` (chain base
/// frame): minimises the angle between the axis and the ray from the tip's origin to the target (damped least
/// squares on the 3-vector u - a, u the unit ray, a the axis, both base frame; |u - a| = 2 sin(angle / 2)),
/// from `start` (default: the middle of the limits, 0 for continuous joints) and options.attempts - 1 random
/// configurations. A target out of the chain's aim (behind a head that cannot turn, beyond a tilt limit) gives
/// reached false with the smallest angle found. \throws std::invalid_argument for a non-finite target, a
/// start of the wrong size or bad options.
AimResult aim(const Chain& chain, const Eigen::Vector3d& target, const AimOptions& options = AimOptions(),
              const Eigen::VectorXd* start = nullptr);

/// \brief The angle (radians) between the tip's `axis` at joints q and the ray from the tip's origin to
/// `target` (chain base frame); pi when the target is at the tip's origin.
double aim_error(const Chain& chain, const Eigen::VectorXd& q, const Eigen::Vector3d& target,
                 const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ());

}  // namespace octoreach
