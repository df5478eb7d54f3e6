// The mesh-pair check with witnesses (cpp/src/mesh_pair_check.hpp): it answers as FCL's narrow phase,
// whatever its witnesses hold, and its separating planes do separate the vertex sets.
#include <gtest/gtest.h>

#include <random>

#include "collision/detail.hpp"
#include "collision/mesh_pair_check.hpp"
#include "octoreach/collision.hpp"
#include "random_shapes.hpp"

using namespace octoreach;
using test::random_pose;
using test::soup;

namespace {

// The vertices of a mesh at a pose, projected on d: [min, max].
std::pair<double, double> extent(const fcl::CollisionGeometryd& g, const Pose& T, const Eigen::Vector3d& d) {
  const auto& m = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(g);
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i < m.num_vertices; ++i) {
    const double s = d.dot(T * m.vertices[i]);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

}  // namespace

TEST(MeshPairCheck, AnswersAsFclAlongAPath) {
  // Two soups moving in small steps (the witnesses of one step mostly decide the next) through
  // touching, overlapping hulls without contact, and clear separation.
  std::mt19937_64 rng(11);
  auto a = soup(rng, 40, 0.15), b = soup(rng, 60, 0.12);
  ASSERT_TRUE(detail::is_mesh(*a));
  detail::MeshPairWitness witness;
  Pose ta = random_pose(rng, 0.1), tb = random_pose(rng, 0.1);
  std::normal_distribution<double> step(0.0, 1.0);
  int hits = 0, misses = 0, kept_axis = 0, kept_triangles = 0;
  for (int i = 0; i < 6000; ++i) {
    // Drift b around a: a slow orbit of radius 0.05-0.5 m plus small random turns.
    const double phase = 0.002 * i, radius = 0.275 + 0.225 * std::sin(7 * phase);
    tb.translation() = radius * Eigen::Vector3d(std::cos(phase * 5), std::sin(phase * 3), std::sin(phase * 2));
    tb.linear() = tb.linear() * Eigen::AngleAxisd(0.02 * step(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                  Eigen::AngleAxisd(0.02 * step(rng), Eigen::Vector3d::UnitX()).toRotationMatrix();
    const detail::MeshPairWitness before = witness;
    const bool fcl = detail::geometry_collide(a.get(), ta, b.get(), tb);
    ASSERT_EQ(detail::meshes_collide(*a, ta, *b, tb, witness), fcl) << "step " << i;
    fcl ? ++hits : ++misses;
    kept_axis += !fcl && before.axis.squaredNorm() > 0 && before.axis == witness.axis;
    kept_triangles += fcl && before.triangles[0][0] >= 0 && before.triangles == witness.triangles;
    Eigen::Vector3d axis = before.axis;
    if (detail::hulls_apart(*a, ta, *b, tb, axis)) {
      // A plane claimed separates the vertex sets (b on the negative side), and FCL agrees.
      EXPECT_FALSE(fcl) << "step " << i;
      const auto ea = extent(*a, ta, axis), eb = extent(*b, tb, axis);
      EXPECT_GT(ea.first - eb.second, detail::kHullMargin * 0.999) << "step " << i;
    }
  }
  // The path means something: both answers, and witnesses that carried over.
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 300);
  EXPECT_GT(kept_axis, 300);
  EXPECT_GT(kept_triangles, 30);
}

TEST(MeshPairCheck, AnyWitnessGivesFclsAnswer) {
  // Witnesses from other meshes, other poses or out of range (a reused key) change no answer.
  std::mt19937_64 rng(5);
  auto a = soup(rng, 30, 0.1), b = soup(rng, 30, 0.1), c = soup(rng, 200, 0.1);
  std::uniform_int_distribution<int> tri(-3, 260);
  for (int i = 0; i < 3000; ++i) {
    const Pose ta = random_pose(rng, 0.15), tb = random_pose(rng, 0.15);
    detail::MeshPairWitness w;
    if (i % 3 == 0) detail::meshes_collide(*c, random_pose(rng, 0.15), *c, random_pose(rng, 0.15), w);
    if (i % 3 == 1) {
      for (auto& t : w.triangles) t = {{tri(rng), tri(rng)}};
      w.axis = random_pose(rng, 1.0).translation();
    }
    const bool fcl = detail::geometry_collide(a.get(), ta, b.get(), tb);
    EXPECT_EQ(detail::meshes_collide(*a, ta, *b, tb, w), fcl) << "pose " << i;
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    if (detail::hulls_apart(*a, ta, *b, tb, axis)) {
      EXPECT_FALSE(fcl) << "pose " << i;
      const auto ea = extent(*a, ta, axis), eb = extent(*b, tb, axis);
      EXPECT_GT(ea.first - eb.second, detail::kHullMargin * 0.999) << "pose " << i;
    }
  }
}

TEST(MeshPairCheck, HullsApartFindsSeparatedHulls) {
  // Two unit-ish soups shifted apart along a random direction by more than their extents: GJK finds a
  // plane from any start; shifted into each other, no plane is claimed.
  std::mt19937_64 rng(9);
  auto a = soup(rng, 25, 0.1), b = soup(rng, 25, 0.1);
  int found = 0;
  for (int i = 0; i < 500; ++i) {
    Pose ta = random_pose(rng, 0.0), tb = random_pose(rng, 0.0);
    const Eigen::Vector3d dir = random_pose(rng, 1.0).translation().normalized();
    ta.translation() = 1.0 * dir;
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    found += detail::hulls_apart(*a, ta, *b, tb, axis);
    tb.translation() = ta.translation();  // same centre: the hulls overlap
    Eigen::Vector3d none = Eigen::Vector3d::Zero();
    EXPECT_FALSE(detail::hulls_apart(*a, ta, *b, tb, none)) << "pose " << i;
  }
  EXPECT_EQ(found, 500);
}

TEST(MeshPairCheck, HullPointsReachAsFarAsAllVertices) {
  // The support points a mesh keeps reach as far as all its vertices in every direction, and drop some; the ball
  // that holds them reaches at least as far as they do at any pose, and not much farther than the radius says.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int m = 0; m < 20; ++m) {
    auto mesh = soup(rng, 10 + 20 * m, 0.1);
    const auto& h = static_cast<const detail::HullMesh&>(*mesh);
    const auto& pts = h.hull_points();
    if (m > 5) EXPECT_LT(static_cast<int>(pts.x.size()), h.num_vertices);
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d d(g(rng), g(rng), g(rng));
      double all = -1e300, kept = -1e300;
      for (int i = 0; i < h.num_vertices; ++i) all = std::max(all, d.dot(h.vertices[i]));
      for (std::size_t i = 0; i < pts.x.size(); ++i) kept = std::max(kept, d.dot(Eigen::Vector3d(pts.x[i], pts.y[i], pts.z[i])));
      EXPECT_GE(kept, all - 1e-12 * d.norm()) << "mesh " << m;
      const Pose T = random_pose(rng, 0.5);
      const detail::PlacedHull placed{pts, T.linear(), T.translation()};
      const double bound = placed.reach_bound(d), reach = placed.reach(d);
      EXPECT_GE(bound, reach) << "mesh " << m;
      EXPECT_LE(bound, reach + 2.0 * pts.radius * d.norm() + 1e-12) << "mesh " << m;
    }
  }
}

TEST(MeshPairCheck, TriangleBallsHoldTheirTrianglesAndEveryContact) {
  // Each triangle's ball holds its vertices; at random poses, every triangle pair FCL's triangle test finds
  // intersecting has balls that meet (the witnesses skip a kept pair only when its balls are apart).
  std::mt19937_64 rng(21);
  auto a = soup(rng, 30, 0.12), b = soup(rng, 30, 0.12);
  const auto& ha = static_cast<const detail::HullMesh&>(*a);
  const auto& hb = static_cast<const detail::HullMesh&>(*b);
  for (const auto* h : {&ha, &hb}) {
    ASSERT_EQ(static_cast<int>(h->triangle_balls().size()), h->num_tris);
    for (int t = 0; t < h->num_tris; ++t)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector4d& ball = h->triangle_balls()[t];
        EXPECT_LE((h->vertices[h->tri_indices[t][k]] - ball.head<3>()).norm(), ball[3]);
      }
  }
  int contacts = 0;
  for (int i = 0; i < 300; ++i) {
    const Pose ta = random_pose(rng, 0.05), tb = random_pose(rng, 0.05);
    const fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
    fcl::Matrix3d R;
    fcl::Vector3d T;
    fcl::relativeTransform(fa.linear(), fa.translation(), fb.linear(), fb.translation(), R, T);
    for (int s = 0; s < ha.num_tris; ++s)
      for (int t = 0; t < hb.num_tris; ++t) {
        const fcl::Triangle& p = ha.tri_indices[s];
        const fcl::Triangle& q = hb.tri_indices[t];
        if (!fcl::detail::Intersect<double>::intersect_Triangle(ha.vertices[p[0]], ha.vertices[p[1]],
                                                                ha.vertices[p[2]], hb.vertices[q[0]],
                                                                hb.vertices[q[1]], hb.vertices[q[2]], R, T))
          continue;
        ++contacts;
        const Eigen::Vector4d& x = ha.triangle_balls()[s];
        const Eigen::Vector4d& y = hb.triangle_balls()[t];
        EXPECT_LE((R * y.head<3>() + T - x.head<3>()).norm(), x[3] + y[3]);
      }
  }
  EXPECT_GT(contacts, 100);
}

TEST(MeshPairCheck, PiecesHoldEveryTriangleAndProveOnlyWhatFclSays) {
  // The pieces' triangle lists split the mesh's triangles, and every triangle's vertices lie in its piece's hull
  // (the piece's support points reach as far as they do in every direction); pieces proved apart are never in
  // contact by FCL; on soups stretched along x, whose hulls hold much empty room, the pieces prove apart pairs
  // whose whole hulls overlap; where they do not, meshes_fcl_collide (the overlapping piece pair's triangles, then
  // FCL) answers as FCL, and a contact it reports is a triangle pair FCL's triangle test finds intersecting.
  std::mt19937_64 rng(13);
  std::normal_distribution<double> g(0.0, 1.0);
  auto a = soup(rng, 40, 0.15), b = soup(rng, 60, 0.12);
  for (const auto* m : {a.get(), b.get()}) {
    const auto& h = static_cast<const detail::HullMesh&>(*m);
    const auto& pieces = h.pieces();
    ASSERT_EQ(static_cast<int>(pieces.size()), detail::kMeshPieces);
    std::vector<int> piece_of(h.num_tris, -1);
    for (std::size_t k = 0; k < pieces.size(); ++k)
      for (int t : pieces[k].triangles) {
        ASSERT_TRUE(t >= 0 && t < h.num_tris);
        EXPECT_EQ(piece_of[t], -1) << "triangle " << t << " in two pieces";
        piece_of[t] = static_cast<int>(k);
      }
    for (int t = 0; t < h.num_tris; ++t) {
      ASSERT_GE(piece_of[t], 0) << "triangle " << t << " in no piece";
      int held = 0;
      for (const auto& p : {pieces[piece_of[t]]}) {
        bool all = true;
        for (int k = 0; k < 100 && all; ++k) {
          const Eigen::Vector3d d(g(rng), g(rng), g(rng));
          double reach = -1e300;
          for (std::size_t i = 0; i < p.points.x.size(); ++i)
            reach = std::max(reach, d.dot(Eigen::Vector3d(p.points.x[i], p.points.y[i], p.points.z[i])));
          for (int v = 0; v < 3; ++v) all = all && reach >= d.dot(h.vertices[h.tri_indices[t][v]]) - 1e-12;
        }
        held += all;
      }
      EXPECT_GE(held, 1) << "triangle " << t;
    }
  }
  int proved = 0, open = 0, contacts = 0;
  const auto& ha = static_cast<const detail::HullMesh&>(*a);
  const auto& hb = static_cast<const detail::HullMesh&>(*b);
  for (int i = 0; i < 3000; ++i) {
    const Pose ta = random_pose(rng, 0.3), tb = random_pose(rng, 0.3);
    detail::MeshPairWitness w;
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    if (detail::hulls_apart(*a, ta, *b, tb, axis)) continue;
    const bool fcl = detail::geometry_collide(a.get(), ta, b.get(), tb);
    open += !fcl;
    if (detail::meshes_pieces_apart(*a, ta, *b, tb, w)) {
      EXPECT_FALSE(fcl) << "pose " << i;
      ++proved;
      EXPECT_EQ(detail::meshes_collide(*a, ta, *b, tb, w), fcl) << "pose " << i;  // with the hint the test left
      continue;
    }
    ASSERT_EQ(detail::meshes_fcl_collide(*a, ta, *b, tb, w), fcl) << "pose " << i;  // the piece pair's hint
    if (!fcl) continue;
    ++contacts;
    const fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
    fcl::Matrix3d R;
    fcl::Vector3d T;
    fcl::relativeTransform(fa.linear(), fa.translation(), fb.linear(), fb.translation(), R, T);
    const fcl::Triangle& p = ha.tri_indices[w.triangles[0][0]];
    const fcl::Triangle& q = hb.tri_indices[w.triangles[0][1]];
    EXPECT_TRUE(fcl::detail::Intersect<double>::intersect_Triangle(ha.vertices[p[0]], ha.vertices[p[1]],
                                                                   ha.vertices[p[2]], hb.vertices[q[0]],
                                                                   hb.vertices[q[1]], hb.vertices[q[2]], R, T))
        << "pose " << i;
  }
  EXPECT_GT(open, 300);
  EXPECT_GT(contacts, 100);
  EXPECT_GT(5 * proved, open);  // about 30 % on these soups
}
