// Obstacles::collides runs an oriented-box pre-test (cpp/src/maps/obb.hpp) before FCL: it must answer
// exactly as FCL alone on every configuration, touching or not.
#include <random>

#include <fcl/fcl.h>
#include <gtest/gtest.h>

#include "collision/detail.hpp"
#include "collision/obb.hpp"
#include "octoreach/collision.hpp"

using namespace octoreach;

namespace {

Pose random_pose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  Pose p = Pose::Identity();
  p.linear() = q.normalized().toRotationMatrix();
  p.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return p;
}

// An irregular closed mesh: an octahedron with jittered vertices, offset from its frame's origin.
std::shared_ptr<fcl::CollisionGeometryd> random_mesh(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.05, 0.25), o(-0.1, 0.1);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> v(6, 3);
  const Eigen::Vector3d off(o(rng), o(rng), o(rng));
  v << u(rng), 0, 0, -u(rng), 0, 0, 0, u(rng), 0, 0, -u(rng), 0, 0, 0, u(rng), 0, 0, -u(rng);
  for (int i = 0; i < 6; ++i) v.row(i) += off.transpose();
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> t(8, 3);
  t << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return make_mesh(v, t);
}

std::shared_ptr<fcl::CollisionGeometryd> random_geometry(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<double> s(0.02, 0.4);
  std::shared_ptr<fcl::CollisionGeometryd> g;
  switch (kind % 4) {
    case 0: g = std::make_shared<fcl::Boxd>(s(rng), s(rng), s(rng)); break;
    case 1: g = std::make_shared<fcl::Cylinderd>(0.5 * s(rng), s(rng)); break;
    case 2: g = std::make_shared<fcl::Sphered>(0.5 * s(rng)); break;
    default: g = random_mesh(rng); break;
  }
  g->computeLocalAABB();
  return g;
}

}  // namespace

TEST(Obstacles, BoxPreTestAnswersAsFclAlone) {
  std::mt19937 rng(7);
  int touching = 0, apart = 0;
  for (int scene = 0; scene < 40; ++scene) {
    Obstacles obs;
    std::vector<std::shared_ptr<fcl::CollisionGeometryd>> geoms;
    std::vector<Pose> poses;
    for (int i = 0; i < 4; ++i) {
      geoms.push_back(random_geometry(rng, scene + i));
      poses.push_back(random_pose(rng, 0.3));
      obs.add_geometry(geoms.back(), poses.back());
    }
    for (int q = 0; q < 150; ++q) {
      auto g = random_geometry(rng, q);
      const Pose p = random_pose(rng, 0.5);
      bool fcl_alone = false;
      for (std::size_t i = 0; i < geoms.size() && !fcl_alone; ++i)
        fcl_alone = detail::geometry_collide(g.get(), p, geoms[i].get(), poses[i]);
      ASSERT_EQ(obs.collides(*g, p), fcl_alone) << "scene " << scene << " query " << q;
      (fcl_alone ? touching : apart)++;
    }
  }
  // Both answers occur often: the test is not between empty scenes or one solid block.
  EXPECT_GT(touching, 1000);
  EXPECT_GT(apart, 1000);
}

TEST(Obstacles, OrientedBoxesApartNeverTouch) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> s(0.01, 0.5);
  int apart = 0;
  for (int i = 0; i < 20000; ++i) {
    fcl::Boxd a(s(rng), s(rng), s(rng)), b(s(rng), s(rng), s(rng));
    a.computeLocalAABB();
    b.computeLocalAABB();
    const Pose pa = random_pose(rng, 0.3), pb = random_pose(rng, 0.3);
    if (!detail::Obb::of(a, pa).apart(detail::Obb::of(b, pb))) continue;
    ++apart;
    ASSERT_FALSE(detail::geometry_collide(&a, pa, &b, pb)) << "configuration " << i;
  }
  EXPECT_GT(apart, 2000);
}
