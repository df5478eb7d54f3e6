// The mesh-box check with witnesses (cpp/src/mesh_box_check.hpp): it answers as FCL's narrow phase
// (fcl::collide), whatever its witnesses hold, on random, grazing and penetrating poses, and the planes
// it claims do separate the vertices from the box.
#include <gtest/gtest.h>

#include <random>

#include "collision/detail.hpp"
#include "collision/mesh_box_check.hpp"
#include "octoreach/collision.hpp"
#include "random_shapes.hpp"

using namespace octoreach;
using test::random_pose;
using test::soup;

namespace {

// Smallest projection of the mesh's vertices on d minus the box's largest: > 0 when d separates them.
double gap(const fcl::CollisionGeometryd& g, const Pose& ta, const fcl::Boxd& box, const Pose& tb,
           const Eigen::Vector3d& d) {
  const auto& m = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(g);
  double lo = 1e300;
  for (int i = 0; i < m.num_vertices; ++i) lo = std::min(lo, d.dot(ta * m.vertices[i]));
  const double hi = d.dot(tb.translation()) + (tb.linear().transpose() * d).cwiseAbs().dot(0.5 * box.side);
  return lo - hi;
}

}  // namespace

TEST(MeshBoxCheck, AnswersAsFclAlongAPath) {
  // A thin long box (a table leg) moving in small steps through a soup: touching, inside the soup's
  // hull without touching a triangle, and clear of it; the witnesses of one step mostly decide the next.
  std::mt19937_64 rng(21);
  auto a = soup(rng, 60, 0.15);
  fcl::Boxd leg(Eigen::Vector3d(0.05, 0.05, 0.7));
  leg.computeLocalAABB();
  ASSERT_TRUE(detail::mesh_box_pair(*a, leg));
  detail::MeshBoxWitness witness;
  const Pose ta = random_pose(rng, 0.05);
  Pose tb = random_pose(rng, 0.0);
  std::normal_distribution<double> step(0.0, 1.0);
  int hits = 0, misses = 0, hull_overlaps = 0;
  for (int i = 0; i < 8000; ++i) {
    const double phase = 0.0015 * i, radius = 0.3 + 0.3 * std::sin(5 * phase);
    tb.translation() = radius * Eigen::Vector3d(std::cos(phase * 5), std::sin(phase * 3), 0.3 * std::sin(phase * 2));
    tb.linear() = tb.linear() * Eigen::AngleAxisd(0.03 * step(rng), Eigen::Vector3d::UnitY()).toRotationMatrix() *
                  Eigen::AngleAxisd(0.03 * step(rng), Eigen::Vector3d::UnitX()).toRotationMatrix();
    const bool fcl = detail::geometry_collide(a.get(), ta, &leg, tb);
    ASSERT_EQ(detail::mesh_box_collide(*a, ta, leg, tb, witness), fcl) << "step " << i;
    fcl ? ++hits : ++misses;
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    if (detail::mesh_box_apart(*a, ta, leg, tb, axis)) {
      EXPECT_FALSE(fcl) << "step " << i;
      EXPECT_GT(gap(*a, ta, leg, tb, axis), detail::kBoxMargin * 0.999) << "step " << i;
    } else {
      hull_overlaps += !fcl;
    }
  }
  // The path means something: both answers, and poses where only the triangles tell.
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 500);
  EXPECT_GT(hull_overlaps, 100);
}

TEST(MeshBoxCheck, AnyWitnessGivesFclsAnswer) {
  // Random poses and boxes, with witnesses from other poses, other meshes or out of range.
  std::mt19937_64 rng(8);
  auto a = soup(rng, 40, 0.1), c = soup(rng, 300, 0.1);
  std::uniform_real_distribution<double> size(0.01, 0.4);
  std::uniform_int_distribution<int> tri(-3, 320);
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    fcl::Boxd box(Eigen::Vector3d(size(rng), size(rng), size(rng)));
    box.computeLocalAABB();
    const Pose ta = random_pose(rng, 0.2), tb = random_pose(rng, 0.3);
    detail::MeshBoxWitness w;
    if (i % 3 == 0) detail::mesh_box_collide(*c, random_pose(rng, 0.2), box, random_pose(rng, 0.2), w);
    if (i % 3 == 1) {
      for (auto& t : w.triangles) t = tri(rng);
      w.axis = random_pose(rng, 1.0).translation();
    }
    const bool fcl = detail::geometry_collide(a.get(), ta, &box, tb);
    ASSERT_EQ(detail::mesh_box_collide(*a, ta, box, tb, w), fcl) << "pose " << i;
    hits += fcl;
  }
  EXPECT_GT(hits, 400);
  EXPECT_LT(hits, 3600);
}

TEST(MeshBoxCheck, GrazingAndPenetratingPosesAnswerAsFcl) {
  // A box face placed at the mesh's farthest vertex along a random direction d, then moved along d
  // by -1 mm .. +1 mm (into the mesh to clear of it; margins are 0.1 mm): the answers near contact,
  // where a loose pre-test would err.
  std::mt19937_64 rng(13);
  auto a = soup(rng, 30, 0.1);
  const auto& m = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(*a);
  fcl::Boxd box(Eigen::Vector3d(0.08, 0.05, 0.3));
  box.computeLocalAABB();
  const double offsets[] = {-1e-3, -2e-4, -1e-4, -5e-5, -1e-5, 0.0, 1e-5, 5e-5, 1e-4, 2e-4, 1e-3};
  int hits = 0, misses = 0;
  detail::MeshBoxWitness w;
  for (int i = 0; i < 600; ++i) {
    const Pose ta = random_pose(rng, 0.1);
    Pose tb = random_pose(rng, 0.0);
    const int k = i % 3;
    const Eigen::Vector3d d = tb.linear().col(k);  // the box's face -d faces the mesh
    Eigen::Vector3d p = ta * m.vertices[0];
    for (int v = 1; v < m.num_vertices; ++v)
      if (d.dot(ta * m.vertices[v]) > d.dot(p)) p = ta * m.vertices[v];
    for (double off : offsets) {
      tb.translation() = p + (0.5 * box.side[k] + off) * d;
      const bool fcl = detail::geometry_collide(a.get(), ta, &box, tb);
      ASSERT_EQ(detail::mesh_box_collide(*a, ta, box, tb, w), fcl) << "pose " << i << " offset " << off;
      detail::MeshBoxWitness fresh;
      ASSERT_EQ(detail::mesh_box_collide(*a, ta, box, tb, fresh), fcl) << "pose " << i << " offset " << off;
      fcl ? ++hits : ++misses;
    }
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 1000);
}
