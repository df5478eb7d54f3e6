// ExplorationMap: the public class. Insertion runs the steps of batch_insert.cpp and upkeep.hpp;
// what the map holds lives in ExplorationState (exploration_state.hpp).
#include "octoreach/exploration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <unordered_map>

#include "exploration/batch_insert.hpp"
#include "exploration/cell_sets.hpp"
#include "common/atomic_file.hpp"
#include "common/cancel.hpp"
#include "common/format.hpp"
#include "common/octree_file.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/upkeep.hpp"
#include "exploration/view_score.hpp"

namespace octoreach {

using detail::kFrontierFlag;
using detail::kStateMask;
using detail::kVoidFlag;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The key of p, false outside the key range. Checked in double first: octomap's coordToKeyChecked converts
// resolution_factor * coordinate to int, undefined (and accepted by optimised code) beyond 2^31.
bool key_checked(const octomap::OcTree& tree, const Eigen::Vector3d& p, octomap::OcTreeKey& k) {
  return p.allFinite() && p.cwiseAbs().maxCoeff() < tree.getResolution() * 32768 &&
         tree.coordToKeyChecked(octomap::point3d(float(p.x()), float(p.y()), float(p.z())), k);
}

// Finite rows as OctoMap points; counts the others in stats.dropped. A point farther from the origin than twice
// the key range is moved along its ray to that distance: the same ray (out of bounds, or cut at max_range), but
// representable as a float (1e300 became inf and crashed the ray walk) and inside octomap's int key arithmetic.
std::vector<octomap::point3d> finite_points(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                            double resolution, InsertStats& st) {
  const double far = resolution * 65536;
  std::vector<octomap::point3d> pc;
  pc.reserve(points.size());
  for (const auto& p : points) {
    if (!p.allFinite()) {
      ++st.dropped;
      continue;
    }
    const Eigen::Vector3d d = p - origin;
    const double m = d.cwiseAbs().maxCoeff();
    const Eigen::Vector3d q = m > far ? Eigen::Vector3d(origin + d * (far / m)) : p;
    pc.emplace_back(float(q.x()), float(q.y()), float(q.z()));
  }
  st.points = pc.size();
  return pc;
}

// Refuses occupied cells whose bounding box (with the hull's vertices), clipped to the search space, holds more
// than options.max_void_box_cells cells: the void upkeep visits that box. Throws E before anything changes.
template <class E>
void check_void_box(const std::vector<Eigen::Vector3d>& hull_vertices, const std::vector<Eigen::Vector3d>& occupied,
                    const ExplorationOptions& options, double resolution, const std::string& what) {
  if (!options.track_voids || occupied.empty()) return;
  Eigen::Vector3d lo = occupied.front(), hi = lo;
  for (const auto* pts : {&hull_vertices, &occupied})
    for (const auto& p : *pts) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const double cells = detail::hull_box_cells(lo, hi, resolution, options.search_lo, options.search_hi);
  if (cells > double(options.max_void_box_cells))
    throw E(what + ": the occupied cells span " + detail::format_point(lo) + " to " + detail::format_point(hi) +
            ", a box of " + detail::format_number(cells) + " cells in which voids would be looked for (limit " +
            std::to_string(options.max_void_box_cells) +
            "); pass a search_space around the region to explore (or track_voids=False)");
}

}  // namespace

ExplorationMap::ExplorationMap(const ExplorationOptions& options) : options_(options) {
  if (!(options.resolution > 0) || !std::isfinite(options.resolution))
    throw std::invalid_argument("resolution must be a positive number of metres, got " +
                                std::to_string(options.resolution));
  if (!(options.void_fit_threshold >= 0) || !std::isfinite(options.void_fit_threshold))
    throw std::invalid_argument("void_fit_threshold must be a finite number >= 0, got " +
                                std::to_string(options.void_fit_threshold));
  if (options.voids_fill_search_space) {
    const double cells = detail::hull_box_cells(options.search_lo, options.search_hi, options.resolution,
                                                options.search_lo, options.search_hi);
    if (!detail::bounded_search_space(options) || cells > double(options.max_void_box_cells))
      throw std::invalid_argument("voids_fill_search_space needs a finite search space of at most " +
                                  std::to_string(options.max_void_box_cells) + " cells, got " +
                                  detail::format_point(options.search_lo) + " to " +
                                  detail::format_point(options.search_hi));
  }
  resolution_ = options.resolution;
  state_ = std::make_unique<detail::ExplorationState>(resolution_);
}

ExplorationMap::~ExplorationMap() = default;

const octomap::OcTree& ExplorationMap::octree() const { return state_->tree; }

CellKey ExplorationMap::key_of(const Eigen::Vector3d& p) const {
  octomap::OcTreeKey k;
  if (!key_checked(state_->tree, p, k))
    throw std::invalid_argument("point " + detail::format_point(p) + " is outside the map bounds");
  return detail::to_cell(k);
}

Eigen::Vector3d ExplorationMap::center(CellKey k) const { return state_->center(k); }

CellState ExplorationMap::state(CellKey key) const {
  detail::MapGuard guard(*state_, false);
  return state_->state(key);
}
CellState ExplorationMap::state(const Eigen::Vector3d& p) const {
  octomap::OcTreeKey k;
  if (!key_checked(state_->tree, p, k)) return CellState::Unknown;
  detail::MapGuard guard(*state_, false);
  return state_->state(detail::to_cell(k));
}
void ExplorationMap::state(const double* rows, std::size_t n, std::uint8_t* out) const {
  detail::MapGuard guard(*state_, false);
  detail::GridReader g(state_->grid);
  for (std::size_t i = 0; i < n; ++i) {
    octomap::OcTreeKey k;
    const Eigen::Vector3d p(rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]);
    if (!p.allFinite()) throw std::invalid_argument("point " + std::to_string(i) + " is not finite (NaN or inf)");
    out[i] = key_checked(state_->tree, p, k) ? std::uint8_t(g.get(detail::to_cell(k)) & kStateMask) : 0;
  }
}
bool ExplorationMap::is_frontier(CellKey key) const {
  detail::MapGuard guard(*state_, false);
  return (state_->grid.get(key) & kFrontierFlag) != 0;
}
bool ExplorationMap::is_void(CellKey key) const {
  detail::MapGuard guard(*state_, false);
  return (state_->grid.get(key) & kVoidFlag) != 0;
}
std::vector<CellChange> ExplorationMap::changed_cells() const {
  detail::MapGuard guard(*state_, false);
  return changed_;
}

InsertStats ExplorationMap::insert(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                   double max_range) {
  auto t_start = Clock::now();
  InsertStats st;
  if (!origin.allFinite())
    throw std::invalid_argument("sensor_origin must be finite, got " + detail::format_point(origin));
  if (std::isnan(max_range)) throw std::invalid_argument("max_range must be a number (<= 0 or inf: unlimited), got nan");
  auto& S = *state_;
  detail::MapGuard guard(S, true);
  octomap::OcTreeKey okey;
  if (!key_checked(S.tree, origin, okey))
    throw std::invalid_argument("sensor_origin " + detail::format_point(origin) +
                                " is outside the map bounds (|coordinate| < " + std::to_string(resolution_ * 32768) +
                                " m)");
  changed_.clear();
  const std::vector<octomap::point3d> pc = finite_points(points, origin, resolution_, st);
  if (pc.empty()) {
    detail::learn_from_missed(*this, S, /*returned=*/false);
    st.seconds_total = seconds_since(t_start);
    return st;
  }
  const int threads = detail::default_threads(options_.threads);
  const octomap::point3d o(float(origin.x()), float(origin.y()), float(origin.z()));

  // 1-2. ray ends, the ray walk, the sorted cell updates
  auto t0 = Clock::now();
  detail::CloudUpdates up = detail::cloud_updates(S.tree, pc, o, max_range, threads, st);
  st.seconds_rays = seconds_since(t0);
  if (options_.track_voids) {  // before any change: a refused insert leaves the map as it was
    std::vector<Eigen::Vector3d> occupied;
    occupied.reserve(up.occupied.size());
    for (CellKey k : up.occupied) occupied.push_back(S.center(k));
    check_void_box<std::invalid_argument>(S.hull.vertices, occupied, options_, resolution_, "insert refused");
  }

  // 3. one batched descent of the tree; the cell cache follows the changed cells
  t0 = Clock::now();
  S.surface.record(S.tree, pc, o, max_range);
  detail::apply_updates(S.tree, up.updates, changed_);
  detail::GridWriter gw(S.grid);
  const detail::SpaceKeys space = detail::space_keys(options_);
  for (const auto& c : changed_) {
    std::uint8_t& cell = gw.at(c.key);
    if (c.before == CellState::Unknown) {  // the visibility model's statistics (void flags still set)
      if (space.contains(c.key)) ++st.space_known;
      const bool occ = c.after == CellState::Occupied;
      const double w = 1.0 / std::max((S.center(c.key) - origin).squaredNorm(), 0.01);
      ++(occ ? S.rays.unknown_to_occupied : S.rays.unknown_to_free);
      (occ ? S.rays.unknown_to_occupied_w : S.rays.unknown_to_free_w) += w;
      if (cell & kVoidFlag) {
        ++(occ ? S.rays.void_to_occupied : S.rays.void_to_free);
        (occ ? S.rays.void_to_occupied_w : S.rays.void_to_free_w) += w;
      }
    }
    cell = std::uint8_t((cell & ~kStateMask) | std::uint8_t(c.after));
  }
  st.changed_cells = changed_.size();
  S.surface.update_grown(S, changed_);
  detail::learn_from_missed(*this, S, /*returned=*/true);  // the announced view's expected cells that are still unknown
  st.seconds_tree = seconds_since(t0);

  // 4. frontiers
  t0 = Clock::now();
  detail::update_frontiers(S, changed_, threads, st);
  st.seconds_frontiers = seconds_since(t0);

  // 5. hull and voids
  if (options_.track_voids) detail::update_voids(S, changed_, up.occupied, options_, threads, st);
  st.seconds_total = seconds_since(t_start);
  return st;
}

RayStatistics ExplorationMap::ray_statistics() const {
  detail::MapGuard guard(*state_, false);
  return state_->rays;
}

double ExplorationMap::pass_probability() const { return ray_statistics().pass_probability(); }
double ExplorationMap::void_pass_probability() const { return ray_statistics().void_pass_probability(); }

std::vector<CellKey> ExplorationMap::known_cells(CellState which) const {
  if (which == CellState::Unknown) throw std::invalid_argument("known_cells: which must be Free or Occupied");
  detail::MapGuard guard(*state_, false);
  const auto& tree = state_->tree;
  const bool want = which == CellState::Occupied;
  std::vector<CellKey> keys;
  detail::for_each_leaf_cell(tree, [&](CellKey c, const auto& it) {
    if (tree.isNodeOccupied(*it) == want) keys.push_back(c);
  });
  std::sort(keys.begin(), keys.end());
  return keys;
}

OccupancyDigest ExplorationMap::occupancy_digest() const {
  detail::MapGuard guard(*state_, false);
  return octoreach::occupancy_digest(state_->tree);
}

ExplorationSnapshot ExplorationMap::snapshot() const {
  detail::MapGuard guard(*state_, false);
  ExplorationSnapshot s;
  s.frontier_cells = frontier_cells();
  s.frontier_clusters = frontier_clusters();
  s.void_cells = void_cells();
  return s;
}

ExplorationSnapshot ExplorationMap::recompute_from_scratch() const {
  detail::MapGuard guard(*state_, false);
  ExplorationSnapshot s;
  const auto& S = *state_;
  // Every known leaf of the tree, expanded to the finest resolution, classified by the tree itself.
  std::unordered_map<CellKey, std::uint8_t> cls;
  detail::for_each_leaf_cell(S.tree, [&](CellKey cell, const auto& it) {
    cls[cell] = std::uint8_t(S.tree.isNodeOccupied(*it) ? CellState::Occupied : CellState::Free);
  });
  auto state_of = [&](CellKey k) {
    auto it = cls.find(k);
    return it == cls.end() ? std::uint8_t(0) : it->second;
  };
  for (const auto& [k, c] : cls) {
    if (c != std::uint8_t(CellState::Free)) continue;
    for (const auto& d : detail::kN6) {
      CellKey n;
      if (detail::neighbour(k, d[0], d[1], d[2], n) && state_of(n) == 0) {
        s.frontier_cells.push_back(k);
        break;
      }
    }
  }
  std::sort(s.frontier_cells.begin(), s.frontier_cells.end());
  s.frontier_clusters = detail::components26(s.frontier_cells);
  if (!S.hull.empty()) {
    detail::HullColumns c = detail::void_columns(S.tree, S.hull, options_.threads, options_);
    for (int y = 0; y < c.ny; ++y)
      for (int x = 0; x < c.nx; ++x) {
        int l, h;
        if (!c.column(c.x0 + x, c.y0 + y, l, h)) continue;
        for (int z = l; z <= h; ++z) {
          CellKey k = pack_key(c.x0 + x, c.y0 + y, z);
          if (state_of(k) == 0) s.void_cells.push_back(k);
        }
      }
  }
  std::sort(s.void_cells.begin(), s.void_cells.end());
  return s;
}

std::pair<std::size_t, std::size_t> ExplorationMap::count_known(const Eigen::Vector3d& lo,
                                                                const Eigen::Vector3d& hi) const {
  CellKey a = key_of(lo), b = key_of(hi);
  const std::uint64_t cells = std::uint64_t(key_x(b) >= key_x(a) ? key_x(b) - key_x(a) + 1 : 0) *
                              (key_y(b) >= key_y(a) ? key_y(b) - key_y(a) + 1 : 0) *
                              (key_z(b) >= key_z(a) ? key_z(b) - key_z(a) + 1 : 0);
  if (cells > kMaxCountCells)
    throw std::invalid_argument("count_known: the box holds " + std::to_string(cells) + " cells, more than the limit " +
                                std::to_string(kMaxCountCells));
  std::size_t known = 0, unknown = 0;
  detail::MapGuard guard(*state_, false);
  detail::GridReader g(state_->grid);
  for (std::uint32_t z = key_z(a); z <= key_z(b); ++z)
    for (std::uint32_t y = key_y(a); y <= key_y(b); ++y)
      for (std::uint32_t x = key_x(a); x <= key_x(b); ++x) {
        if (g.get(pack_key(x, y, z)) & kStateMask)
          ++known;
        else
          ++unknown;
      }
  return {known, unknown};
}

void ExplorationMap::write_bt(const std::string& path) const {
  detail::MapGuard guard(*state_, false);
  detail::write_file_atomically(path, [&](std::ostream& out) {
    if (!state_->tree.writeBinaryConst(out)) throw FileError("cannot write OctoMap file '" + path + "'");
  }, "OctoMap file");
}

std::unique_ptr<ExplorationMap> ExplorationMap::from_file(const std::string& path, const ExplorationOptions& options) {
  detail::CancellableScope cancellable;
  auto m = std::make_unique<ExplorationMap>(options);
  auto& S = *m->state_;
  detail::read_bt(S.tree, path, "OctoMap file", options.max_file_cells);
  m->resolution_ = S.tree.getResolution();
  m->options_.resolution = m->resolution_;
  std::vector<Eigen::Vector3d> occupied;
  std::size_t visited = 0;
  detail::for_each_leaf_cell(S.tree, [&](CellKey c, const auto& it) {
    if ((++visited & 0xffff) == 0) detail::poll_cancel("OctoMap loading cancelled");
    bool occ = S.tree.isNodeOccupied(*it);
    S.grid.at(c) = std::uint8_t(occ ? CellState::Occupied : CellState::Free);
    if (occ) occupied.push_back(S.center(c));
  });
  check_void_box<FileError>({}, occupied, options, m->resolution_, "'" + path + "'");
  ExplorationSnapshot s = m->recompute_from_scratch();  // frontiers only: no hull yet
  for (CellKey k : s.frontier_cells) S.grid.at(k) |= kFrontierFlag;
  detail::label_frontier_clusters(S, std::move(s.frontier_clusters));
  if (options.track_voids && detail::convex_hull(occupied, S.hull)) {
    S.columns = detail::void_columns(S.tree, S.hull, options.threads, options);
    ExplorationSnapshot v = m->recompute_from_scratch();
    for (CellKey k : v.void_cells) {
      S.grid.at(k) |= kVoidFlag;
      S.void_set.insert(k);
      S.void_added.push_back(k);
    }
  }
  return m;
}

}  // namespace octoreach
