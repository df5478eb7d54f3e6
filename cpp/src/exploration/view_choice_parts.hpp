#pragma once
// Internal: what the parts of choose_view share (view_choice.cpp: frontier-void; sampled_views.cpp: the
// baselines).
#include <cstdint>
#include <vector>

#include "octoreach/view_choice.hpp"

namespace octoreach::detail {

// One choice's inputs, and the search options for each base.
struct ChoiceContext {
  const ExplorationMap& map;
  const CameraIntrinsics& camera;
  const ViewSites& sites;
  int current;
  const ExploreOptions& options;
  const ChoiceMemory& memory;
  bool reach_sphere;  // the camera stays within sites.reach of each base (a chain and no workspace given)
  // Base indices, the current one first (so ties keep it).
  std::vector<int> order() const;
  // options.search from base i (chain and capability base, reach sphere, the failed views kept away) with `seed`.
  NbvOptions at(int i, std::uint64_t seed) const;
  // The best valid of `views` by `key` as the choice from base i (utility: its expected void cells).
  ViewChoice best_of(const ScoredViews& views, std::size_t scored, int base, RankKey key, bool aimed) const;
};

// The baselines (random, frontiers, unknown): options.sampled_poses camera poses sampled per base in the
// reach sphere (or the workspace box) above min_camera_height, each looking at a uniform random point of the
// map's search space, scored with score_views; the best valid by the strategy's gain (random: the first valid,
// its utility the most expected void cells on offer). With `coarse_first` (frontier-void's views beyond the voids)
// the poses go through rescored_views as the loop's aimed looks do (a coarse first score, IK in its order until
// at most 2 are valid, those scored in full; a camera that only aims: look_at_views' coarse ranking, the best 2
// scored in full); the baselines score every pose in full.
ViewChoice sampled_choice(const ChoiceContext& ctx, std::uint64_t seed, ViewStrategy strategy,
                          bool coarse_first = false);

}  // namespace octoreach::detail
