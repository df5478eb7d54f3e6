// The baselines' choice of a view: sampled reachable poses, scored (view_choice_parts.hpp).
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "exploration/exploration_state.hpp"
#include "exploration/look_at_views.hpp"
#include "exploration/view_choice_parts.hpp"
#include "exploration/view_score.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::detail {

namespace {

// With coarse_first (the view beyond the voids, a single pick compared with one number, frontier-void's utility):
// the poses scored in full after the coarse ranking (rescored_views; look_at_views for a camera that only aims).
// Fewer finalists make rescored_views' chunks smaller (16 poses per finalist), so most sampled poses get only its
// first pass (a sixteenth of the rays); two guard against a misrank of the coarse score (one alone chose a view
// expecting 78 cells where the full score finds 101, on a collapsed slab). A chosen margin, checked with
// benchmarks/view_choice_times.py and the families' record (exploration_families.py).
constexpr int kBeyondFinalists = 2;

// `n` camera poses: positions uniform in the workspace sphere and/or box above `floor` (neither: the search
// space grown by 0.5 m), each looking at a uniform random point of the search space at least 0.1 m away.
std::vector<Pose> sample_poses(std::mt19937_64& rng, const NbvOptions& opt, const Eigen::Vector3d& s_lo,
                               const Eigen::Vector3d& s_hi, int n, double floor) {
  const SensorWorkspace& ws = opt.workspace;
  Eigen::Vector3d lo = s_lo.array() - 0.5, hi = s_hi.array() + 0.5;
  if (ws.sphere_center) {
    lo = ws.sphere_center->array() - ws.sphere_radius;
    hi = ws.sphere_center->array() + ws.sphere_radius;
  } else if (ws.box) {
    lo = ws.box->lo;
    hi = ws.box->hi;
  }
  if (ws.box) {
    lo = lo.cwiseMax(ws.box->lo);
    hi = hi.cwiseMin(ws.box->hi);
  }
  lo.z() = std::max(lo.z(), floor);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto draw = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = a[k] + u(rng) * (b[k] - a[k]);
    return p;
  };
  std::vector<Pose> out;
  if ((hi.array() <= lo.array()).any()) return out;
  for (long t = 0; t < 200L * n && int(out.size()) < n; ++t) {
    const Eigen::Vector3d p = draw(lo, hi);
    if (ws.sphere_center && (p - *ws.sphere_center).norm() > ws.sphere_radius) continue;
    const Eigen::Vector3d target = draw(s_lo, s_hi);
    if ((target - p).norm() < 0.1) continue;
    out.push_back(look_at(p, target));
  }
  return out;
}

// `n` uniform random points of the search space (a look-at camera's targets).
std::vector<Eigen::Vector3d> sample_targets(std::mt19937_64& rng, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                            int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> out(std::size_t(std::max(n, 0)));
  for (auto& p : out)
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + u(rng) * (hi[k] - lo[k]);
  return out;
}

NbvGain score_gain(ViewStrategy s) {
  return s == ViewStrategy::Frontiers ? NbvGain::Frontiers
         : s == ViewStrategy::Unknown ? NbvGain::Unknown
                                      : NbvGain::FrontierVoid;
}

}  // namespace

ViewChoice sampled_choice(const ChoiceContext& ctx, std::uint64_t seed, ViewStrategy strategy, bool coarse_first) {
  const Eigen::Vector3d s_lo = ctx.map.options().search_lo, s_hi = ctx.map.options().search_hi;
  if (!detail::bounded_search_space(ctx.map.options()))
    throw std::invalid_argument(std::string("the ") + strategy_name(strategy) + " strategy needs a finite search space");
  std::mt19937_64 rng(seed);
  ViewChoice best;
  std::size_t scored = 0, valid = 0;
  double most_void = 0;
  const NbvOptions plain;  // the baselines count every void cell alike: the paper's count, not the loop's weights
  for (int i : ctx.order()) {
    NbvOptions opt = ctx.at(i, seed);
    opt.gain = score_gain(strategy);
    opt.enclosure_power = plain.enclosure_power;
    opt.unexposed_weight = plain.unexposed_weight;
    if (coarse_first) opt.rescore_best = std::min(opt.rescore_best, kBeyondFinalists);
    ScoredViews views;
    if (looks_at(opt)) {  // the chain aims its camera at uniform random points of the search space
      const std::vector<Eigen::Vector3d> targets = sample_targets(rng, s_lo, s_hi, ctx.options.sampled_poses);
      auto guard = read_guard(ctx.map);
      const ViewChecker checker(ctx.map, opt);
      views = look_at_views(ctx.map, ctx.camera, targets, opt, checker, score_model(ctx.map, opt), targets.size(),
                            coarse_first ? std::size_t(std::max(opt.rescore_best, 0)) : 0).scored;
      scored += targets.size();
    } else {
      const std::vector<Pose> poses = sample_poses(rng, opt, s_lo, s_hi, ctx.options.sampled_poses,
                                                   ctx.options.min_camera_height);
      if (poses.empty()) continue;
      views = coarse_first ? rescored_views(ctx.map, ctx.camera, poses, opt, RankKey::Gain)
                           : score_views(ctx.map, ctx.camera, poses, opt, false);
      scored += poses.size();
    }
    const ScoredView* first = nullptr;
    for (const ScoredView& v : views.views)
      if (v.valid()) {
        ++valid;
        if (!first) first = &v;
        most_void = std::max(most_void, v.expected_void);
      }
    const ScoredView* pick = strategy == ViewStrategy::Random ? first : views.best(RankKey::Gain);
    if (!pick) continue;
    const bool better = !best.found || (strategy != ViewStrategy::Random && ranks_before(*pick, best.view));
    if (better) {
      best.found = true;
      best.view = *pick;
      best.base = i;
    }
  }
  best.candidates = scored;
  best.valid = valid;
  if (best.found)
    best.utility = strategy == ViewStrategy::Random ? most_void : best.view.gain(score_gain(strategy));
  return best;
}

}  // namespace octoreach::detail
