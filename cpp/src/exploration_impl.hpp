#pragma once
// Private parts of ExplorationMap shared by exploration.cpp and next_best_view.cpp.
#include <array>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <octomap/OcTree.h>

#include "octoreach/exploration.hpp"

namespace octoreach {
namespace detail {

// OcTree with access to its root, so batched updates can create it like updateNode does.
class MapTree : public octomap::OcTree {
 public:
  using octomap::OcTree::OcTree;
  octomap::OcTreeNode* root_node() { return root; }
  octomap::OcTreeNode* make_root() {
    if (!root) {
      root = new octomap::OcTreeNode();
      tree_size++;
      size_changed = true;
    }
    return root;
  }
};

// Cell flags kept beside the class: bits 0-1 CellState, then frontier and void marks.
constexpr std::uint8_t kStateMask = 3, kFrontierFlag = 4, kVoidFlag = 8;

// Dense 16^3 blocks in a hash map: a finest-resolution cache of the tree's cell classes,
// written from the exact list of changed cells, so neighbour queries avoid tree descents.
class StateGrid {
 public:
  using Block = std::array<std::uint8_t, 4096>;
  static CellKey block_of(CellKey k) { return pack_key(key_x(k) >> 4, key_y(k) >> 4, key_z(k) >> 4); }
  static int offset(CellKey k) {
    return int(key_x(k) & 15) | (int(key_y(k) & 15) << 4) | (int(key_z(k) & 15) << 8);
  }
  std::uint8_t get(CellKey k) const {
    auto it = blocks_.find(block_of(k));
    return it == blocks_.end() ? 0 : (*it->second)[offset(k)];
  }
  std::uint8_t& at(CellKey k) {
    auto& b = blocks_[block_of(k)];
    if (!b) {
      b = std::make_unique<Block>();
      b->fill(0);
    }
    return (*b)[offset(k)];
  }
  Block& block(CellKey block) {
    auto& b = blocks_[block];
    if (!b) {
      b = std::make_unique<Block>();
      b->fill(0);
    }
    return *b;
  }
  const Block* find_block(CellKey block) const {
    auto it = blocks_.find(block);
    return it == blocks_.end() ? nullptr : it->second.get();
  }
  void clear() { blocks_.clear(); }
  template <class F>
  void for_each_block(F&& f) const {
    for (const auto& [k, b] : blocks_) f(k, *b);
  }

 private:
  std::unordered_map<CellKey, std::unique_ptr<Block>> blocks_;
};

// Read-only view of a StateGrid with a one-block cache (one per thread).
class GridReader {
 public:
  explicit GridReader(const StateGrid& g) : g_(g) {}
  std::uint8_t get(CellKey k) const {
    CellKey b = StateGrid::block_of(k);
    if (b != last_key_) {
      last_key_ = b;
      last_ = g_.find_block(b);
    }
    return last_ ? (*last_)[StateGrid::offset(k)] : 0;
  }

 private:
  const StateGrid& g_;
  mutable CellKey last_key_ = ~CellKey(0);
  mutable const StateGrid::Block* last_ = nullptr;
};

// Read-write access to existing cells of a StateGrid with a one-block cache. Blocks are never
// freed or moved while the grid lives (unique_ptr), so the cached pointer stays valid even when
// other blocks are created.
class GridWriter {
 public:
  explicit GridWriter(StateGrid& g) : g_(g) {}
  std::uint8_t& at(CellKey k) {
    CellKey b = StateGrid::block_of(k);
    if (b != last_key_ || !last_) {
      last_ = &g_.block(b);
      last_key_ = b;
    }
    return (*last_)[StateGrid::offset(k)];
  }
  std::uint8_t get(CellKey k) { return at_if(k); }

 private:
  std::uint8_t at_if(CellKey k) {
    CellKey b = StateGrid::block_of(k);
    if (b == last_key_ && last_) return (*last_)[StateGrid::offset(k)];
    const StateGrid::Block* p = g_.find_block(b);
    if (!p) return 0;
    last_ = const_cast<StateGrid::Block*>(p);
    last_key_ = b;
    return (*p)[StateGrid::offset(k)];
  }
  StateGrid& g_;
  CellKey last_key_ = ~CellKey(0);
  StateGrid::Block* last_ = nullptr;
};

// Neighbour of k by (dx, dy, dz); false when it would leave the key range.
inline bool neighbour(CellKey k, int dx, int dy, int dz, CellKey& out) {
  int x = int(key_x(k)) + dx, y = int(key_y(k)) + dy, z = int(key_z(k)) + dz;
  if (x < 0 || y < 0 || z < 0 || x > 0xffff || y > 0xffff || z > 0xffff) return false;
  out = pack_key(x, y, z);
  return true;
}

constexpr int kN6[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

struct N26 {
  int d[26][3];
  N26() {
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx || dy || dz) {
            d[n][0] = dx;
            d[n][1] = dy;
            d[n][2] = dz;
            ++n;
          }
  }
};
extern const N26 kN26;

// Hull facets and, per (x, y) column of cells, the key interval [lo, hi] of cells whose
// centre is inside the hull (lo > hi: empty).
struct HullColumns {
  int x0 = 0, y0 = 0, nx = 0, ny = 0;
  std::vector<std::int32_t> lo, hi;
  bool column(int x, int y, int& l, int& h) const {
    if (x < x0 || y < y0 || x >= x0 + nx || y >= y0 + ny) return false;
    std::size_t i = std::size_t(y - y0) * nx + (x - x0);
    l = lo[i];
    h = hi[i];
    return l <= h;
  }
};

}  // namespace detail

struct ExplorationMap::Impl {
  explicit Impl(double res) : tree(res) {}
  detail::MapTree tree;
  detail::StateGrid grid;
  // frontier cell -> cluster label, label -> cells (cells may be stale; filter by the flag)
  std::unordered_map<CellKey, int> frontier_label;
  std::unordered_map<int, std::vector<CellKey>> frontier_members;
  int next_label = 0;
  std::unordered_set<CellKey> void_set;
  std::vector<Eigen::Vector3d> hull_vertices;
  std::vector<Eigen::Vector4d> hull_planes;
  detail::HullColumns columns;

  // caches rebuilt on demand after an insert
  mutable std::mutex cache_mutex;
  mutable bool clusters_dirty = true, voids_dirty = true;
  mutable std::vector<std::vector<CellKey>> clusters;
  mutable std::unordered_map<int, int> label_to_cluster;
  mutable std::vector<VoidCluster> void_clusters;

  CellState state(CellKey k) const { return CellState(grid.get(k) & detail::kStateMask); }
};

}  // namespace octoreach
