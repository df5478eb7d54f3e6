// The camera's clearance (ViewChecker::camera_clear) with the safe-view rule: an unknown cell of the search space
// near the camera rules it out, those no insert has reached too. The arm's check (ViewChecker::arm_clear) gives the
// plain check's answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <octomap/OcTree.h>

#include "box_scene.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/view_score.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {

bool clear_at(const ExplorationMap& map, const Eigen::Vector3d& p) {
  auto guard = detail::read_guard(map);
  const detail::ViewChecker checker(map, NbvOptions());
  return checker.camera_clear(p);
}

}  // namespace

TEST(ViewChecker, EveryUnknownCellOfTheSearchSpaceCounts) {
  ExplorationOptions o;
  o.resolution = 0.05;
  o.search_lo = {-3.0, -3.0, 0.0};
  o.search_hi = {3.0, 3.0, 2.0};
  ExplorationMap map(o);
  const Eigen::Vector3d origin(0.0, 0.0, 0.5), far(1.5, 1.5, 1.0), outside(3.5, 0.0, 1.0);
  // before any insert every cell of the search space is unknown: no camera in it is clear, one outside it is
  EXPECT_FALSE(clear_at(map, far));
  EXPECT_FALSE(clear_at(map, origin));
  EXPECT_TRUE(clear_at(map, outside));
  // a wall at x = 2 seen from the origin: the rays clear a wide fan of cells in front of it
  std::vector<Eigen::Vector3d> wall;
  for (double y = -1.0; y <= 1.0; y += 0.02)
    for (double z = 0.0; z <= 1.5; z += 0.02) wall.emplace_back(2.0, y, z);
  map.insert(wall, origin, 4.0);
  ASSERT_EQ(map.state(map.key_of(far)), CellState::Unknown);
  // beyond the box of the cells an insert has reached (|y| > 1), an unknown cell of the search space still counts
  EXPECT_FALSE(clear_at(map, far));
  // inside the fan, more than the margin from every unknown cell
  EXPECT_TRUE(clear_at(map, Eigen::Vector3d(0.8, 0.0, 0.5)));
  EXPECT_TRUE(clear_at(map, outside));
}

// min_distance is a distance to the nearest point of an occupied cell (the surface may lie anywhere in it): a camera
// 4.9 cm from the cell is refused and one 5.1 cm away is clear, along an axis, a face diagonal or a space
// diagonal, whichever cells of the cube around the camera's cell they fall in.
TEST(ViewChecker, TheClearanceIsADistanceToTheCells) {
  ExplorationOptions o;
  o.resolution = 0.025;
  ExplorationMap map(o);
  map.insert({{1.0, 0.0, 0.5}}, Eigen::Vector3d(0.0, 0.0, 0.5), 4.0);
  const Eigen::Vector3d c = map.center(map.key_of(Eigen::Vector3d(1.0, 0.0, 0.5)));
  ASSERT_EQ(map.state(map.key_of(c)), CellState::Occupied);
  NbvOptions opt;
  opt.min_distance = 0.05;
  opt.unknown_is_obstacle = false;
  auto guard = detail::read_guard(map);
  const detail::ViewChecker checker(map, opt);
  const double h = 0.0125;  // half a cell: the corner of the cell nearest a diagonal
  for (const Eigen::Vector3d& u : {Eigen::Vector3d(-1.0, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 1.0),
                                   Eigen::Vector3d(1.0, 1.0, 0.0).normalized(), Eigen::Vector3d(1.0, 1.0, 1.0).normalized()}) {
    const Eigen::Vector3d edge = c + h * u.cwiseSign();  // the cell's point nearest the direction u
    EXPECT_FALSE(checker.camera_clear(edge + 0.049 * u)) << u.transpose();
    EXPECT_TRUE(checker.camera_clear(edge + 0.051 * u)) << u.transpose();
  }
  EXPECT_FALSE(checker.camera_clear(c));
}

// arm_clear asks FCL only about the links that have an obstacle cell in their box. Its answer is the plain check's:
// every link the chain moves against octrees of the map's occupied cells and (safe views) of the unknown cells of
// the search space clipped to the known box, and the robot against itself; for the test arm beside a seen box,
// in configurations all around it.
TEST(ViewChecker, TheArmCheckIsThePlainChecksAnswer) {
  Scene scene;
  auto map = test_scenes::box_with_lid_opening(
      scene, {look_at({0.8, 0.0, 1.1}, {0.8, 0.0, 0.0}), look_at({0.2, -0.6, 0.7}, {0.8, 0.0, 0.2})});
  const auto robot = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  const Chain chain = robot->chain("base_link", "tool0");
  const std::vector<int> moved = chain.moved_collision_links();
  const Eigen::MatrixXd Q = chain.random_configurations(3000, 7);
  for (const bool unknown : {false, true}) {
    NbvOptions opt = NbvOptions::exploration_loop();
    opt.chain = &chain;
    opt.chain_base = Pose::Identity();
    opt.chain_base.translation() = Eigen::Vector3d(0.7, -0.45, 0.0);
    opt.unknown_is_obstacle = unknown;
    opt.ground_is_obstacle = false;
    Obstacles plain;
    plain.add_octree(std::shared_ptr<const octomap::OcTree>(&map->octree(), [](const octomap::OcTree*) {}));
    if (unknown) {
      // the unknown cells of the (bounded) search space: every cell that shares volume with it
      auto cells = std::make_shared<octomap::OcTree>(map->resolution());
      const ExplorationOptions& mo = map->options();
      const double res = map->resolution();
      unsigned a[3], b[3];
      for (int i = 0; i < 3; ++i) {
        a[i] = unsigned(std::floor(mo.search_lo[i] / res) + 32768.0);
        b[i] = unsigned(std::ceil(mo.search_hi[i] / res) - 1.0 + 32768.0);
      }
      for (unsigned z = a[2]; z <= b[2]; ++z)
        for (unsigned y = a[1]; y <= b[1]; ++y)
          for (unsigned x = a[0]; x <= b[0]; ++x)
            if (map->state(pack_key(x, y, z)) == CellState::Unknown)
              cells->updateNode(octomap::OcTreeKey(x, y, z), true);
      ASSERT_GT(cells->size(), 0u);
      plain.add_octree(cells);
    }
    auto guard = detail::read_guard(*map);
    const detail::ViewChecker checker(*map, opt);
    ASSERT_EQ(checker.unknown_obstacle_cells() > 0, unknown);
    int collisions = 0;
    for (Eigen::Index i = 0; i < Q.rows(); ++i) {
      const Eigen::VectorXd q = Q.row(i).transpose();
      const bool hit = robot->in_collision(chain.to_robot_configuration(q, robot->home()), plain, opt.chain_base,
                                           /*check_self=*/true, &moved);
      collisions += hit;
      ASSERT_EQ(checker.arm_clear(q) == ViewStatus::ArmCollision, hit) << "unknown " << unknown << ", row " << i;
    }
    // both answers, often
    EXPECT_GT(collisions, 300) << unknown;
    EXPECT_LT(collisions, int(Q.rows()) - 300) << unknown;
  }
}

// A bounded search space's unknown cells are the arm's obstacles before any insert too: every cell of it is one.
TEST(ViewChecker, BeforeAnyInsertTheArmKeepsOutOfABoundedSearchSpace) {
  ExplorationOptions o;
  o.resolution = 0.05;
  o.search_lo = {0.31, -0.29, 0.01};  // (no bound on a cell face: 12 cells along each axis)
  o.search_hi = {0.89, 0.29, 0.59};
  ExplorationMap map(o);
  const auto robot = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  const Chain chain = robot->chain("base_link", "tool0");
  const Eigen::MatrixXd Q = chain.random_configurations(500, 3);
  for (const bool unknown : {false, true}) {
    NbvOptions opt = NbvOptions::exploration_loop();
    opt.chain = &chain;
    opt.unknown_is_obstacle = unknown;
    opt.ground_is_obstacle = false;
    auto guard = detail::read_guard(map);
    const detail::ViewChecker checker(map, opt);
    EXPECT_EQ(checker.unknown_obstacle_cells(), unknown ? std::size_t(12 * 12 * 12) : std::size_t(0));
    int collisions = 0;
    for (Eigen::Index i = 0; i < Q.rows(); ++i) {
      const Eigen::VectorXd q = Q.row(i).transpose();
      if (robot->in_self_collision(chain.to_robot_configuration(q, robot->home()))) continue;
      collisions += checker.arm_clear(q) == ViewStatus::ArmCollision;
    }
    if (unknown) EXPECT_GT(collisions, 20);  // the arm reaches into the box in front of it
    else EXPECT_EQ(collisions, 0);          // nothing else to touch
  }
}
