#pragma once
/// \file surface.hpp
/// \brief A flat working surface (table top, shelf board): a planar polygon with a thickness.

#include <array>
#include <memory>
#include <vector>

#include "octoreach/collision.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

/// \brief A planar polygon (convex or not, any height and tilt) given by 3D vertices in the world
/// frame, extruded by `thickness` below its top face, plus optional obstacle boxes (legs, walls).
///
/// The normal points up (n_z > 0); for a vertical polygon it follows the vertex order
/// (counter-clockwise seen from the normal). Local axes: u along the first edge, v = n x u.
class Surface {
 public:
  /// \throws std::invalid_argument for fewer than three vertices, non-finite values, a non-planar,
  /// degenerate or self-intersecting polygon, or a non-positive thickness.
  Surface(const std::vector<Eigen::Vector3d>& vertices, double thickness = 0.03);
  /// \brief An axis-aligned rectangular table top of the given size, centred at (x, y), top at `height`.
  static Surface rectangle(double size_x, double size_y, double height, double x = 0, double y = 0,
                           double yaw = 0, double thickness = 0.03);

  /// \brief Adds an obstacle box (extents `size`, centre pose in the world frame).
  void add_box(const Eigen::Vector3d& size, const Pose& pose);
  /// \brief Adds a leg under each corner of the polygon, down to the floor (for rectangular tables): a box `width`
  /// by `width` across, its sides along the world axes, its centre `width` from the corner towards the polygon's
  /// centre (along the diagonal of a rectangle).
  void add_legs(double width = 0.05);

  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  const std::vector<Eigen::Vector2d>& polygon() const { return polygon_; }
  const Eigen::Vector3d& normal() const { return normal_; }
  const Eigen::Vector3d& origin() const { return origin_; }
  const Eigen::Vector3d& u_axis() const { return u_; }
  const Eigen::Vector3d& v_axis() const { return v_; }
  double thickness() const { return thickness_; }
  double area() const { return area_; }
  const std::vector<std::pair<Eigen::Vector3d, Pose>>& boxes() const { return boxes_; }

  /// \brief (u, v) coordinates of a world point projected on the plane.
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    Eigen::Vector3d d = p - origin_;
    return {d.dot(u_), d.dot(v_)};
  }
  /// \brief True when (u, v) lies inside the polygon (half-planes for convex polygons, else even-odd);
  /// false for a non-finite (u, v).
  bool contains(const Eigen::Vector2d& uv) const {
    if (convex_) {
      for (const auto& h : halfplanes_)
        if (!(h.x() * uv.x() + h.y() * uv.y() <= h.z())) return false;
      return true;
    }
    return contains_even_odd(uv);
  }
  bool convex() const { return convex_; }
  /// \brief The polygon's triangles (ear clipping, O(n r) for r reflex corners): vertex indices, counter-clockwise
  /// seen from the normal; their areas add up to area().
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  /// \brief For a convex polygon, its edges as half-planes (a, b, c): inside where a u + b v <= c.
  const std::vector<Eigen::Vector3d>& halfplanes() const { return halfplanes_; }
  /// \brief Grid points inside the polygon at `resolution` (cell centres of a grid aligned with u, v
  /// starting at the polygon's bounding box): 1.4 x 0.65 m at 0.05 m gives 28 x 13 = 364 points.
  std::vector<Eigen::Vector3d> sample_points(double resolution) const;
  /// \brief The surface slab (convex prisms of its triangles) and the boxes, as collision objects.
  std::shared_ptr<Obstacles> obstacles() const;

 private:
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Eigen::Vector2d> polygon_;
  bool contains_even_odd(const Eigen::Vector2d& uv) const;
  std::vector<std::array<int, 3>> triangles_;
  bool convex_ = false;
  std::vector<Eigen::Vector3d> halfplanes_;  // (a, b, c): inside where a u + b v <= c
  Eigen::Vector3d normal_, origin_, u_, v_;
  double thickness_ = 0.03, area_ = 0;
  std::vector<std::pair<Eigen::Vector3d, Pose>> boxes_;
};

}  // namespace octoreach
