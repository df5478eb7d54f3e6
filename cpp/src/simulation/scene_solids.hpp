#pragma once
// Internal: the solids of a scene ray casting meets other than axis-aligned boxes and triangles: oriented
// boxes, spheres, cylinders and OctoMaps with their poses, each kept in the form its ray test needs.
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "octoreach/simulation.hpp"

namespace octoreach {

struct Scene::Solids {
  // A solid in its own frame: world -> local is R^T (p - c).
  struct Placed {
    Eigen::Matrix3d R;   // local -> world rotation
    Eigen::Vector3d c;   // origin in the world
    Eigen::Vector3d half;  // box: half extents; cylinder: (radius, radius, half length); sphere: (radius, ...)
  };
  std::vector<Placed> boxes, spheres, cylinders;
  struct Octree {
    std::shared_ptr<const octomap::OcTree> tree;
    Pose pose;      // tree frame -> world
    bool identity;  // placed as read: rays stay in world coordinates
    Eigen::Vector3d lo, hi;  // the tree's metric bounds (tree frame), read once: OctoMap walks every leaf for them
  };
  std::vector<Octree> octrees;

  /// Adds a box (rotated), sphere, cylinder or OctoMap shape; false for other kinds.
  bool add(const Shape& shape);
  /// The first hit within `best` (lowered to it); `normal` (when given) gets the unit normal facing the ray.
  bool raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& best, Eigen::Vector3d* normal) const;
  /// The OctoMaps only (ray casting meets them after every other solid).
  bool raycast_octrees(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& inv, double& best,
                       Eigen::Vector3d* normal) const;
  /// True when p lies inside an oriented box, sphere or cylinder (OctoMaps are surfaces: false).
  bool contains(const Eigen::Vector3d& p) const;
  /// Grows `b` over every solid.
  void extend(Aabb& b) const;
};

}  // namespace octoreach
