// Surface extents (cpp/src/exploration/surface_extents.hpp): the grown boxes an insert keeps up to date are the
// ones each cell's record and the map's cells give, after every insert of views from many sides.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "exploration/exploration_state.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/simulation.hpp"

using namespace octoreach;

TEST(SurfaceExtents, GrownBoxesAfterEveryInsertAreTheOnesWorkedOutFromScratch) {
  Scene s;
  s.add_box({-1.5, -1.5, -0.05}, {1.5, 1.5, 0.0});  // floor
  s.add_crate({0.3, -0.5, 0.0}, {0.7, -0.1, 0.3}, 0.02);
  s.add_closed_box({0.3, 0.2, 0.0}, {0.8, 0.6, 0.4}, 0.02, "-x", 0.12, 0.1);
  s.add_box({-0.2, 0.6, 0.0}, {0.6, 0.65, 0.2});  // a board
  DepthCamera cam(96, 72, 1.0123, 3.0, 0.003, 7);  // depth noise: cells turn free and occupied again
  ExplorationOptions o;
  o.resolution = 0.025;
  ExplorationMap m(o);
  const std::vector<Pose> views = {
      look_at({-0.6, 0.0, 0.9}, {0.5, 0.0, 0.1}), look_at({-0.3, -0.9, 0.8}, {0.5, 0.0, 0.1}),
      look_at({0.0, 0.9, 1.0}, {0.5, 0.1, 0.1}),  look_at({1.4, 0.3, 0.9}, {0.5, 0.1, 0.1}),
      look_at({0.5, 0.0, 1.4}, {0.5, 0.0, 0.0}),  look_at({-0.6, 0.0, 0.9}, {0.5, 0.0, 0.1}),
      look_at({0.1, 0.4, 0.25}, {0.5, 0.4, 0.2}), look_at({0.9, -0.9, 0.5}, {0.5, -0.3, 0.1})};
  std::size_t grown = 0;
  for (const Pose& T : views) {
    m.insert(cam.capture(s, T), T.translation(), 3.0);
    const auto& S = detail::state(m);
    ASSERT_TRUE(S.surface.grown_current(S));
    grown = 0;
    for (CellKey k : m.known_cells(CellState::Occupied)) grown += S.surface.grown(k) != nullptr;
  }
  EXPECT_GT(grown, 100u);  // the boards' rims and the floor's cells go on past their faces
}
