// Surface maps record their room (obstacles and body) in their files; the sampler keeps the body out of it.
#include <gtest/gtest.h>

#include <cstdio>

#include "octoreach/map_files.hpp"
#include "octoreach/pose_sampler.hpp"

using namespace octoreach;

namespace {
const std::string kArm = std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf";

Pose at(double x, double y, double z) {
  Pose T = Pose::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}
}  // namespace

TEST(MapRoom, RecordedSavedAndChecked) {
  auto robot = Robot::from_urdf(kArm);
  CapabilityMapOptions co;
  co.resolution = 0.15;
  co.directions = 24;
  const CapabilityMap cap = CapabilityMap::build(robot->chain("base_link", "tool0"), co);
  auto room = std::make_shared<Obstacles>();
  room->add(Shape::box(Eigen::Vector3d(0.3, 0.3, 0.6), at(-0.5, 0.0, 0.3)), "crate");
  room->add(Shape::cylinder(0.1, 0.5, at(0.0, -0.7, 0.25)), "bin");
  SurfaceMapOptions so;
  so.theta_bins = 8;
  so.obstacles = room;
  Surface table = Surface::rectangle(0.6, 0.4, 0.4, 0.55);
  table.add_legs(0.05);
  auto sm = std::make_shared<SurfaceMap>(SurfaceMap::build(*robot, cap, table, so));
  ASSERT_EQ(sm->room().surface_count(), 2u + 4u);
  ASSERT_EQ(sm->room().obstacles().size(), 8u);
  ASSERT_FALSE(sm->room().body().empty());
  EXPECT_TRUE(sm->room().body_collides(Eigen::Vector4d(-0.5, 0.0, 0.0, 0.0)));
  EXPECT_EQ(sm->room().touched(Eigen::Vector4d(-0.5, 0.0, 0.0, 0.0), sm->room().obstacles()), 6);

  const std::string path = ::testing::TempDir() + "/octoreach_map_room.orsm";
  sm->save(path);
  const SurfaceMap loaded = SurfaceMap::load(path);
  EXPECT_TRUE(loaded.room().differences(sm->room().obstacles()).empty());
  EXPECT_EQ(loaded.room().obstacles().names(), sm->room().obstacles().names());
  EXPECT_EQ(loaded.room().body_links(), sm->room().body_links());
  EXPECT_EQ(loaded.room().surface_count(), sm->room().surface_count());
  EXPECT_TRUE(loaded.room().body_collides(Eigen::Vector4d(-0.5, 0.0, 0.0, 0.0)));
  EXPECT_EQ(map_kinds()[2].format_version, 2);
  EXPECT_EQ(map_kinds()[0].format_version, 3);  // capability maps: 2 (mixed cells and quality), 3 with poles
  EXPECT_EQ(map_kinds()[1].format_version, 1);  // point maps: unchanged payload
  EXPECT_EQ(map_format_version(), 3);

  PoseSamplerOptions po;
  po.seed = 3;
  PoseSampler sampler(sm, po);
  ASSERT_TRUE(sampler.checks_room());
  for (int i = 0; i < 20; ++i) {
    auto p = sampler.sample();
    ASSERT_TRUE(p.has_value());
    EXPECT_FALSE(sm->room().body_collides(*p));
  }
  po.room_check = false;
  EXPECT_FALSE(PoseSampler(sm, po).checks_room());
  std::remove(path.c_str());
}

TEST(MapRoom, DifferencesNameTheObstacle) {
  Obstacles a, b;
  a.add(Shape::box(Eigen::Vector3d(1, 1, 1), at(0, 0, 0.5)), "cabinet");
  b.add(Shape::box(Eigen::Vector3d(1, 1, 1), at(0.2, 0, 0.5)), "cabinet");
  const MapRoom room(a, 0, {}, {});
  const std::vector<std::string> d = room.differences(b);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NE(d[0].find("box 'cabinet'"), std::string::npos);
  EXPECT_TRUE(room.differences(a).empty());
  EXPECT_THROW(MapRoom(a, 2, {}, {}), std::invalid_argument);
}
