#pragma once
// Internal: the steps of Robot::from_urdf. Only this builder (and Robot itself) writes a Robot's
// members, and only before from_urdf hands the robot out; after that a Robot never changes.

#include <set>
#include <string>
#include <utility>
#include <vector>

#include <urdf_model/model.h>

#include "octoreach/robot.hpp"

namespace octoreach::detail {

/// Link pairs to leave unchecked (i < j), collected while building.
using PairSet = std::set<std::pair<int, int>>;

/// Inserts the pair {a, b} as (min, max); a link paired with itself is skipped.
inline void add_pair(PairSet& pairs, int a, int b) {
  if (a != b) pairs.insert({std::min(a, b), std::max(a, b)});
}

struct RobotBuilder {
  Robot& r;

  // urdf.cpp: the kinematic tree, collision shapes and visuals of an urdfdom model.
  /// Links breadth-first from the root (parents first), with their collision shapes and visuals.
  void add_links(const urdf::ModelInterface& model, const std::vector<std::string>& package_dirs,
                 const std::string& urdf_dir);
  /// Joints in the order of their child links; limits and axes checked.
  void add_joints(const urdf::ModelInterface& model);
  /// Mimic joints resolved, then the configuration vector numbered (moving, non-mimic joints).
  void add_mimics_and_number_joints(const urdf::ModelInterface& model);

  // srdf.cpp: groups, group states and disabled collision pairs of an SRDF (path or XML).
  void read_srdf(const std::string& srdf, SrdfMismatch mismatch, PairSet& allowed);

  // robot_collision.cpp: collision links, adjacent pairs, then the allowed and checked pairs.
  void finish_collision_model(PairSet allowed);
};

/// True when `s` starts (after white space) with '<': an XML string rather than a file path.
bool looks_like_xml(const std::string& s);
/// The whole file as a string; FileError naming `what` ("URDF", "SRDF") and the path otherwise.
std::string read_text_file(const std::string& path, const char* what);

}  // namespace octoreach::detail
