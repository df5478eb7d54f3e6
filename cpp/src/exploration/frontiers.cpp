// Frontier upkeep: flags and 26-connected cluster labels maintained from the changed cells.
#include <algorithm>
#include <unordered_set>

#include "exploration/cell_sets.hpp"
#include "common/thread_pool.hpp"
#include "exploration/upkeep.hpp"

namespace octoreach::detail {

bool is_frontier_cell(const GridReader& g, CellKey k) {
  if ((g.get(k) & kStateMask) != std::uint8_t(CellState::Free)) return false;
  for (const auto& d : kN6) {
    CellKey n;
    if (neighbour(k, d[0], d[1], d[2], n) && (g.get(n) & kStateMask) == std::uint8_t(CellState::Unknown))
      return true;
  }
  return false;
}

void label_frontier_clusters(ExplorationState& s, std::vector<std::vector<CellKey>> components) {
  for (auto& comp : components) {
    int label = s.next_label++;
    for (CellKey k : comp) s.frontier_label[k] = label;
    s.frontier_members.emplace(label, std::move(comp));
  }
}

namespace {

// The clusters touched by an update: those that lost a cell or border a new cell.
std::vector<int> touched_clusters(const ExplorationState& s, const std::vector<CellKey>& added,
                                  const std::vector<std::pair<CellKey, int>>& removed) {
  std::unordered_set<int> affected;
  for (const auto& r : removed) affected.insert(r.second);
  for (CellKey a : added)
    for (const auto& d : kN26.d) {
      CellKey nb;
      if (!neighbour(a, d[0], d[1], d[2], nb)) continue;
      auto it = s.frontier_label.find(nb);
      if (it != s.frontier_label.end()) affected.insert(it->second);
    }
  std::vector<int> out(affected.begin(), affected.end());
  std::sort(out.begin(), out.end());
  return out;
}

// Reclusters the added cells with the remaining cells of the touched clusters.
void recluster(ExplorationState& s, const std::vector<CellKey>& added,
               const std::vector<std::pair<CellKey, int>>& removed) {
  std::vector<CellKey> pool = added;
  for (int label : touched_clusters(s, added, removed)) {
    auto it = s.frontier_members.find(label);
    if (it == s.frontier_members.end()) continue;
    for (CellKey k : it->second)
      if (s.grid.get(k) & kFrontierFlag) pool.push_back(k);
    s.frontier_members.erase(it);
  }
  label_frontier_clusters(s, components26(std::move(pool)));
}

}  // namespace

void update_frontiers(ExplorationState& s, const std::vector<CellChange>& changed, int threads, InsertStats& st) {
  std::vector<std::uint8_t> own(changed.size());
  std::vector<GridReader> readers(threads, GridReader(s.grid));
  parallel_for(changed.size(), threads, [&](std::size_t i, int tid) {
    own[i] = is_frontier_cell(readers[tid], changed[i].key);
  }, 512);
  std::vector<CellKey> added;
  std::vector<std::pair<CellKey, int>> removed;
  GridWriter gw(s.grid);  // every cell touched here already has its block
  auto remove = [&](CellKey k) {
    std::uint8_t& f = gw.at(k);
    f = std::uint8_t(f & ~kFrontierFlag);
    auto it = s.frontier_label.find(k);
    if (it != s.frontier_label.end()) {
      removed.emplace_back(k, it->second);
      s.frontier_label.erase(it);
    }
  };
  GridReader g(s.grid);
  for (std::size_t i = 0; i < changed.size(); ++i) {
    CellKey k = changed[i].key;
    std::uint8_t& fk = gw.at(k);
    bool was = (fk & kFrontierFlag) != 0;
    if (own[i] && !was) {
      fk |= kFrontierFlag;
      added.push_back(k);
    } else if (!own[i] && was) {
      remove(k);
    }
    if (changed[i].before != CellState::Unknown) continue;
    for (const auto& d : kN6) {
      CellKey nb;
      if (!neighbour(k, d[0], d[1], d[2], nb)) continue;
      if ((g.get(nb) & kFrontierFlag) && !is_frontier_cell(g, nb)) remove(nb);
    }
  }
  st.frontier_added = added.size();
  st.frontier_removed = removed.size();
  recluster(s, added, removed);
  std::lock_guard<std::mutex> lock(s.cache_mutex);
  s.clusters_dirty = true;
}

}  // namespace octoreach::detail

namespace octoreach {

using detail::kFrontierFlag;

std::vector<CellKey> ExplorationMap::frontier_cells() const {
  detail::MapGuard guard(*state_, false);
  std::vector<CellKey> out;
  out.reserve(state_->frontier_label.size());
  for (const auto& kv : state_->frontier_label) out.push_back(kv.first);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::vector<CellKey>> ExplorationMap::frontier_clusters() const {
  detail::MapGuard guard(*state_, false);
  return detail::cached_frontier_clusters(*state_);
}

const std::vector<std::vector<CellKey>>& detail::cached_frontier_clusters(const detail::ExplorationState& I) {
  std::lock_guard<std::mutex> lock(I.cache_mutex);
  if (I.clusters_dirty) {
    std::vector<std::pair<int, std::vector<CellKey>>> tmp;
    for (const auto& [label, cells] : I.frontier_members) {
      std::vector<CellKey> c;
      for (CellKey k : cells)
        if (I.grid.get(k) & kFrontierFlag) c.push_back(k);
      std::sort(c.begin(), c.end());
      if (!c.empty()) tmp.emplace_back(label, std::move(c));
    }
    std::sort(tmp.begin(), tmp.end(), [](const auto& a, const auto& b) { return a.second[0] < b.second[0]; });
    I.clusters.clear();
    I.label_to_cluster.clear();
    for (auto& [label, c] : tmp) {
      I.label_to_cluster[label] = int(I.clusters.size());
      I.clusters.push_back(std::move(c));
    }
    I.clusters_dirty = false;
  }
  return I.clusters;
}

}  // namespace octoreach
