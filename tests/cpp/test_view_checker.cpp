// The camera's clearance (ViewChecker::camera_clear) with the safe-view rule: an unknown cell of the search space
// near the camera rules it out, where the search space is clipped to the box of the known cells, and that box
// follows every insert.
#include <gtest/gtest.h>

#include <vector>

#include "exploration/exploration_state.hpp"
#include "exploration/view_score.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/next_best_view.hpp"

using namespace octoreach;

namespace {

bool clear_at(const ExplorationMap& map, const Eigen::Vector3d& p) {
  auto guard = detail::read_guard(map);
  const detail::ViewChecker checker(map, NbvOptions());
  return checker.camera_clear(p);
}

}  // namespace

TEST(ViewChecker, TheSearchSpacesKnownBoxFollowsEveryInsert) {
  ExplorationOptions o;
  o.resolution = 0.05;
  o.search_lo = {-3.0, -3.0, 0.0};
  o.search_hi = {3.0, 3.0, 2.0};
  ExplorationMap map(o);
  const Eigen::Vector3d origin(0.0, 0.0, 0.5), far(1.5, 1.5, 1.0);
  map.insert({{0.3, 0.0, 0.5}, {0.0, 0.3, 0.5}}, origin, 4.0);
  ASSERT_EQ(map.state(map.key_of(far)), CellState::Unknown);
  // outside the box of the known cells an unknown cell does not count (an unbounded space would hold infinitely
  // many)
  EXPECT_TRUE(clear_at(map, far));
  // rays that widen the known box past `far` without meeting it: `far` is an unknown cell of the search space
  map.insert({{1.8, 0.0, 1.2}, {0.0, 1.8, 1.2}}, origin, 4.0);
  ASSERT_EQ(map.state(map.key_of(far)), CellState::Unknown);
  EXPECT_FALSE(clear_at(map, far));
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
