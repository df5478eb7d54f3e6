#pragma once
/// \file self_collision_report.hpp
/// \brief How often a robot collides with itself in random configurations, and which link pairs do it:
/// the check that finds a collision model that fights its own joints (a forearm cylinder that meets the
/// upper arm whenever the elbow bends) before a map is built from it.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/robot.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

/// \brief Share of an arm's random configurations free of collisions among its own links below which `octoreach
/// robot` gives a hint. Why three quarters: the arms of example-robot-data, whose collision models match their
/// hardware, lose at most a quarter of their configurations drawn inside the joint limits to their own links
/// (UR3 23 %, UR5 14 %, PR2 6 %, Panda 2 %: wrists that fold back onto the upper arm); two cylinders that meet
/// whenever an elbow of +-2.5 rad bends past 1 rad lose 60 %. Collisions with the body are not counted: an arm
/// that can reach into its robot's base (the PR2's forearms) is drawn right.
inline constexpr double kFreeShareHint = 0.75;

/// \brief What self_collision_report samples.
struct SelfCollisionOptions {
  int samples = 2000;        ///< random configurations
  std::uint64_t seed = 0;    ///< sample i draws from the stream mix64(seed, i): the result never depends on threads
  int threads = 0;           ///< 0: every core
  /// Joints drawn at random (names; empty: every joint of the configuration); the others keep `reference`.
  std::vector<std::string> joints;
  Eigen::VectorXd reference;  ///< values of the joints not drawn (empty: Robot::home())
  /// Only the checked pairs of two of these links count (names; empty: every checked pair).
  std::vector<std::string> links;
};

/// \brief A checked link pair and how many of the sampled configurations put it in collision.
struct PairHits {
  std::string link_a, link_b;
  int hits = 0;
};

/// \brief Result of self_collision_report.
struct SelfCollisionReport {
  int samples = 0;  ///< configurations drawn
  int free = 0;     ///< of those, free of self-collision (over the robot's checked pairs)
  /// Every checked pair in collision in at least one sample, most often first (ties in link order).
  std::vector<PairHits> pairs;
  /// \brief free / samples (1 when nothing was sampled).
  double free_share() const { return samples > 0 ? static_cast<double>(free) / samples : 1.0; }
  /// \brief True when free_share() < kFreeShareHint: the collision model likely blocks the joints.
  bool suspicious() const { return free_share() < kFreeShareHint; }
};

/// \brief Draws options.samples configurations uniformly inside the joint limits (continuous joints in
/// [-pi, pi)) and counts those free of self-collision and, per checked pair (the pairs not allowed to
/// touch: adjacent, SRDF and sampled pairs are left out; only pairs within options.links when given), the
/// configurations that put it in collision.
/// \throws std::invalid_argument for samples < 1, an unknown joint or link name or a reference of the wrong size;
/// Cancelled when `progress` returns false
SelfCollisionReport self_collision_report(const Robot& robot, const SelfCollisionOptions& options = {},
                                          const ProgressCallback& progress = nullptr);

}  // namespace octoreach
