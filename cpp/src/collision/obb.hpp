#pragma once
// Private: an oriented box and the separating-axis test between two of them, as a cheap exact
// pre-test before FCL's narrow phase (a geometry lies inside its local AABB placed at its pose).
#include <cmath>

#include <fcl/geometry/collision_geometry.h>

#include "octoreach/collision.hpp"

namespace octoreach::detail {

struct Obb {
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;  // columns: the box axes in the world
  Eigen::Vector3d half;

  /// The local AABB of `g` (computed) placed at `pose`.
  static Obb of(const fcl::CollisionGeometryd& g, const Pose& pose) {
    const fcl::AABBd& local = g.aabb_local;
    return {pose * local.center(), pose.linear(), 0.5 * (local.max_ - local.min_)};
  }

  /// True when a plane separates the two boxes with more than `margin` (metres) to spare on the
  /// 15 axes of the separating-axis theorem: then they cannot touch. False may still mean apart.
  bool apart(const Obb& b, double margin = 1e-4) const {
    const Eigen::Vector3d t = axes.transpose() * (b.centre - centre);
    Eigen::Matrix3d R, A;  // A guards near-parallel edge axes
    for (int j = 0; j < 3; ++j) {  // axes of b first, R column by column (most apart pairs end here)
      R.col(j) = axes.transpose() * b.axes.col(j);
      A.col(j) = R.col(j).cwiseAbs().array() + 1e-9;
      if (std::abs(t.dot(R.col(j))) > half.dot(A.col(j)) + b.half[j] + margin) return true;
    }
    for (int i = 0; i < 3; ++i)  // axes of this box
      if (std::abs(t[i]) > half[i] + A.row(i).dot(b.half) + margin) return true;
    for (int i = 0; i < 3; ++i)  // cross products of one axis of each
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double ra = half[i1] * A(i2, j) + half[i2] * A(i1, j);
        const double rb = b.half[j1] * A(i, j2) + b.half[j2] * A(i, j1);
        if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb + margin) return true;
      }
    return false;
  }
};

}  // namespace octoreach::detail
