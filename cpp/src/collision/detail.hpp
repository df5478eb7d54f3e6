#pragma once
// Internal: the two FCL steps shared by obstacle checks (collision.cpp) and the robot's own
// collision checks (robot_collision.cpp).

#include <utility>
#include <vector>

#include <fcl/fcl.h>

#include "octoreach/types.hpp"

namespace octoreach {
class Robot;
}

namespace octoreach::detail {

/// Index into `pairs` of the first pair (in that order) whose links collide at the link poses, or -1
/// (Robot::in_self_collision_poses is this >= 0; IK uses the index to test often-hit pairs first).
int first_colliding_pair(const Robot& robot, const std::vector<Pose>& poses,
                         const std::vector<std::pair<int, int>>& pairs);

/// World poses and world AABBs of the shapes of a robot's links (per link, per shape).
struct ShapeBoxes {
  std::vector<std::vector<fcl::AABBd>> boxes;
  std::vector<std::vector<Pose>> poses;
  /// Recomputes link `link`'s entries from its link pose.
  void update(const Robot& robot, const std::vector<Pose>& link_poses, int link);
};

/// first_colliding_pair with the shape boxes given: `shape_boxes` must hold every link named by `pairs`, at
/// the link poses the check is about (IK keeps the boxes of the links its chain never moves and
/// recomputes only the others).
int first_colliding_pair(const Robot& robot, const ShapeBoxes& shape_boxes,
                         const std::vector<std::pair<int, int>>& pairs);

/// World-frame AABB of a geometry at a pose, from its local AABB (cheap and conservative).
inline fcl::AABBd world_aabb(const fcl::CollisionGeometryd& g, const Pose& T) {
  const fcl::AABBd& local = g.aabb_local;
  Eigen::Vector3d c = T * local.center();
  Eigen::Vector3d h = 0.5 * (local.max_ - local.min_);
  Eigen::Vector3d e = T.linear().cwiseAbs() * h;
  return fcl::AABBd(c - e, c + e);
}

/// True when two geometries at their world poses touch (FCL narrow phase, no AABB test).
inline bool geometry_collide(const fcl::CollisionGeometryd* a, const Pose& ta, const fcl::CollisionGeometryd* b,
                             const Pose& tb) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
  return fcl::collide(a, fa, b, fb, request, result) > 0;
}

}  // namespace octoreach::detail
