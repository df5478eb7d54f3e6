#pragma once
/// \file arm_discovery.hpp
/// \brief The arms of a robot: found from the SRDF or the kinematic tree, each with the tool axis that
/// approaches an object and why (the approach axis is inferred from the chain's geometry).

#include <string>
#include <vector>

#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

/// \brief An arm as capability maps see it: the chain's base and tip links, the tool axis that
/// approaches an object, and why that axis. The reference posture of the joints it does not move
/// is default_reference(). Found by find_arms() (arm_discovery.cpp) or given by links.
struct Arm {
  std::string base_link, tip_link;
  Eigen::Vector3d approach_axis = Eigen::Vector3d::UnitZ();
  std::string reason;  ///< why approach_axis: inferred from the gripper, or "given"
  std::string name;    ///< the arm's name ("" for an arm given by links)
  std::string source;  ///< where the arm was found: "SRDF chain group 'x'", "kinematic tree", ...

  /// \brief The arm called `name`: an arm of find_arms(), else any serial SRDF group of that name
  /// (its tip extended to the tool frame rigid with it).
  /// \throws std::invalid_argument naming the robot, the arm and the arms that exist, or saying how
  /// to give the approach axis when it cannot be inferred.
  static Arm named(const Robot& robot, const std::string& name);
  /// \brief An arm given by its links and approach axis (reason "given"); throws
  /// std::invalid_argument naming a link the robot lacks (and the nearest names).
  static Arm from_links(const Robot& robot, const std::string& base_link, const std::string& tip_link,
                        const Eigen::Vector3d& approach_axis);
  /// \brief An arm given by its links, the approach axis inferred (infer_approach_axis).
  static Arm from_links(const Robot& robot, const std::string& base_link, const std::string& tip_link);
  /// \brief This arm with a given approach axis (reason "given"); throws for a zero or non-finite axis.
  Arm with_approach_axis(const Eigen::Vector3d& axis) const;
};

/// \brief Approach axis of a tool frame and why it was chosen.
struct ApproachAxis {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  std::string reason;
};

/// \brief The approach axis of the tool frame `tip_link` of the chain base_link -> tip_link, in the
/// tip frame, snapped to the nearest of its six axes: the direction from the wrist (the chain's last
/// moving joint) to the tool frame; when the tool frame sits at the wrist, the direction to the
/// fingers (moving joints on the tool's rigid body), else the last joint's axis pointing away from
/// the arm (a bare flange).
/// \throws std::invalid_argument saying why and how to give the axis when none of these is clear.
ApproachAxis infer_approach_axis(const Robot& robot, const std::string& base_link, const std::string& tip_link);

/// \brief The arms of a robot: SRDF groups whose moving joints form one serial chain (chain, joint-list,
/// link-list groups and subgroups), their tips moved to the tool frame rigid with them (an
/// end_effector's parent_link, else the link named most like a tool frame); without an SRDF arm,
/// every branch of the kinematic tree that ends in a gripper-like tip (named "left_arm"/"right_arm"
/// by side, or "arm" for one). Legs and heads (by link names) and arms whose approach axis cannot be
/// inferred are left out.
std::vector<Arm> find_arms(const Robot& robot);
/// \brief Why find_arms() finds no arm on a robot, in the words of the errors that say so.
extern const char kNoArmFound[];

/// \brief Names of find_arms(robot), sorted.
std::vector<std::string> arm_names(const Robot& robot);

}  // namespace octoreach
