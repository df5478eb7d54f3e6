// Views of a camera its chain can only aim (look_at_views.hpp).
#include "exploration/look_at_views.hpp"

#include <algorithm>
#include <chrono>
#include <random>
#include <set>
#include <tuple>

#include "common/thread_pool.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/view_score.hpp"
#include "exploration/void_aims.hpp"
#include "octoreach/aim.hpp"
#include "octoreach/capability_map.hpp"

namespace octoreach::detail {

namespace {

constexpr double kSameAim = 0.02;  // joints (rad or m) within one such step aim the camera alike
constexpr double kTargetsUnexposedShare = 0.25;  // the second look's share (ExploreOptions::unexposed_share)

std::vector<long> aim_key(const Eigen::VectorXd& q) {
  std::vector<long> k(std::size_t(q.size()));
  for (Eigen::Index i = 0; i < q.size(); ++i) k[std::size_t(i)] = long(std::lround(q[i] / kSameAim));
  return k;
}

}  // namespace

std::vector<Eigen::Vector3d> look_at_targets(const ExplorationMap& map, NbvGain gain, std::size_t n,
                                             double unexposed_share, std::uint64_t seed) {
  const ExplorationState& S = state(map);
  std::vector<Eigen::Vector3d> out;
  if (gain == NbvGain::FrontierVoid && !S.void_set.empty()) {
    AimRequest req;
    req.cells = n;
    req.unexposed_share = unexposed_share;
    req.seed = seed;
    for (CellKey k : draw_void_cells(S, req)) out.push_back(S.center(k));
    return out;
  }
  std::vector<CellKey> cells;
  cells.reserve(S.frontier_label.size());
  for (const auto& kv : S.frontier_label) cells.push_back(kv.first);
  std::sort(cells.begin(), cells.end());
  std::mt19937_64 rng(seed);
  n = std::min(n, cells.size());
  for (std::size_t i = 0; i < n; ++i) {
    std::swap(cells[i], cells[i + std::size_t(rng() % (cells.size() - i))]);
    out.push_back(S.center(cells[i]));
  }
  return out;
}

AimResult aim_camera(const NbvOptions& opt, const Eigen::Vector3d& target, std::size_t index) {
  const Chain& chain = *opt.chain;
  AimOptions o;
  o.tolerance = opt.look_at_tolerance;
  o.seed = opt.seed + index;
  std::mt19937_64 rng(~o.seed);  // not aim()'s restart stream: the start is not its first restart
  const Eigen::VectorXd start = chain.random_configuration(rng);
  return aim(chain, opt.chain_base.inverse() * target, o, &start);
}

LookAtViews look_at_views(const ExplorationMap& map, const CameraIntrinsics& cam,
                          const std::vector<Eigen::Vector3d>& targets, const NbvOptions& opt,
                          const ViewChecker& checker, const ScoreModel& model, std::size_t max_valid,
                          std::size_t full_best) {
  const Chain& chain = *opt.chain;
  const int threads = default_threads(opt.threads);
  std::vector<AimResult> aims(targets.size());
  parallel_for(targets.size(), threads, [&](std::size_t i, int) { aims[i] = aim_camera(opt, targets[i], i); }, 4);
  LookAtViews out;
  std::set<std::vector<long>> seen;
  std::vector<ScoredView> views;
  for (const AimResult& a : aims) {
    if (!a.reached) {
      ++out.aim_failures;
      continue;
    }
    if (!seen.insert(aim_key(a.q)).second) continue;
    ScoredView v;
    v.q = a.q;
    v.pose = opt.chain_base * chain.fk(a.q);
    views.push_back(std::move(v));
  }
  std::vector<Eigen::Vector3d> pos(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) pos[i] = views[i].pose.translation();
  const std::vector<bool> keep = filter_verdicts(opt, pos);
  const Pose to_arm = opt.capability_base.inverse();
  parallel_for(views.size(), threads, [&](std::size_t i, int) {
    ScoredView& s = views[i];
    const Eigen::Vector3d p = s.pose.translation();
    if (!keep[i] || !opt.workspace.contains(p))
      s.status = ViewStatus::OutsideWorkspace;
    else if (!position_reachable(opt, to_arm, p) || !checker.axis_reachable(s.pose))
      s.status = ViewStatus::NotReachable;
    else if (!checker.camera_clear(p))
      s.status = ViewStatus::CameraNotClear;
    else
      s.status = checker.arm_clear(s.q);
  }, 1);
  std::vector<std::size_t> valid;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const ViewStatus st = views[i].status;
    out.camera_not_clear += st == ViewStatus::CameraNotClear;
    out.arm_collisions += st == ViewStatus::ArmCollision;
    out.capability_rejected += st == ViewStatus::NotReachable;
    if (st == ViewStatus::Valid && valid.size() < max_valid) valid.push_back(i);
  }
  // full_best > 0: a quarter of the rays (as rescored_views' coarse score) rank the valid views, and only the best
  // full_best by the gain go on, scored in full
  const bool coarse = full_best > 0 && valid.size() > full_best;
  parallel_for(valid.size(), threads, [&](std::size_t j, int) {
    score_view(map, cam, opt, model, views[valid[j]], coarse ? 2 : 1);
  }, 1);
  if (coarse) {  // the best full_best in turn (a few: a scan each; ties keep the earlier target)
    std::vector<char> taken(views.size(), 0);
    for (std::size_t k = 0; k < full_best; ++k) {
      std::size_t pick = views.size();
      for (std::size_t i : valid)
        if (!taken[i] && (pick == views.size() || ranks_before(views[i], views[pick], RankKey::Gain))) pick = i;
      taken[pick] = 1;
    }
    valid.clear();
    for (std::size_t i = 0; i < views.size(); ++i)  // target order
      if (taken[i]) valid.push_back(i);
    parallel_for(valid.size(), threads, [&](std::size_t j, int) { score_view(map, cam, opt, model, views[valid[j]]); }, 1);
  }
  out.scored.gain = opt.gain;
  std::tie(out.scored.pass_probability, out.scored.void_pass_probability) = model.p;
  out.scored.dof = std::size_t(chain.dof());
  for (std::size_t i : valid) out.scored.views.push_back(std::move(views[i]));
  return out;
}

NbvResult look_at_search(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  NbvResult r;
  r.gain = opt.gain;
  const ScoreModel model = score_model(map, opt);
  std::tie(r.pass_probability, r.void_pass_probability) = model.p;
  const std::vector<Eigen::Vector3d> targets =
      look_at_targets(map, opt.gain, std::size_t(opt.max_candidate_cells), kTargetsUnexposedShare, opt.seed);
  r.candidate_cells = targets.size();
  const ViewChecker checker(map, opt);
  const auto t_score = Clock::now();
  r.seconds_prune = std::chrono::duration<double>(t_score - t0).count();
  LookAtViews found = look_at_views(map, cam, targets, opt, checker, model, std::size_t(opt.max_valid_poses));
  r.ik_failures = found.aim_failures;
  r.camera_not_clear = found.camera_not_clear;
  r.arm_collisions = found.arm_collisions;
  r.capability_rejected = found.capability_rejected;
  r.poses_scored = found.scored.views.size();
  for (ScoredView& v : found.scored.views) r.ranked.push_back(std::move(v));
  std::stable_sort(r.ranked.begin(), r.ranked.end(),
                   [](const ViewCandidate& a, const ViewCandidate& b) { return ranks_before(a, b); });
  r.seconds_score = std::chrono::duration<double>(Clock::now() - t_score).count();
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

}  // namespace octoreach::detail
