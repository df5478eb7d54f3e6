// Void upkeep: the hull of the occupied cells and the unknown cells inside it.
#include <algorithm>
#include <chrono>

#include "common/format.hpp"
#include "common/thread_pool.hpp"
#include "exploration/upkeep.hpp"

namespace octoreach::detail {

namespace {

void set_void(GridWriter& gw, ExplorationState& s, CellKey k, InsertStats& st) {
  gw.at(k) |= kVoidFlag;
  s.void_set.insert(k);
  s.void_added.push_back(k);
  ++st.void_added;
}

void clear_void(GridWriter& gw, ExplorationState& s, CellKey k, InsertStats& st) {
  gw.at(k) &= std::uint8_t(~kVoidFlag);
  s.void_set.erase(k);
  s.void_removed.push_back(k);
  ++st.void_removed;
}

// Void flags of the cells that entered or left the hull, visiting the union of both column boxes.
void diff_columns(GridWriter& gw, ExplorationState& s, const HullColumns& oc, const HullColumns& nc, InsertStats& st) {
  int x0 = nc.x0, y0 = nc.y0, x1 = nc.x0 + nc.nx, y1 = nc.y0 + nc.ny;
  if (oc.nx > 0) {
    x0 = std::min(x0, oc.x0);
    y0 = std::min(y0, oc.y0);
    x1 = std::max(x1, oc.x0 + oc.nx);
    y1 = std::max(y1, oc.y0 + oc.ny);
  }
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      int ol = 1, oh = 0, nl = 1, nh = 0;
      oc.column(x, y, ol, oh);
      nc.column(x, y, nl, nh);
      if (ol == nl && oh == nh) continue;
      for (int z = nl; z <= nh; ++z) {  // new cells of the hull
        if (z >= ol && z <= oh) continue;
        CellKey k = pack_key(x, y, z);
        std::uint8_t f = gw.get(k);
        if ((f & kStateMask) == 0 && !(f & kVoidFlag)) set_void(gw, s, k, st);
      }
      for (int z = ol; z <= oh; ++z) {  // cells that left the hull (numerical merging only)
        if (z >= nl && z <= nh) continue;
        CellKey k = pack_key(x, y, z);
        if (gw.get(k) & kVoidFlag) clear_void(gw, s, k, st);
      }
    }
}

}  // namespace

void update_voids(ExplorationState& s, const std::vector<CellChange>& changed, const std::vector<CellKey>& occupied,
                  const ExplorationOptions& options, int threads, InsertStats& st) {
  auto t0 = std::chrono::steady_clock::now();
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  std::vector<Eigen::Vector3d> hull_in = s.hull.vertices;
  hull_in.reserve(hull_in.size() + occupied.size());
  for (CellKey k : occupied) hull_in.push_back(s.center(k));
  Hull hull;
  bool have_hull = convex_hull(hull_in, hull);
  st.seconds_hull = since(t0);
  t0 = std::chrono::steady_clock::now();
  GridWriter gw(s.grid);
  // cells that became known are no longer voids
  for (const auto& c : changed)
    if (c.before == CellState::Unknown && (gw.get(c.key) & kVoidFlag)) clear_void(gw, s, c.key, st);
  if (have_hull) {
    HullColumns nc = void_columns(s.tree, hull, threads, options);
    diff_columns(gw, s, s.columns, nc, st);
    s.columns = std::move(nc);
    s.hull = std::move(hull);
  } else {
    // no hull yet (fewer than 4 points, all coplanar: the first view of a flat face): keep the points, the
    // next insert's hull is made from them too (else the faces of a solid, each seen flat, never made one)
    s.hull.vertices = std::move(hull_in);
  }
  update_sealed(s, options);
  std::lock_guard<std::mutex> lock(s.cache_mutex);
  s.voids_dirty = true;
  s.enclosure.reset();
  st.seconds_voids = since(t0);
}

}  // namespace octoreach::detail

namespace octoreach {

std::vector<CellKey> ExplorationMap::void_cells() const {
  detail::MapGuard guard(*state_, false);
  std::vector<CellKey> out(state_->void_set.begin(), state_->void_set.end());
  std::sort(out.begin(), out.end());
  return out;
}
std::size_t ExplorationMap::void_cell_count() const {
  detail::MapGuard guard(*state_, false);
  return state_->void_set.size();
}

std::size_t ExplorationMap::sealed_void_cell_count() const {
  detail::MapGuard guard(*state_, false);
  return state_->sealed.size();
}

std::vector<Eigen::Vector3d> ExplorationMap::hull_vertices() const {
  detail::MapGuard guard(*state_, false);
  return state_->hull.vertices;
}
std::vector<Eigen::Vector4d> ExplorationMap::hull_planes() const {
  detail::MapGuard guard(*state_, false);
  return state_->hull.planes;
}
bool ExplorationMap::inside_hull(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) throw std::invalid_argument("inside_hull: point " + detail::format_point(p) + " is not finite");
  detail::MapGuard guard(*state_, false);
  if (state_->hull.planes.empty()) return false;
  for (const auto& pl : state_->hull.planes)
    if (pl.head<3>().dot(p) + pl[3] > 1e-7 * resolution_) return false;
  return true;
}

}  // namespace octoreach
