#pragma once
// Internal: the per-thread scratch of the sampling loops over random configurations (the allowed-collision
// matrix, the self-collision report): every collision shape's world pose and box at q, and the pair test.
#include <cmath>
#include <random>
#include <vector>

#include <fcl/fcl.h>

#include "collision/detail.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::detail {

/// Shape poses and world boxes of every collision link at q (scratch of one thread).
struct LinkBoxes {
  std::vector<Pose> link_poses;
  ShapeBoxes shapes;

  /// Poses and boxes of every collision link at configuration q.
  void update(const Robot& robot, const Eigen::VectorXd& q) {
    robot.link_poses(q, link_poses);
    update_shapes(robot);
  }
  /// Poses and boxes of every collision link from `link_poses` as set.
  void update_shapes(const Robot& robot) {
    for (int li : robot.collision_links()) shapes.update(robot, link_poses, li);
  }
  /// True when a shape of link a touches a shape of link b.
  bool touch(const Robot& robot, int a, int b) const {
    const auto& sa = robot.links()[a].shapes;
    const auto& sb = robot.links()[b].shapes;
    for (std::size_t i = 0; i < sa.size(); ++i)
      for (std::size_t k = 0; k < sb.size(); ++k)
        if (shapes.boxes[a][i].overlap(shapes.boxes[b][k]) &&
            geometry_collide(sa[i].geometry.get(), shapes.poses[a][i], sb[k].geometry.get(), shapes.poses[b][k]))
          return true;
    return false;
  }
};

/// A configuration drawn uniformly inside the limits from the stream `stream` (continuous joints in
/// [-pi, pi)); only the entries `joints` (configuration indices; all when null) are drawn, the others
/// keep their values in `q`.
inline void random_configuration(const Robot& robot, std::uint64_t stream, Eigen::VectorXd& q,
                                 const std::vector<int>* joints = nullptr) {
  std::mt19937_64 rng(stream);
  const Eigen::VectorXd lo = robot.lower(), hi = robot.upper();
  const int n = joints ? static_cast<int>(joints->size()) : robot.dof();
  for (int k = 0; k < n; ++k) {
    const int i = joints ? (*joints)[k] : k;
    const double a = std::isfinite(lo[i]) ? lo[i] : -kPi, b = std::isfinite(hi[i]) ? hi[i] : kPi;
    q[i] = std::uniform_real_distribution<double>(a, b)(rng);
  }
}

}  // namespace octoreach::detail
