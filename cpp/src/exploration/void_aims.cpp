// Camera poses aimed at void cells, their eyes found along rays out of the cells (void_aims.hpp).
#include "exploration/void_aims.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

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

// A random n of v (partial Fisher-Yates), kept in v's front; v shrinks to them.
template <class T>
void shuffle_first(std::vector<T>& v, std::size_t n, Stream& rng) {
  n = std::min(n, v.size());
  for (std::size_t i = 0; i < n; ++i) std::swap(v[i], v[i + std::size_t(rng.uniform() * double(v.size() - i))]);
  v.resize(n);
}

}  // namespace

std::vector<CellKey> draw_void_cells(const ExplorationState& S, const AimRequest& req) {
  std::vector<CellKey> all(S.void_set.begin(), S.void_set.end());
  std::sort(all.begin(), all.end());
  Stream rng(mix(req.seed, 1));
  if (req.every_cell) {
    shuffle_first(all, req.max_cells, rng);
    return all;
  }
  const GridReader g(S.grid);
  std::vector<CellKey> exposed, other;
  for (CellKey k : all) (has_free_neighbour(g, k) ? exposed : other).push_back(k);
  shuffle_first(exposed, exposed.size(), rng);
  shuffle_first(other, other.size(), rng);
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

constexpr std::uint64_t kRayChunk = 8192;  // rays walked between two looks at the eyes found (a few ms of work)

// A gate of the voids: an observed-free cell with a void cell across a face. A line of sight out of the voids
// leaves them into a gate; where their openings span a small solid angle (a closed box's slot a few cells wide),
// few of the rays a void cell sends uniformly pass them, while every line through a gate into the voids meets
// void cells.
struct Gate {
  CellKey cell;
  Eigen::Vector3d inward;  // unit: towards a void cell across a face
};

// The gates (at most req.max_cells, drawn at random for req.seed), in a deterministic order.
std::vector<Gate> draw_gates(const ExplorationState& S, const AimRequest& req) {
  std::vector<std::pair<CellKey, int>> found;  // (gate, index of a face towards a void cell)
  {
    const GridReader g(S.grid);
    for (CellKey k : S.void_set)
      for (int f = 0; f < 6; ++f) {
        CellKey nb;
        if (neighbour(k, kN6[f][0], kN6[f][1], kN6[f][2], nb) &&
            (g.get(nb) & kStateMask) == std::uint8_t(CellState::Free))
          found.emplace_back(nb, f ^ 1);  // kN6 pairs opposite faces: from the gate back to k
      }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
              found.end());
  Stream rng(mix(req.seed, 4));
  shuffle_first(found, req.max_cells, rng);
  std::vector<Gate> out(found.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    const int* f = kN6[found[i].second];
    out[i] = Gate{found[i].first, Eigen::Vector3d(f[0], f[1], f[2])};
  }
  return out;
}

// The eyes along the last chance's rays (its own random stream per ray: the same whatever the thread).
struct RayEyes {
  using Stretch = std::vector<std::pair<CellKey, double>>;  // the free cells of a ray (key, distance along it)
  const ExplorationState& S;
  const ViewChecker& checker;
  const NbvOptions& opt;
  const AimRequest& req;
  double res;
  Eigen::Vector3d s_lo, s_hi;  // the search space
  Pose cap_inv;                // opt.capability_base.inverse()
  // The eye along the ray out of void cell `from_key` (centre c) in direction d, if any.
  std::optional<Eye> along(CellKey from_key, const Eigen::Vector3d& c, const Eigen::Vector3d& d, Stream& rng,
                           Stretch& stretch) const;
  // The eye of ray r through `gate`: a direction into the voids across the gate's face, a void cell on that
  // line drawn at random, and the ray out of that cell through a random point of the gate.
  std::optional<Eye> through(const Gate& gate, std::size_t r, Stretch& stretch) const;
};

std::optional<Eye> RayEyes::along(CellKey from_key, const Eigen::Vector3d& c, const Eigen::Vector3d& d, Stream& rng,
                                  Stretch& stretch) const {
  const GridReader g(S.grid);
  stretch.clear();
  bool left_unknown = false;
  walk_cells(res, c, d, req.distance.second, [&](CellKey k) {
    if (k == from_key) return true;
    const std::uint8_t cell = g.get(k);
    std::uint8_t st = cell & kStateMask;
    const Eigen::Vector3d p = S.center(k);
    const bool inside = (p.array() >= s_lo.array()).all() && (p.array() <= s_hi.array()).all();
    if (st == std::uint8_t(CellState::Unknown) && !inside) {
      if (p.z() < s_lo.z()) return false;  // the ground under the search space
      st = std::uint8_t(CellState::Free);  // the robot's side of the scene: no view needs to have seen it
    }
    if (st == std::uint8_t(CellState::Occupied)) return !surface_meets_line(S, k, c, d);  // no eye inside it
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
    if (!position_reachable(opt, cap_inv, eye)) continue;
    const std::optional<Eigen::Vector3d> axis = checker.reachable_axis(eye, -d, turned);
    if (!axis || !checker.camera_clear(eye)) continue;
    return Eye{eye, *axis};
  }
  return std::nullopt;
}

std::optional<Eye> RayEyes::through(const Gate& gate, std::size_t r, Stretch& stretch) const {
  Stream rng(mix(mix(req.seed ^ 0x6A09E667F3BCC909ULL, gate.cell), std::uint64_t(r)));
  Eigen::Vector3d u = rng.direction();
  if (u.dot(gate.inward) < 0) u = -u;
  const Eigen::Vector3d o = S.center(gate.cell);
  // a void cell drawn at random (reservoir) of those on the line into the voids, up to the first other cell
  CellKey at = gate.cell;
  std::size_t behind = 0;
  {
    const GridReader g(S.grid);
    walk_cells(res, o, u, req.distance.second - req.distance.first, [&](CellKey k) {
      if (k == gate.cell) return true;
      if ((g.get(k) & kVoidFlag) == 0) return false;
      if (rng.uniform() * double(++behind) < 1.0) at = k;
      return true;
    });
  }
  if (behind == 0) return std::nullopt;
  const Eigen::Vector3d c = S.center(at);
  Eigen::Vector3d q = o;
  for (int a = 0; a < 3; ++a) q[a] += res * (rng.uniform() - 0.5);  // a point of the gate (not in `at`'s cell)
  return along(at, c, (q - c).normalized(), rng, stretch);
}

}  // namespace

std::vector<Pose> aim_at_voids(const ExplorationMap& map, const ViewChecker& checker, const NbvOptions& opt,
                               const AimRequest& req) {
  const ExplorationState& S = state(map);
  if (S.void_set.empty() || req.poses == 0 || req.directions <= 0) return {};
  const std::vector<CellKey> from = draw_void_cells(S, req);
  const RayEyes ray_eyes{S, checker, opt, req, map.resolution(), map.options().search_lo, map.options().search_hi,
                         opt.capability_base.inverse()};
  // with gates, half of a cell's rays go through them instead: as many rays as without, at the same cost
  const std::vector<Gate> gates = req.through_gates ? draw_gates(S, req) : std::vector<Gate>{};
  const std::size_t all_dirs = std::size_t(req.directions);
  const std::size_t dirs = gates.empty() ? all_dirs : (all_dirs + 1) / 2;
  const std::size_t gate_dirs =
      gates.empty() ? 0 : std::max<std::size_t>(1, from.size() * (all_dirs - dirs) / gates.size());
  // The eye of ray r out of cell from[i], uniform over the sphere (its own random stream: the same whatever the
  // thread).
  const auto eye_of = [&](std::size_t i, std::size_t r, RayEyes::Stretch& stretch) {
    Stream rng(mix(mix(req.seed, from[i]), std::uint64_t(r)));
    const Eigen::Vector3d d = rng.direction();
    return ray_eyes.along(from[i], S.center(from[i]), d, rng, stretch);
  };
  // The eye of ray r through gate i.
  const auto eye_through = [&](std::size_t i, std::size_t r, RayEyes::Stretch& stretch) {
    return ray_eyes.through(gates[i], r, stretch);
  };
  // The rays in a random order of (cell, ray), in chunks, until `poses` eyes are found: the eyes of the first
  // rays are a random sample of all the rays' eyes, and the rest need not be walked (about 12 000 of a table
  // top's 150 000 rays give eyes, 1000 are wanted).
  const std::uint64_t cell_rays = std::uint64_t(from.size()) * dirs;
  const std::uint64_t pairs = cell_rays + std::uint64_t(gates.size()) * gate_dirs;
  // Fisher-Yates as far as the rays walked, the swapped slots in a table (memory for the rays walked only)
  std::unordered_map<std::uint64_t, std::uint64_t> swapped;
  const auto slot = [&](std::uint64_t k) {
    const auto it = swapped.find(k);
    return it == swapped.end() ? k : it->second;
  };
  Stream rng(mix(req.seed, 2));
  const int threads = default_threads(opt.threads);
  std::vector<Eye> eyes;
  for (std::uint64_t b = 0; b < pairs && eyes.size() < req.poses; b += kRayChunk) {
    const std::size_t n = std::size_t(std::min<std::uint64_t>(pairs - b, kRayChunk));
    std::vector<std::uint64_t> rays(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint64_t at = b + k, j = at + std::uint64_t(rng.uniform() * double(pairs - at));
      rays[k] = slot(j);
      swapped[j] = slot(at);
    }
    std::vector<std::optional<Eye>> got(n);
    std::vector<RayEyes::Stretch> scratch(std::size_t(std::max(threads, 1)));
    parallel_for(n, threads, [&](std::size_t k, int tid) {
      const std::uint64_t ray = rays[k];
      got[k] = ray < cell_rays ? eye_of(std::size_t(ray / dirs), std::size_t(ray % dirs), scratch[std::size_t(tid)])
                               : eye_through(std::size_t((ray - cell_rays) / gate_dirs),
                                             std::size_t((ray - cell_rays) % gate_dirs), scratch[std::size_t(tid)]);
    }, 64);
    std::vector<Eye> chunk;
    for (auto& g : got)
      if (g) chunk.push_back(*g);
    if (opt.workspace.filter) {  // the caller's filter, once per chunk
      std::vector<Eigen::Vector3d> pos(chunk.size());
      for (std::size_t i = 0; i < chunk.size(); ++i) pos[i] = chunk[i].at;
      const std::vector<bool> keep = filter_verdicts(opt, pos);
      std::size_t w = 0;
      for (std::size_t i = 0; i < chunk.size(); ++i)
        if (keep[i]) chunk[w++] = chunk[i];
      chunk.resize(w);
    }
    for (std::size_t i = 0; i < chunk.size() && eyes.size() < req.poses; ++i) eyes.push_back(chunk[i]);
  }
  std::vector<Pose> out;
  out.reserve(eyes.size());
  for (const Eye& y : eyes) out.push_back(camera_pose(y.at, y.axis, 0.0));
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
      if (k != from[i] && (g.get(k) & kStateMask) == std::uint8_t(CellState::Occupied) &&
          surface_meets_line(S, k, c, d))
        clear = false;
      return clear;
    });
    if (clear) out.push_back(camera_pose(eye, c - eye, 0.0));
  }
  return out;
}

}  // namespace octoreach::detail
