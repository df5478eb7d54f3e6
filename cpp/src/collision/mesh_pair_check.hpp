#pragma once
// Internal: the collision check of two triangle meshes with witnesses kept from the last check of the
// same shape pair, so that most checks need no FCL narrow phase. The answer is FCL's, always:
//  - touching: the triangle pairs FCL found intersecting lately (the last 16) are tested, with FCL's
//    own triangle test on FCL's own relative transform; if one still intersects, FCL's traversal
//    (which reaches every intersecting triangle pair) would report a collision too. A pair whose
//    triangles' balls are apart is skipped: those triangles cannot meet.
//  - apart: FCL's mesh-mesh collision intersects triangles, and every triangle lies in the convex hull
//    of its mesh's vertices. If a plane separates the two vertex sets by more than kHullMargin, no
//    triangle pair can meet. The plane's normal is the one that separated the pair last time, else
//    GJK (Gilbert-Johnson-Keerthi) on the vertex sets finds one; either way the plane is checked by
//    projecting both vertex sets on its normal, so the answer rests on that check alone, never on
//    GJK's arithmetic.
//  - apart, closer: the same argument on the mesh's convex pieces (HullMesh::pieces), whose hulls hug a
//    concave mesh closer than its whole hull: every piece of one mesh apart from the other's hull or from
//    each of its pieces.
//  - touching, found: the triangles of the piece pair that overlapped (one piece of each mesh, a few dozen
//    triangles) tested pairwise with FCL's triangle test, pairs whose boxes are apart skipped; a pair that
//    intersects is one FCL's traversal reaches too.
//  - otherwise (no such pair intersects): FCL decides, and the triangle pair of its hit, if any, joins the
//    witnesses.
// Order: the kept plane (two passes over the vertices), the kept triangle pairs, GJK on the hulls, the
// pieces, the overlapping pieces' triangles, FCL.
// Consecutive checks are of neighbouring configurations, so the witnesses usually still hold. They
// are per thread (the caller keeps them): a witness only ever changes the cost of a check.
#include <array>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

#include <fcl/fcl.h>

#include "octoreach/types.hpp"

namespace octoreach::detail {

/// Gap (m) a separating plane needs: FCL's triangle test is exact, this only absorbs rounding.
constexpr double kHullMargin = 1e-6;

/// Pieces a mesh is split into (HullMesh::pieces). On the PR2 arm's map build, 16 rather than 8 leave FCL 23k
/// instead of 40k pairs whose pieces overlap while the meshes do not.
constexpr int kMeshPieces = 16;

/// What decided the last check of one shape pair.
struct MeshPairWitness {
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  // separating direction (world, from b to a); zero: none
  static constexpr int kTriangles = 16;
  // Intersecting triangle pairs ({a's, b's}) FCL found lately, the last confirmed first; -1: none.
  // (One pair alone confirmed a fifth of the PR2 map build's collisions, sixteen half of them.)
  std::array<std::array<int, 2>, kTriangles> triangles = none();
  // The meshes' pieces (HullMesh::pieces): the piece pair ({a's, b's}, b's -1 for its hull) that overlapped
  // last, -1: none; per piece of a, the direction that separated it from b's hull last (zero: none).
  std::array<int, 2> pieces = {{-1, -1}};
  std::array<Eigen::Vector3d, kMeshPieces> piece_axes = zeros();

 private:
  static std::array<Eigen::Vector3d, kMeshPieces> zeros() {
    std::array<Eigen::Vector3d, kMeshPieces> z;
    for (auto& x : z) x.setZero();
    return z;
  }
  static std::array<std::array<int, 2>, kTriangles> none() {
    std::array<std::array<int, 2>, kTriangles> t;
    for (auto& x : t) x = {{-1, -1}};
    return t;
  }
};

/// Witnesses per shape pair, under keys the caller chooses.
class MeshPairWitnesses {
 public:
  MeshPairWitness& of(std::uint64_t key) { return witnesses_[key]; }
  /// A key for shape `i` of link `a` against shape `k` of link `b`.
  static std::uint64_t key(int a, std::size_t i, int b, std::size_t k) {
    return (static_cast<std::uint64_t>(a) << 44) ^ (static_cast<std::uint64_t>(b) << 24) ^ (i << 12) ^ k;
  }

 private:
  std::unordered_map<std::uint64_t, MeshPairWitness> witnesses_;
};

/// The library's triangle meshes (collision.cpp builds every mesh as one): an FCL BVHModel<OBBRSS> that
/// also keeps the support points of its convex hull, the vertices a separating-plane test scans. They
/// are the vertices not clearly inside the hull's facets (libqhull_r; more than 1e-9 m inside every
/// facet plane), so that the hull of the points kept is the hull of all vertices: on the PR2, 24 of 50
/// vertices (base) to 74 of 172 (forearm). Measured at the first use, once (thread-safe); the library
/// never updates a mesh's vertices after building it (FCL's update calls would leave these stale).
class HullMesh : public fcl::BVHModel<fcl::OBBRSSd> {
 public:
  /// Coordinate columns of the support points, and a ball that holds them all (centre: the centre of their box,
  /// which is the box of all the vertices they stand for; radius).
  struct Points {
    std::vector<double> x, y, z;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0.0;
  };
  const Points& hull_points() const {
    std::call_once(once_, [this] { measure(); });
    return points_;
  }
  /// Per triangle, a ball that holds it (centre xyz, radius w; mesh frame): two triangles whose balls are apart
  /// cannot meet, which rules out a kept triangle pair without FCL's triangle test.
  const std::vector<Eigen::Vector4d>& triangle_balls() const {
    std::call_once(once_, [this] { measure(); });
    return balls_;
  }
  /// The mesh's triangles split into up to kMeshPieces spatially compact pieces (medians of the triangles'
  /// centroids along the longest axis, four times), each with its hull's support points and its triangles: every
  /// triangle lies in its piece's hull, which hugs a concave mesh closer than the whole hull.
  struct Piece {
    Points points;
    std::vector<int> triangles;  // indices into tri_indices
  };
  const std::vector<Piece>& pieces() const {
    std::call_once(pieces_once_, [this] { split(); });
    return pieces_;
  }

 private:
  void measure() const;
  void split() const;
  mutable std::once_flag once_, pieces_once_;
  mutable Points points_;
  mutable std::vector<Eigen::Vector4d> balls_;
  mutable std::vector<Piece> pieces_;
};

/// `g` as a HullMesh of triangles with support points (the geometries meshes_collide handles), or null.
const HullMesh* hull_mesh(const fcl::CollisionGeometryd& g);

/// True when `g` is a geometry meshes_collide handles: a HullMesh of triangles.
bool is_mesh(const fcl::CollisionGeometryd& g);

/// A mesh's hull support points at a world pose (the support function GJK and the plane checks read).
struct PlacedHull {
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
  // At least reach(d), from the ball that holds the points: no pass over them.
  double reach_bound(const Eigen::Vector3d& d) const { return d.dot(R * p.centre + t) + p.radius * d.norm(); }
};

/// FCL's answer for two meshes (both is_mesh) at world poses, using and refreshing `witness`: the
/// witnesses' verdict if they give one, else GJK on the hulls (meshes_hulls_apart), else the pieces
/// (meshes_pieces_apart), else FCL (meshes_fcl_collide).
bool meshes_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                    const Pose& tb, MeshPairWitness& witness);

/// What the witnesses alone say of two meshes (the kept plane, then the kept triangle pairs): FCL's
/// answer when they decide, unknown otherwise. A check of many pairs can ask every pair this first and
/// leave the costly steps to the pairs it leaves open: a configuration that collides is then often
/// confirmed without FCL.
enum class MeshVerdict { apart, touching, unknown };
MeshVerdict mesh_witness_verdict(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                                 const Pose& tb, MeshPairWitness& witness);
/// The steps after the witnesses: GJK on the hulls (true: apart, the plane kept), else nothing decided.
bool meshes_hulls_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                        const Pose& tb, MeshPairWitness& witness);
/// True when the meshes' pieces prove them apart: every piece of `a` is apart from `b`'s hull or from each
/// of `b`'s pieces (a triangle lies in its piece's hull, so no triangle pair can meet). The piece pair that
/// overlapped last is tried first (witness), so that a pair in contact is handed to FCL after one test.
bool meshes_pieces_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                         const Pose& tb, MeshPairWitness& witness);
/// FCL's narrow phase, the triangle pair of its hit joining the witnesses. The triangles of the piece pair that
/// overlapped last (the witness's) are tested first, with FCL's own triangle test: a pair that intersects there is
/// a hit FCL's traversal would find too, and FCL runs only when none does.
bool meshes_fcl_collide(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                        const Pose& tb, MeshPairWitness& witness);

/// True when the convex hulls of the vertices of meshes `a` (at world pose `ta`) and `b` (at `tb`) are
/// more than kHullMargin apart along some direction, which is then returned in `axis` (unit, world
/// frame, pointing from b to a). `axis` on input: a direction to try first (zero: none).
bool hulls_apart(const fcl::CollisionGeometryd& a, const Pose& ta, const fcl::CollisionGeometryd& b,
                 const Pose& tb, Eigen::Vector3d& axis);

}  // namespace octoreach::detail
