// A coarse first score (NbvOptions::rescore_best): the views kept are scored exactly as the full grid scores
// them, keeping every view gives the paper's search, of many aimed poses a first pass with fewer rays keeps the
// best, the search's batches follow the share of valid poses, and with an arm the views do not depend on the
// thread count.
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

// The valid ones of `full` (score_views of poses) scored with every step-th ray, best first by expected void cells
// (ties: the order of `full`).
std::vector<ViewCandidate> scored_with_step(const ExplorationMap& map, const NbvOptions& opt, const ScoredViews& full,
                                            int step) {
  std::vector<ViewCandidate> out;
  auto guard = detail::read_guard(map);
  const detail::ScoreModel model = detail::score_model(map, opt);
  for (const ScoredView& s : full.views) {
    if (!s.valid()) continue;
    ViewCandidate c;
    c.pose = s.pose;
    detail::score_view(map, camera(), opt, model, c, step);
    out.push_back(c);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ViewCandidate& a, const ViewCandidate& b) { return ranks_before(a, b, RankKey::ExpectedVoid); });
  return out;
}

// The rank of pose p in `views` (views.size() when absent).
std::ptrdiff_t rank_of(const std::vector<ViewCandidate>& views, const Pose& p) {
  return std::find_if(views.begin(), views.end(), [&](const ViewCandidate& w) { return w.pose.isApprox(p, 0); }) -
         views.begin();
}

// rescored_views of `poses` with rescore_best n (no arm): n views, each with the full score, the best n by the coarse
// score among the poses the first pass keeps (all of them, or the 16 n best with every fourth ray).
void expect_best_by_coarse_score(const ExplorationMap& map, const std::vector<Pose>& poses, int n, bool first_pass) {
  NbvOptions opt = NbvOptions::exploration_loop();
  opt.rescore_best = n;
  const ScoredViews kept = detail::rescored_views(map, camera(), poses, opt, RankKey::ExpectedVoid);
  ASSERT_EQ(kept.views.size(), std::size_t(n));
  opt.rescore_best = 0;
  const ScoredViews full = score_views(map, camera(), poses, opt, false);
  std::vector<ViewCandidate> coarse = scored_with_step(map, opt, full, 2);
  ASSERT_EQ(coarse.size() > 16 * std::size_t(n), first_pass);
  const std::vector<ViewCandidate> every = coarse;  // the coarse order of every valid pose
  if (first_pass) {  // the coarse order of the first pass's 16 n best
    const std::vector<ViewCandidate> quarter = scored_with_step(map, opt, full, 4);
    coarse.erase(std::remove_if(coarse.begin(), coarse.end(),
                                [&](const ViewCandidate& c) { return rank_of(quarter, c.pose) >= 16 * n; }),
                 coarse.end());
    ASSERT_EQ(coarse.size(), 16 * std::size_t(n));
  }
  std::size_t outside_best = 0;  // kept views that are not among the n best of every pose's coarse score
  for (const ScoredView& v : kept.views) {
    ASSERT_TRUE(v.valid());
    const auto twin = std::find_if(full.views.begin(), full.views.end(),
                                   [&](const ScoredView& w) { return w.pose.isApprox(v.pose, 0); });
    ASSERT_NE(twin, full.views.end());
    EXPECT_TRUE(same_gains(v, *twin));
    EXPECT_LT(rank_of(coarse, v.pose), n);
    outside_best += rank_of(every, v.pose) >= n ? 1 : 0;
  }
  // on this map the first pass's 16 n hold the coarse score's n best: it loses none of them
  EXPECT_EQ(outside_best, 0u);
}

TEST(Rescore, AimedViewsWithoutAnArmAreTheBestByTheCoarseScoreScoredInFull) {
  Scene scene;
  auto map = box_map(scene);
  const std::vector<Pose> poses = aims(*map, 200);
  ASSERT_GT(poses.size(), 50u);
  expect_best_by_coarse_score(*map, poses, 13, false);  // 13 x 16 poses or more: the coarse score of every pose
  expect_best_by_coarse_score(*map, poses, 3, true);    // a first pass keeps 48
}

TEST(Rescore, BatchesGrowWithTheShareOfInvalidPoses) {
  // 50 wanted, 49 of 99 valid: the 100 the rate expects, at most twice the last batch
  EXPECT_EQ(detail::next_batch(50, 49, 99, 8, 80), 100u);
  EXPECT_EQ(detail::next_batch(50, 49, 99, 8, 40), 80u);
  // every pose valid: no fewer than a few per thread; none valid yet: the batch doubles, up to 16 x least
  EXPECT_EQ(detail::next_batch(2, 100, 100, 8, 8), 8u);
  EXPECT_EQ(detail::next_batch(50, 0, 200, 8, 64), 128u);
  EXPECT_EQ(detail::next_batch(50, 0, 200, 8, 128), 128u);
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
  // the first chunk (the 64 best of the first pass with every fourth ray) holds fewer than 4 valid poses: the next
  // chunks are checked
  EXPECT_GT(one.views.size(), 64u);
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
