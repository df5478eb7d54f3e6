#include "mesh_pair_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <typeinfo>

#include "common/convex_hull.hpp"

namespace octoreach::detail {
namespace {

using Mesh = HullMesh;

const Mesh* mesh_of(const fcl::CollisionGeometryd& g) {
  if (g.getObjectType() != fcl::OT_BVH || g.getNodeType() != fcl::BV_OBBRSS || typeid(g) != typeid(HullMesh))
    return nullptr;
  const auto* m = static_cast<const Mesh*>(&g);
  const bool triangles = m->getModelType() == fcl::BVH_MODEL_TRIANGLES && m->tri_indices && m->num_tris > 0;
  // No support points: a vertex is not finite, and planes prove nothing; FCL decides.
  return triangles && m->vertices && m->num_vertices > 0 && !m->hull_points().x.empty() ? m : nullptr;
}

// A mesh's hull support points at a world pose.
struct Placed {
  const HullMesh::Points& p;
  const Eigen::Matrix3d R;
  const Eigen::Vector3d t;
  // The projections of the points on local direction l.
  auto projections(const Eigen::Vector3d& l) const {
    using Col = Eigen::Map<const Eigen::ArrayXd>;
    const Eigen::Index n = static_cast<Eigen::Index>(p.x.size());
    return l.x() * Col(p.x.data(), n) + l.y() * Col(p.y.data(), n) + l.z() * Col(p.z.data(), n);
  }
  // The world position of a point farthest along world direction d.
  Eigen::Vector3d support(const Eigen::Vector3d& d) const {
    Eigen::Index i = 0;
    projections(R.transpose() * d).maxCoeff(&i);
    return R * Eigen::Vector3d(p.x[i], p.y[i], p.z[i]) + t;
  }
  // max over the points of d . x (world).
  double reach(const Eigen::Vector3d& d) const { return projections(R.transpose() * d).maxCoeff() + d.dot(t); }
};

// Closest point to the origin of the triangle (a, b, c) (Ericson, Real-Time Collision Detection
// 5.1.5); out/m: the vertices of the feature it lies on.
Eigen::Vector3d closest_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                 Eigen::Vector3d* out, int& m) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) {
    out[0] = a;
    m = 1;
    return a;
  }
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) {
    out[0] = b;
    m = 1;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    out[0] = a;
    out[1] = b;
    m = 2;
    return a + d1 / (d1 - d3) * ab;
  }
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) {
    out[0] = c;
    m = 1;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    out[0] = a;
    out[1] = c;
    m = 2;
    return a + d2 / (d2 - d6) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    out[0] = b;
    out[1] = c;
    m = 2;
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  out[0] = a;
  out[1] = b;
  out[2] = c;
  m = 3;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// True when the origin and d lie on opposite sides of the plane through a, b, c.
bool origin_outside(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  const Eigen::Vector3d nrm = (b - a).cross(c - a);
  return (-a).dot(nrm) * (d - a).dot(nrm) < 0;
}

// Closest point to the origin of the simplex W[0..n), W reduced to the feature it lies on. A
// tetrahedron holding the origin gives zero.
Eigen::Vector3d closest(Eigen::Vector3d* W, int& n) {
  if (n == 1) return W[0];
  if (n == 2) {
    const Eigen::Vector3d ab = W[1] - W[0];
    const double t = -W[0].dot(ab) / ab.squaredNorm();
    if (!(t > 0)) {
      n = 1;
      return W[0];
    }
    if (t >= 1) {
      W[0] = W[1];
      n = 1;
      return W[0];
    }
    return W[0] + t * ab;
  }
  Eigen::Vector3d out[3];
  int m = 0;
  if (n == 3) {
    const Eigen::Vector3d p = closest_triangle(W[0], W[1], W[2], out, m);
    for (int i = 0; i < m; ++i) W[i] = out[i];
    n = m;
    return p;
  }
  // Tetrahedron: the closest of the faces the origin lies outside of.
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), keep[3];
  int kept = 4;
  for (const auto& f : kFaces) {
    if (!origin_outside(W[f[0]], W[f[1]], W[f[2]], W[f[3]])) continue;
    const Eigen::Vector3d q = closest_triangle(W[f[0]], W[f[1]], W[f[2]], out, m);
    if (q.squaredNorm() < best) {
      best = q.squaredNorm();
      p = q;
      for (int i = 0; i < m; ++i) keep[i] = out[i];
      kept = m;
    }
  }
  if (kept == 4) return Eigen::Vector3d::Zero();  // inside every face: the hulls overlap
  for (int i = 0; i < kept; ++i) W[i] = keep[i];
  n = kept;
  return p;
}

// z = a - b over both hulls: w (out) minimises z . d, so z . d >= w . d everywhere. When w . d exceeds
// the margin times |d|, the plane normal to d separates the hulls: this test is the certificate.
bool apart_along(const Placed& A, const Placed& B, const Eigen::Vector3d& d, Eigen::Vector3d& w) {
  w = A.support(-d) - B.support(d);
  return w.dot(d) > kHullMargin * d.norm();
}

// apart_along without the support point: the two vertex passes alone.
bool apart_by(const Placed& A, const Placed& B, const Eigen::Vector3d& d) {
  return -A.reach(-d) - B.reach(d) > kHullMargin * d.norm();
}

// GJK on the Minkowski difference A - B, started along the direction between the meshes' local box
// centres ca, cb: v, the point of the simplex W nearest the origin, approaches the difference's
// nearest point; each step adds the support point w against v. True (axis: unit v) when some v
// certifies the separation (apart_along); false when the hulls come closer than the margin.
bool gjk_apart(const Placed& A, const Placed& B, const Eigen::Vector3d& ca, const Eigen::Vector3d& cb,
               Eigen::Vector3d& axis) {
  Eigen::Vector3d d = (A.R * ca + A.t) - (B.R * cb + B.t);
  if (!(d.squaredNorm() > 0)) d = Eigen::Vector3d::UnitX();
  Eigen::Vector3d w;
  if (apart_along(A, B, d, w)) {
    axis = d.normalized();
    return true;
  }
  Eigen::Vector3d W[4] = {w};
  int n = 1;
  Eigen::Vector3d v = w;
  for (int it = 0; it < 64; ++it) {
    const double vv = v.squaredNorm();
    if (!(vv > 1e-24)) return false;  // the origin is in the difference: the hulls overlap
    if (apart_along(A, B, v, w)) {
      axis = v / std::sqrt(vv);
      return true;
    }
    if (vv - w.dot(v) <= 1e-12 * vv) return false;  // converged closer than the margin
    for (int i = 0; i < n; ++i)
      if (W[i] == w) return false;  // no progress
    W[n++] = w;
    v = closest(W, n);
  }
  return false;
}

}  // namespace

void HullMesh::measure() const {
  if (!vertices || num_vertices <= 0) return;
  std::vector<Eigen::Vector3d> all(vertices, vertices + num_vertices);
  for (const auto& v : all)
    if (!v.allFinite()) return;  // no support points: is_mesh is false
  double scale = 1.0;
  for (const auto& v : all) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  const double inside = 1e-9 * scale;  // far beyond qhull's rounding
  Hull hull;
  const bool ok = convex_hull(all, hull);  // false when degenerate (flat ...): every vertex is kept
  for (const auto& v : all) {
    bool interior = ok;
    for (std::size_t f = 0; interior && f < hull.planes.size(); ++f)
      interior = hull.planes[f].head<3>().dot(v) + hull.planes[f][3] < -inside;
    if (interior) continue;
    points_.x.push_back(v.x());
    points_.y.push_back(v.y());
    points_.z.push_back(v.z());
  }
}

bool is_mesh(const fcl::CollisionGeometryd& g) { return mesh_of(g) != nullptr; }

bool meshes_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                    const Pose& tb, MeshPairWitness& witness) {
  const Mesh& ma = *mesh_of(a);
  const Mesh& mb = *mesh_of(b);
  const Placed A{ma.hull_points(), ta.linear(), ta.translation()};
  const Placed B{mb.hull_points(), tb.linear(), tb.translation()};
  // Cheapest first: the old separating direction (two passes over the vertices), then the old
  // triangle pair, then GJK, then FCL.
  if (witness.axis.squaredNorm() > 0 && apart_by(A, B, witness.axis)) return false;
  const fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
  // A witness only ever saves work: one kept under a key the caller reused for other meshes is still
  // a valid test of these meshes once its triangle indices are in range. The pairs are kept newest
  // (or last confirmed) first.
  if (witness.triangles[0][0] >= 0) {
    // FCL's leaf test (mesh_collision_traversal_node-inl.h): b's triangle moved into a's frame by the
    // relative transform FCL's traversal node computes.
    fcl::Matrix3d R;
    fcl::Vector3d T;
    fcl::relativeTransform(fa.linear(), fa.translation(), fb.linear(), fb.translation(), R, T);
    auto& tris = witness.triangles;
    for (std::size_t k = 0; k < tris.size(); ++k) {
      const int ia = tris[k][0], ib = tris[k][1];
      if (ia < 0 || ia >= ma.num_tris || ib < 0 || ib >= mb.num_tris) continue;  // another mesh's witness
      const fcl::Triangle& p = ma.tri_indices[ia];
      const fcl::Triangle& q = mb.tri_indices[ib];
      if (fcl::detail::Intersect<double>::intersect_Triangle(ma.vertices[p[0]], ma.vertices[p[1]], ma.vertices[p[2]],
                                                             mb.vertices[q[0]], mb.vertices[q[1]], mb.vertices[q[2]],
                                                             R, T)) {
        std::rotate(tris.begin(), tris.begin() + k, tris.begin() + k + 1);  // the last hit first
        return true;
      }
    }
  }
  if (gjk_apart(A, B, a.aabb_local.center(), b.aabb_local.center(), witness.axis)) return false;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  if (fcl::collide(&a, fa, &b, fb, request, result) == 0) return false;
  std::rotate(witness.triangles.begin(), witness.triangles.end() - 1, witness.triangles.end());
  witness.triangles[0] = {{static_cast<int>(result.getContact(0).b1), static_cast<int>(result.getContact(0).b2)}};
  return true;
}

bool hulls_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                 const Pose& tb, Eigen::Vector3d& axis) {
  const Mesh* ma = mesh_of(a);
  const Mesh* mb = mesh_of(b);
  if (!ma || !mb) return false;
  const Placed A{ma->hull_points(), ta.linear(), ta.translation()};
  const Placed B{mb->hull_points(), tb.linear(), tb.translation()};
  if (axis.squaredNorm() > 0 && apart_by(A, B, axis)) return true;
  return gjk_apart(A, B, a.aabb_local.center(), b.aabb_local.center(), axis);
}

}  // namespace octoreach::detail
