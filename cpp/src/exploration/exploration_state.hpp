#pragma once
// Internal: the state behind an ExplorationMap (OcTree, finest-resolution cell cache, frontier
// labels, void cells, hull), shared by the files of the exploration room and by next_best_view.
// Nothing here is part of the public API.
#include <array>
#include <cmath>
#include <memory>
#include <algorithm>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <octomap/OcTree.h>

#include "exploration/blind_lines.hpp"
#include "exploration/cell_blocks.hpp"
#include "exploration/cell_sets.hpp"
#include "common/shared_mutex.hpp"
#include "exploration/hull.hpp"
#include "exploration/surface_extents.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::detail {

class ScoreCells;

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

// Read-write access to cells of a StateGrid with a one-block cache. Blocks are never freed or
// moved while the grid lives (unique_ptr), so the cached pointer stays valid even when other
// blocks are created.
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
  // Reads without creating a block.
  std::uint8_t get(CellKey k) {
    CellKey b = StateGrid::block_of(k);
    if (b == last_key_ && last_) return (*last_)[StateGrid::offset(k)];
    const StateGrid::Block* p = g_.find_block(b);
    if (!p) return 0;
    last_ = const_cast<StateGrid::Block*>(p);
    last_key_ = b;
    return (*p)[StateGrid::offset(k)];
  }

 private:
  StateGrid& g_;
  CellKey last_key_ = ~CellKey(0);
  StateGrid::Block* last_ = nullptr;
};

inline CellKey to_cell(const octomap::OcTreeKey& k) { return pack_key(k[0], k[1], k[2]); }
inline octomap::OcTreeKey to_octo(CellKey k) {
  return octomap::OcTreeKey(octomap::key_type(key_x(k)), octomap::key_type(key_y(k)), octomap::key_type(key_z(k)));
}

// A search-space bound beyond this many metres leaves that side open (ExplorationOptions' default bounds are 1e9 m).
constexpr double kOpenSearchBound = 1e8;
inline bool open_below(double lo) { return !(lo > -kOpenSearchBound); }
inline bool open_above(double hi) { return !(hi < kOpenSearchBound); }
// True when the map's search space is bounded on every side.
inline bool bounded_search_space(const ExplorationOptions& o) {
  for (int a = 0; a < 3; ++a)
    if (open_below(o.search_lo[a]) || open_above(o.search_hi[a])) return false;
  return true;
}

// A box of cell keys, lo..hi on each axis (every key by default; empty when lo > hi on some axis). space_keys gives
// a map's search space as the hull counts it, the cells whose centre lies in it (every key along an unbounded
// axis): the cells a view's unknown figures and InsertStats::space_known count.
struct SpaceKeys {
  std::uint32_t lo[3] = {0, 0, 0}, hi[3] = {0xffff, 0xffff, 0xffff};
  static SpaceKeys none() { return SpaceKeys{{1, 1, 1}, {0, 0, 0}}; }
  bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
  bool contains(CellKey k) const { return contains(int(key_x(k)), int(key_y(k)), int(key_z(k))); }
  bool contains(int x, int y, int z) const {
    return x >= int(lo[0]) && x <= int(hi[0]) && y >= int(lo[1]) && y <= int(hi[1]) && z >= int(lo[2]) &&
           z <= int(hi[2]);
  }
};
inline SpaceKeys space_keys(const ExplorationOptions& o) {
  SpaceKeys s;
  const double half = 32768.0 - 0.5;
  for (int a = 0; a < 3; ++a) {
    if (!open_below(o.search_lo[a]))
      s.lo[a] = std::uint32_t(std::clamp(std::ceil(o.search_lo[a] / o.resolution + half - 1e-9), 0.0, 65535.0));
    if (!open_above(o.search_hi[a]))
      s.hi[a] = std::uint32_t(std::clamp(std::floor(o.search_hi[a] / o.resolution + half + 1e-9), 0.0, 65535.0));
  }
  return s;
}

// The one leaf-to-cells expansion: calls f(cell, leaf iterator) for every finest-resolution cell
// an octree leaf covers (a pruned leaf of depth d covers 8^(16 - d) cells starting at its key
// rounded down to the leaf size), for every leaf of the tree.
template <class F>
void for_each_leaf_cell(const octomap::OcTree& tree, F&& f) {
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    octomap::OcTreeKey k = it.getKey();
    int size = 1 << (16 - it.getDepth());
    int mask = ~(size - 1);
    int x0 = k[0] & mask, y0 = k[1] & mask, z0 = k[2] & mask;
    for (int z = 0; z < size; ++z)
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) f(pack_key(x0 + x, y0 + y, z0 + z), it);
  }
}

// One unknown cell an announced view (expect_view) expected: its ray weight w, the unknown depth d of
// that ray (unknown cells it crossed before this one) and its class (1: void cell).
// The camera and score grid of the view announced by expect_view: after the insert its rays are walked
// again through the updated map, to tell a miss a newly seen surface explains from one it does not.
struct AnnouncedView {
  CameraIntrinsics camera;
  Pose pose = Pose::Identity();
  int score_width = 0, score_height = 0;
};

struct ExpectedCell {
  CellKey key;
  float weight;
  float beam;  // cells its coarse ray stands for at its distance (>= 1)
  std::uint16_t depth;
  std::uint8_t void_cell;
};

// The visibility model's curve learned from what announced views did (view_score.cpp): per class
// (0: unknown cells outside the voids, and frontier cells; 1: void cells) and unknown depth d (capped
// at kDepths - 1), the cells views expected and the ones their insert turned known, and the seen share
// made non-increasing in d (weighted isotonic regression). A ray's weight at depth d is the blend
// (n s + kPrior w_geom) / (n + kPrior) of the learned share s over n cells and the geometric weight
// w_geom (the product of pass probabilities), so a map no announced view taught keeps the geometric model.
struct VisibilityCurve {
  static constexpr int kDepths = 128;
  static constexpr double kPrior = 30.0;  // cells: the geometric weight's worth in a depth bin
  double expected[2][kDepths] = {}, seen[2][kDepths] = {};
  double share[2][kDepths] = {};
  bool taught = false;  // an announced view has been learned from
  // The beam: a coarse ray stands for max(1, t^2 beam) cells at distance t; per class, the cells the
  // announced views' inserts turned known against the beam-weighted count of the coarse-met cells
  // they turned known (the prior: 1 worth kBeamPrior cells).
  static constexpr double kBeamPrior = 200.0;
  double known_total[2] = {}, known_met_beam[2] = {};
  std::uint64_t known_at_announce[2] = {};  // the ray statistics' known cells (outside voids, void) when announced
  double beam_scale(int cls) const { return (known_total[cls] + kBeamPrior) / (known_met_beam[cls] + kBeamPrior); }
  double weight(int cls, int d, double w_geom) const {
    if (d >= kDepths) d = kDepths - 1;
    const double n = expected[cls][d];
    return (n * share[cls][d] + kPrior * w_geom) / (n + kPrior);
  }
};

// Everything an ExplorationMap maintains. `rw` is the map's reader-writer lock: insert holds it
// exclusively, every other public method (and next_best_view for its whole search) shared, through
// MapGuard; the caches below are rebuilt under cache_mutex by readers.
struct ExplorationState {
  explicit ExplorationState(double res) : tree(res) {}
  mutable SharedMutex rw;  // writer first: a stream of queries cannot starve an insert
  MapTree tree;
  StateGrid grid;
  // frontier cell -> cluster label, label -> cells (cells may be stale; filter by the flag)
  std::unordered_map<CellKey, int> frontier_label;
  std::unordered_map<int, std::vector<CellKey>> frontier_members;
  int next_label = 0;
  std::unordered_set<CellKey> void_set;
  Hull hull;
  HullColumns columns;
  RayStatistics rays;  // what rays did to unknown cells, over all inserts
  // The visibility model's memory of views that missed (view_score.cpp, expect_view): per unknown
  // cell, 1 - its seeability s (absent: 0, s = 1). A view announced by expect_view lists the unknown
  // cells it expects with their ray weights w; the next insert multiplies s by (1 - w) for each of
  // them it left unknown and its rays still meet in the updated map (no surface seen in between), unless
  // a line that returned nothing (`blind`) already made the view count it 0. The view score counts an
  // unknown cell with w * s.
  HiddenCells hidden;
  std::vector<ExpectedCell> expected_by_view;
  std::optional<AnnouncedView> announced;  // set with expected_by_view by expect_view
  VisibilityCurve curve;  // learned from the announced views' cells (view_score.cpp)
  // Lines of sight that returned nothing (blind_lines.hpp, learned with `hidden`): a cell counts 0 in a
  // view that looks at it along one of its lines.
  BlindLines blind;
  // Void cells no ray can reach (update_sealed): seeability 0.
  KeyTable<std::uint8_t> sealed;
  // Per occupied cell, the box of the points that hit it (surface_extents.hpp): where rays through it pass.
  SurfaceExtents surface;
  double seeability(CellKey k) const {
    if (sealed.size() && sealed.find(k)) return 0.0;
    return 1.0 - double(hidden.get(k));
  }

  // caches rebuilt on demand after an insert
  mutable std::mutex cache_mutex;
  mutable bool clusters_dirty = true, voids_dirty = true;
  mutable std::vector<std::vector<CellKey>> clusters;
  mutable std::unordered_map<int, int> label_to_cluster;
  mutable std::vector<VoidCluster> void_clusters;
  // What the incremental void clustering keeps between inserts (void_clusters.cpp): the clusters in
  // slots that keep their index while the cluster lives (a free slot has no cells), each slot's seed
  // cell, cell -> slot + 1 (0: none), and the void cells added and removed since the clusters were
  // last brought up to date (written by insert).
  mutable std::vector<VoidCluster> void_slots;
  mutable std::vector<CellKey> void_slot_seed;
  mutable KeyTable<int> void_slot_of;
  mutable std::vector<CellKey> void_added, void_removed;
  // How enclosed each void cell is (void_enclosure.cpp), for enclosure_range; dropped by every insert.
  mutable std::shared_ptr<const KeyTable<std::uint8_t>> enclosure;
  mutable double enclosure_range = -1;
  mutable bool enclosure_exposure = false;  // the table carries the exposed bit (void_enclosure.hpp)
  // Bumped by every write guard (MapGuard): a cache made at one generation is stale at the next.
  mutable std::uint64_t generation = 0;
  // What view scoring reads per cell, flat (score_cells.hpp), made at score_cells_generation.
  mutable std::shared_ptr<const ScoreCells> score_cells;
  mutable std::uint64_t score_cells_generation = 0;
  // The tree's metric bounds (min x y z, max x y z), made at bounds_generation: OctoMap's const getMetricMin and
  // getMetricMax walk every leaf of a tree changed since its last non-const call, and every search asks.
  mutable double tree_bounds[6] = {};
  mutable std::uint64_t bounds_generation = ~std::uint64_t(0);
  // The unknown cells of the search space as an octree (the safe views' obstacles, view_check.cpp), their
  // count and key box, made at unknown_tree_generation.
  mutable std::shared_ptr<octomap::OcTree> unknown_tree;
  mutable std::size_t unknown_tree_cells = 0;
  mutable std::uint32_t unknown_tree_box[6] = {};
  mutable std::uint64_t unknown_tree_generation = ~std::uint64_t(0);

  CellState state(CellKey k) const { return CellState(grid.get(k) & kStateMask); }
  Eigen::Vector3d center(CellKey k) const {
    return {tree.keyToCoord(octomap::key_type(key_x(k))), tree.keyToCoord(octomap::key_type(key_y(k))),
            tree.keyToCoord(octomap::key_type(key_z(k)))};
  }
};

// Holds a map's lock for the scope, shared (read) or exclusive (write). Re-entrant per thread: a
// thread that already holds the lock of this map (a public method calling another, next_best_view
// calling the map's queries) passes without locking again.
class MapGuard {
 public:
  MapGuard(const ExplorationState& s, bool write) {
    auto& h = held();
    if (std::find(h.begin(), h.end(), &s) != h.end()) return;
    if (write) {
      s.rw.lock();
      ++s.generation;
    } else {
      s.rw.lock_shared();
    }
    s_ = &s;
    write_ = write;
    h.push_back(&s);
  }
  ~MapGuard() {
    if (!s_) return;
    auto& h = held();
    h.erase(std::find(h.begin(), h.end(), s_));
    if (write_) {
      ++s_->generation;  // (and after: nothing cached while writing outlives the write)
      s_->rw.unlock();
    } else {
      s_->rw.unlock_shared();
    }
  }
  MapGuard(const MapGuard&) = delete;
  MapGuard& operator=(const MapGuard&) = delete;

 private:
  static std::vector<const ExplorationState*>& held() {
    thread_local std::vector<const ExplorationState*> h;
    return h;
  }
  const ExplorationState* s_ = nullptr;
  bool write_ = false;
};

// The only door from outside the class to its state (declared a friend in exploration.hpp).
struct ExplorationAccess {
  static const ExplorationState& state(const ExplorationMap& m) { return *m.state_; }
  static ExplorationState& state(ExplorationMap& m) { return *m.state_; }
};

/// \brief The state behind `map`, for octoreach's own algorithms (next_best_view).
inline const ExplorationState& state(const ExplorationMap& map) { return ExplorationAccess::state(map); }
/// \brief The same, writable (expect_view); the caller takes the map's write lock.
inline ExplorationState& mutable_state(ExplorationMap& map) { return ExplorationAccess::state(map); }

/// \brief The cached frontier clusters / void clusters (rebuilt when stale); valid while the caller
/// holds the map's lock (ExplorationMap::frontier_clusters / void_clusters return copies).
const std::vector<std::vector<CellKey>>& cached_frontier_clusters(const ExplorationState& s);
const std::vector<VoidCluster>& cached_void_clusters(const ExplorationMap& map);

/// \brief Shared lock of `map` for a whole computation (next_best_view and its helpers).
inline MapGuard read_guard(const ExplorationMap& map) { return MapGuard(state(map), false); }

}  // namespace octoreach::detail
