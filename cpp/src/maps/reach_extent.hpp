#pragma once
// Private: how far an arm reaches, seen from the robot's reference frame (for point- and surface-map grids).
#include <algorithm>
#include <vector>

#include "octoreach/types.hpp"

namespace octoreach::detail {

/// Largest horizontal distance and the height range of capability-voxel centres (arm frame) placed
/// in the reference frame by `reference_to_arm`.
struct ReachExtent {
  double radius_xy = 0, z_lo = 1e9, z_hi = -1e9;
};

inline ReachExtent reach_extent(const std::vector<Eigen::Vector3d>& arm_centres, const Pose& reference_to_arm) {
  ReachExtent e;
  for (const auto& c : arm_centres) {
    Eigen::Vector3d w = reference_to_arm * c;
    e.radius_xy = std::max(e.radius_xy, w.head<2>().norm());
    e.z_lo = std::min(e.z_lo, w.z());
    e.z_hi = std::max(e.z_hi, w.z());
  }
  return e;
}

}  // namespace octoreach::detail
