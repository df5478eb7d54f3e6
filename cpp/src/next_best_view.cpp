// Next best view: utility vectors, workspace pruning, frustum scoring (Algorithm 1, section IV-C).
#include "octoreach/next_best_view.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <unordered_map>

#include "exploration_impl.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {

namespace {

// Walks the cells of the segment o + t d, t in [0, length] (d unit), in order; `visit(key)`
// returns false to stop. Amanatides & Woo in key units (cell k covers [k, k + 1)).
template <class Visit>
void walk_cells(double res, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double length, Visit&& visit) {
  Eigen::Vector3d u = o / res + Eigen::Vector3d::Constant(32768.0);
  if ((u.array() < 0).any() || (u.array() >= 65536).any()) return;
  int k[3] = {int(std::floor(u[0])), int(std::floor(u[1])), int(std::floor(u[2]))};
  int step[3];
  double t_max[3], t_delta[3];
  const double len = length / res;
  for (int i = 0; i < 3; ++i) {
    if (d[i] > 0) {
      step[i] = 1;
      t_max[i] = (k[i] + 1 - u[i]) / d[i];
      t_delta[i] = 1.0 / d[i];
    } else if (d[i] < 0) {
      step[i] = -1;
      t_max[i] = (k[i] - u[i]) / d[i];
      t_delta[i] = -1.0 / d[i];
    } else {
      step[i] = 0;
      t_max[i] = t_delta[i] = std::numeric_limits<double>::infinity();
    }
  }
  for (;;) {
    if (!visit(pack_key(k[0], k[1], k[2]))) return;
    int dim = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    if (t_max[dim] > len) return;
    k[dim] += step[dim];
    if (k[dim] < 0 || k[dim] > 0xffff) return;
    t_max[dim] += t_delta[dim];
  }
}


// Open-addressing table CellKey -> accumulated utility and direction (power-of-two capacity,
// multiplicative hash): the accumulation touches a few hundred thousand cells millions of times.
struct UtilityTable {
  struct Acc {
    double u = 0;
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
  };
  static constexpr CellKey kEmpty = ~CellKey(0);
  std::vector<CellKey> keys;
  std::vector<Acc> vals;
  std::size_t used = 0;
  int bits = 0;
  UtilityTable() { rehash(12); }
  void rehash(int b) {
    std::vector<CellKey> ok = std::move(keys);
    std::vector<Acc> ov = std::move(vals);
    bits = b;
    keys.assign(std::size_t(1) << b, kEmpty);
    vals.assign(std::size_t(1) << b, Acc());
    used = 0;
    for (std::size_t i = 0; i < ok.size(); ++i)
      if (ok[i] != kEmpty) at(ok[i]) = ov[i];
  }
  Acc& at(CellKey k) {
    const std::size_t mask = keys.size() - 1;
    std::size_t i = std::size_t((k * 0x9E3779B97F4A7C15ULL) >> (64 - bits));
    for (;; i = (i + 1) & mask) {
      if (keys[i] == k) return vals[i];
      if (keys[i] == kEmpty) {
        if (2 * (used + 1) > keys.size()) {
          rehash(bits + 1);
          return at(k);
        }
        keys[i] = k;
        ++used;
        return vals[i];
      }
    }
  }
};

// Algorithm 1's utility vectors: from each void's centre and the ends of its axes through every
// frontier cell next to it, carrying the void's utility; in a fixed order.
struct UtilityVector {
  Eigen::Vector3d from, dir;
  double u;
};

std::vector<UtilityVector> utility_vectors(const ExplorationMap& map) {
  std::vector<UtilityVector> out;
  const auto& vcs = map.void_clusters();
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

}  // namespace

bool SensorWorkspace::contains(const Eigen::Vector3d& p) const {
  if (box && !box->contains(p)) return false;
  if (sphere_center && (p - *sphere_center).norm() > sphere_radius) return false;
  return true;
}

std::vector<std::pair<CellKey, double>> accumulate_utility(const ExplorationMap& map, double sensor_range,
                                                           std::size_t* vectors) {
  const auto& I = map.internals();
  const double res = map.resolution();
  std::unordered_map<CellKey, double> util;
  const std::vector<UtilityVector> vecs = utility_vectors(map);
  detail::GridReader g(I.grid);
  for (const UtilityVector& v : vecs)
    walk_cells(res, v.from, v.dir, sensor_range, [&](CellKey k) {
      if ((g.get(k) & detail::kStateMask) != std::uint8_t(CellState::Free)) return false;
      util[k] += v.u;
      return true;
    });
  if (vectors) *vectors = vecs.size();
  std::vector<std::pair<CellKey, double>> out(util.begin(), util.end());
  std::sort(out.begin(), out.end());
  return out;
}

std::pair<std::size_t, std::size_t> view_utility(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                 const Pose& pose, int sw, int sh) {
  if (sw <= 0 || sh <= 0)
    throw std::invalid_argument("score grid must be positive, got " + std::to_string(sw) + " x " + std::to_string(sh));
  const auto& I = map.internals();
  detail::GridReader g(I.grid);
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
    walk_cells(res, o, d, cam.max_range, [&](CellKey k) {
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

NbvResult next_best_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt) {
  auto t0 = std::chrono::steady_clock::now();
  cam.validate();
  if (opt.max_valid_poses <= 0 || opt.orientations_per_cell <= 0 || opt.max_candidate_cells <= 0)
    throw std::invalid_argument("max_valid_poses, orientations_per_cell and max_candidate_cells must be positive");
  if (!(opt.orientation_spread >= 0)) throw std::invalid_argument("orientation_spread must be >= 0");
  if (!(opt.min_reachability >= 0 && opt.min_reachability < 1))
    throw std::invalid_argument("min_reachability must be in [0, 1), got " + std::to_string(opt.min_reachability));
  NbvResult r;
  const auto& I = map.internals();
  const double res = map.resolution();

  // 1-2. utility vectors and per-cell accumulation, with the mean direction back to the voids
  using Acc = UtilityTable::Acc;
  const int threads = detail::default_threads(opt.threads);
  std::vector<std::pair<CellKey, Acc>> cells;
  {
    const std::vector<UtilityVector> vecs = utility_vectors(map);
    r.utility_vectors = vecs.size();
    // A fixed number of slices, each summed into its own table and merged in slice order: the
    // sums do not depend on the number of threads or on scheduling.
    constexpr std::size_t kSlices = 8;
    std::vector<UtilityTable> tables(kSlices);
    detail::parallel_for(kSlices, threads, [&](std::size_t sl, int) {
      detail::GridReader g(I.grid);
      UtilityTable& t = tables[sl];
      const std::size_t b = vecs.size() * sl / kSlices, e = vecs.size() * (sl + 1) / kSlices;
      for (std::size_t i = b; i < e; ++i) {
        const UtilityVector& v = vecs[i];
        walk_cells(res, v.from, v.dir, cam.max_range, [&](CellKey k) {
          if ((g.get(k) & detail::kStateMask) != std::uint8_t(CellState::Free)) return false;
          Acc& a = t.at(k);
          a.u += v.u;
          a.dir -= v.u * v.dir;
          return true;
        });
      }
    }, 1);
    UtilityTable& all = tables[0];
    for (std::size_t sl = 1; sl < kSlices; ++sl) {
      const UtilityTable& t = tables[sl];
      for (std::size_t i = 0; i < t.keys.size(); ++i) {
        if (t.keys[i] == UtilityTable::kEmpty) continue;
        Acc& a = all.at(t.keys[i]);
        a.u += t.vals[i].u;
        a.dir += t.vals[i].dir;
      }
    }
    cells.reserve(all.used);
    for (std::size_t i = 0; i < all.keys.size(); ++i)
      if (all.keys[i] != UtilityTable::kEmpty) cells.emplace_back(all.keys[i], all.vals[i]);
  }
  r.utility_cells = cells.size();
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  r.seconds_vectors = since(t0);
  auto t_prune = std::chrono::steady_clock::now();

  // 3. prune by the workspace and the capability map, best utility first; the clearance check
  //    (min_distance) runs only until max_candidate_cells cells are kept.
  std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  {
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
      // Zacharias et al.: a cell is a sensor position only where the arm reaches some orientation.
      if (opt.capability_map && !(opt.capability_map->reachability(to_arm * pos[i]) > opt.min_reachability)) {
        ++r.capability_pruned;
        continue;
      }
      cells[w++] = cells[i];
    }
    cells.resize(w);
  }
  r.candidate_cells = cells.size();
  std::stable_sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.second.u > b.second.u; });
  {
    const int margin = int(std::ceil(opt.min_distance / res));
    detail::GridReader g(I.grid);
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

  r.seconds_prune = since(t_prune);
  auto t_score = std::chrono::steady_clock::now();
  // 4. sample orientations at the best cells, check IK, score; stop after N valid poses
  IkOptions ik = opt.ik;
  ik.mode = IkMode::Approach;
  ik.approach_axis = Eigen::Vector3d::UnitZ();
  const Pose base_inv = opt.chain_base.inverse();
  const std::size_t per_cell = std::size_t(opt.orientations_per_cell);
  const std::size_t total = cells.size() * per_cell;
  const std::size_t batch = std::size_t(std::max(threads, 1)) * 4;
  // The map's occupied cells as FCL obstacles for the arm (the tree is not copied: the map
  // outlives the search, so the shared_ptr does not own it).
  std::optional<Obstacles> obstacles;
  Pose robot_root = Pose::Identity();
  Eigen::VectorXd reference;
  if (opt.chain && opt.arm_collisions && map.octree().size() > 0) {
    const Robot& robot = opt.chain->robot();
    obstacles.emplace();
    obstacles->add_octree(std::shared_ptr<const octomap::OcTree>(&map.octree(), [](const octomap::OcTree*) {}));
    reference = robot.home();
    robot_root = opt.chain_base * robot.link_poses(reference)[robot.link_index(opt.chain->base_link())].inverse();
  }
  const bool cap_orient = opt.capability_map && opt.capability_orientations &&
                          opt.capability_map->approach_axis().isApprox(Eigen::Vector3d::UnitZ(), 1e-9);
  const Pose cap_inv = opt.capability_base.inverse();
  struct Slot {
    bool valid = false, tried_ik = false, collides = false, cap_rejected = false;
    ViewCandidate view;
  };
  std::vector<std::pair<std::size_t, ViewCandidate>> valid;
  for (std::size_t start = 0; start < total && valid.size() < std::size_t(opt.max_valid_poses); start += batch) {
    std::size_t end = std::min(total, start + batch);
    std::vector<Slot> slots(end - start);
    detail::parallel_for(end - start, threads, [&](std::size_t b, int) {
      std::size_t idx = start + b, ci = idx / per_cell, k = idx % per_cell;
      const auto& cell = cells[ci];
      Eigen::Vector3d forward = cell.second.dir;
      if (forward.norm() < 1e-12) return;
      forward.normalize();
      std::mt19937_64 rng(opt.seed * 0x9E3779B97F4A7C15ULL + idx);
      std::uniform_real_distribution<double> U(0.0, 1.0);
      double roll = 0;
      if (k > 0) {
        double th = opt.orientation_spread * std::sqrt(U(rng)), ph = 2 * M_PI * U(rng);
        Eigen::Vector3d a = forward.unitOrthogonal(), bvec = forward.cross(a);
        forward = (std::cos(th) * forward + std::sin(th) * (std::cos(ph) * a + std::sin(ph) * bvec)).normalized();
        roll = (U(rng) - 0.5) * 2 * M_PI;
      }
      Slot& s = slots[b];
      s.view.pose = camera_pose(map.center(cell.first), forward, roll);
      s.view.cell_utility = cell.second.u;
      if (cap_orient && !opt.capability_map->reachable(cap_inv * s.view.pose)) {
        s.cap_rejected = true;
        return;
      }
      if (opt.chain) {
        s.tried_ik = true;
        IkOptions o = ik;
        o.seed = ik.seed + idx;
        auto q = opt.chain->ik(base_inv * s.view.pose, o);
        if (!q) return;
        if (obstacles &&
            opt.chain->robot().in_collision(opt.chain->to_robot_configuration(*q, reference), *obstacles, robot_root)) {
          s.collides = true;
          return;
        }
        s.view.q = *q;
        s.view.pose = opt.chain_base * opt.chain->fk(*q);  // the roll the arm actually reaches
      }
      auto [v, u] = view_utility(map, cam, s.view.pose, opt.score_width, opt.score_height);
      s.view.void_cells = v;
      s.view.unknown_cells = u;
      s.valid = true;
    }, 1);
    for (std::size_t b = 0; b < slots.size(); ++b) {
      if (slots[b].cap_rejected) ++r.capability_rejected;
      if (slots[b].collides) ++r.arm_collisions;
      else if (slots[b].tried_ik && !slots[b].valid) ++r.ik_failures;
      if (!slots[b].valid) continue;
      ++r.poses_scored;
      if (valid.size() < std::size_t(opt.max_valid_poses)) valid.emplace_back(start + b, std::move(slots[b].view));
    }
  }
  std::sort(valid.begin(), valid.end(), [](const auto& a, const auto& b) {
    if (a.second.void_cells != b.second.void_cells) return a.second.void_cells > b.second.void_cells;
    if (a.second.unknown_cells != b.second.unknown_cells) return a.second.unknown_cells > b.second.unknown_cells;
    return a.first < b.first;
  });
  for (auto& v : valid) r.ranked.push_back(std::move(v.second));
  r.seconds_score = since(t_score);
  r.seconds = since(t0);
  return r;
}

}  // namespace octoreach
