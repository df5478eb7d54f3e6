// The surface map's arm-against-obstacles check (maps/arm_obstacles) against brute force: FCL on every
// shape of every arm and tool link at the cell's stored solution. Its pre-tests (integer centimetre
// boxes, arm-frame oriented boxes) may only skip shapes that cannot touch, so the answers must agree.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "maps/arm_obstacles.hpp"
#include "collision/mesh_pair_check.hpp"
#include "octoreach/capability_map.hpp"

using namespace octoreach;

namespace {

// The arm check against FCL on every link shape of the arm `robot` at many base poses.
void expect_equals_fcl(std::shared_ptr<Robot> robot) {
  Chain chain = robot->chain("base_link", "tool0");
  CapabilityMapOptions co;
  co.resolution = 0.15;
  co.directions = 24;
  co.seed = 1;
  CapabilityMap cap = CapabilityMap::build(chain, co);
  ASSERT_TRUE(cap.has_solutions());
  const ArmPlacement place = ArmPlacement::make(*robot, cap, "", Eigen::VectorXd(), {}, "upper_hemisphere");
  // Table legs (vertical boxes), a yawed and tilted box and a thin plate: near the arm at many poses.
  auto obstacles = std::make_shared<Obstacles>();
  for (double x : {-0.3, 0.3})
    for (double y : {-0.25, 0.25}) {
      Pose p = Pose::Identity();
      p.translation() = Eigen::Vector3d(x, y, 0.35);
      obstacles->add_box(Eigen::Vector3d(0.05, 0.05, 0.7), p);
    }
  Pose tilted = Pose::Identity();
  tilted.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
  tilted.translation() = Eigen::Vector3d(0.1, -0.4, 0.5);
  obstacles->add_box(Eigen::Vector3d(0.3, 0.1, 0.2), tilted);
  Pose plate = Pose::Identity();
  plate.translation() = Eigen::Vector3d(0.0, 0.5, 0.3);
  obstacles->add_box(Eigen::Vector3d(0.6, 0.02, 0.4), plate);

  std::vector<char> wanted(cap.orientations().size(), 1);
  auto slots = std::make_shared<const detail::CellSlots>(cap, wanted);
  ASSERT_GT(slots->size(), 0u);
  detail::ArmObstacles arm(*robot, cap, place, obstacles, slots, 1);
  std::vector<int> links = place.roles.arm;
  links.insert(links.end(), place.roles.tool.begin(), place.roles.tool.end());
  const Pose arm_from_root = place.link_poses[robot->link_index(cap.base_link())].inverse();

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-0.6, 0.6), yaw(-M_PI, M_PI);
  detail::ArmScratch scratch;
  detail::NearObstacles near;
  std::vector<Pose> poses;
  std::size_t hits = 0, checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Pose world_from_arm = base_pose(xy(rng), xy(rng), 0.0, yaw(rng)) * place.reference_to_arm;
    arm.near(world_from_arm, near);
    for (std::size_t s = trial % 3; s < slots->size(); s += 3) {
      const auto& c = slots->cell(s);
      const float* qf = cap.record_solution(c.rec, c.orient);
      Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, chain.dof()).cast<double>();
      robot->link_poses(chain.to_robot_configuration(q, place.reference), poses);
      bool expected = false;
      for (int li : links)
        for (const auto& sh : robot->links()[li].shapes) {
          // The link pose in the arm frame rounded to float, as the check caches it.
          Pose in_arm = Pose::Identity();
          in_arm.matrix().topRows<3>() = (arm_from_root * poses[li]).matrix().topRows<3>().cast<float>().cast<double>();
          expected = expected || obstacles->collides(*sh.geometry, world_from_arm * in_arm * sh.origin);
        }
      const bool got = arm.collides(static_cast<std::int32_t>(s), near, world_from_arm, scratch);
      ASSERT_EQ(got, expected) << "slot " << s << " trial " << trial;
      hits += expected;
      ++checked;
    }
  }
  // Both answers occur, so the comparison means something.
  EXPECT_GT(hits, 0u);
  EXPECT_LT(hits, checked);
}

// An open square tube along z (four walls, no ends) as an ASCII STL: its hull holds room a table leg can
// pass through without touching a triangle, so the mesh-box check's every step is needed.
std::string write_tube(const std::filesystem::path& dir, const std::string& name, double w, double length) {
  const std::filesystem::path path = dir / (name + ".stl");
  std::ofstream f(path);
  f << "solid " << name << "\n";
  const double h = w / 2;
  const double c[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
  auto facet = [&](const double* a, const double* b, double za, double zb, double zc, const double* cc) {
    f << "facet normal 0 0 0\nouter loop\n";
    f << "vertex " << a[0] << " " << a[1] << " " << za << "\n";
    f << "vertex " << b[0] << " " << b[1] << " " << zb << "\n";
    f << "vertex " << cc[0] << " " << cc[1] << " " << zc << "\n";
    f << "endloop\nendfacet\n";
  };
  for (int i = 0; i < 4; ++i) {
    const double* a = c[i];
    const double* b = c[(i + 1) % 4];
    facet(a, b, 0.0, 0.0, length, b);
    facet(a, b, 0.0, length, length, a);
  }
  f << "endsolid " << name << "\n";
  return path.string();
}

}  // namespace

TEST(SurfaceMapArmObstacles, EqualsFclOnEveryLinkShape) {
  expect_equals_fcl(Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf"));
}

TEST(SurfaceMapArmObstacles, EqualsFclOnMeshLinks) {
  // The test arm with its upper arm and forearm as open tubes (meshes: the mesh-box check decides
  // them against the boxes).
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "octoreach_arm_obstacles_meshes";
  std::filesystem::create_directories(dir);
  std::ifstream in(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto swap = [&](const std::string& from, const std::string& to) {
    const auto at = urdf.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    urdf.replace(at, from.size(), to);
  };
  swap("<origin xyz=\"0 0 0.2\"/><geometry><box size=\"0.06 0.06 0.36\"/>",
       "<origin xyz=\"0 0 0.02\"/><geometry><mesh filename=\"" + write_tube(dir, "upper", 0.09, 0.36) + "\"/>");
  swap("<origin xyz=\"0 0 0.15\"/><geometry><box size=\"0.05 0.05 0.26\"/>",
       "<origin xyz=\"0 0 0.02\"/><geometry><mesh filename=\"" + write_tube(dir, "fore", 0.08, 0.26) + "\"/>");
  const std::filesystem::path path = dir / "mesh_arm.urdf";
  std::ofstream(path) << urdf;
  auto robot = Robot::from_urdf(path.string());
  bool meshes = false;
  for (const auto& link : robot->links())
    for (const auto& s : link.shapes) meshes = meshes || detail::hull_mesh(*s.geometry) != nullptr;
  ASSERT_TRUE(meshes);
  expect_equals_fcl(robot);
}
