#pragma once
// Internal: the convex hull of 3D points (libqhull_r), used by exploration (hull of the occupied cells) and by
// the mesh-pair check (vertex hulls of link meshes).
#include <vector>

#include <Eigen/Core>

namespace octoreach::detail {

// Facet planes (outward unit normal n, offset d; inside n.x + d <= 0) and vertices, both sorted.
struct Hull {
  std::vector<Eigen::Vector4d> planes;
  std::vector<Eigen::Vector3d> vertices;
  bool empty() const { return planes.empty(); }
};

// Convex hull with libqhull_r. Returns false (and leaves `hull` alone) when the points are
// degenerate (fewer than 4, coplanar ...).
bool convex_hull(const std::vector<Eigen::Vector3d>& points, Hull& hull);

}  // namespace octoreach::detail
