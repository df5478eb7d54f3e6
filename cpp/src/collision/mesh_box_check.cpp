#include "collision/mesh_box_check.hpp"

#include <algorithm>
#include <cmath>

#include "collision/gjk_separation.hpp"
#include "collision/obb.hpp"
#include "collision/mesh_pair_check.hpp"

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

// FCL's leaf test of a mesh-box pair and a traversal of the mesh's own bounding-volume tree that
// gives FCL's answer (fcl::collide with a default request): FCL reports a collision exactly when its
// leaf test holds for some triangle (its traversal reaches every triangle whose bounding volume meets
// the box's). Here a node whose box (FCL's OBB of the node, mesh frame) is more than kBoxMargin from
// the box, or a triangle more than kBoxMargin from it on one of the 13 separating axes, holds no such
// triangle; every other triangle is given FCL's own leaf test.
class LeafTest {
 public:
  LeafTest(const HullMesh& m, const Pose& ta, const fcl::CollisionGeometryd& b, const Pose& tb)
      : m_(m), box_(static_cast<const fcl::Boxd&>(b)), fa_(ta.matrix()), fb_(tb.matrix()) {
    solver_.collision_tolerance = fcl::CollisionRequestd().gjk_tolerance;  // as fcl::collide sets it
    // The box in the mesh frame.
    const Eigen::Matrix3d Rt = ta.linear().transpose();
    in_mesh_ = {Rt * (tb.translation() - ta.translation()), Rt * tb.linear(), 0.5 * box_.side};
  }

  /// FCL's leaf test (mesh_shape_collision_traversal_node-inl.h, no contact asked) for triangle t,
  /// after the exact separating-axis pre-test.
  bool touches(int t) const {
    const fcl::Triangle& tri = m_.tri_indices[t];
    if (triangle_apart(m_.vertices[tri[0]], m_.vertices[tri[1]], m_.vertices[tri[2]])) return false;
    return solver_.shapeTriangleIntersect(box_, fb_, m_.vertices[tri[0]], m_.vertices[tri[1]], m_.vertices[tri[2]], fa_,
                                          nullptr, nullptr, nullptr);
  }

  /// A triangle FCL's leaf test finds touching the box, or -1 (then FCL reports no collision).
  int first_touching() const {
    if (m_.getNumBVs() <= 0) return -1;
    int stack[128];
    int n = 0;
    stack[n++] = 0;
    while (n > 0) {
      const fcl::BVNode<fcl::OBBRSSd>& node = m_.getBV(stack[--n]);
      const fcl::OBBd& o = node.bv.obb;
      if (in_mesh_.apart(Obb{o.To, o.axis, o.extent}, kBoxMargin)) continue;
      if (node.isLeaf()) {
        if (touches(node.primitiveId())) return node.primitiveId();
        continue;
      }
      if (n + 2 > 128) return fcl_first_touching();  // deeper than any mesh the library loads
      stack[n++] = node.rightChild();
      stack[n++] = node.leftChild();
    }
    return -1;
  }

 private:
  const HullMesh& m_;
  const fcl::Boxd& box_;
  const fcl::Transform3d fa_, fb_;
  fcl::detail::GJKSolver_libccd<double> solver_;
  Obb in_mesh_;

  // FCL itself (kept for a tree too deep for the stack).
  int fcl_first_touching() const {
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    if (fcl::collide(&m_, fa_, &box_, fb_, request, result) == 0) return -1;
    return static_cast<int>(result.getContact(0).b1);
  }

  // True when the triangle (mesh frame) is more than kBoxMargin from the box on one of the 13 axes of
  // the separating-axis theorem (the box's 3 face normals, the triangle's normal, and the 9 cross
  // products of their edges); false may still mean apart.
  bool triangle_apart(const fcl::Vector3d& p0, const fcl::Vector3d& p1, const fcl::Vector3d& p2) const {
    const Eigen::Matrix3d& R = in_mesh_.axes;
    const Eigen::Vector3d& h = in_mesh_.half;
    const Eigen::Vector3d v[3] = {R.transpose() * (p0 - in_mesh_.centre), R.transpose() * (p1 - in_mesh_.centre),
                                  R.transpose() * (p2 - in_mesh_.centre)};
    // An axis a (box frame) separates when the triangle's interval lies beyond the box's h . |a|.
    auto separates = [&](const Eigen::Vector3d& ax) {
      const double q0 = ax.dot(v[0]), q1 = ax.dot(v[1]), q2 = ax.dot(v[2]);
      const double r = h.dot(ax.cwiseAbs()) + kBoxMargin * ax.norm();
      return std::min({q0, q1, q2}) > r || std::max({q0, q1, q2}) < -r;
    };
    for (int i = 0; i < 3; ++i)
      if (std::min({v[0][i], v[1][i], v[2][i]}) > h[i] + kBoxMargin ||
          std::max({v[0][i], v[1][i], v[2][i]}) < -h[i] - kBoxMargin)
        return true;
    const Eigen::Vector3d e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    if (separates(e[0].cross(e[1]))) return true;
    for (const auto& ed : e)
      for (int i = 0; i < 3; ++i)
        if (separates(ed.cross(Eigen::Vector3d::Unit(i)))) return true;
    return false;
  }
};

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
  const LeafTest leaf(m, ta, b, tb);
  auto& tris = witness.triangles;
  for (std::size_t k = 0; k < tris.size() && tris[0] >= 0; ++k) {
    if (tris[k] < 0 || tris[k] >= m.num_tris) continue;  // none, or another mesh's witness
    if (leaf.touches(tris[k])) {
      std::rotate(tris.begin(), tris.begin() + k, tris.begin() + k + 1);  // the last hit first
      return true;
    }
  }
  if (gjk_apart(m, A, B, witness.axis)) return false;
  const int hit = leaf.first_touching();
  if (hit < 0) return false;
  std::rotate(tris.begin(), tris.end() - 1, tris.end());
  tris[0] = hit;
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
