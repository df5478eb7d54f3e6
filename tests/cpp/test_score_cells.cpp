// View scoring's flat cells (cpp/src/exploration/score_cells.hpp) read the map's own values: a search's scores
// (through the cells) equal view_gains' (through the map's tables) on a map with a memory of missed views (the
// seeability and the lines that returned nothing), with the block directory and with the hash lookups of a map spread over a huge box.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "box_scene.hpp"
#include "exploration/exploration_state.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/simulation.hpp"

using namespace octoreach;

namespace {

const CameraIntrinsics kCamera{48, 36, 1.0123, 4.0};

// The box map after one more view, announced with expect_view or not: the cells an announced view expected and
// missed lose seeability.
std::unique_ptr<ExplorationMap> box_map(Scene& scene, bool announce) {
  auto map = test_scenes::box_with_lid_opening(scene, {look_at({0.8, 0.0, 1.1}, {0.8, 0.0, 0.0})});
  const Pose T = look_at({0.2, -0.6, 0.7}, {0.8, 0.0, 0.2});
  if (announce) expect_view(*map, kCamera, T, NbvOptions());
  DepthCamera cam(48, 36, 1.0123, 4.0, 0.0, 0);
  map->insert(cam.capture(scene, T), T.translation(), 4.0);
  return map;
}

std::vector<Pose> poses() {
  std::vector<Pose> out;
  for (double y : {-0.6, -0.3, 0.3, 0.6})
    for (double z : {0.6, 0.9}) out.push_back(look_at({0.3, y, z}, {0.8, 0.0, 0.2}));
  out.push_back(look_at({0.2, -0.6, 0.7}, {0.8, 0.1, 0.3}));  // the missed view's eye: its lines that returned nothing
  return out;
}

// score_views (the flat cells) with a fixed pass probability and no clip box (the unknown gain).
ScoredViews flat_scores(const ExplorationMap& map) {
  NbvOptions opt;
  opt.gain = NbvGain::Unknown;
  opt.unknown_pass_probability = 0.9;
  return score_views(map, kCamera, poses(), opt);
}

// The flat scores equal view_gains' (the map's tables), and the memory of misses lowers some of them.
void expect_scores_match(ExplorationMap& map, const ExplorationMap& unannounced) {
  ASSERT_GT(missed_cells(map), 100u);
  ASSERT_EQ(missed_cells(unannounced), 0u);
  ASSERT_GT(detail::state(map).blind.size(), 0u);  // the missed view's lines that returned nothing
  const ScoredViews flat = flat_scores(map), plain = flat_scores(unannounced);
  const std::vector<Pose> P = poses();
  int lowered = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const ViewGains direct = view_gains(map, kCamera, P[i], 48, 36, 0.9, 0.9);
    EXPECT_EQ(flat.views[i].expected_unknown, direct.expected_unknown) << i;
    EXPECT_EQ(flat.views[i].expected_void, direct.expected_void) << i;
    EXPECT_EQ(flat.views[i].expected_frontier, direct.expected_frontier) << i;
    EXPECT_EQ(flat.views[i].unknown_cells, direct.unknown_cells) << i;
    EXPECT_LE(flat.views[i].expected_unknown, plain.views[i].expected_unknown) << i;
    lowered += flat.views[i].expected_unknown < plain.views[i].expected_unknown ? 1 : 0;
  }
  EXPECT_GT(lowered, 0);
  // from the missed view's eye, the cells along its lines count 0: less than the seeability alone gives
  detail::ExplorationState& S = detail::mutable_state(map);
  const detail::BlindLines lines = S.blind;
  S.blind = detail::BlindLines();
  const ViewGains seeability_only = view_gains(map, kCamera, P.back(), 48, 36, 0.9, 0.9);
  S.blind = lines;
  EXPECT_LT(flat.views.back().expected_unknown, seeability_only.expected_unknown);
}

}  // namespace

TEST(ScoreCells, ScoresThroughTheBlockDirectoryEqualTheMapsOwn) {
  Scene a, b;
  auto map = box_map(a, true), unannounced = box_map(b, false);
  expect_scores_match(*map, *unannounced);
}

TEST(ScoreCells, ScoresThroughHashLookupsEqualTheMapsOwn) {
  Scene a, b;
  auto map = box_map(a, true), unannounced = box_map(b, false);
  // a few cells 300 m away along every axis: the block box (over 2^21 blocks) is too big for a directory
  const Eigen::Vector3d far(300.0, 300.0, 300.0);
  for (ExplorationMap* m : {map.get(), unannounced.get()})
    m->insert({far + Eigen::Vector3d(1.0, 0.0, 0.0), far + Eigen::Vector3d(0.0, 1.0, 0.0)}, far, 4.0);
  expect_scores_match(*map, *unannounced);
}
