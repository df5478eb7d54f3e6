// Batched point-cloud insertion: ray ends, the ray walk into a bitmap, Morton sort, one tree descent.
#include "exploration/batch_insert.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/thread_pool.hpp"
#include "exploration/grid_ray.hpp"

namespace octoreach::detail {

namespace {

// LSD radix sort of values below 2^bits.
void radix_sort(std::vector<std::uint64_t>& v, int bits) {
  if (v.size() < 4096) {
    std::sort(v.begin(), v.end());
    return;
  }
  constexpr int kDigit = 13;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigit;
  std::vector<std::uint64_t> tmp(v.size());
  std::vector<std::size_t> count(kBuckets);
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0);
    for (std::uint64_t x : v) ++count[(x >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (auto& c : count) {
      std::size_t t = c;
      c = sum;
      sum += t;
    }
    for (std::uint64_t x : v) tmp[count[(x >> shift) & (kBuckets - 1)]++] = x;
    v.swap(tmp);
  }
}

inline CellState classify(const octomap::OcTree& tree, const octomap::OcTreeNode* n) {
  return tree.isNodeOccupied(n) ? CellState::Occupied : CellState::Free;
}

// Applies the sorted, distinct updates [b, e) ((morton << 1) | occupied) below `node` exactly as
// OccupancyOcTreeBase::updateNode would one key at a time (non-lazy: children are pruned or
// their parent's occupancy refreshed on the way up), but descends each shared prefix once.
struct BatchUpdater {
  MapTree& tree;
  float hit, miss, clamp_min, clamp_max;
  std::vector<CellChange>& changed;

  void run(octomap::OcTreeNode* node, bool just_created, const std::uint64_t* b, const std::uint64_t* e,
           int depth) {
    if (depth == 16) {
      bool occ = (*b & 1) != 0;
      CellState before = just_created ? CellState::Unknown : classify(tree, node);
      tree.updateNodeLogOdds(node, occ ? hit : miss);
      CellState after = classify(tree, node);
      if (before != after) changed.push_back({key_from_morton(*b >> 1), before, after});
      return;
    }
    if (!just_created && !tree.nodeHasChildren(node)) {
      // A pruned leaf: updateNode skips keys whose update cannot change it (early abort).
      float lo = node->getLogOdds();
      bool all_noop = true;
      for (const std::uint64_t* p = b; p != e && all_noop; ++p)
        all_noop = (*p & 1) ? lo >= clamp_max : lo <= clamp_min;
      if (all_noop) return;
    }
    const int shift = 3 * (15 - depth) + 1;  // +1: the occupied flag
    const std::uint64_t* it = b;
    while (it != e) {
      std::uint64_t prefix = *it >> shift;
      unsigned pos = unsigned(prefix & 7);
      std::uint64_t bound = (prefix + 1) << shift;
      const std::uint64_t* jt = std::lower_bound(it + 1, e, bound);
      bool created = false;
      if (!tree.nodeChildExists(node, pos)) {
        if (!tree.nodeHasChildren(node) && !just_created) {
          tree.expandNode(node);
        } else {
          tree.createNodeChild(node, pos);
          created = true;
        }
      }
      run(tree.getNodeChild(node, pos), created, it, jt, depth + 1);
      it = jt;
    }
    if (!tree.pruneNode(node)) node->updateOccupancyChildren();
  }
};

// Bitmap over a box of keys (one per thread, OR-ed at the end), one bit per cell, x fastest,
// so a step of a ray along an axis is a constant step of the bit index.
class KeyBitmap {
 public:
  KeyBitmap(const int lo[3], const int hi[3]) {
    for (int i = 0; i < 3; ++i) {
      lo_[i] = lo[i];
      n_[i] = std::size_t(hi[i] - lo[i] + 1);
    }
    words_.assign((n_[0] * n_[1] * n_[2] + 63) / 64, 0);
  }
  std::size_t index(const octomap::OcTreeKey& k) const {
    return (std::size_t(k[2] - lo_[2]) * n_[1] + std::size_t(k[1] - lo_[1])) * n_[0] + std::size_t(k[0] - lo_[0]);
  }
  void set(const octomap::OcTreeKey& k) { set(index(k)); }
  void set(std::size_t i) { words_[i >> 6] |= std::uint64_t(1) << (i & 63); }
  void clear(const octomap::OcTreeKey& k) {
    std::size_t i = index(k);
    words_[i >> 6] &= ~(std::uint64_t(1) << (i & 63));
  }
  std::vector<std::uint64_t>& words() { return words_; }
  std::uint64_t* data() { return words_.data(); }
  std::size_t size(int i) const { return n_[i]; }
  // Appends (morton << 1) of every set bit.
  void extract(std::vector<std::uint64_t>& out) const {
    const std::size_t nxy = n_[0] * n_[1];
    for (std::size_t w = 0; w < words_.size(); ++w) {
      std::uint64_t bits = words_[w];
      while (bits) {
        std::size_t i = w * 64 + unsigned(__builtin_ctzll(bits));
        bits &= bits - 1;
        std::size_t z = i / nxy, r = i % nxy, y = r / n_[0], x = r % n_[0];
        out.push_back(morton(std::uint32_t(x + lo_[0]), std::uint32_t(y + lo_[1]), std::uint32_t(z + lo_[2])) << 1);
      }
    }
  }

 private:
  int lo_[3];
  std::size_t n_[3];
  std::vector<std::uint64_t> words_;
};

// Ray end points (exactly as computeUpdate forms them), what each ray is, and the key box they
// span (with the origin).
struct RaySet {
  std::vector<octomap::point3d> ends;
  std::vector<std::uint8_t> kind;  // 0 out of bounds, 1 hit, 2 max-range ray (free only)
  int lo[3], hi[3];
};

RaySet ray_ends(const octomap::OcTree& tree, const std::vector<octomap::point3d>& pc, const octomap::point3d& o,
                const octomap::OcTreeKey& okey, double max_range, int threads) {
  const bool unlimited = !(max_range > 0) || std::isinf(max_range);
  const std::size_t n = pc.size();
  RaySet r;
  r.ends.resize(n);
  r.kind.resize(n);
  std::vector<std::array<int, 6>> boxes(threads, {okey[0], okey[1], okey[2], okey[0], okey[1], okey[2]});
  parallel_for(n, threads, [&](std::size_t i, int tid) {
    const octomap::point3d& p = pc[i];
    if (unlimited || (p - o).norm() <= max_range) {
      r.ends[i] = p;
      r.kind[i] = 1;
    } else {
      octomap::point3d direction = (p - o).normalized();
      r.ends[i] = o + direction * float(max_range);
      r.kind[i] = 2;
    }
    octomap::OcTreeKey k;
    if (!tree.coordToKeyChecked(r.ends[i], k)) {
      r.kind[i] = 0;
      return;
    }
    auto& b = boxes[tid];
    for (int j = 0; j < 3; ++j) {
      b[j] = std::min(b[j], int(k[j]));
      b[3 + j] = std::max(b[3 + j], int(k[j]));
    }
  }, 1024);
  for (int j = 0; j < 3; ++j) r.lo[j] = r.hi[j] = okey[j];
  for (const auto& b : boxes)
    for (int j = 0; j < 3; ++j) {
      r.lo[j] = std::min(r.lo[j], b[j]);
      r.hi[j] = std::max(r.hi[j], b[3 + j]);
    }
  return r;
}

// Free cells of all rays in one bitmap (one per thread, OR-ed into the first), occupied end cells
// as sorted, distinct updates.
KeyBitmap walk_rays(const octomap::OcTree& tree, const RaySet& rays, const octomap::point3d& o,
                    const octomap::OcTreeKey& okey, const int lo[3], const int hi[3], int threads,
                    std::vector<std::uint64_t>& occupied) {
  const std::size_t n = rays.ends.size();
  std::vector<KeyBitmap> free_local;
  free_local.reserve(threads);
  for (int t = 0; t < threads; ++t) free_local.emplace_back(lo, hi);
  std::vector<std::vector<std::uint64_t>> occ_local(threads);
  // rays in pairs: two walks share the SSE registers (see walk_pair)
  parallel_for((n + 1) / 2, threads, [&](std::size_t pair, int tid) {
    RayWalk w[2];
    int m = 0;
    for (std::size_t i = 2 * pair; i < std::min(n, 2 * pair + 2); ++i) {
      if (rays.kind[i] == 0) continue;
      octomap::OcTreeKey kend = tree.coordToKey(rays.ends[i]);
      if (w[m].init(tree, o, okey, rays.ends[i], kend, free_local[tid])) ++m;
      if (rays.kind[i] == 1) occ_local[tid].push_back((morton(kend[0], kend[1], kend[2]) << 1) | 1);
    }
    if (m == 2)
      walk_pair(w[0], w[1], free_local[tid].data());
    else if (m == 1)
      w[0].run(free_local[tid].data());
  }, 128);
  auto& w0 = free_local[0].words();
  parallel_for(w0.size(), threads, [&](std::size_t w, int) {
    for (int t = 1; t < threads; ++t) w0[w] |= free_local[t].words()[w];
  }, 4096);
  occupied.clear();
  for (auto& v : occ_local) occupied.insert(occupied.end(), v.begin(), v.end());
  radix_sort(occupied, 50);
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());
  return std::move(free_local[0]);
}

}  // namespace

CloudUpdates cloud_updates(const octomap::OcTree& tree, const std::vector<octomap::point3d>& pc,
                           const octomap::point3d& o, double max_range, int threads, InsertStats& st) {
  const octomap::OcTreeKey okey = tree.coordToKey(o);
  RaySet rays = ray_ends(tree, pc, o, okey, max_range, threads);
  for (std::uint8_t k : rays.kind) st.out_of_bounds += k == 0;
  // a walk may step one cell past its end cell by rounding: pad the bitmap's box
  int lo[3], hi[3];
  for (int j = 0; j < 3; ++j) {
    lo[j] = std::max(rays.lo[j] - 2, 0);
    hi[j] = std::min(rays.hi[j] + 2, 0xffff);
  }
  double cells = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
  if (cells > 8.0e9)
    throw std::invalid_argument("the cloud spans " + std::to_string(cells) +
                                " cells; pass a max_range or a coarser resolution");
  CloudUpdates out;
  KeyBitmap free_bits = walk_rays(tree, rays, o, okey, lo, hi, threads, out.updates);
  // occupied wins over free (computeUpdate makes the sets disjoint the same way)
  out.occupied.reserve(out.updates.size());
  for (std::uint64_t u : out.updates) {
    out.occupied.push_back(key_from_morton(u >> 1));
    free_bits.clear(to_octo(out.occupied.back()));
  }
  st.occupied_cells = out.updates.size();
  free_bits.extract(out.updates);
  st.free_cells = out.updates.size() - st.occupied_cells;
  radix_sort(out.updates, 50);
  return out;
}

void apply_updates(MapTree& tree, const std::vector<std::uint64_t>& updates, std::vector<CellChange>& changed) {
  // no update, no root: a root without children would be one occupied leaf covering the whole key range
  if (updates.empty()) return;
  bool created_root = tree.root_node() == nullptr;
  octomap::OcTreeNode* root = tree.make_root();
  BatchUpdater up{tree,
                  tree.getProbHitLog(),
                  tree.getProbMissLog(),
                  tree.getClampingThresMinLog(),
                  tree.getClampingThresMaxLog(),
                  changed};
  up.run(root, created_root, updates.data(), updates.data() + updates.size(), 0);
}

}  // namespace octoreach::detail
