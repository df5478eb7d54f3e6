#include "stock_insert.hpp"

#include <chrono>
#include <stdexcept>

#include <octomap/OcTree.h>

#include "common/format.hpp"

namespace octoreach::bench {

double stock_insert(octomap::OcTree& tree, const std::vector<Eigen::Vector3d>& points,
                    const Eigen::Vector3d& origin, double max_range) {
  if (!origin.allFinite())
    throw std::invalid_argument("sensor_origin must be finite, got " + detail::format_point(origin));
  octomap::Pointcloud pc;
  pc.reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) pc.push_back(float(p.x()), float(p.y()), float(p.z()));
  auto t0 = std::chrono::steady_clock::now();
  tree.insertPointCloud(pc, octomap::point3d(float(origin.x()), float(origin.y()), float(origin.z())),
                        max_range > 0 ? max_range : -1.0);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace octoreach::bench
