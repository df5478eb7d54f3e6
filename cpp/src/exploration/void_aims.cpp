// Camera poses aimed at void cells, their eyes found along rays out of the cells (void_aims.hpp).
#include "exploration/void_aims.hpp"

#include <algorithm>
#include <cmath>

#include "common/thread_pool.hpp"
#include "exploration/cell_sets.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/grid_ray.hpp"
#include "exploration/view_score.hpp"
#include "exploration/void_enclosure.hpp"
#include "octoreach/capability_map.hpp"

namespace octoreach::detail {

namespace {

// splitmix64: one independent stream per (seed, cell, ray), so the result does not depend on threads.
struct Stream {
  std::uint64_t s;
  explicit Stream(std::uint64_t seed) : s(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
  Eigen::Vector3d direction() {  // uniform on the unit sphere
    const double z = 2 * uniform() - 1, phi = 2 * kPi * uniform(), r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
};

std::uint64_t mix(std::uint64_t a, std::uint64_t b) { return Stream(a * 0x2545F4914F6CDD1DULL ^ b).next(); }

}  // namespace

std::vector<CellKey> draw_void_cells(const ExplorationState& S, const AimRequest& req) {
  std::vector<CellKey> all(S.void_set.begin(), S.void_set.end());
  std::sort(all.begin(), all.end());
  Stream rng(mix(req.seed, 1));
  const auto shuffle_first = [&](std::vector<CellKey>& v, std::size_t n) {  // a random n of v, in v's front
    n = std::min(n, v.size());
    for (std::size_t i = 0; i < n; ++i) std::swap(v[i], v[i + std::size_t(rng.uniform() * double(v.size() - i))]);
    v.resize(n);
  };
  if (req.every_cell) {
    shuffle_first(all, req.max_cells);
    return all;
  }
  const GridReader g(S.grid);
  std::vector<CellKey> exposed, other;
  for (CellKey k : all) (has_free_neighbour(g, k) ? exposed : other).push_back(k);
  shuffle_first(exposed, exposed.size());
  shuffle_first(other, other.size());
  std::vector<CellKey> out;
  std::size_t e = 0, o = 0;
  while (out.size() < req.cells && (e < exposed.size() || o < other.size())) {
    // an exposed cell, or with probability unexposed_share an unexposed one (as the loop's aims always drew)
    const bool take_other = o < other.size() && (e >= exposed.size() || rng.uniform() < req.unexposed_share);
    out.push_back(take_other ? other[o++] : exposed[e++]);
  }
  return out;
}

namespace {

struct Eye {
  Eigen::Vector3d at;
  Eigen::Vector3d axis;  // the optical axis (unit)
};

}  // namespace

std::vector<Pose> aim_at_voids(const ExplorationMap& map, const ViewChecker& checker, const NbvOptions& opt,
                               const AimRequest& req) {
  const ExplorationState& S = state(map);
  if (S.void_set.empty() || req.poses == 0 || req.directions <= 0) return {};
  const std::vector<CellKey> from = draw_void_cells(S, req);
  const double res = map.resolution();
  const Eigen::Vector3d s_lo = map.options().search_lo, s_hi = map.options().search_hi;
  const Pose cap_inv = opt.capability_base.inverse();
  const int dirs = req.directions;
  std::vector<std::vector<Eye>> found(from.size());
  parallel_for(from.size(), default_threads(opt.threads), [&](std::size_t i, int) {
    const GridReader g(S.grid);
    const Eigen::Vector3d c = S.center(from[i]);
    std::vector<std::pair<CellKey, double>> stretch;  // free cells of one ray (key, distance along it)
    for (int r = 0; r < dirs; ++r) {
      Stream rng(mix(mix(req.seed, from[i]), std::uint64_t(r)));
      const Eigen::Vector3d d = rng.direction();
      stretch.clear();
      bool left_unknown = false;
      walk_cells(res, c, d, req.distance.second, [&](CellKey k) {
        if (k == from[i]) return true;
        const std::uint8_t cell = g.get(k);
        std::uint8_t st = cell & kStateMask;
        const Eigen::Vector3d p = S.center(k);
        const bool inside = (p.array() >= s_lo.array()).all() && (p.array() <= s_hi.array()).all();
        if (st == std::uint8_t(CellState::Unknown) && !inside) {
          if (p.z() < s_lo.z()) return false;  // the ground under the search space
          st = std::uint8_t(CellState::Free);  // the robot's side of the scene: no view needs to have seen it
        }
        if (st == std::uint8_t(CellState::Occupied)) return false;
        // past free space an unknown cell ends the ray unless it is a void cell: the score weighs what lies
        // behind one by the void pass probability
        if (st == std::uint8_t(CellState::Unknown)) return !left_unknown || (cell & kVoidFlag) != 0;
        left_unknown = true;
        const double s = (p - c).dot(d);
        if (s >= req.distance.first) stretch.emplace_back(k, s);
        return true;
      });
      // the eye: a random cell of the free stretch that passes the checks (tried in random order); its axis
      // looks back along the ray at the cell, or turns to a direction the arm reaches
      const std::vector<Eigen::Vector3d> turned = stretch.empty() ? std::vector<Eigen::Vector3d>{}
                                                                  : checker.turned_axes(-d, req.max_turn);
      while (!stretch.empty()) {
        const std::size_t j = std::size_t(rng.uniform() * double(stretch.size()));
        const Eigen::Vector3d eye = c + stretch[j].second * d;
        stretch[j] = stretch.back();
        stretch.pop_back();
        if (eye.z() < req.min_height || !opt.workspace.contains(eye)) continue;
        if (opt.capability_map && !(opt.capability_map->reachability(cap_inv * eye) > opt.min_reachability)) continue;
        const std::optional<Eigen::Vector3d> axis = checker.reachable_axis(eye, -d, turned);
        if (!axis || !checker.camera_clear(eye)) continue;
        found[i].push_back({eye, *axis});
        break;
      }
    }
  }, 4);
  std::vector<Eye> eyes;
  for (auto& f : found) eyes.insert(eyes.end(), f.begin(), f.end());
  if (opt.workspace.filter && !eyes.empty()) {  // the caller's batch filter, once for all eyes
    std::vector<Eigen::Vector3d> pos(eyes.size());
    for (std::size_t i = 0; i < eyes.size(); ++i) pos[i] = eyes[i].at;
    const std::vector<bool> keep = opt.workspace.filter(pos);
    std::size_t w = 0;
    for (std::size_t i = 0; i < eyes.size(); ++i)
      if (i < keep.size() && keep[i]) eyes[w++] = eyes[i];
    eyes.resize(w);
  }
  Stream rng(mix(req.seed, 2));  // `poses` of them at random
  const std::size_t n = std::min(req.poses, eyes.size());
  for (std::size_t i = 0; i < n; ++i) std::swap(eyes[i], eyes[i + std::size_t(rng.uniform() * double(eyes.size() - i))]);
  std::vector<Pose> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.push_back(camera_pose(eyes[i].at, eyes[i].axis, 0.0));
  return out;
}

std::vector<Pose> aim_along_sight(const ExplorationMap& map, const NbvOptions& opt, const AimRequest& req) {
  const ExplorationState& S = state(map);
  if (S.void_set.empty() || req.poses == 0) return {};
  AimRequest draw = req;
  draw.every_cell = false;
  const std::vector<CellKey> from = draw_void_cells(S, draw);
  const double res = map.resolution();
  std::vector<Pose> out;
  const GridReader g(S.grid);
  for (std::size_t i = 0; i < from.size() && out.size() < req.poses; ++i) {
    Stream rng(mix(mix(req.seed, from[i]), 3));
    Eigen::Vector3d d = rng.direction();
    d.z() = std::abs(d.z());
    const double s = req.distance.first + rng.uniform() * (req.distance.second - req.distance.first);
    const Eigen::Vector3d c = S.center(from[i]), eye = c + s * d;
    if (eye.z() < req.min_height || !opt.workspace.contains(eye)) continue;
    bool clear = true;
    walk_cells(res, c, d, s, [&](CellKey k) {
      if (k != from[i] && (g.get(k) & kStateMask) == std::uint8_t(CellState::Occupied)) clear = false;
      return clear;
    });
    if (clear) out.push_back(camera_pose(eye, c - eye, 0.0));
  }
  return out;
}

}  // namespace octoreach::detail
