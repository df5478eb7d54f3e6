// A coarse first score (NbvOptions::rescore_best): the views kept are scored exactly as the full grid scores
// them, keeping every view gives the paper's search, and with an arm the views do not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "box_scene.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/view_score.hpp"
#include "exploration/void_aims.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/simulation.hpp"

using namespace octoreach;

namespace {

// The box seen from above and from one side: void cells inside.
std::unique_ptr<ExplorationMap> box_map(Scene& scene) {
  return test_scenes::box_with_lid_opening(
      scene, {look_at({0.8, 0.0, 1.1}, {0.8, 0.0, 0.0}), look_at({0.2, -0.6, 0.7}, {0.8, 0.0, 0.2})});
}

CameraIntrinsics camera() { return CameraIntrinsics{48, 36, 1.0123, 4.0}; }

// Poses looking at the box's void cells from 0.3-1 m (the second look's aims).
std::vector<Pose> aims(const ExplorationMap& map, std::size_t n) {
  detail::AimRequest req;
  req.poses = n;
  req.cells = 4 * n;
  req.seed = 3;
  auto guard = detail::read_guard(map);
  return detail::aim_along_sight(map, NbvOptions(), req);
}

bool same_gains(const ViewGains& a, const ViewGains& b) {
  return a.expected_void == b.expected_void && a.expected_unknown == b.expected_unknown &&
         a.expected_frontier == b.expected_frontier && a.expected_enclosed_void == b.expected_enclosed_void &&
         a.void_cells == b.void_cells && a.unknown_cells == b.unknown_cells;
}

bool same_view(const ScoredView& a, const ScoredView& b) {
  return a.status == b.status && a.pose.isApprox(b.pose, 0) && a.q == b.q &&
         (!a.valid() || (same_gains(a, b) && a.expected_gain == b.expected_gain));
}

// The project's test arm, standing beside the box on the floor, carries the camera (its tool frame).
Chain test_arm_chain() {
  return Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf")->chain("base_link", "tool0");
}

NbvOptions arm_options(const Chain& chain) {
  NbvOptions opt = NbvOptions::exploration_loop();
  opt.chain = &chain;
  opt.chain_base = Pose::Identity();
  opt.chain_base.translation() = Eigen::Vector3d(0.8, -0.75, 0.0);
  return opt;
}

}  // namespace

TEST(Rescore, KeepingEveryViewIsThePapersSearchAndKeptViewsGetTheFullScore) {
  Scene scene;
  auto map = box_map(scene);
  ASSERT_GT(map->void_cell_count(), 100u);
  NbvOptions opt = NbvOptions::exploration_loop();
  opt.rescore_best = 0;
  const NbvResult full = next_best_view(*map, camera(), opt);
  ASSERT_GT(full.ranked.size(), 20u);
  // rescore_best at least the number of valid poses: the same views with the same scores
  opt.rescore_best = int(full.ranked.size());
  const NbvResult all = next_best_view(*map, camera(), opt);
  ASSERT_EQ(all.ranked.size(), full.ranked.size());
  for (std::size_t i = 0; i < all.ranked.size(); ++i) {  // in the same order (ties: the sample order)
    EXPECT_TRUE(all.ranked[i].pose.isApprox(full.ranked[i].pose, 0)) << i;
    EXPECT_TRUE(same_gains(all.ranked[i], full.ranked[i])) << i;
  }
  // a few kept: at most that many per ranking key, each scored exactly as score_views scores its pose
  opt.rescore_best = 3;
  const NbvResult few = next_best_view(*map, camera(), opt);
  ASSERT_GE(few.ranked.size(), 3u);
  EXPECT_LE(few.ranked.size(), 6u);
  EXPECT_EQ(few.poses_scored, full.poses_scored);
  std::vector<Pose> poses;
  for (const ViewCandidate& v : few.ranked) poses.push_back(v.pose);
  const ScoredViews again = score_views(*map, camera(), poses, opt);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_TRUE(same_gains(few.ranked[i], again.views[i])) << i;
    if (i) EXPECT_FALSE(ranks_before(few.ranked[i], few.ranked[i - 1]));
  }
  // the coarse score looks at a quarter of the rays: the views it keeps are not the full list's first ones
  // by construction, but the best kept one is as good as the full list's within the coarse grid's reach
  EXPECT_GT(few.ranked[0].expected_gain, 0.5 * full.ranked[0].expected_gain);
}

TEST(Rescore, AimedViewsWithoutAnArmAreTheBestByTheCoarseScoreScoredInFull) {
  Scene scene;
  auto map = box_map(scene);
  const std::vector<Pose> poses = aims(*map, 200);
  ASSERT_GT(poses.size(), 50u);
  NbvOptions opt = NbvOptions::exploration_loop();
  opt.rescore_best = 5;
  const ScoredViews one = detail::rescored_views(*map, camera(), poses, opt, RankKey::ExpectedVoid);
  ASSERT_EQ(one.views.size(), 5u);
  // the full score of every pose: the kept ones have it; the coarse score of every pose: they are its best
  opt.rescore_best = 0;
  const ScoredViews full = score_views(*map, camera(), poses, opt, false);
  std::vector<ViewCandidate> coarse;
  {
    auto guard = detail::read_guard(*map);
    const detail::ScoreModel model = detail::score_model(*map, opt);
    for (const ScoredView& s : full.views) {
      if (!s.valid()) continue;
      ViewCandidate c;
      c.pose = s.pose;
      detail::score_view(*map, camera(), opt, model, c, true);
      coarse.push_back(c);
    }
  }
  std::stable_sort(coarse.begin(), coarse.end(),
                   [](const ViewCandidate& a, const ViewCandidate& b) { return ranks_before(a, b, RankKey::ExpectedVoid); });
  for (const ScoredView& v : one.views) {
    ASSERT_TRUE(v.valid());
    const auto twin = std::find_if(full.views.begin(), full.views.end(),
                                   [&](const ScoredView& w) { return w.pose.isApprox(v.pose, 0); });
    ASSERT_NE(twin, full.views.end());
    EXPECT_TRUE(same_gains(v, *twin));
    const auto rank = std::find_if(coarse.begin(), coarse.end(),
                                   [&](const ViewCandidate& w) { return w.pose.isApprox(v.pose, 0); });
    ASSERT_NE(rank, coarse.end());
    EXPECT_LT(rank - coarse.begin(), 5);
  }
}

TEST(Rescore, AimedViewsWithAnArmGetIkInCoarseOrderUntilEnoughAreValidForAnyThreadCount) {
  Scene scene;
  auto map = box_map(scene);
  const std::vector<Pose> poses = aims(*map, 300);
  const Chain chain = test_arm_chain();
  NbvOptions opt = arm_options(chain);
  opt.rescore_best = 4;
  opt.threads = 1;
  const ScoredViews one = detail::rescored_views(*map, camera(), poses, opt, RankKey::ExpectedVoid);
  opt.threads = 2;
  const ScoredViews two = detail::rescored_views(*map, camera(), poses, opt, RankKey::ExpectedVoid);
  ASSERT_EQ(one.views.size(), two.views.size());
  std::size_t valid = 0;
  for (std::size_t i = 0; i < one.views.size(); ++i) {
    EXPECT_TRUE(same_view(one.views[i], two.views[i])) << i;
    valid += one.views[i].valid() ? 1 : 0;
  }
  ASSERT_EQ(valid, 4u);
  EXPECT_GT(one.views.size(), valid);  // some of the coarse best fail IK or collide
  // each valid view is the one score_views makes of its pose (the same IK seed, the full score)
  opt.rescore_best = 0;
  const ScoredViews full = score_views(*map, camera(), poses, opt, false);
  for (const ScoredView& v : one.views) {
    if (!v.valid()) continue;
    const auto twin = std::find_if(full.views.begin(), full.views.end(),
                                   [&](const ScoredView& w) { return w.valid() && w.q == v.q; });
    ASSERT_NE(twin, full.views.end());
    EXPECT_TRUE(same_view(v, *twin));
  }
}

TEST(Rescore, TheSearchWithAnArmKeepsTheSameViewsForAnyThreadCount) {
  Scene scene;
  auto map = box_map(scene);
  const Chain chain = test_arm_chain();
  NbvOptions opt = arm_options(chain);
  opt.max_valid_poses = 30;
  opt.rescore_best = 4;
  opt.threads = 1;
  const NbvResult one = next_best_view(*map, camera(), opt);
  opt.threads = 2;
  const NbvResult two = next_best_view(*map, camera(), opt);
  ASSERT_GE(one.ranked.size(), 4u);
  ASSERT_EQ(one.ranked.size(), two.ranked.size());
  for (std::size_t i = 0; i < one.ranked.size(); ++i) {
    EXPECT_TRUE(one.ranked[i].pose.isApprox(two.ranked[i].pose, 0)) << i;
    EXPECT_TRUE(one.ranked[i].q == two.ranked[i].q) << i;
    EXPECT_TRUE(same_gains(one.ranked[i], two.ranked[i])) << i;
  }
}
