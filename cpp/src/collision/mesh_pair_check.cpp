#include "collision/mesh_pair_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <typeinfo>

#include "common/convex_hull.hpp"
#include "collision/gjk_separation.hpp"

namespace octoreach::detail {
namespace {

using Mesh = HullMesh;

using Placed = PlacedHull;

// apart_along without the support point: the two vertex passes alone, or none when the balls that hold the
// points are apart along d already.
bool apart_by(const Placed& A, const Placed& B, const Eigen::Vector3d& d) {
  const double margin = kHullMargin * d.norm();
  if (-A.reach_bound(-d) - B.reach_bound(d) > margin) return true;
  return -A.reach(-d) - B.reach(d) > margin;
}

// GJK on the hulls, started along the direction between the meshes' local box centres ca, cb.
bool gjk_apart(const Placed& A, const Placed& B, const Eigen::Vector3d& ca, const Eigen::Vector3d& cb,
               Eigen::Vector3d& axis) {
  Eigen::Vector3d d = (A.R * ca + A.t) - (B.R * cb + B.t);
  if (!(d.squaredNorm() > 0)) d = Eigen::Vector3d::UnitX();
  return gjk::apart(A, B, d, kHullMargin, axis);
}

// The ball that holds the points point(0), ..., point(n - 1) (centre xyz, radius w): centred on their box, its
// radius their farthest distance from there plus what rounding in that distance could hide.
template <class Point>
Eigen::Vector4d holding_ball(std::size_t n, const Point& point) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double scale = 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d v = point(i);
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
    scale = std::max(scale, v.cwiseAbs().maxCoeff());
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  double r2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) r2 = std::max(r2, (point(i) - centre).squaredNorm());
  Eigen::Vector4d ball;
  ball << centre, std::sqrt(r2) * (1.0 + 1e-12) + 1e-12 * scale;
  return ball;
}

// The support points of `all`'s convex hull (the points not clearly inside it), into `points`.
void support_points(const std::vector<Eigen::Vector3d>& all, HullMesh::Points& points) {
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
    points.x.push_back(v.x());
    points.y.push_back(v.y());
    points.z.push_back(v.z());
  }
  // The ball that holds them.
  if (points.x.empty()) return;
  const Eigen::Vector4d ball = holding_ball(
      points.x.size(), [&](std::size_t i) { return Eigen::Vector3d(points.x[i], points.y[i], points.z[i]); });
  points.centre = ball.head<3>();
  points.radius = ball[3];
}

// The relative transform FCL's mesh traversal computes (b's frame into a's), which its triangle test takes.
void fcl_relative(const Pose& ta, const Pose& tb, fcl::Matrix3d& R, fcl::Vector3d& T) {
  const fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
  fcl::relativeTransform(fa.linear(), fa.translation(), fb.linear(), fb.translation(), R, T);
}

// The triangles of a's piece ia and of b's piece ib (-1: all of b's) tested pairwise with FCL's leaf test, pairs
// whose boxes (in a's frame) are apart skipped: the first pair that intersects, or {-1, -1}.
std::array<int, 2> piece_pair_touch(const HullMesh& ma, int ia, const HullMesh& mb, int ib, const fcl::Matrix3d& R,
                                    const fcl::Vector3d& T) {
  struct Box {
    Eigen::Vector3d lo, hi;
  };
  auto box = [](const fcl::Vector3d& p, const fcl::Vector3d& q, const fcl::Vector3d& r) {
    return Box{p.cwiseMin(q).cwiseMin(r), p.cwiseMax(q).cwiseMax(r)};
  };
  const std::vector<int>& ta = ma.pieces()[ia].triangles;
  thread_local std::vector<int> all;
  const std::vector<int>* tb = &all;
  if (ib >= 0) {
    tb = &mb.pieces()[ib].triangles;
  } else {
    all.resize(mb.num_tris);
    for (int t = 0; t < mb.num_tris; ++t) all[t] = t;
  }
  thread_local std::vector<Box> boxes_b;
  boxes_b.clear();
  Box bound{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
            Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (int t : *tb) {
    const fcl::Triangle& q = mb.tri_indices[t];
    boxes_b.push_back(box(R * mb.vertices[q[0]] + T, R * mb.vertices[q[1]] + T, R * mb.vertices[q[2]] + T));
    bound.lo = bound.lo.cwiseMin(boxes_b.back().lo);
    bound.hi = bound.hi.cwiseMax(boxes_b.back().hi);
  }
  auto overlap = [](const Box& x, const Box& y) {
    return (x.lo.array() <= y.hi.array()).all() && (y.lo.array() <= x.hi.array()).all();
  };
  for (int s : ta) {
    const fcl::Triangle& p = ma.tri_indices[s];
    const Box bs = box(ma.vertices[p[0]], ma.vertices[p[1]], ma.vertices[p[2]]);
    if (!overlap(bs, bound)) continue;
    for (std::size_t k = 0; k < tb->size(); ++k) {
      if (!overlap(bs, boxes_b[k])) continue;
      const fcl::Triangle& q = mb.tri_indices[(*tb)[k]];
      if (fcl::detail::Intersect<double>::intersect_Triangle(ma.vertices[p[0]], ma.vertices[p[1]], ma.vertices[p[2]],
                                                             mb.vertices[q[0]], mb.vertices[q[1]], mb.vertices[q[2]],
                                                             R, T))
        return {{s, (*tb)[k]}};
    }
  }
  return {{-1, -1}};
}

}  // namespace

void HullMesh::measure() const {
  if (!vertices || num_vertices <= 0) return;
  std::vector<Eigen::Vector3d> all(vertices, vertices + num_vertices);
  for (const auto& v : all)
    if (!v.allFinite()) return;  // no support points: is_mesh is false
  support_points(all, points_);
  if (!tri_indices || num_tris <= 0) return;
  balls_.resize(num_tris);
  for (int t = 0; t < num_tris; ++t) {
    const fcl::Triangle& f = tri_indices[t];
    balls_[t] = holding_ball(3, [&](std::size_t k) { return all[f[k]]; });
  }
}

void HullMesh::split() const {
  if (hull_points().x.empty() || !tri_indices || num_tris <= 0) return;
  std::vector<int> order(num_tris);
  for (int t = 0; t < num_tris; ++t) order[t] = t;
  auto centroid = [&](int t) {
    const fcl::Triangle& f = tri_indices[t];
    return Eigen::Vector3d((vertices[f[0]] + vertices[f[1]] + vertices[f[2]]) / 3.0);
  };
  // Ranges of `order`, split at the median along the longest axis of their centroids' box.
  std::vector<std::pair<int, int>> ranges = {{0, num_tris}};
  while (static_cast<int>(ranges.size()) < kMeshPieces) {
    std::vector<std::pair<int, int>> next;
    for (auto [lo, hi] : ranges) {
      if (hi - lo < 2) {
        next.push_back({lo, hi});
        continue;
      }
      Eigen::Vector3d bmin = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), bmax = -bmin;
      for (int i = lo; i < hi; ++i) {
        bmin = bmin.cwiseMin(centroid(order[i]));
        bmax = bmax.cwiseMax(centroid(order[i]));
      }
      Eigen::Index axis = 0;
      (bmax - bmin).maxCoeff(&axis);
      const int mid = (lo + hi) / 2;
      std::nth_element(order.begin() + lo, order.begin() + mid, order.begin() + hi,
                       [&](int x, int y) { return centroid(x)[axis] < centroid(y)[axis]; });
      next.push_back({lo, mid});
      next.push_back({mid, hi});
    }
    if (next.size() == ranges.size()) break;
    ranges.swap(next);
  }
  for (auto [lo, hi] : ranges) {
    std::vector<Eigen::Vector3d> pts;
    for (int i = lo; i < hi; ++i)
      for (int k = 0; k < 3; ++k) pts.push_back(vertices[tri_indices[order[i]][k]]);
    Piece piece;
    support_points(pts, piece.points);
    piece.triangles.assign(order.begin() + lo, order.begin() + hi);
    pieces_.push_back(std::move(piece));
  }
}

const HullMesh* hull_mesh(const fcl::CollisionGeometryd& g) {
  if (g.getObjectType() != fcl::OT_BVH || g.getNodeType() != fcl::BV_OBBRSS || typeid(g) != typeid(HullMesh))
    return nullptr;
  const auto* m = static_cast<const HullMesh*>(&g);
  const bool triangles = m->getModelType() == fcl::BVH_MODEL_TRIANGLES && m->tri_indices && m->num_tris > 0;
  // No support points: a vertex is not finite, and planes prove nothing; FCL decides.
  return triangles && m->vertices && m->num_vertices > 0 && !m->hull_points().x.empty() ? m : nullptr;
}

bool is_mesh(const fcl::CollisionGeometryd& g) { return hull_mesh(g) != nullptr; }

MeshVerdict mesh_witness_verdict(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                                 const Pose& tb, MeshPairWitness& witness) {
  const Mesh& ma = *hull_mesh(a);
  const Mesh& mb = *hull_mesh(b);
  // Cheapest first: the old separating direction (two passes over the vertices), then the old
  // triangle pairs.
  if (witness.axis.squaredNorm() > 0 &&
      apart_by(Placed{ma.hull_points(), ta.linear(), ta.translation()},
               Placed{mb.hull_points(), tb.linear(), tb.translation()}, witness.axis))
    return MeshVerdict::apart;
  // A witness only ever saves work: one kept under a key the caller reused for other meshes is still
  // a valid test of these meshes once its triangle indices are in range. The pairs are kept newest
  // (or last confirmed) first.
  if (witness.triangles[0][0] < 0) return MeshVerdict::unknown;
  // FCL's leaf test (mesh_collision_traversal_node-inl.h): b's triangle moved into a's frame by the
  // relative transform FCL's traversal node computes.
  fcl::Matrix3d R;
  fcl::Vector3d T;
  fcl_relative(ta, tb, R, T);
  auto& tris = witness.triangles;
  const auto& balls_a = ma.triangle_balls();
  const auto& balls_b = mb.triangle_balls();
  for (std::size_t k = 0; k < tris.size(); ++k) {
    const int ia = tris[k][0], ib = tris[k][1];
    if (ia < 0 || ia >= ma.num_tris || ib < 0 || ib >= mb.num_tris) continue;  // another mesh's witness
    // Most kept pairs have moved apart: their balls show it at a tenth of the triangle test's cost.
    const Eigen::Vector4d& x = balls_a[ia];
    const Eigen::Vector4d& y = balls_b[ib];
    const double reach = x[3] + y[3];
    if ((R * y.head<3>() + T - x.head<3>()).squaredNorm() > reach * reach) continue;
    const fcl::Triangle& p = ma.tri_indices[ia];
    const fcl::Triangle& q = mb.tri_indices[ib];
    if (fcl::detail::Intersect<double>::intersect_Triangle(ma.vertices[p[0]], ma.vertices[p[1]], ma.vertices[p[2]],
                                                           mb.vertices[q[0]], mb.vertices[q[1]], mb.vertices[q[2]],
                                                           R, T)) {
      std::rotate(tris.begin(), tris.begin() + k, tris.begin() + k + 1);  // the last hit first
      return MeshVerdict::touching;
    }
  }
  return MeshVerdict::unknown;
}

bool meshes_hulls_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                        const Pose& tb, MeshPairWitness& witness) {
  const Placed A{hull_mesh(a)->hull_points(), ta.linear(), ta.translation()};
  const Placed B{hull_mesh(b)->hull_points(), tb.linear(), tb.translation()};
  return gjk_apart(A, B, a.aabb_local.center(), b.aabb_local.center(), witness.axis);
}

bool meshes_pieces_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                         const Pose& tb, MeshPairWitness& witness) {
  const Mesh& ma = *hull_mesh(a);
  const Mesh& mb = *hull_mesh(b);
  const auto& pa = ma.pieces();
  const auto& pb = mb.pieces();
  if (pa.size() < 2 && pb.size() < 2) return false;  // a piece is the whole hull, already tested
  auto placed = [](const HullMesh::Points& p, const Pose& t) { return Placed{p, t.linear(), t.translation()}; };
  auto apart = [&](const Placed& x, const Eigen::Vector3d& cx, const Placed& y, const Eigen::Vector3d& cy) {
    Eigen::Vector3d axis;
    return gjk_apart(x, y, cx, cy, axis);
  };
  auto& hint = witness.pieces;
  if (hint[0] >= 0 && hint[0] < static_cast<int>(pa.size()) && hint[1] < static_cast<int>(pb.size()) &&
      !apart(placed(pa[hint[0]].points, ta), pa[hint[0]].points.centre,
             hint[1] < 0 ? placed(mb.hull_points(), tb) : placed(pb[hint[1]].points, tb),
             hint[1] < 0 ? Eigen::Vector3d(b.aabb_local.center()) : pb[hint[1]].points.centre))
    return false;
  const Placed B = placed(mb.hull_points(), tb);
  for (std::size_t i = 0; i < pa.size(); ++i) {
    const Placed A = placed(pa[i].points, ta);
    Eigen::Vector3d& kept = witness.piece_axes[i];
    if (kept.squaredNorm() > 0 && apart_by(A, B, kept)) continue;
    if (gjk_apart(A, B, pa[i].points.centre, b.aabb_local.center(), kept)) continue;
    kept.setZero();
    if (pb.size() < 2) {
      hint = {{static_cast<int>(i), -1}};
      return false;
    }
    for (std::size_t k = 0; k < pb.size(); ++k)
      if (!apart(A, pa[i].points.centre, placed(pb[k].points, tb), pb[k].points.centre)) {
        hint = {{static_cast<int>(i), static_cast<int>(k)}};
        return false;
      }
  }
  return true;
}

bool meshes_fcl_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                        const Pose& tb, MeshPairWitness& witness) {
  auto keep = [&](std::array<int, 2> pair) {
    std::rotate(witness.triangles.begin(), witness.triangles.end() - 1, witness.triangles.end());
    witness.triangles[0] = pair;
    return true;
  };
  const Mesh* ma = hull_mesh(a);
  const Mesh* mb = hull_mesh(b);
  const auto& hint = witness.pieces;
  if (ma && mb && hint[0] >= 0 && hint[0] < static_cast<int>(ma->pieces().size()) &&
      hint[1] < static_cast<int>(mb->pieces().size())) {
    fcl::Matrix3d R;
    fcl::Vector3d T;
    fcl_relative(ta, tb, R, T);
    const std::array<int, 2> pair = piece_pair_touch(*ma, hint[0], *mb, hint[1], R, T);
    if (pair[0] >= 0) return keep(pair);
  }
  const fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  if (fcl::collide(&a, fa, &b, fb, request, result) == 0) return false;
  return keep({{static_cast<int>(result.getContact(0).b1), static_cast<int>(result.getContact(0).b2)}});
}

bool meshes_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                    const Pose& tb, MeshPairWitness& witness) {
  const MeshVerdict v = mesh_witness_verdict(a, ta, b, tb, witness);
  if (v != MeshVerdict::unknown) return v == MeshVerdict::touching;
  if (meshes_hulls_apart(a, ta, b, tb, witness) || meshes_pieces_apart(a, ta, b, tb, witness)) return false;
  return meshes_fcl_collide(a, ta, b, tb, witness);
}

bool hulls_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                 const Pose& tb, Eigen::Vector3d& axis) {
  const Mesh* ma = hull_mesh(a);
  const Mesh* mb = hull_mesh(b);
  if (!ma || !mb) return false;
  const Placed A{ma->hull_points(), ta.linear(), ta.translation()};
  const Placed B{mb->hull_points(), tb.linear(), tb.translation()};
  if (axis.squaredNorm() > 0 && apart_by(A, B, axis)) return true;
  return gjk_apart(A, B, a.aabb_local.center(), b.aabb_local.center(), axis);
}

}  // namespace octoreach::detail
