#include "mesh_box_check.hpp"

#include <algorithm>
#include <cmath>

#include "gjk_separation.hpp"
#include "mesh_pair_check.hpp"

namespace octoreach::detail {
namespace {

// A box at a world pose: the support function GJK and the plane checks read.
struct PlacedBox {
  const Eigen::Matrix3d R;  // columns: the box axes (world)
  const Eigen::Vector3d c;  // centre (world)
  const Eigen::Vector3d h;  // half extents
  Eigen::Vector3d support(const Eigen::Vector3d& d) const {
    const Eigen::Vector3d l = R.transpose() * d;
    return c + R * Eigen::Vector3d(l.x() >= 0 ? h.x() : -h.x(), l.y() >= 0 ? h.y() : -h.y(), l.z() >= 0 ? h.z() : -h.z());
  }
  // max over the box of d . x.
  double reach(const Eigen::Vector3d& d) const { return d.dot(c) + (R.transpose() * d).cwiseAbs().dot(h); }
};

// The mesh's hull more than the margin beyond the box along d (pointing from the box to the mesh).
bool apart_by(const PlacedHull& A, const PlacedBox& B, const Eigen::Vector3d& d) {
  return -A.reach(-d) - B.reach(d) > kBoxMargin * d.norm();
}

// The box's face planes: the hull's extent along each box axis (box frame) beyond the box's.
bool apart_on_faces(const PlacedHull& A, const PlacedBox& B, Eigen::Vector3d& axis) {
  const Eigen::Matrix3d M = B.R.transpose() * A.R;  // rows: the box axes in the mesh frame
  const Eigen::Vector3d o = B.R.transpose() * (A.t - B.c);
  for (int i = 0; i < 3; ++i) {
    const auto p = A.projections(M.row(i).transpose());
    if (p.minCoeff() + o[i] > B.h[i] + kBoxMargin) {
      axis = B.R.col(i);
      return true;
    }
    if (p.maxCoeff() + o[i] < -B.h[i] - kBoxMargin) {
      axis = -B.R.col(i);
      return true;
    }
  }
  return false;
}

PlacedBox placed_box(const fcl::CollisionGeometryd& b, const Pose& tb) {
  const auto& box = static_cast<const fcl::Boxd&>(b);
  return {tb.linear(), tb.translation(), 0.5 * box.side};
}

// The kept direction, then the box's faces.
bool quick_apart(const PlacedHull& A, const PlacedBox& B, Eigen::Vector3d& axis) {
  return (axis.squaredNorm() > 0 && apart_by(A, B, axis)) || apart_on_faces(A, B, axis);
}

// GJK, started from the box centre towards the mesh's local box centre.
bool gjk_apart(const HullMesh& m, const PlacedHull& A, const PlacedBox& B, Eigen::Vector3d& axis) {
  Eigen::Vector3d d = (A.R * m.aabb_local.center() + A.t) - B.c;
  if (!(d.squaredNorm() > 0)) d = Eigen::Vector3d::UnitX();
  return gjk::apart(A, B, d, kBoxMargin, axis);
}

}  // namespace

bool mesh_box_pair(const fcl::CollisionGeometryd& g, const fcl::CollisionGeometryd& box) {
  return box.getObjectType() == fcl::OT_GEOM && box.getNodeType() == fcl::GEOM_BOX && hull_mesh(g) != nullptr;
}

bool mesh_box_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                      const Pose& tb, MeshBoxWitness& witness) {
  const HullMesh& m = *hull_mesh(a);
  const PlacedHull A{m.hull_points(), ta.linear(), ta.translation()};
  const PlacedBox B = placed_box(b, tb);
  if (quick_apart(A, B, witness.axis)) return false;
  const fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
  auto& tris = witness.triangles;
  if (tris[0] >= 0) {
    // FCL's leaf test (mesh_shape_collision_traversal_node-inl.h, no contact asked): the solver
    // fcl::collide builds for a default request, the box at its pose, the triangle in the mesh frame.
    fcl::detail::GJKSolver_libccd<double> solver;
    solver.collision_tolerance = fcl::CollisionRequestd().gjk_tolerance;
    const auto& box = static_cast<const fcl::Boxd&>(b);
    for (std::size_t k = 0; k < tris.size(); ++k) {
      if (tris[k] < 0 || tris[k] >= m.num_tris) continue;  // none, or another mesh's witness
      const fcl::Triangle& t = m.tri_indices[tris[k]];
      if (solver.shapeTriangleIntersect(box, fb, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], fa, nullptr,
                                        nullptr, nullptr)) {
        std::rotate(tris.begin(), tris.begin() + k, tris.begin() + k + 1);  // the last hit first
        return true;
      }
    }
  }
  if (gjk_apart(m, A, B, witness.axis)) return false;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  if (fcl::collide(&a, fa, &b, fb, request, result) == 0) return false;
  std::rotate(tris.begin(), tris.end() - 1, tris.end());
  tris[0] = static_cast<int>(result.getContact(0).b1);
  return true;
}

bool mesh_box_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                    const Pose& tb, Eigen::Vector3d& axis) {
  if (!mesh_box_pair(a, b)) return false;
  const HullMesh& m = *hull_mesh(a);
  const PlacedHull A{m.hull_points(), ta.linear(), ta.translation()};
  const PlacedBox B = placed_box(b, tb);
  return quick_apart(A, B, axis) || gjk_apart(m, A, B, axis);
}

}  // namespace octoreach::detail
