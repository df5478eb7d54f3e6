// Next best view (Algorithm 1, section IV-C), in its steps: utility vectors and their accumulation
// (1-2), pruning of the candidate cells (3), sampling and scoring camera poses (4).
#include "octoreach/next_best_view.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <tuple>

#include "exploration/cell_sets.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/grid_ray.hpp"
#include "exploration/look_at_views.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "exploration/view_score.hpp"

namespace octoreach {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Algorithm 1's utility vectors: from each void's centre and the ends of its axes through every
// frontier cell next to it, carrying the void's utility; in a fixed order.
struct UtilityVector {
  Eigen::Vector3d from, dir;
  double u;
};

std::vector<UtilityVector> utility_vectors(const ExplorationMap& map, const detail::VoidWeights& weights = {}) {
  std::vector<UtilityVector> out;
  const auto& vcs = detail::cached_void_clusters(map);
  const auto& S = detail::state(map);
  const double cell = std::pow(map.resolution(), 3);
  for (const auto& fv : map.frontier_voids()) {
    const VoidCluster& v = vcs[fv.void_index];
    // the paper's u_i, "the expectation of the void volume that will be discovered": the void's volume,
    // each cell weighted by its seeability (1 until views that expected it missed it, see expect_view)
    // and, with enclosure_power, by its enclosure
    double utility = fv.utility;
    if (S.hidden.size() || S.sealed.size() || weights) {
      utility = 0;
      for (CellKey k : v.cells) utility += S.seeability(k) * weights.of(k) * cell;
    }
    if (utility <= 0) continue;
    std::vector<Eigen::Vector3d> corners{v.centroid};
    for (int j = 0; j < 3; ++j)
      for (int s = -1; s <= 1; s += 2) corners.push_back(v.centroid + s * v.semi_axes[j] * v.axes.col(j));
    for (const Eigen::Vector3d& c : corners)
      for (CellKey f : fv.frontier_cells) {
        Eigen::Vector3d pf = map.center(f);
        Eigen::Vector3d dir = pf - c;
        if (dir.norm() < 1e-9) continue;
        out.push_back({pf, dir.normalized(), utility});
      }
  }
  return out;
}

// The utility vectors of the Frontiers and Unknown gains: from every frontier cell (at most
// kMaxFrontierVectors, evenly strided) away from its unknown 6-neighbours, carrying one cell's volume
// (Frontiers) or one per unknown neighbour (Unknown).
constexpr std::size_t kMaxFrontierVectors = 20000;
std::vector<UtilityVector> frontier_vectors(const ExplorationMap& map, NbvGain gain) {
  std::vector<UtilityVector> out;
  const auto& S = detail::state(map);
  detail::GridReader g(S.grid);
  std::vector<CellKey> fr;
  for (const auto& [k, label] : S.frontier_label)
    if (g.get(k) & detail::kFrontierFlag) fr.push_back(k);
  std::sort(fr.begin(), fr.end());
  const std::size_t stride = std::max<std::size_t>(1, (fr.size() + kMaxFrontierVectors - 1) / kMaxFrontierVectors);
  const double cell = std::pow(map.resolution(), 3);
  for (std::size_t i = 0; i < fr.size(); i += stride) {
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    int unknown = 0;
    for (const auto& d : detail::kN6) {
      CellKey nb;
      if (detail::neighbour(fr[i], d[0], d[1], d[2], nb) && (g.get(nb) & detail::kStateMask) == 0) {
        dir -= Eigen::Vector3d(d[0], d[1], d[2]);
        ++unknown;
      }
    }
    if (dir.norm() < 1e-9) continue;
    out.push_back({map.center(fr[i]), dir.normalized(), cell * (gain == NbvGain::Unknown ? unknown : 1)});
  }
  return out;
}

// Utility summed over the vectors that reach a free cell, and the mean direction back to the voids.
struct Utility {
  double u = 0;
  Eigen::Vector3d dir = Eigen::Vector3d::Zero();
};
using UtilityCell = std::pair<CellKey, Utility>;

// How far along a ray (origin o, unit dir, up to `length`) a cell whose centre lies in the workspace's
// box and sphere can be met: the exit of the box and sphere grown by half a cell diagonal (a cell the ray
// passes through has its centre that close to the ray), plus one cell; -1 when the ray meets none.
double workspace_reach(const SensorWorkspace& ws, double res, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                       double length) {
  const double grow = 0.5 * std::sqrt(3.0) * res + 1e-9;
  double t0 = 0, t1 = length;
  if (ws.sphere_center) {
    const Eigen::Vector3d oc = o - *ws.sphere_center;
    const double b = oc.dot(dir), r = ws.sphere_radius + grow;
    const double disc = b * b - (oc.squaredNorm() - r * r);
    if (!(disc >= 0)) return -1;
    t0 = std::max(t0, -b - std::sqrt(disc));
    t1 = std::min(t1, -b + std::sqrt(disc));
  }
  if (ws.box)
    for (int i = 0; i < 3; ++i) {
      const double lo = ws.box->lo[i] - grow, hi = ws.box->hi[i] + grow;
      if (dir[i] == 0) {
        if (o[i] < lo || o[i] > hi) return -1;
        continue;
      }
      double a = (lo - o[i]) / dir[i], b = (hi - o[i]) / dir[i];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
  return t0 <= t1 ? std::min(length, t1 + res) : -1;
}

// Step 2: each vector traced from its frontier cell through free cells, and through unknown cells
// outside the map's search space but not below its floor (the safe-view rule does not count them as
// obstacles either: the robot's side of the scene, which no view of the search space needs to have
// seen; below the search space lies the ground the robot stands on), up to `range`. The vectors
// are cut into `slices` fixed slices, each summed into its own table and merged in slice order,
// so the sums depend neither on the number of threads nor on scheduling. Sorted by key.
// With `workspace`, only cells whose centre it contains are summed, and a walk ends where the ray
// leaves it (workspace_reach): the same sums for those cells, the only ones step 3 keeps.
std::vector<UtilityCell> accumulate(const ExplorationMap& map, const std::vector<UtilityVector>& vecs, double range,
                                    std::size_t slices, int threads, const SensorWorkspace* workspace = nullptr) {
  const auto& S = detail::state(map);
  const auto& grid = S.grid;
  const double res = map.resolution();
  const Eigen::Vector3d s_lo = map.options().search_lo, s_hi = map.options().search_hi;
  std::vector<detail::KeyTable<Utility>> tables(slices, detail::KeyTable<Utility>(2040));
  detail::parallel_for(slices, threads, [&](std::size_t sl, int) {
    detail::GridReader g(grid);
    auto& t = tables[sl];
    const std::size_t b = vecs.size() * sl / slices, e = vecs.size() * (sl + 1) / slices;
    for (std::size_t i = b; i < e; ++i) {
      const UtilityVector& v = vecs[i];
      const double length = workspace ? workspace_reach(*workspace, res, v.from, v.dir, range) : range;
      if (length < 0) continue;
      detail::walk_cells(res, v.from, v.dir, length, [&](CellKey k) {
        const std::uint8_t st = g.get(k) & detail::kStateMask;
        if (st == std::uint8_t(CellState::Occupied)) return !detail::surface_meets_line(S, k, v.from, v.dir);
        if (st == std::uint8_t(CellState::Unknown)) {  // only outside the search space, and not below its floor
          const Eigen::Vector3d c = S.center(k);
          if (c.z() < s_lo.z() || ((c.array() >= s_lo.array()).all() && (c.array() <= s_hi.array()).all()))
            return false;
        }
        if (workspace && !workspace->contains(map.center(k))) return true;
        Utility& a = t.at(k);
        a.u += v.u;
        a.dir -= v.u * v.dir;
        return true;
      });
    }
  }, 1);
  auto& all = tables[0];
  for (std::size_t sl = 1; sl < slices; ++sl)
    tables[sl].for_each([&](CellKey k, const Utility& x) {
      Utility& a = all.at(k);
      a.u += x.u;
      a.dir += x.dir;
    });
  std::vector<UtilityCell> cells;
  cells.reserve(all.size());
  all.for_each([&](CellKey k, const Utility& x) { cells.emplace_back(k, x); });
  std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return cells;
}

// Step 3a: keeps the cells inside the workspace where the capability map (if any) reaches some
// orientation in one of the 8 voxels around them (Zacharias et al.: a cell is a sensor position only there;
// between the map's voxels IK decides).
void prune_by_workspace(const ExplorationMap& map, const NbvOptions& opt, std::vector<UtilityCell>& cells,
                        NbvResult& r) {
  std::vector<Eigen::Vector3d> pos(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) pos[i] = map.center(cells[i].first);
  const std::vector<bool> keep = detail::filter_verdicts(opt, pos);
  const Pose to_arm = opt.capability_base.inverse();
  std::size_t w = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!keep[i] || !opt.workspace.contains(pos[i])) continue;
    if (!detail::position_reachable(opt, to_arm, pos[i])) {
      ++r.capability_pruned;
      continue;
    }
    cells[w++] = cells[i];
  }
  cells.resize(w);
}

// Step 3b: best utility first, the cells where the camera would sit in observed-free space (no
// occupied cell within min_distance; with unknown_is_obstacle no unknown cell of the search space
// within unknown_margin), until max_candidate_cells are kept (the check runs only that far).
// The next max_candidate_cells clear cells of `cells` (sorted by utility, best first) from index
// `from`; returns the index after the last cell looked at.
std::size_t keep_clear_cells(const detail::ViewChecker& checker, const ExplorationMap& map, const NbvOptions& opt,
                             const std::vector<UtilityCell>& cells, std::size_t from, std::vector<UtilityCell>& out,
                             NbvResult& r) {
  out.clear();
  std::size_t i = from;
  for (; i < cells.size() && out.size() < std::size_t(opt.max_candidate_cells); ++i) {
    if (checker.camera_clear(map.center(cells[i].first)))
      out.push_back(cells[i]);
    else
      ++r.camera_not_clear;
  }
  return i;
}

constexpr int kMaxCellBatches = 8;  // batches of max_candidate_cells cells tried while no pose is valid

// What scoring one sampled pose came to.
struct Slot {
  bool valid = false, tried_ik = false, collides = false, cap_rejected = false;
  ViewCandidate view;
};

// Step 4, per sampled pose: what every pose of one search shares.
class PoseScorer {
 public:
  PoseScorer(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt,
             const std::vector<UtilityCell>& cells, const detail::ViewChecker& checker, const detail::ScoreModel& model)
      : map_(map), cam_(cam), opt_(opt), cells_(cells), per_cell_(std::size_t(opt.orientations_per_cell)),
        checker_(checker), model_(model) {}
  std::size_t total() const { return cells_.size() * per_cell_; }
  // Pose idx: orientation idx % per_cell of cell idx / per_cell, sampled from its own stream.
  Slot score(std::size_t idx) const;

 private:
  Eigen::Vector3d sample_axis(std::size_t idx, Eigen::Vector3d forward, double& roll) const;

  const ExplorationMap& map_;
  const CameraIntrinsics& cam_;
  const NbvOptions& opt_;
  const std::vector<UtilityCell>& cells_;
  const std::size_t per_cell_;
  const detail::ViewChecker& checker_;
  const detail::ScoreModel& model_;
};

// Orientation 0 looks along the mean direction; the others are drawn in a cone around it.
Eigen::Vector3d PoseScorer::sample_axis(std::size_t idx, Eigen::Vector3d forward, double& roll) const {
  roll = 0;
  if (idx % per_cell_ == 0) return forward;
  detail::Mt64Prefix rng(opt_.seed * 0x9E3779B97F4A7C15ULL + idx);  // (std::mt19937_64's numbers)
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double th = opt_.orientation_spread * std::sqrt(U(rng)), ph = 2 * kPi * U(rng);
  Eigen::Vector3d a = forward.unitOrthogonal(), bvec = forward.cross(a);
  forward = (std::cos(th) * forward + std::sin(th) * (std::cos(ph) * a + std::sin(ph) * bvec)).normalized();
  roll = (U(rng) - 0.5) * 2 * kPi;
  return forward;
}

Slot PoseScorer::score(std::size_t idx) const {
  Slot s;
  const UtilityCell& cell = cells_[idx / per_cell_];
  Eigen::Vector3d forward = cell.second.dir;
  if (forward.norm() < 1e-12) return s;
  double roll;
  forward = sample_axis(idx, forward.normalized(), roll);
  s.view.pose = camera_pose(map_.center(cell.first), forward, roll);
  s.view.cell_utility = cell.second.u;
  if (!checker_.axis_reachable(s.view.pose)) {
    s.cap_rejected = true;
    return s;
  }
  if (opt_.chain) {
    s.tried_ik = true;
    ViewStatus st = checker_.reach(s.view.pose, s.view.q, idx);
    s.collides = st == ViewStatus::ArmCollision;
    if (st != ViewStatus::Valid) return s;
  }
  detail::score_view(map_, cam_, opt_, model_, s.view, opt_.rescore_best > 0 ? 2 : 1);
  s.valid = true;
  return s;
}

// A sampled view (its sample index, the view) ranks before another by ranks_before, then by sample order.
using SampledView = std::pair<std::size_t, ViewCandidate>;
bool ranks_before_sampled(const SampledView& a, const SampledView& b) {
  if (ranks_before(a.second, b.second)) return true;
  if (ranks_before(b.second, a.second)) return false;
  return a.first < b.first;
}

// Step 4: poses in batches (next_batch), in index order, until max_valid_poses are valid;
// ranked by ranks_before (the expected gain, then expected unknown cells), then index.
void score_candidates(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt,
                      const std::vector<UtilityCell>& cells, const detail::ViewChecker& checker,
                      const detail::ScoreModel& model, int threads, NbvResult& r, std::vector<std::size_t>& sampled) {
  const PoseScorer scorer(map, cam, opt, cells, checker, model);
  const std::size_t total = scorer.total(), max_valid = std::size_t(opt.max_valid_poses);
  const std::size_t least = std::size_t(std::max(threads, 1)) * 4;
  std::size_t batch = least;
  std::vector<std::pair<std::size_t, ViewCandidate>> valid;
  std::size_t valid_seen = 0;  // valid poses of this call, also those past max_valid
  for (std::size_t start = 0; start < total && valid.size() < max_valid;) {
    std::vector<Slot> slots(std::min(total, start + batch) - start);
    detail::parallel_for(slots.size(), threads, [&](std::size_t b, int) { slots[b] = scorer.score(start + b); }, 1);
    for (std::size_t b = 0; b < slots.size(); ++b) {
      if (slots[b].cap_rejected) ++r.capability_rejected;
      if (slots[b].collides) ++r.arm_collisions;
      else if (slots[b].tried_ik && !slots[b].valid) ++r.ik_failures;
      if (!slots[b].valid) continue;
      ++r.poses_scored;
      ++valid_seen;
      if (valid.size() < max_valid) valid.emplace_back(start + b, std::move(slots[b].view));
    }
    start += slots.size();
    batch = detail::next_batch(max_valid - std::min(max_valid, valid.size()), valid_seen, start, least, batch);
  }
  std::sort(valid.begin(), valid.end(), ranks_before_sampled);
  for (auto& v : valid) {
    sampled.push_back(v.first);
    r.ranked.push_back(std::move(v.second));
  }
}

// NbvOptions::rescore_best: the ranked views (scored with the coarse grid; `sampled`: each one's sample index)
// become the best of each ranking key, scored with the full grid and ranked again (ties: the sample order).
void rescore_best(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt,
                  const detail::ScoreModel& model, int threads, NbvResult& r, const std::vector<std::size_t>& sampled) {
  std::vector<const ViewCandidate*> coarse;
  for (const ViewCandidate& v : r.ranked) coarse.push_back(&v);
  std::vector<std::pair<std::size_t, ViewCandidate>> best;
  for (std::size_t i : detail::best_by_each_key(coarse, std::size_t(opt.rescore_best)))
    best.emplace_back(sampled[i], r.ranked[i]);
  detail::parallel_for(best.size(), threads, [&](std::size_t i, int) {
    detail::score_view(map, cam, opt, model, best[i].second);
  }, 1);
  std::sort(best.begin(), best.end(), ranks_before_sampled);
  r.ranked.clear();
  for (auto& v : best) r.ranked.push_back(std::move(v.second));
}

}  // namespace

bool SensorWorkspace::contains(const Eigen::Vector3d& p) const {
  if (box && !box->contains(p)) return false;
  if (sphere_center && (p - *sphere_center).norm() > sphere_radius) return false;
  return true;
}

std::vector<std::pair<CellKey, double>> accumulate_utility(const ExplorationMap& map, double sensor_range,
                                                           std::size_t* vectors) {
  detail::CancellableScope cancellable;
  if (!(sensor_range > 0) || !(sensor_range <= limits::kCoordinate))
    throw std::invalid_argument("sensor_range must be a positive number of metres up to " +
                                std::to_string(int(limits::kCoordinate)) + ", got " + std::to_string(sensor_range));
  auto guard = detail::read_guard(map);
  const std::vector<UtilityVector> vecs = utility_vectors(map);
  if (vectors) *vectors = vecs.size();
  std::vector<std::pair<CellKey, double>> out;
  for (const auto& [k, a] : accumulate(map, vecs, sensor_range, 1, 1)) out.emplace_back(k, a.u);
  return out;
}

NbvResult next_best_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt) {
  detail::CancellableScope cancellable;  // every parallel step polls; the map is only read
  auto t0 = Clock::now();
  detail::validate_options(cam, opt);
  auto guard = detail::read_guard(map);
  if (looks_at(opt)) return detail::look_at_search(map, cam, opt);  // the chain aims its camera at targets
  NbvResult r;
  r.gain = opt.gain;
  const detail::ScoreModel model = detail::score_model(map, opt);
  std::tie(r.pass_probability, r.void_pass_probability) = model.p;
  const int threads = detail::default_threads(opt.threads);
  const std::vector<UtilityVector> vecs =
      opt.gain == NbvGain::FrontierVoid ? utility_vectors(map, model.void_weights) : frontier_vectors(map, opt.gain);
  r.utility_vectors = vecs.size();
  std::vector<UtilityCell> cells = accumulate(map, vecs, cam.max_range, 8, threads, &opt.workspace);
  r.utility_cells = cells.size();
  r.seconds_vectors = seconds_since(t0);

  auto t_prune = Clock::now();
  prune_by_workspace(map, opt, cells, r);
  r.candidate_cells = cells.size();
  const detail::ViewChecker checker(map, opt);
  std::stable_sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.second.u > b.second.u; });
  std::vector<UtilityCell> batch;
  std::size_t next = keep_clear_cells(checker, map, opt, cells, 0, batch, r);
  r.seconds_prune = seconds_since(t_prune);

  auto t_score = Clock::now();
  std::vector<std::size_t> sampled;  // the ranked views' sample indices
  score_candidates(map, cam, opt, batch, checker, model, threads, r, sampled);
  // The paper walks the cells by utility until it has valid poses: when the best max_candidate_cells
  // cells give none (arm collisions, no IK), the next ones are tried, up to kMaxCellBatches batches.
  for (int round = 1; round < kMaxCellBatches && r.ranked.empty() && next < cells.size(); ++round) {
    next = keep_clear_cells(checker, map, opt, cells, next, batch, r);
    score_candidates(map, cam, opt, batch, checker, model, threads, r, sampled);
  }
  if (opt.rescore_best > 0) rescore_best(map, cam, opt, model, threads, r, sampled);
  r.seconds_score = seconds_since(t_score);
  r.seconds = seconds_since(t0);
  return r;
}

}  // namespace octoreach
