#pragma once
// Internal: the collision check of a triangle mesh against a box with witnesses kept from the last
// check of the same pair, so that most checks need no FCL narrow phase. The answer is FCL's, always:
//  - apart: FCL's mesh-box collision tests the box against triangles, and every triangle lies in the
//    convex hull of its mesh's vertices. If a plane separates that hull (its support points,
//    HullMesh) from the box by more than kBoxMargin, no triangle can meet the box. The planes tried:
//    the one that separated the pair last time, the box's three face planes, then one found by GJK;
//    each is checked by projecting the support points and the box on its normal, so the answer rests
//    on that check alone.
//  - touching: the triangles found touching the box lately are retested with FCL's own leaf test
//    (the narrow-phase solver fcl::collide builds for a default request, on the same transforms); if
//    one still touches, FCL's traversal, which reaches every triangle whose bounding volume meets the
//    box's, reports a collision too.
//  - otherwise the mesh's own bounding-volume tree (FCL's OBBRSS nodes) is traversed: a node or a
//    triangle more than kBoxMargin from the box on a separating axis holds no touching triangle (FCL's
//    leaf test is a GJK to a tolerance far below the margin), every other triangle gets FCL's leaf
//    test, and the first that touches joins the witnesses. FCL reports a collision exactly when its
//    leaf test holds for some triangle, so this is FCL's answer without fcl::collide (which also fits
//    a bounding volume to the box on every call).
// Order: the kept plane, the face planes, the kept triangles, GJK, the traversal. The witnesses are
// per thread (the caller keeps them): a witness only ever changes the cost of a check.
#include <array>

#include <fcl/fcl.h>

#include "octoreach/types.hpp"

namespace octoreach::detail {

/// Gap (m) a separating plane needs against a box: FCL's box-triangle test runs GJK (libccd) to a
/// tolerance, and this stays far above it (the same margin as the oriented-box pre-test, obb.hpp).
constexpr double kBoxMargin = 1e-4;

/// What decided the last check of one mesh-box pair.
struct MeshBoxWitness {
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  // separating direction (world, from the box to the mesh); zero: none
  static constexpr int kTriangles = 4;
  std::array<int, kTriangles> triangles{{-1, -1, -1, -1}};  // touching triangles, the last confirmed first; -1: none
};

/// True when `g` is a geometry mesh_box_collide handles as its mesh (a HullMesh of triangles), and
/// `box` one it handles as its box (an fcl::Box).
bool mesh_box_pair(const fcl::CollisionGeometryd& g, const fcl::CollisionGeometryd& box);

/// FCL's answer (fcl::collide, default request) for mesh `a` at world pose `ta` against box `b` at
/// `tb` (mesh_box_pair(a, b)), using and refreshing `witness`.
bool mesh_box_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                      const Pose& tb, MeshBoxWitness& witness);

/// True when the hull of mesh `a`'s vertices (at `ta`) and box `b` (at `tb`) are more than kBoxMargin
/// apart along some direction, returned in `axis` (unit, world, from the box to the mesh). `axis` on
/// input: a direction to try first (zero: none).
bool mesh_box_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                    const Pose& tb, Eigen::Vector3d& axis);

}  // namespace octoreach::detail
