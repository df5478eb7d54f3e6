#pragma once
/// \file stock_insert.hpp
/// \brief Benchmark and test support (not part of the octoreach library): stock OctoMap
/// insertPointCloud, the reference ExplorationMap::insert is measured against and must equal.

#include <vector>

#include <Eigen/Core>

namespace octomap {
class OcTree;
}

namespace octoreach::bench {

/// \brief Stock octomap::OcTree::insertPointCloud of the finite rows of `points` (map frame) seen
/// from `sensor_origin` into `tree` (max_range <= 0: unlimited). Returns the seconds it took.
/// \throws std::invalid_argument for a non-finite origin.
double stock_insert(octomap::OcTree& tree, const std::vector<Eigen::Vector3d>& points,
                    const Eigen::Vector3d& sensor_origin, double max_range);

}  // namespace octoreach::bench
