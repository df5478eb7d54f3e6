// Next best view: utility vectors, workspace pruning, frustum scoring (Algorithm 1, section IV-C).
#include "octoreach/next_best_view.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <unordered_map>

#include "exploration_impl.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/robot.hpp"
#include "parallel.hpp"

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

Pose camera_pose(const Eigen::Vector3d& position, const Eigen::Vector3d& forward, double roll) {
  Eigen::Vector3d z = forward.normalized();
  Eigen::Vector3d up = std::abs(z.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d x = z.cross(up).normalized();
  Eigen::Vector3d y = z.cross(x);
  double c = std::cos(roll), s = std::sin(roll);
  Pose T = Pose::Identity();
  T.linear().col(0) = c * x + s * y;
  T.linear().col(1) = -s * x + c * y;
  T.linear().col(2) = z;
  T.translation() = position;
  return T;
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
  std::vector<FrontierVoid> fvs = map.frontier_voids();
  const auto& vcs = map.void_clusters();
  std::unordered_map<CellKey, double> util;
  std::size_t count = 0;
  detail::GridReader g(I.grid);
  for (const auto& fv : fvs) {
    const VoidCluster& v = vcs[fv.void_index];
    std::vector<Eigen::Vector3d> corners{v.centroid};
    for (int j = 0; j < 3; ++j)
      for (int s = -1; s <= 1; s += 2) corners.push_back(v.centroid + s * v.semi_axes[j] * v.axes.col(j));
    for (const Eigen::Vector3d& c : corners)
      for (CellKey f : fv.frontier_cells) {
        Eigen::Vector3d pf = map.center(f);
        Eigen::Vector3d dir = pf - c;
        if (dir.norm() < 1e-9) continue;
        dir.normalize();
        ++count;
        walk_cells(res, pf, dir, sensor_range, [&](CellKey k) {
          if ((g.get(k) & detail::kStateMask) != std::uint8_t(CellState::Free)) return false;
          util[k] += fv.utility;
          return true;
        });
      }
  }
  if (vectors) *vectors = count;
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
  std::vector<CellKey> voids, unknown;
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d o = pose.translation();
  for (int j = 0; j < sh; ++j)
    for (int i = 0; i < sw; ++i) {
      Eigen::Vector3d d = R * cam.ray((i + 0.5) * cam.width / sw, (j + 0.5) * cam.height / sh);
      walk_cells(map.resolution(), o, d, cam.max_range, [&](CellKey k) {
        std::uint8_t f = g.get(k);
        std::uint8_t s = f & detail::kStateMask;
        if (s == std::uint8_t(CellState::Occupied)) return false;
        if (s == std::uint8_t(CellState::Unknown)) {
          unknown.push_back(k);
          if (f & detail::kVoidFlag) voids.push_back(k);
        }
        return true;
      });
    }
  for (auto* v : {&voids, &unknown}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return {voids.size(), unknown.size()};
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
  std::vector<FrontierVoid> fvs = map.frontier_voids();
  const auto& vcs = map.void_clusters();
  struct Acc {
    double u = 0;
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
  };
  std::unordered_map<CellKey, Acc> acc;
  {
    detail::GridReader g(I.grid);
    for (const auto& fv : fvs) {
      const VoidCluster& v = vcs[fv.void_index];
      std::vector<Eigen::Vector3d> corners{v.centroid};
      for (int j = 0; j < 3; ++j)
        for (int s = -1; s <= 1; s += 2) corners.push_back(v.centroid + s * v.semi_axes[j] * v.axes.col(j));
      for (const Eigen::Vector3d& c : corners)
        for (CellKey f : fv.frontier_cells) {
          Eigen::Vector3d pf = map.center(f);
          Eigen::Vector3d dir = pf - c;
          if (dir.norm() < 1e-9) continue;
          dir.normalize();
          ++r.utility_vectors;
          walk_cells(res, pf, dir, cam.max_range, [&](CellKey k) {
            if ((g.get(k) & detail::kStateMask) != std::uint8_t(CellState::Free)) return false;
            Acc& a = acc[k];
            a.u += fv.utility;
            a.dir -= fv.utility * dir;
            return true;
          });
        }
    }
  }
  r.utility_cells = acc.size();

  // 3. prune by the workspace
  std::vector<std::pair<CellKey, Acc>> cells(acc.begin(), acc.end());
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
    if (opt.capability_map) {
      // Zacharias et al.: a cell is a sensor position only where the arm reaches some orientation.
      const Pose to_arm = opt.capability_base.inverse();
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (keep[i] && opt.workspace.contains(pos[i]) &&
            !(opt.capability_map->reachability(to_arm * pos[i]) > opt.min_reachability)) {
          keep[i] = false;
          ++r.capability_pruned;
        }
    }
    const int margin = int(std::ceil(opt.min_distance / res));
    detail::GridReader g(I.grid);
    std::size_t w = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (!keep[i] || !opt.workspace.contains(pos[i])) continue;
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
  r.candidate_cells = cells.size();
  std::stable_sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.second.u > b.second.u; });
  if (cells.size() > std::size_t(opt.max_candidate_cells)) cells.resize(opt.max_candidate_cells);

  // 4. sample orientations at the best cells, check IK, score; stop after N valid poses
  IkOptions ik = opt.ik;
  ik.mode = IkMode::Approach;
  ik.approach_axis = Eigen::Vector3d::UnitZ();
  const Pose base_inv = opt.chain_base.inverse();
  const std::size_t per_cell = std::size_t(opt.orientations_per_cell);
  const std::size_t total = cells.size() * per_cell;
  const int threads = detail::default_threads(opt.threads);
  const std::size_t batch = std::size_t(std::max(threads, 1)) * 4;
  struct Slot {
    bool valid = false, tried_ik = false;
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
      if (opt.chain) {
        s.tried_ik = true;
        IkOptions o = ik;
        o.seed = ik.seed + idx;
        auto q = opt.chain->ik(base_inv * s.view.pose, o);
        if (!q) return;
        s.view.q = *q;
        s.view.pose = opt.chain_base * opt.chain->fk(*q);  // the roll the arm actually reaches
      }
      auto [v, u] = view_utility(map, cam, s.view.pose, opt.score_width, opt.score_height);
      s.view.void_cells = v;
      s.view.unknown_cells = u;
      s.valid = true;
    }, 1);
    for (std::size_t b = 0; b < slots.size(); ++b) {
      if (slots[b].tried_ik && !slots[b].valid) ++r.ik_failures;
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
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace octoreach
