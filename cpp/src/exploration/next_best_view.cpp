// Next best view (Algorithm 1, section IV-C), in its steps: utility vectors and their accumulation
// (1-2), pruning of the candidate cells (3), sampling and scoring camera poses (4).
#include "octoreach/next_best_view.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "cell_sets.hpp"
#include "common/thread_pool.hpp"
#include "exploration_state.hpp"
#include "grid_ray.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"

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

std::pair<std::size_t, std::size_t> view_utility_unlocked(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                          const Pose& pose, int sw, int sh);

std::vector<UtilityVector> utility_vectors(const ExplorationMap& map) {
  std::vector<UtilityVector> out;
  const auto& vcs = detail::cached_void_clusters(map);
  for (const auto& fv : map.frontier_voids()) {
    const VoidCluster& v = vcs[fv.void_index];
    std::vector<Eigen::Vector3d> corners{v.centroid};
    for (int j = 0; j < 3; ++j)
      for (int s = -1; s <= 1; s += 2) corners.push_back(v.centroid + s * v.semi_axes[j] * v.axes.col(j));
    for (const Eigen::Vector3d& c : corners)
      for (CellKey f : fv.frontier_cells) {
        Eigen::Vector3d pf = map.center(f);
        Eigen::Vector3d dir = pf - c;
        if (dir.norm() < 1e-9) continue;
        out.push_back({pf, dir.normalized(), fv.utility});
      }
  }
  return out;
}

// Utility summed over the vectors that reach a free cell, and the mean direction back to the voids.
struct Utility {
  double u = 0;
  Eigen::Vector3d dir = Eigen::Vector3d::Zero();
};
using UtilityCell = std::pair<CellKey, Utility>;

// Step 2: each vector traced from its frontier cell through free cells up to `range`. The vectors
// are cut into `slices` fixed slices, each summed into its own table and merged in slice order,
// so the sums depend neither on the number of threads nor on scheduling. Sorted by key.
std::vector<UtilityCell> accumulate(const ExplorationMap& map, const std::vector<UtilityVector>& vecs, double range,
                                    std::size_t slices, int threads) {
  const auto& grid = detail::state(map).grid;
  const double res = map.resolution();
  std::vector<detail::KeyTable<Utility>> tables(slices, detail::KeyTable<Utility>(2040));
  detail::parallel_for(slices, threads, [&](std::size_t sl, int) {
    detail::GridReader g(grid);
    auto& t = tables[sl];
    const std::size_t b = vecs.size() * sl / slices, e = vecs.size() * (sl + 1) / slices;
    for (std::size_t i = b; i < e; ++i) {
      const UtilityVector& v = vecs[i];
      detail::walk_cells(res, v.from, v.dir, range, [&](CellKey k) {
        if ((g.get(k) & detail::kStateMask) != std::uint8_t(CellState::Free)) return false;
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
// orientation (Zacharias et al.: a cell is a sensor position only there).
void prune_by_workspace(const ExplorationMap& map, const NbvOptions& opt, std::vector<UtilityCell>& cells,
                        NbvResult& r) {
  std::vector<Eigen::Vector3d> pos(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) pos[i] = map.center(cells[i].first);
  std::vector<bool> keep(cells.size(), true);
  if (opt.workspace.filter) {
    keep = opt.workspace.filter(pos);
    if (keep.size() != cells.size())
      throw std::invalid_argument("workspace filter returned " + std::to_string(keep.size()) + " values for " +
                                  std::to_string(cells.size()) + " positions");
  }
  const Pose to_arm = opt.capability_base.inverse();
  std::size_t w = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!keep[i] || !opt.workspace.contains(pos[i])) continue;
    if (opt.capability_map && !(opt.capability_map->reachability(to_arm * pos[i]) > opt.min_reachability)) {
      ++r.capability_pruned;
      continue;
    }
    cells[w++] = cells[i];
  }
  cells.resize(w);
}

// Step 3b: best utility first, the cells with no occupied cell within min_distance, until
// max_candidate_cells are kept (the clearance check runs only that far).
void keep_clear_cells(const ExplorationMap& map, const NbvOptions& opt, std::vector<UtilityCell>& cells) {
  std::stable_sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.second.u > b.second.u; });
  const int margin = int(std::ceil(opt.min_distance / map.resolution()));
  detail::GridReader g(detail::state(map).grid);
  std::size_t w = 0;
  for (std::size_t i = 0; i < cells.size() && w < std::size_t(opt.max_candidate_cells); ++i) {
    bool clear = true;
    for (int dz = -margin; dz <= margin && clear; ++dz)
      for (int dy = -margin; dy <= margin && clear; ++dy)
        for (int dx = -margin; dx <= margin && clear; ++dx) {
          CellKey nb;
          if (detail::neighbour(cells[i].first, dx, dy, dz, nb) &&
              (g.get(nb) & detail::kStateMask) == std::uint8_t(CellState::Occupied))
            clear = false;
        }
    if (clear) cells[w++] = cells[i];
  }
  cells.resize(w);
}

// What scoring one sampled pose came to.
struct Slot {
  bool valid = false, tried_ik = false, collides = false, cap_rejected = false;
  ViewCandidate view;
};

// Step 4, per sampled pose: what every pose of one search shares.
class PoseScorer {
 public:
  PoseScorer(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt,
             const std::vector<UtilityCell>& cells)
      : map_(map), cam_(cam), opt_(opt), cells_(cells), per_cell_(std::size_t(opt.orientations_per_cell)) {
    ik_ = opt.ik;
    ik_.mode = IkMode::Approach;
    ik_.approach_axis = Eigen::Vector3d::UnitZ();
    base_inv_ = opt.chain_base.inverse();
    cap_inv_ = opt.capability_base.inverse();
    cap_orient_ = opt.capability_map && opt.capability_orientations &&
                  opt.capability_map->approach_axis().isApprox(Eigen::Vector3d::UnitZ(), 1e-9);
    // The map's occupied cells as FCL obstacles for the arm (the tree is not copied: the map
    // outlives the search, so the shared_ptr does not own it).
    if (opt.chain && opt.arm_collisions && map.octree().size() > 0) {
      const Robot& robot = opt.chain->robot();
      obstacles_.emplace();
      obstacles_->add_octree(std::shared_ptr<const octomap::OcTree>(&map.octree(), [](const octomap::OcTree*) {}));
      reference_ = robot.home();
      robot_root_ = opt.chain_base * robot.link_poses(reference_)[robot.link_index(opt.chain->base_link())].inverse();
    }
  }
  std::size_t total() const { return cells_.size() * per_cell_; }
  // Pose idx: orientation idx % per_cell of cell idx / per_cell, sampled from its own stream.
  Slot score(std::size_t idx) const;

 private:
  Eigen::Vector3d sample_axis(std::size_t idx, Eigen::Vector3d forward, double& roll) const;
  bool reach(Slot& s, std::size_t idx) const;

  const ExplorationMap& map_;
  const CameraIntrinsics& cam_;
  const NbvOptions& opt_;
  const std::vector<UtilityCell>& cells_;
  const std::size_t per_cell_;
  IkOptions ik_;
  Pose base_inv_, cap_inv_, robot_root_ = Pose::Identity();
  bool cap_orient_ = false;
  std::optional<Obstacles> obstacles_;
  Eigen::VectorXd reference_;
};

// Orientation 0 looks along the mean direction; the others are drawn in a cone around it.
Eigen::Vector3d PoseScorer::sample_axis(std::size_t idx, Eigen::Vector3d forward, double& roll) const {
  roll = 0;
  if (idx % per_cell_ == 0) return forward;
  std::mt19937_64 rng(opt_.seed * 0x9E3779B97F4A7C15ULL + idx);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double th = opt_.orientation_spread * std::sqrt(U(rng)), ph = 2 * kPi * U(rng);
  Eigen::Vector3d a = forward.unitOrthogonal(), bvec = forward.cross(a);
  forward = (std::cos(th) * forward + std::sin(th) * (std::cos(ph) * a + std::sin(ph) * bvec)).normalized();
  roll = (U(rng) - 0.5) * 2 * kPi;
  return forward;
}

// The arm's check: IK for the pose, clear of the occupied cells; the pose becomes the one reached.
bool PoseScorer::reach(Slot& s, std::size_t idx) const {
  s.tried_ik = true;
  IkOptions o = ik_;
  o.seed = ik_.seed + idx;
  auto q = opt_.chain->ik(base_inv_ * s.view.pose, o);
  if (!q) return false;
  if (obstacles_ &&
      opt_.chain->robot().in_collision(opt_.chain->to_robot_configuration(*q, reference_), *obstacles_, robot_root_)) {
    s.collides = true;
    return false;
  }
  s.view.q = *q;
  s.view.pose = opt_.chain_base * opt_.chain->fk(*q);  // the roll the arm actually reaches
  return true;
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
  if (cap_orient_ && !opt_.capability_map->reachable(cap_inv_ * s.view.pose)) {
    s.cap_rejected = true;
    return s;
  }
  if (opt_.chain && !reach(s, idx)) return s;
  auto [v, u] = view_utility_unlocked(map_, cam_, s.view.pose, opt_.score_width, opt_.score_height);
  const double res = map_.resolution();
  s.view.void_cells = v;
  s.view.unknown_cells = u;
  s.view.utility_dm3 = double(v) * res * res * res * 1000.0;
  s.valid = true;
  return s;
}

// Step 4: poses in batches of a few per thread, in index order, until max_valid_poses are valid;
// ranked by void cells, then unknown cells, then index.
void score_candidates(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt,
                      const std::vector<UtilityCell>& cells, int threads, NbvResult& r) {
  const PoseScorer scorer(map, cam, opt, cells);
  const std::size_t total = scorer.total(), max_valid = std::size_t(opt.max_valid_poses);
  const std::size_t batch = std::size_t(std::max(threads, 1)) * 4;
  std::vector<std::pair<std::size_t, ViewCandidate>> valid;
  for (std::size_t start = 0; start < total && valid.size() < max_valid; start += batch) {
    std::vector<Slot> slots(std::min(total, start + batch) - start);
    detail::parallel_for(slots.size(), threads, [&](std::size_t b, int) { slots[b] = scorer.score(start + b); }, 1);
    for (std::size_t b = 0; b < slots.size(); ++b) {
      if (slots[b].cap_rejected) ++r.capability_rejected;
      if (slots[b].collides) ++r.arm_collisions;
      else if (slots[b].tried_ik && !slots[b].valid) ++r.ik_failures;
      if (!slots[b].valid) continue;
      ++r.poses_scored;
      if (valid.size() < max_valid) valid.emplace_back(start + b, std::move(slots[b].view));
    }
  }
  std::sort(valid.begin(), valid.end(), [](const auto& a, const auto& b) {
    if (a.second.void_cells != b.second.void_cells) return a.second.void_cells > b.second.void_cells;
    if (a.second.unknown_cells != b.second.unknown_cells) return a.second.unknown_cells > b.second.unknown_cells;
    return a.first < b.first;
  });
  for (auto& v : valid) r.ranked.push_back(std::move(v.second));
}

void validate(const CameraIntrinsics& cam, const NbvOptions& opt) {
  cam.validate();
  if (opt.max_valid_poses <= 0 || opt.orientations_per_cell <= 0 || opt.max_candidate_cells <= 0)
    throw std::invalid_argument("max_valid_poses, orientations_per_cell and max_candidate_cells must be positive");
  if (!(opt.orientation_spread >= 0)) throw std::invalid_argument("orientation_spread must be >= 0");
  if (!(opt.min_reachability >= 0 && opt.min_reachability < 1))
    throw std::invalid_argument("min_reachability must be in [0, 1), got " + std::to_string(opt.min_reachability));
}

}  // namespace

bool SensorWorkspace::contains(const Eigen::Vector3d& p) const {
  if (box && !box->contains(p)) return false;
  if (sphere_center && (p - *sphere_center).norm() > sphere_radius) return false;
  return true;
}

std::vector<std::pair<CellKey, double>> accumulate_utility(const ExplorationMap& map, double sensor_range,
                                                           std::size_t* vectors) {
  auto guard = detail::read_guard(map);
  const std::vector<UtilityVector> vecs = utility_vectors(map);
  if (vectors) *vectors = vecs.size();
  std::vector<std::pair<CellKey, double>> out;
  for (const auto& [k, a] : accumulate(map, vecs, sensor_range, 1, 1)) out.emplace_back(k, a.u);
  return out;
}

std::pair<std::size_t, std::size_t> view_utility(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                 const Pose& pose, int sw, int sh) {
  if (sw <= 0 || sh <= 0)
    throw std::invalid_argument("score grid must be positive, got " + std::to_string(sw) + " x " + std::to_string(sh));
  auto guard = detail::read_guard(map);
  return view_utility_unlocked(map, cam, pose, sw, sh);
}

namespace {

// view_utility without taking the map's lock: its caller holds it (pool workers of next_best_view
// must not lock again: a writer waiting in between would deadlock them against their caller).
std::pair<std::size_t, std::size_t> view_utility_unlocked(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                          const Pose& pose, int sw, int sh) {
  detail::GridReader g(detail::state(map).grid);
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d o = pose.translation();
  const double res = map.resolution();
  std::vector<Eigen::Vector3d> dirs(std::size_t(sw) * sh);
  // key box of the frustum (every walked cell lies within a cell of a ray's end points)
  Eigen::Vector3d lo = o, hi = o;
  for (int j = 0; j < sh; ++j)
    for (int i = 0; i < sw; ++i) {
      Eigen::Vector3d d = R * cam.ray((i + 0.5) * cam.width / sw, (j + 0.5) * cam.height / sh);
      dirs[std::size_t(j) * sw + i] = d;
      Eigen::Vector3d e = o + d.normalized() * cam.max_range;
      lo = lo.cwiseMin(e);
      hi = hi.cwiseMax(e);
    }
  std::int64_t klo[3], n[3];
  for (int a = 0; a < 3; ++a) {
    klo[a] = std::int64_t(std::floor(lo[a] / res + 32768.0)) - 2;
    n[a] = std::int64_t(std::floor(hi[a] / res + 32768.0)) + 2 - klo[a] + 1;
  }
  // distinct unknown cells: one bit per cell of the box instead of collecting and sorting keys
  std::vector<std::uint64_t> seen(std::size_t((n[0] * n[1] * n[2] + 63) / 64), 0);
  std::size_t voids = 0, unknown = 0;
  for (const Eigen::Vector3d& d : dirs) {
    detail::walk_cells(res, o, d, cam.max_range, [&](CellKey k) {
      std::uint8_t f = g.get(k);
      std::uint8_t s = f & detail::kStateMask;
      if (s == std::uint8_t(CellState::Occupied)) return false;
      if (s == std::uint8_t(CellState::Unknown)) {
        std::int64_t x = std::int64_t(key_x(k)) - klo[0], y = std::int64_t(key_y(k)) - klo[1],
                     z = std::int64_t(key_z(k)) - klo[2];
        if (x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) return false;  // cannot happen
        std::size_t idx = std::size_t((z * n[1] + y) * n[0] + x);
        std::uint64_t bit = std::uint64_t(1) << (idx & 63);
        if (!(seen[idx >> 6] & bit)) {
          seen[idx >> 6] |= bit;
          ++unknown;
          if (f & detail::kVoidFlag) ++voids;
        }
      }
      return true;
    });
  }
  return {voids, unknown};
}

}  // namespace

NbvResult next_best_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt) {
  auto t0 = Clock::now();
  validate(cam, opt);
  auto guard = detail::read_guard(map);
  NbvResult r;
  const int threads = detail::default_threads(opt.threads);
  const std::vector<UtilityVector> vecs = utility_vectors(map);
  r.utility_vectors = vecs.size();
  std::vector<UtilityCell> cells = accumulate(map, vecs, cam.max_range, 8, threads);
  r.utility_cells = cells.size();
  r.seconds_vectors = seconds_since(t0);

  auto t_prune = Clock::now();
  prune_by_workspace(map, opt, cells, r);
  r.candidate_cells = cells.size();
  keep_clear_cells(map, opt, cells);
  r.seconds_prune = seconds_since(t_prune);

  auto t_score = Clock::now();
  score_candidates(map, cam, opt, cells, threads, r);
  r.seconds_score = seconds_since(t_score);
  r.seconds = seconds_since(t0);
  return r;
}

}  // namespace octoreach
