#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "octoreach/capability_map.hpp"
#include "octoreach/point_map.hpp"
#include "octoreach/pose_sampler.hpp"
#include "octoreach/surface_map.hpp"

using namespace octoreach;

namespace {
const std::string kArm = std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf";

struct Fixture {
  std::shared_ptr<Robot> robot = Robot::from_urdf(kArm);
  Chain chain = robot->chain("base_link", "tool0");
  CapabilityMap cap = [this] {
    CapabilityMapOptions o;
    o.resolution = 0.15;
    o.directions = 24;
    o.seed = 1;
    return CapabilityMap::build(chain, o);
  }();
};

Fixture& fixture() {
  static Fixture f;
  return f;
}
}  // namespace

TEST(Surface, RejectsBadPolygons) {
  EXPECT_THROW(Surface({{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(Surface({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3}, {0, 1, 0}}), std::invalid_argument);
  EXPECT_THROW(Surface({{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}), std::invalid_argument);
  EXPECT_THROW(Surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(Surface({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, 0.0), std::invalid_argument);
}

TEST(Surface, SamplesThePapersGrid) {
  Surface table = Surface::rectangle(1.4, 0.65, 0.72);
  EXPECT_EQ(table.sample_points(0.05).size(), 364u);  // 28 x 13, as in the paper
  EXPECT_EQ(table.sample_points(0.1).size(), 84u);    // 14 x 6
  EXPECT_NEAR(table.area(), 1.4 * 0.65, 1e-12);
  EXPECT_TRUE(table.convex());
}

TEST(PointMap, GridEqualsDirectEvaluation) {
  auto& f = fixture();
  PointMapOptions o;
  InversePointMap pm = InversePointMap::build(*f.robot, f.cap, o);
  std::vector<Eigen::Vector3d> c;
  std::vector<float> v;
  pm.map().voxels(c, v);
  ASSERT_FALSE(c.empty());
  for (std::size_t i = 0; i < c.size(); i += 7)
    for (int k = 0; k < 16; k += 3) {
      double th = 2 * M_PI * k / 16;
      double direct = InversePointMap::direct_reachability(f.cap, pm.reference_to_arm(), pm.grasp_orientations(),
                                                           c[i].x(), c[i].y(), c[i].z(), th);
      EXPECT_NEAR(pm.reachability(c[i].x(), c[i].y(), c[i].z(), th), direct, 1e-6);
    }
}

TEST(SurfaceMap, BuildsSavesLoadsAndSamples) {
  auto& f = fixture();
  Surface table = Surface::rectangle(0.6, 0.4, 0.4, 0.55);
  SurfaceMapOptions o;
  o.z_min = o.z_max = 0.0;
  SurfaceMap sm = SurfaceMap::build(*f.robot, f.cap, table, o);
  ASSERT_GT(sm.map().voxel_count(), 0u);
  EXPECT_GT(sm.map().max_value(), 0.2);
  EXPECT_LE(sm.map().max_value(), 1.0);
  EXPECT_EQ(sm.reachability(0.55, 0.0, 0.0, 0.0), 0.0);  // under the table
  EXPECT_EQ(sm.reachability(5.0, 5.0, 0.0, 0.0), 0.0);   // far away
  const std::string path = ::testing::TempDir() + "/octoreach_surface.orsm";
  sm.save(path);
  SurfaceMap back = SurfaceMap::load(path);
  std::vector<Eigen::Vector3d> c1, c2;
  std::vector<float> v1, v2;
  sm.map().voxels(c1, v1);
  back.map().voxels(c2, v2);
  EXPECT_EQ(v1, v2);
  {  // a truncated copy is refused with a message
    std::ifstream in(path, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream out(path + ".cut", std::ios::binary);
    out.write(data.data(), data.size() / 2);
  }
  EXPECT_THROW(SurfaceMap::load(path + ".cut"), FileError);
  std::remove(path.c_str());
  std::remove((path + ".cut").c_str());

  auto shared = std::make_shared<const SurfaceMap>(sm);
  PoseSampler sampler(shared);
  for (int i = 0; i < 5; ++i) {
    auto pose = sampler.sample();
    ASSERT_TRUE(pose.has_value());
    EXPECT_GT(sm.reachability((*pose)[0], (*pose)[1], (*pose)[2], (*pose)[3]), 0.0);
    EXPECT_EQ((*pose)[2], 0.0);
  }
  EXPECT_EQ(sampler.history().size(), 5u);
}
