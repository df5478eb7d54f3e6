// What announced views teach (next_best_view.hpp, "Visibility model"): after the insert of a view announced with
// expect_view, the visibility curve learns the share of its expected cells it saw, the cells it missed lose
// seeability, and lines of sight that returned nothing are kept (blind_lines.hpp).
#include <algorithm>
#include <cmath>

#include "exploration/exploration_state.hpp"
#include "exploration/grid_ray.hpp"
#include "exploration/view_score.hpp"

namespace octoreach {

namespace detail {

namespace {

// Weighted isotonic regression (pool adjacent violators): the non-increasing sequence closest to
// seen[d] / n[d] in the n-weighted least squares sense; bins without cells take their left neighbour's value.
void non_increasing_share(const double* n, const double* seen, double* share, int count) {
  std::vector<double> val, wt;
  std::vector<int> len;
  for (int d = 0; d < count; ++d) {
    if (n[d] <= 0) {
      len.empty() ? void() : void(++len.back());  // an empty bin joins the block before it
      if (len.empty()) val.push_back(1.0), wt.push_back(0.0), len.push_back(1);
      continue;
    }
    val.push_back(seen[d] / n[d]), wt.push_back(n[d]), len.push_back(1);
    while (val.size() > 1 && val[val.size() - 2] < val.back()) {  // a rise: pool the two blocks
      const std::size_t b = val.size() - 1;
      const double w = wt[b - 1] + wt[b];
      val[b - 1] = w > 0 ? (val[b - 1] * wt[b - 1] + val[b] * wt[b]) / w : val[b];
      wt[b - 1] = w, len[b - 1] += len[b];
      val.pop_back(), wt.pop_back(), len.pop_back();
    }
  }
  int d = 0;
  for (std::size_t b = 0; b < val.size(); ++b)
    for (int i = 0; i < len[b]; ++i) share[d++] = val[b];
}

// True when the line from `eye` through cell k goes on to an occupied cell within `range` of the eye: rays
// through k could have ended on it, so k's staying unknown proves nothing about where they ended (no pixel's
// ray may have crossed k).
bool surface_behind(const ExplorationState& S, double res, const Eigen::Vector3d& eye, CellKey k, double range) {
  const Eigen::Vector3d c = S.center(k);
  const double n = (c - eye).norm();
  if (!(n > 0) || n >= range) return false;
  bool hit = false;
  walk_cells(res, c, (c - eye) / n, range - n, [&](CellKey x) {
    hit = x != k && S.state(x) == CellState::Occupied && surface_meets_line(S, x, c, (c - eye) / n);
    return !hit;
  });
  return hit;
}

}  // namespace

void learn_from_missed(const ExplorationMap& map, ExplorationState& S, bool returned) {
  VisibilityCurve& c = S.curve;
  // The announced view's rays walked again through the updated map: the unknown cells they still meet
  // before the first occupied cell. A cell the view expected, left unknown and no longer met lies
  // behind a surface this insert saw: the miss says nothing about views from other sides, so its
  // seeability stays (views from this side stop at that surface anyway).
  KeyTable<std::uint8_t> still_met(S.announced ? S.expected_by_view.size() : 0);
  if (S.announced && !S.expected_by_view.empty()) {
    std::vector<ExpectedCell> met;
    const AnnouncedView& a = *S.announced;
    view_gains_unlocked(map, a.camera, a.pose, a.score_width, a.score_height, 1.0, 1.0, false, &met);
    for (const ExpectedCell& e : met) still_met.at(e.key) = 1;
  }
  if (!S.expected_by_view.empty()) {
    const std::uint64_t known_void = S.rays.void_to_free + S.rays.void_to_occupied;
    const std::uint64_t known_other = S.rays.unknown_to_free + S.rays.unknown_to_occupied - known_void;
    c.known_total[0] += double(known_other - c.known_at_announce[0]);
    c.known_total[1] += double(known_void - c.known_at_announce[1]);
  }
  const double res = map.resolution();
  const SpaceKeys space = space_keys(map.options());
  const Eigen::Vector3d eye = S.announced ? Eigen::Vector3d(S.announced->pose.translation()) : Eigen::Vector3d::Zero();
  for (const ExpectedCell& e : S.expected_by_view) {
    // the model expects w s of a cell (s: its seeability from the view's eye, 0 along a line that returned
    // nothing): the curve learns the seen share per unit of seeability, so cells already missed weigh less in it
    const int d = std::min<int>(e.depth, VisibilityCurve::kDepths - 1);
    const Eigen::Vector3d centre = S.center(e.key);
    if (S.announced && S.blind.covers(e.key, centre, eye)) continue;
    c.expected[e.void_cell][d] += S.seeability(e.key);
    if (S.state(e.key) != CellState::Unknown) {
      c.seen[e.void_cell][d] += 1;
      c.known_met_beam[e.void_cell] += e.beam;
      continue;
    }
    if (S.announced && !still_met.find(e.key)) continue;  // explained by a surface seen in between
    // a void cell still met and still unknown, nothing behind it within range, and the insert had points: the
    // camera's rays through it returned nothing (blind_lines.hpp; an empty insert, a dropped frame, proves nothing)
    // (for void cells and the search space's unknown cells: those are what views count)
    if (S.announced && returned && (e.void_cell || space.contains(e.key)) &&
        !surface_behind(S, res, eye, e.key, S.announced->camera.max_range))
      S.blind.add(e.key, centre, eye, res);
    float& h = S.hidden.at(e.key);  // s' = s (1 - w), kept as h = 1 - s
    h = float(1.0 - (1.0 - double(h)) * (1.0 - std::min(std::max(double(e.weight), 0.0), 1.0)));
  }
  if (!S.expected_by_view.empty()) c.taught = true;
  if (!S.expected_by_view.empty())
    for (int cls = 0; cls < 2; ++cls)
      non_increasing_share(c.expected[cls], c.seen[cls], c.share[cls], VisibilityCurve::kDepths);
  S.expected_by_view.clear();
  S.announced.reset();
}

}  // namespace detail

void expect_view(ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, const NbvOptions& opt) {
  detail::validate_options(cam, opt);
  check_rigid(pose, "camera pose");
  detail::ExplorationState& S = detail::mutable_state(map);
  detail::MapGuard guard(S, true);
  const auto p = detail::pass_probabilities(map, opt);
  S.expected_by_view.clear();
  S.announced = detail::AnnouncedView{cam, pose, opt.score_width, opt.score_height};
  const std::uint64_t known_void = S.rays.void_to_free + S.rays.void_to_occupied;
  S.curve.known_at_announce[0] = S.rays.unknown_to_free + S.rays.unknown_to_occupied - known_void;
  S.curve.known_at_announce[1] = known_void;
  detail::view_gains_unlocked(map, cam, pose, opt.score_width, opt.score_height, p.first, p.second,
                              opt.unknown_pass_probability < 0, &S.expected_by_view);
}

std::size_t missed_cells(const ExplorationMap& map) {
  auto guard = detail::read_guard(map);
  return detail::state(map).hidden.size();
}

VisibilityCurveTable visibility_curve(const ExplorationMap& map) {
  auto guard = detail::read_guard(map);
  const detail::VisibilityCurve& c = detail::state(map).curve;
  VisibilityCurveTable t;
  for (int cls = 0; cls < 2; ++cls) {
    const int n = detail::VisibilityCurve::kDepths;
    t.expected[cls].assign(c.expected[cls], c.expected[cls] + n);
    t.seen[cls].assign(c.seen[cls], c.seen[cls] + n);
    t.share[cls].assign(c.share[cls], c.share[cls] + n);
  }
  return t;
}

}  // namespace octoreach
