// The exploration loop's choice of a view (view_choice.hpp): frontier-void's search and looks, the stop
// decision; the baselines' sampled poses are in sampled_views.cpp.
#include "octoreach/view_choice.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "exploration/exploration_state.hpp"
#include "exploration/look_at_views.hpp"
#include "exploration/view_choice_parts.hpp"
#include "exploration/view_score.hpp"
#include "exploration/void_aims.hpp"

namespace octoreach {

const char* strategy_name(ViewStrategy s) {
  switch (s) {
    case ViewStrategy::FrontierVoid: return "frontier_void";
    case ViewStrategy::Random: return "random";
    case ViewStrategy::Frontiers: return "frontiers";
    case ViewStrategy::Unknown: return "unknown";
  }
  return "?";
}

ViewStrategy strategy_from_name(const std::string& name) {
  for (ViewStrategy s : {ViewStrategy::FrontierVoid, ViewStrategy::Random, ViewStrategy::Frontiers, ViewStrategy::Unknown})
    if (name == strategy_name(s)) return s;
  throw std::invalid_argument("unknown strategy '" + name + "'; choose one of frontier_void, random, frontiers, unknown");
}

namespace detail {

std::vector<int> ChoiceContext::order() const {
  std::vector<int> out{current};
  for (int j = 0; j < int(sites.bases.size()); ++j)
    if (j != current) out.push_back(j);
  return out;
}

NbvOptions ChoiceContext::at(int i, std::uint64_t s) const {
  NbvOptions o = options.search;
  const Pose& bp = sites.bases[std::size_t(i)];
  o.chain_base = bp;
  if (o.capability_map) o.capability_base = bp;
  if (reach_sphere) {
    o.workspace.sphere_center = bp.translation();
    o.workspace.sphere_radius = sites.reach;
  }
  if (!memory.failed_views.empty()) {  // no view near the camera of a view not taken
    auto user = o.workspace.filter;
    const std::vector<Eigen::Vector3d> failed = memory.failed_views;
    const double r2 = options.failed_view_radius * options.failed_view_radius;
    o.workspace.filter = [user, failed, r2](const std::vector<Eigen::Vector3d>& P) {
      std::vector<bool> ok = user ? user(P) : std::vector<bool>(P.size(), true);
      for (std::size_t i = 0; i < P.size() && i < ok.size(); ++i)
        for (const auto& f : failed)
          if ((P[i] - f).squaredNorm() <= r2) ok[i] = false;
      return ok;
    };
  }
  o.seed = s;
  o.ik.seed = s;
  return o;
}

ViewChoice ChoiceContext::best_of(const ScoredViews& views, std::size_t scored, int base, RankKey key,
                                  bool aimed) const {
  ViewChoice c;
  c.base = base;
  c.candidates = scored;
  for (const auto& v : views.views) c.valid += v.valid() ? 1 : 0;
  if (const ScoredView* v = views.best(key)) {
    c.found = true;
    c.view = *v;
    c.utility = v->expected_void;
    c.aimed = aimed;
  }
  return c;
}

}  // namespace detail

namespace {

using detail::ChoiceContext;

enum class Look { Sight, Rays };

// Half the narrower field angle of `camera`: an axis turned this far from a cell still has it in the image.
double half_narrow_field(const CameraIntrinsics& camera) {
  return std::atan(0.5 * std::min(camera.width, camera.height) / camera.focal());
}

// The best valid of the poses one look aims at void cells (frontier_void's gain), by `key`.
ViewChoice aimed_choice(const ChoiceContext& ctx, int i, std::uint64_t seed, Look look, std::size_t n, RankKey key,
                        double unexposed_share, std::pair<double, double> distance) {
  NbvOptions opt = ctx.at(i, seed);
  opt.gain = NbvGain::FrontierVoid;
  detail::AimRequest req;
  req.poses = n;
  req.cells = 4 * n;
  req.unexposed_share = unexposed_share;
  req.distance = distance;
  req.min_height = ctx.options.min_camera_height;
  req.seed = seed;
  if (looks_at(opt)) {  // the chain aims its camera at the void cells themselves
    auto guard = detail::read_guard(ctx.map);
    const std::size_t cells = look == Look::Sight ? n : std::min(n, std::size_t(ctx.options.max_ray_cells));
    const auto targets = detail::look_at_targets(ctx.map, NbvGain::FrontierVoid, cells, unexposed_share, seed);
    if (targets.empty()) return ViewChoice{};
    const detail::ScoreModel model = detail::score_model(ctx.map, opt);
    const detail::ViewChecker checker(ctx.map, opt);
    const detail::LookAtViews found =
        detail::look_at_views(ctx.map, ctx.camera, targets, opt, checker, model, targets.size());
    return ctx.best_of(found.scored, targets.size(), i, key, true);
  }
  std::vector<Pose> poses;
  {
    auto guard = detail::read_guard(ctx.map);
    if (look == Look::Sight) {
      poses = detail::aim_along_sight(ctx.map, opt, req);
    } else {
      req.every_cell = true;
      req.max_cells = std::size_t(ctx.options.max_ray_cells);
      req.directions = ctx.options.last_directions;
      req.max_turn = half_narrow_field(ctx.camera);
      // IK may turn the axis as far as the eye's may turn (the cell stays in the image): at the edge of the arm's
      // reach, where the look straight at a cell seen through a slot fails, a turned one often does not
      opt.ik.approach_cone = std::max(opt.ik.approach_cone, req.max_turn);
      const detail::ViewChecker checker(ctx.map, opt);
      poses = detail::aim_at_voids(ctx.map, checker, opt, req);
    }
  }
  if (poses.empty()) return ViewChoice{};
  return ctx.best_of(detail::rescored_views(ctx.map, ctx.camera, poses, opt, key), poses.size(), i, key, true);
}

// next_best_view from every base; the best by utility (the current base first: ties keep it).
ViewChoice searched_choice(const ChoiceContext& ctx, std::uint64_t seed, std::optional<double> widen_below) {
  std::optional<ViewChoice> best;
  for (int i : ctx.order()) {
    NbvOptions opt = ctx.at(i, seed);
    opt.gain = NbvGain::FrontierVoid;
    ViewChoice c;
    c.search = next_best_view(ctx.map, ctx.camera, opt);
    c.base = i;
    c.candidates = c.search.poses_scored;
    // the valid poses kept (ranked holds only those scored in full with rescore_best)
    c.valid = std::min(c.search.poses_scored, std::size_t(opt.max_valid_poses));
    const ViewCandidate* top = c.search.best(RankKey::Gain);
    // a view is low only when none on offer expects more: then the one expecting the most
    if (widen_below && top && top->expected_void <= *widen_below) top = c.search.best(RankKey::ExpectedVoid);
    if (top) {
      c.found = true;
      c.view = *top;
      c.utility = top->expected_void;
    }
    if (!best || c.utility > best->utility) best = std::move(c);
  }
  return std::move(*best);
}

void adopt(ViewChoice& best, ViewChoice&& a, bool harder) {
  a.search = std::move(best.search);
  a.harder = harder;
  best = std::move(a);
}

ViewChoice frontier_void_choice(const ChoiceContext& ctx, std::uint64_t seed, bool last_chance, double threshold) {
  const ExploreOptions& o = ctx.options;
  const std::optional<double> widen = o.second_look ? std::optional<double>(threshold) : std::nullopt;
  ViewChoice best = searched_choice(ctx, seed, widen);
  if (!widen) return best;
  // the second look: by the ranking gain, or by expected void cells when the search's best is low
  const bool low = best.utility <= *widen;
  ViewChoice most = best;  // the view on offer with the most expected void cells
  for (int i : ctx.order()) {
    ViewChoice a = aimed_choice(ctx, i, seed, Look::Sight, std::size_t(o.aimed_poses),
                                low ? RankKey::ExpectedVoid : RankKey::Gain, o.unexposed_share, o.aimed_distance);
    const double best_rank = best.found ? best.view.expected_gain : 0.0;
    if (a.found && (low ? a.utility > best.utility : a.view.expected_gain > best_rank)) adopt(best, std::move(a), false);
    if (best.utility > most.utility) most = best;
  }
  if (best.utility > *widen) return best;
  if (most.utility > best.utility) best = std::move(most);
  // the last chance from base i: eyes along rays out of every void cell
  const auto last_look = [&](int i) {
    ViewChoice a = aimed_choice(ctx, i, seed + 7919 + std::uint64_t(o.last_directions), Look::Rays,
                                std::size_t(o.last_poses), RankKey::ExpectedVoid, 1.0, o.last_distance);
    if (a.found && a.utility > best.utility) adopt(best, std::move(a), true);
  };
  // about to take a low view: more aims at any void cell; when it would end the loop, the last chance
  for (int i : ctx.order()) {
    ViewChoice a = aimed_choice(ctx, i, seed + 7919 + 1, Look::Sight, std::size_t(o.low_aimed_poses),
                                RankKey::ExpectedVoid, 1.0, o.aimed_distance);
    if (a.found && a.utility > best.utility) adopt(best, std::move(a), true);
    if (last_chance) last_look(i);
  }
  // a choice that found no valid view, or only views of utility 0, ends the loop as well: the last chance first
  if (!last_chance && (!best.found || best.utility <= 0))
    for (int i : ctx.order()) last_look(i);
  return best;
}

// True when the map's search space is finite and holds no known cell (no view has seen any of it).
bool search_space_unseen(const ExplorationMap& map) {
  if (!detail::bounded_search_space(map.options())) return false;
  const Eigen::Vector3d lo = map.options().search_lo, hi = map.options().search_hi;
  auto guard = detail::read_guard(map);
  const detail::MapTree& tree = detail::state(map).tree;
  return tree.begin_leafs_bbx(octomap::point3d(float(lo.x()), float(lo.y()), float(lo.z())),
                              octomap::point3d(float(hi.x()), float(hi.y()), float(hi.z()))) == tree.end_leafs_bbx();
}

void check_sites(const ViewSites& sites, int current, const ExploreOptions& options) {
  options.validate();
  if (sites.bases.empty()) throw std::invalid_argument("choose_view needs at least one base pose");
  if (current < 0 || current >= int(sites.bases.size()))
    throw std::invalid_argument("current base index " + std::to_string(current) + " is out of range (0 to " +
                                std::to_string(sites.bases.size() - 1) + ")");
  for (std::size_t i = 0; i < sites.bases.size(); ++i) check_rigid(sites.bases[i], "base pose " + std::to_string(i));
  if (!(sites.reach >= 0) || !std::isfinite(sites.reach))
    throw std::invalid_argument("reach must be a finite number of metres >= 0, got " + std::to_string(sites.reach));
}

// The stop decision on a choice made (counted in memory): no valid view, or the row of low views.
ViewChoice& decide(ViewChoice& c, ChoiceMemory& memory, const ExploreOptions& options, double threshold) {
  ++memory.choices;
  if (!c.found) {
    c.stop = true;
    c.stop_reason = "no valid view";
    return c;
  }
  memory.low_views = c.utility <= threshold ? memory.low_views + 1 : 0;
  if (memory.low_views >= options.patience || c.utility <= 0) {
    c.stop = true;
    c.stop_reason = c.utility <= 0 ? "utility 0" : "utility below min_utility";
  }
  return c;
}

// A view beyond the voids: the search space may hold unknown cells outside them (beside and above what the hull of
// the occupied cells encloses, where the paper's voids end), which frontier-void's gain leaves out: while
// the way beyond the voids is open (ChoiceMemory::beyond_misses), the sampled view expecting the most unknown cells
// of the search space (the "unknown" strategy's poses, whose rays count an unknown cell outside the voids by the
// chance that they return, ranked by a coarse first score: sampled_choice's coarse_first) when it expects more than
// the stop threshold; else none (found false). Only with ExploreOptions::beyond_voids.
ViewChoice beyond(const ChoiceContext& ctx, std::uint64_t seed, double threshold) {
  if (!ctx.options.beyond_voids || ctx.memory.beyond_misses >= ctx.options.patience) return ViewChoice{};
  if (!detail::bounded_search_space(ctx.map.options())) return ViewChoice{};  // no bounded space to look at
  ViewChoice c = detail::sampled_choice(ctx, seed, ViewStrategy::Unknown, true);
  if (!c.found || c.utility <= threshold) return ViewChoice{};
  c.beyond = true;
  return c;
}

}  // namespace

ViewChoice choose_view(const ExplorationMap& map, const CameraIntrinsics& camera, const ViewSites& sites, int current,
                       const ExploreOptions& options, ChoiceMemory& memory, ViewStrategy strategy) {
  check_sites(sites, current, options);
  const SensorWorkspace& ws = options.search.workspace;
  const ChoiceContext ctx{map, camera, sites, current, options, memory,
                          options.search.chain && sites.reach > 0 && !ws.box && !ws.sphere_center && !ws.filter};
  const std::uint64_t seed = options.search.seed;
  const double threshold = options.stop_threshold(camera, map.resolution());
  // evidence: a low view taken that saw more void cells than the threshold breaks the row (only where the
  // utility counts void cells: frontier-void's and random's; the other baselines' counts other cells)
  const bool void_utility = strategy == ViewStrategy::FrontierVoid || strategy == ViewStrategy::Random;
  if (void_utility && memory.last_void_seen && double(*memory.last_void_seen) > threshold) memory.low_views = 0;
  // what views beyond the voids saw decides whether the way stays open (any view that saw more opens it again)
  if (memory.last_space_seen) {
    if (double(*memory.last_space_seen) > threshold) memory.beyond_misses = 0;
    else if (memory.last_beyond) ++memory.beyond_misses;
  }
  memory.last_void_seen.reset();
  memory.last_space_seen.reset();
  memory.last_beyond = false;
  const bool last_chance = memory.low_views + 1 >= options.patience;
  const bool frontier_void = strategy == ViewStrategy::FrontierVoid;
  ViewChoice c;
  if (map.void_cell_count() == map.sealed_void_cell_count()) {  // no void cell a view could reveal
    // frontier-void: the unknown cells of the search space beyond the voids (beyond); every strategy, while no
    // cell of the search space is known (the views so far looked past it): the view expecting the most of them
    const bool unseen = map.void_cell_count() == 0 && search_space_unseen(map);
    // (neither counts in the row of low views: there is no void to count it against)
    c = unseen ? detail::sampled_choice(ctx, seed, ViewStrategy::Unknown)
               : frontier_void ? beyond(ctx, seed, threshold) : ViewChoice{};
    if (c.found && c.utility > 0) {
      ++memory.choices;
      memory.last_beyond = c.beyond;
      return c;
    }
    c = ViewChoice{};
    c.stop = true;
    c.stop_reason = "nothing to explore";
    ++memory.choices;
    return c;
  }
  if (!frontier_void) return decide(c = detail::sampled_choice(ctx, seed, strategy), memory, options, threshold);
  // frontier-void first; a view beyond the voids is taken where it expects more unknown cells of the search space
  // (void cells included) than frontier-void's view expects void cells: both are cells the view would make known,
  // and frontier-void's view also makes known cells outside the voids, which its utility leaves out, so a tie
  // keeps it. That covers the choices that end the loop (their view expects at most the threshold, a view beyond
  // more); the row of low views counts frontier-void's utility, so after such a choice it stays full and the next
  // one ends the loop unless frontier-void or the way beyond finds more.
  c = frontier_void_choice(ctx, seed, last_chance, threshold);
  decide(c, memory, options, threshold);
  ViewChoice b = beyond(ctx, seed, threshold);
  if (!b.found || b.utility <= c.utility) return c;
  memory.last_beyond = true;
  return b;
}

}  // namespace octoreach
