#pragma once
/// \file ik.hpp
/// \brief Options of the inverse-kinematics solver (Chain::ik, Chain::ik_batch).

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "octoreach/collision.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

/// \brief What an IK solution must match.
enum class IkMode {
  Full,      ///< position and orientation
  Position,  ///< position only
  Approach,  ///< position and the approach axis (any roll about it)
};

/// \brief Options of the damped least-squares (Levenberg-Marquardt) IK with random restarts.
struct IkOptions {
  IkMode mode = IkMode::Full;
  double position_tolerance = 1e-4;     ///< metres
  double orientation_tolerance = 1e-3;  ///< radians
  int max_iterations = 100;             ///< per attempt (stalled attempts stop early)
  int attempts = 20;                    ///< seed (or first random start) plus random restarts
  std::uint64_t seed = 0;               ///< random restarts are deterministic for a seed
  Eigen::Vector3d approach_axis = Eigen::Vector3d::UnitZ();  ///< tip-frame axis used in Approach mode
  bool check_self_collision = false;    ///< reject solutions in self-collision
  /// With check_self_collision: also check the link pairs the chain never moves relative to each
  /// other (a caller that checked the reference posture once may switch this off).
  bool check_fixed_pairs = true;
  std::shared_ptr<const Obstacles> obstacles;  ///< reject solutions touching these (world frame)
  std::vector<int> obstacle_links;      ///< links checked against the obstacles (empty: every link)
  Pose base_pose = Pose::Identity();    ///< robot root pose in the world (for obstacles)
  /// Full robot configuration for joints outside the chain (empty: Robot::home()).
  Eigen::VectorXd reference;
};

}  // namespace octoreach
