#pragma once
/// \file arm_report.hpp
/// \brief What a map build does with a robot's joints for one arm: the joints it moves, the joints that carry
/// the arm (a torso lift) held at the reference posture, and how often the arm's own joints put the robot in
/// self-collision. `octoreach robot` prints it.

#include <string>
#include <vector>

#include "octoreach/arm.hpp"
#include "octoreach/self_collision_report.hpp"

namespace octoreach {

/// \brief A moving joint a map build holds still, at its value in the reference posture.
struct HeldJoint {
  std::string name;
  double value = 0.0;
};

/// \brief An arm's joints as map builds see them.
struct ArmReport {
  std::vector<std::string> moving;  ///< the chain's moving joints, base to tip
  /// Moving joints between the robot's root and the arm's base link (they carry the arm: a torso lift, a
  /// spine), at default_reference(): a map build never moves them.
  std::vector<HeldJoint> held;
  /// The link to give as the chain's base (`--base LINK`) so the chain includes every held joint; "" when none.
  std::string base_to_include_held;
  /// The arm's joints drawn at random, the rest of the robot at default_reference(); only the pairs of two links
  /// the arm moves count: an arm whose own links collide often fights its joints (a collision model to mend),
  /// while an arm that can reach into its robot's body (the PR2's forearm into its base) is drawn right.
  SelfCollisionReport self_collision;
  /// The same draws with every checked pair (the arm against the body too).
  SelfCollisionReport with_body;
};

/// \brief The report of `arm` on `robot`; `options` choose the self-collision sampling (its joints and
/// reference are the arm's and default_reference(); values given there are ignored).
/// \throws std::invalid_argument as Robot::chain for an arm the robot does not have
ArmReport arm_report(const Robot& robot, const Arm& arm, const SelfCollisionOptions& options = {},
                     const ProgressCallback& progress = nullptr);

}  // namespace octoreach
