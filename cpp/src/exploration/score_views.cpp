// Scores given camera poses: score_views (every pose, the checks that make it a view, the full score) and
// rescored_views (the loop's aimed looks: a coarse first score, IK in its order, the best scored in full).
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include "common/thread_pool.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/look_at_views.hpp"
#include "exploration/view_score.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/robot.hpp"

namespace octoreach {

namespace {

// score_views' checks of pose i before IK: the workspace (and its filter's verdict `kept`), the capability map,
// the camera's clearance.
ViewStatus check_before_ik(const NbvOptions& opt, const detail::ViewChecker& checker, const Pose& to_arm,
                           const Pose& pose, bool kept) {
  const Eigen::Vector3d p = pose.translation();
  if (!kept || !opt.workspace.contains(p)) return ViewStatus::OutsideWorkspace;
  if (!detail::position_reachable(opt, to_arm, p) || !checker.axis_reachable(pose))
    return ViewStatus::NotReachable;
  if (!checker.camera_clear(p)) return ViewStatus::CameraNotClear;
  return ViewStatus::Valid;
}

// The options and every pose checked (a bad one throws std::invalid_argument naming it).
void check_poses(const CameraIntrinsics& cam, const NbvOptions& opt, const std::vector<Pose>& poses) {
  detail::validate_options(cam, opt);
  for (std::size_t i = 0; i < poses.size(); ++i) check_rigid(poses[i], "pose " + std::to_string(i));
}

void set_not_scored(ScoredView& s) {
  constexpr double kNotScored = std::numeric_limits<double>::quiet_NaN();
  s.expected_void = s.expected_unknown = s.expected_frontier = s.expected_gain = s.utility_dm3 =
      s.expected_enclosed_void = kNotScored;
}

void set_model_fields(ScoredViews& out, const detail::ScoreModel& model, const NbvOptions& opt) {
  out.gain = opt.gain;
  std::tie(out.pass_probability, out.void_pass_probability) = model.p;
  out.dof = opt.chain ? opt.chain->dof() : 0;
}

}  // namespace

ScoredViews score_views(const ExplorationMap& map, const CameraIntrinsics& cam, const std::vector<Pose>& poses,
                        const NbvOptions& opt, bool score_invalid) {
  detail::CancellableScope cancellable;  // poses are polled between them; the map is only read
  check_poses(cam, opt, poses);
  ScoredViews out;
  out.views.resize(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) out.views[i].pose = poses[i];
  // A chain that can only aim its camera looks at the point half the camera's range along each pose's optical
  // axis (where the pose's own position matters least): every check and the score are of the pose it reaches.
  const bool aims = looks_at(opt);
  std::vector<char> aimed(poses.size(), 1);
  if (aims)
    detail::parallel_for(poses.size(), detail::default_threads(opt.threads), [&](std::size_t i, int) {
      const Eigen::Vector3d target = poses[i].translation() + 0.5 * cam.max_range * poses[i].linear().col(2);
      const AimResult a = detail::aim_camera(opt, target, i);
      aimed[i] = a.reached;
      if (!a.reached) return;
      out.views[i].q = a.q;
      out.views[i].pose = opt.chain_base * opt.chain->fk(a.q);
    }, 4);
  std::vector<Eigen::Vector3d> pos(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) pos[i] = out.views[i].pose.translation();
  const std::vector<bool> keep = detail::filter_verdicts(opt, pos);
  auto guard = detail::read_guard(map);
  const detail::ScoreModel model = detail::score_model(map, opt);
  const detail::ViewChecker checker(map, opt);
  const Pose to_arm = opt.capability_base.inverse();
  set_model_fields(out, model, opt);
  detail::parallel_for(poses.size(), detail::default_threads(opt.threads), [&](std::size_t i, int) {
    ScoredView& s = out.views[i];
    s.status = aimed[i] ? check_before_ik(opt, checker, to_arm, s.pose, keep[i]) : ViewStatus::NoIk;
    if (s.status == ViewStatus::Valid && opt.chain)
      s.status = aims ? checker.arm_clear(s.q) : checker.reach(s.pose, s.q, i);
    if (score_invalid || s.valid())
      detail::score_view(map, cam, opt, model, s);
    else
      set_not_scored(s);
  }, 1);
  return out;
}

namespace detail {

std::vector<bool> filter_verdicts(const NbvOptions& opt, const std::vector<Eigen::Vector3d>& pos) {
  if (!opt.workspace.filter || pos.empty()) return std::vector<bool>(pos.size(), true);
  std::vector<bool> keep = opt.workspace.filter(pos);
  if (keep.size() != pos.size())
    throw std::invalid_argument("workspace filter returned " + std::to_string(keep.size()) + " values for " +
                                std::to_string(pos.size()) + " positions");
  return keep;
}

// rescored_views: when more than kFirstPass x rescore_best poses pass the checks before IK (the second look's
// 400 aims may, a low view's 1200 and the last chance's 1000 do), a score with every fourth ray of the grid (a
// sixteenth of the full score's rays) ranks them, and they get the coarse score and IK in chunks of kFirstPass x
// rescore_best in that order until rescore_best are valid. 16 is a chosen margin, as rescore_best's 16 is,
// checked with benchmarks/view_choice_times.py (the same views and stops as without the first pass).
constexpr std::size_t kFirstPass = 16;

ScoredViews rescored_views(const ExplorationMap& map, const CameraIntrinsics& cam, const std::vector<Pose>& poses,
                           const NbvOptions& opt, RankKey key) {
  if (opt.rescore_best <= 0 || looks_at(opt)) return score_views(map, cam, poses, opt, false);
  CancellableScope cancellable;
  check_poses(cam, opt, poses);
  std::vector<Eigen::Vector3d> pos(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) pos[i] = poses[i].translation();
  const std::vector<bool> keep = filter_verdicts(opt, pos);
  auto guard = read_guard(map);
  const ScoreModel model = score_model(map, opt);
  const ViewChecker checker(map, opt);
  const Pose to_arm = opt.capability_base.inverse();
  const int threads = default_threads(opt.threads);
  // the checks before IK of every pose
  std::vector<ScoredView> coarse(poses.size());
  parallel_for(poses.size(), threads, [&](std::size_t i, int) {
    ScoredView& s = coarse[i];
    s.pose = poses[i];
    s.status = check_before_ik(opt, checker, to_arm, s.pose, keep[i]);
  }, 16);
  std::vector<std::size_t> order;  // the poses that pass, in sample order
  for (std::size_t i = 0; i < coarse.size(); ++i)
    if (coarse[i].valid()) order.push_back(i);
  const auto by_key = [&](std::size_t a, std::size_t b) { return ranks_before(coarse[a], coarse[b], key); };
  // of many, a first pass with every fourth ray of the grid ranks them, and they go on in chunks of kFirstPass x
  // rescore_best in that order; else in one chunk
  const std::size_t want = std::size_t(opt.rescore_best);
  const std::size_t chunk = order.size() > kFirstPass * want ? kFirstPass * want : order.size();
  if (chunk < order.size()) {
    parallel_for(order.size(), threads, [&](std::size_t j, int) {
      score_view(map, cam, opt, model, coarse[order[j]], 4);
    }, 1);
    std::stable_sort(order.begin(), order.end(), by_key);
  }
  // each chunk: the coarse score, then IK and the arm's collisions in its order, in batches, until rescore_best
  // are valid (those after the rescore_best-th valid one are dropped, whatever the batch size: the same views for
  // any thread count)
  const std::size_t batch = std::size_t(std::max(threads, 1)) * 4;
  std::vector<std::size_t> checked;
  std::size_t valid = 0;
  for (std::size_t c = 0; c < order.size() && valid < want; c += chunk) {
    const std::size_t end = std::min(order.size(), c + chunk);
    const auto first = order.begin() + std::ptrdiff_t(c), last = order.begin() + std::ptrdiff_t(end);
    std::sort(first, last);  // ties in the coarse order: the sample order
    parallel_for(end - c, threads, [&](std::size_t j, int) {
      score_view(map, cam, opt, model, coarse[order[c + j]], 2);
    }, 1);
    std::stable_sort(first, last, by_key);
    for (std::size_t b = c; b < end && valid < want; b += batch) {
      const std::size_t e = std::min(end, b + batch);
      if (opt.chain)
        parallel_for(e - b, threads, [&](std::size_t j, int) {
          ScoredView& s = coarse[order[b + j]];
          s.status = checker.reach(s.pose, s.q, order[b + j]);
        }, 1);
      for (std::size_t j = b; j < e && valid < want; ++j) {
        checked.push_back(order[j]);
        valid += coarse[order[j]].valid() ? 1 : 0;
      }
    }
  }
  std::sort(checked.begin(), checked.end());
  ScoredViews out;
  set_model_fields(out, model, opt);
  for (std::size_t i : checked) out.views.push_back(coarse[i]);
  parallel_for(out.views.size(), threads, [&](std::size_t j, int) {
    ScoredView& s = out.views[j];
    if (s.valid())
      score_view(map, cam, opt, model, s);
    else
      set_not_scored(s);
  }, 1);
  return out;
}

}  // namespace detail

}  // namespace octoreach
