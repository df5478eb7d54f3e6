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

TEST(ArmPlacement, ArmsAndReferencePosture) {
  auto& f = fixture();
  EXPECT_THROW(Arm::named(*f.robot, "no_such_arm"), std::invalid_argument);
  EXPECT_THROW(Arm::from_links(*f.robot, "base_link", "no_such_link"), std::invalid_argument);
  Arm a = Arm::from_links(*f.robot, "base_link", "tool0");
  EXPECT_EQ(a.approach_axis, Eigen::Vector3d::UnitZ());
  // No SRDF tuck states on the test arm: the default reference is home.
  EXPECT_TRUE(default_reference(*f.robot, f.chain).isApprox(f.robot->home(), 0.0));
  EXPECT_THROW(reference_or_default(*f.robot, f.chain, Eigen::VectorXd::Zero(f.robot->dof() + 1)), std::invalid_argument);
}

TEST(ArmPlacement, LinkRolesPartitionTheCollisionLinks) {
  auto& f = fixture();
  LinkRoles r = link_roles(*f.robot, f.chain);
  EXPECT_EQ(r.body.size() + r.arm.size() + r.tool.size(), f.robot->collision_links().size());
  for (int l : r.body) EXPECT_EQ(f.chain.link_mask(l), 0u);
  for (int l : r.arm) EXPECT_NE(f.chain.link_mask(l), 0u);
}

TEST(ArmPlacement, GraspsPlacementAndBasePose) {
  auto& f = fixture();
  const OrientationSet& set = f.cap.orientations();
  EXPECT_THROW(GraspSet::make(set, {set.directions()}, ""), std::invalid_argument);
  GraspSet g = GraspSet::make(set, {}, "upper_hemisphere");
  EXPECT_EQ(g.name, "upper_hemisphere");
  EXPECT_EQ(g.orientations, grasp_orientations(set, set.subset("upper_hemisphere")));
  ArmPlacement p = ArmPlacement::make(*f.robot, f.cap, "", Eigen::VectorXd(), {}, "upper_hemisphere");
  EXPECT_EQ(p.reference_frame, f.robot->links()[f.robot->root_link()].name);
  Pose B = base_pose(1, 2, 3, M_PI / 2);
  EXPECT_TRUE(B.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE((B.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(p.root_pose(1, 2, 3, M_PI / 2).isApprox(B * p.root_in_reference));
}

TEST(ArmPlacement, MapsTieToTheModelHash) {
  auto& f = fixture();
  EXPECT_EQ(f.cap.model_hash(), f.robot->model_hash());
  EXPECT_NO_THROW(check_map_robot(*f.robot, f.cap));
  // Another allowed-collision matrix is another model: the map does not belong to it.
  auto robot = Robot::from_urdf(kArm);
  const auto& links = robot->links();
  std::shared_ptr<Robot> other;
  bool added = false;
  for (std::size_t i = 0; i < links.size() && !added; ++i)
    for (std::size_t j = i + 1; j < links.size() && !added; ++j)
      if (!links[i].shapes.empty() && !links[j].shapes.empty()) {
        other = robot->with_allowed_collisions(
            std::vector<std::pair<std::string, std::string>>{{links[i].name, links[j].name}});
        added = other->allowed_pairs().size() > robot->allowed_pairs().size();
      }
  ASSERT_TRUE(added);
  EXPECT_THROW(check_map_robot(*other, f.cap), std::invalid_argument);
}

TEST(Maps, BatchedLookupsEqualSingleOnes) {
  auto& f = fixture();
  InversePointMap pm = InversePointMap::build(*f.robot, f.cap, PointMapOptions());
  std::vector<double> rows, points;
  for (int i = 0; i < 500; ++i) {
    double t = i * 0.37;
    rows.insert(rows.end(), {std::sin(t), std::cos(1.3 * t), 0.2 * std::sin(2.1 * t), t});
    points.insert(points.end(), {0.5 * std::sin(t), 0.5 * std::cos(t), 0.3 * std::sin(0.7 * t)});
  }
  std::vector<double> out(500), cap_out(500);
  pm.reachability(rows.data(), 500, out.data());
  f.cap.reachability(points.data(), 500, cap_out.data());
  for (int i = 0; i < 500; ++i) {
    EXPECT_EQ(out[i], pm.reachability(rows[4 * i], rows[4 * i + 1], rows[4 * i + 2], rows[4 * i + 3]));
    EXPECT_EQ(cap_out[i], f.cap.reachability(Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2])));
  }
}
