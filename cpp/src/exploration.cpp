// ExplorationMap: batched OctoMap integration, incremental frontiers and voids, void clustering.
#include "octoreach/exploration.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include <Eigen/Eigenvalues>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "exploration_impl.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {
namespace detail {
const N26 kN26;
}

using detail::kFrontierFlag;
using detail::kStateMask;
using detail::kVoidFlag;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Morton interleave of three 16-bit key components: bit 3l+0 = x_l, 3l+1 = y_l, 3l+2 = z_l,
// so the 3-bit group of level l is OctoMap's child index at that level.
inline std::uint64_t spread3(std::uint64_t v) {
  v &= 0xffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
inline std::uint64_t compact3(std::uint64_t v) {
  v &= 0x1249249249249249ULL;
  v = (v ^ (v >> 2)) & 0x10c30c30c30c30c3ULL;
  v = (v ^ (v >> 4)) & 0x100f00f00f00f00fULL;
  v = (v ^ (v >> 8)) & 0x1f0000ff0000ffULL;
  v = (v ^ (v >> 16)) & 0x1f00000000ffffULL;
  v = (v ^ (v >> 32)) & 0x1fffffULL;
  return v;
}
inline std::uint64_t morton(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return spread3(x) | (spread3(y) << 1) | (spread3(z) << 2);
}
inline CellKey key_from_morton(std::uint64_t m) {
  return pack_key(std::uint32_t(compact3(m)), std::uint32_t(compact3(m >> 1)), std::uint32_t(compact3(m >> 2)));
}
inline CellKey to_cell(const octomap::OcTreeKey& k) { return pack_key(k[0], k[1], k[2]); }
// Calls f(cell) for every finest-resolution cell an octree leaf covers: a pruned leaf of depth d covers
// 8^(16 - d) cells starting at its key rounded down to the leaf size.
template <class LeafIterator, class F>
void for_each_covered_cell(const LeafIterator& it, F&& f) {
  octomap::OcTreeKey k = it.getKey();
  int size = 1 << (16 - it.getDepth());
  int mask = ~(size - 1);
  int x0 = k[0] & mask, y0 = k[1] & mask, z0 = k[2] & mask;
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) f(pack_key(x0 + x, y0 + y, z0 + z));
}
inline octomap::OcTreeKey to_octo(CellKey k) {
  return octomap::OcTreeKey(octomap::key_type(key_x(k)), octomap::key_type(key_y(k)), octomap::key_type(key_z(k)));
}

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
  detail::MapTree& tree;
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

// The cells OcTreeBaseImpl::computeRayKeys(origin, end) returns, written straight into a bitmap
// instead of a KeyRay. The set-up (RayWalk::init) is computeRayKeys' code; the walk does the
// same double arithmetic in the same order (t_max[dim] += t_delta[dim], the same comparisons and
// tie-breaks), so it yields the same cells. It is written without data-dependent branches: the
// axis is picked with SSE masks, and the cell is kept as its bit index in the bitmap (a step
// along an axis adds a constant) and compared with the end cell's index. Both keys are known to
// be inside the map and the bitmap's box is padded, so a walk that overshoots the end cell by
// rounding stays inside. Two rays are walked side by side in the two lanes of the SSE registers,
// which hides the latency of each step's compare-select-add chain.
struct RayWalk {
  double t[3], d[3], len;
  std::size_t idx, target;
  std::size_t inc[4];  // by the chosen axis: [m0 | m1 << 1] -> 0: z, 1: x, 2: y
  // false when there is nothing to walk (origin and end in one cell)
  bool init(const octomap::OcTree& tree, const octomap::point3d& origin, const octomap::OcTreeKey& key_origin,
            const octomap::point3d& end, const octomap::OcTreeKey& key_end, KeyBitmap& bits) {
    if (key_origin == key_end) return false;
    bits.set(key_origin);
    octomap::point3d direction = (end - origin);
    float length = (float)direction.norm();
    direction /= length;
    int step[3];
    const double res = tree.getResolution();
    for (unsigned i = 0; i < 3; ++i) {
      if (direction(i) > 0.0)
        step[i] = 1;
      else if (direction(i) < 0.0)
        step[i] = -1;
      else
        step[i] = 0;
      if (step[i] != 0) {
        double border = tree.keyToCoord(key_origin[i]);
        border += (float)(step[i] * res * 0.5);
        t[i] = (border - origin(i)) / direction(i);
        d[i] = res / std::fabs(direction(i));
      } else {
        t[i] = std::numeric_limits<double>::max();
        d[i] = std::numeric_limits<double>::max();
      }
    }
    len = length;
    idx = bits.index(key_origin);
    target = bits.index(key_end);
    const std::int64_t nx = std::int64_t(bits.size(0)), nxy = nx * std::int64_t(bits.size(1));
    inc[0] = std::size_t(std::int64_t(step[2]) * nxy);
    inc[1] = std::size_t(std::int64_t(step[0]));
    inc[2] = std::size_t(std::int64_t(step[1]) * nx);
    inc[3] = 0;
    return true;
  }
  // One step; false when the walk ends (the cell is then not free space of this ray).
  bool step(std::uint64_t* words) {
    const bool lt01 = t[0] < t[1];
    const bool c0 = lt01 & (t[0] < t[2]);
    const bool c1 = !lt01 & (t[1] < t[2]);
    idx += inc[unsigned(c0) | (unsigned(c1) << 1)];
    t[0] += c0 ? d[0] : 0.0;
    t[1] += c1 ? d[1] : 0.0;
    t[2] += (c0 | c1) ? 0.0 : d[2];
    if (idx == target) return false;
    if (std::min(std::min(t[0], t[1]), t[2]) > len) return false;
    words[idx >> 6] |= std::uint64_t(1) << (idx & 63);
    return true;
  }
  void run(std::uint64_t* words) {
#if defined(__SSE2__)
    __m128d t0 = _mm_set_sd(t[0]), t1 = _mm_set_sd(t[1]), t2 = _mm_set_sd(t[2]);
    const __m128d d0 = _mm_set_sd(d[0]), d1 = _mm_set_sd(d[1]), d2 = _mm_set_sd(d[2]);
    for (;;) {
      // computeRayKeys: t0 < t1 ? (t0 < t2 ? 0 : 2) : (t1 < t2 ? 1 : 2); adding (mask & d) adds
      // d or +0.0, and t + 0.0 == t
      const __m128d lt01 = _mm_cmplt_sd(t0, t1);
      const __m128d m0 = _mm_and_pd(lt01, _mm_cmplt_sd(t0, t2));
      const __m128d m1 = _mm_andnot_pd(lt01, _mm_cmplt_sd(t1, t2));
      idx += inc[_mm_movemask_pd(_mm_unpacklo_pd(m0, m1))];
      t0 = _mm_add_sd(t0, _mm_and_pd(m0, d0));
      t1 = _mm_add_sd(t1, _mm_and_pd(m1, d1));
      t2 = _mm_add_sd(t2, _mm_andnot_pd(_mm_or_pd(m0, m1), d2));
      if (idx == target) return;
      if (_mm_cvtsd_f64(_mm_min_sd(_mm_min_sd(t0, t1), t2)) > len) return;
      words[idx >> 6] |= std::uint64_t(1) << (idx & 63);
    }
#else
    while (step(words)) {
    }
#endif
  }
};

// Walks two rays side by side (lane 0: a, lane 1: b) until one ends, then finishes the other.
void walk_pair(RayWalk& a, RayWalk& b, std::uint64_t* words) {
#if defined(__SSE2__)
  __m128d t0 = _mm_set_pd(b.t[0], a.t[0]), t1 = _mm_set_pd(b.t[1], a.t[1]), t2 = _mm_set_pd(b.t[2], a.t[2]);
  const __m128d d0 = _mm_set_pd(b.d[0], a.d[0]), d1 = _mm_set_pd(b.d[1], a.d[1]), d2 = _mm_set_pd(b.d[2], a.d[2]);
  const __m128d len = _mm_set_pd(b.len, a.len);
  bool a_on = true, b_on = true;
  for (;;) {
    const __m128d lt01 = _mm_cmplt_pd(t0, t1);
    const __m128d m0 = _mm_and_pd(lt01, _mm_cmplt_pd(t0, t2));
    const __m128d m1 = _mm_andnot_pd(lt01, _mm_cmplt_pd(t1, t2));
    a.idx += a.inc[_mm_movemask_pd(_mm_unpacklo_pd(m0, m1))];
    b.idx += b.inc[_mm_movemask_pd(_mm_unpackhi_pd(m0, m1))];
    t0 = _mm_add_pd(t0, _mm_and_pd(m0, d0));
    t1 = _mm_add_pd(t1, _mm_and_pd(m1, d1));
    t2 = _mm_add_pd(t2, _mm_andnot_pd(_mm_or_pd(m0, m1), d2));
    const int past = _mm_movemask_pd(_mm_cmpgt_pd(_mm_min_pd(_mm_min_pd(t0, t1), t2), len));
    a_on = a.idx != a.target && !(past & 1);
    b_on = b.idx != b.target && !(past & 2);
    if (!(a_on & b_on)) break;
    words[a.idx >> 6] |= std::uint64_t(1) << (a.idx & 63);
    words[b.idx >> 6] |= std::uint64_t(1) << (b.idx & 63);
  }
  alignas(16) double v[2];
  _mm_store_pd(v, t0);
  a.t[0] = v[0];
  b.t[0] = v[1];
  _mm_store_pd(v, t1);
  a.t[1] = v[0];
  b.t[1] = v[1];
  _mm_store_pd(v, t2);
  a.t[2] = v[0];
  b.t[2] = v[1];
  // the lane still walking: this step's cell is free, then it goes on alone
  RayWalk* rest = a_on ? &a : b_on ? &b : nullptr;
  if (rest) {
    words[rest->idx >> 6] |= std::uint64_t(1) << (rest->idx & 63);
    rest->run(words);
  }
#else
  a.run(words);
  b.run(words);
#endif
}

std::string fmt_vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

// Convex hull with libqhull_r: facet planes (outward unit normal n, offset d; inside n.x + d <= 0)
// and vertices. Returns false when the points are degenerate (fewer than 4, coplanar ...).
bool convex_hull(const std::vector<Eigen::Vector3d>& pts, std::vector<Eigen::Vector4d>& planes,
                 std::vector<Eigen::Vector3d>& vertices) {
  if (pts.size() < 4) return false;
  std::vector<coordT> coords(pts.size() * 3);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int j = 0; j < 3; ++j) coords[3 * i + j] = pts[i][j];
  qhT qh_qh;
  qhT* qh = &qh_qh;
  FILE* devnull = std::fopen("/dev/null", "w");
  qh_zero(qh, devnull);
  char flags[] = "qhull Qt";
  int exitcode = qh_new_qhull(qh, 3, int(pts.size()), coords.data(), False, flags, nullptr, devnull);
  bool ok = exitcode == 0;
  if (ok) {
    planes.clear();
    vertices.clear();
    facetT* facet;
    FORALLfacets {
      planes.emplace_back(facet->normal[0], facet->normal[1], facet->normal[2], facet->offset);
    }
    vertexT* vertex;
    FORALLvertices {
      vertices.emplace_back(vertex->point[0], vertex->point[1], vertex->point[2]);
    }
    std::sort(vertices.begin(), vertices.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    std::sort(planes.begin(), planes.end(), [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
      return std::lexicographical_compare(a.data(), a.data() + 4, b.data(), b.data() + 4);
    });
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (devnull) std::fclose(devnull);
  return ok && planes.size() >= 4;
}

// Union-find with path halving.
struct UnionFind {
  std::vector<int> p;
  explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0); }
  int find(int a) {
    while (p[a] != a) a = p[a] = p[p[a]];
    return a;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
};

// Open-addressing index CellKey -> position (power-of-two capacity, multiplicative hash).
class KeyIndex {
 public:
  explicit KeyIndex(std::size_t n) {
    bits_ = 4;
    while ((std::size_t(1) << bits_) < 2 * n + 16) ++bits_;
    keys_.assign(std::size_t(1) << bits_, kEmpty);
    vals_.resize(keys_.size());
  }
  void insert(CellKey k, int v) {
    std::size_t i = slot(k);
    while (keys_[i] != kEmpty && keys_[i] != k) i = (i + 1) & (keys_.size() - 1);
    keys_[i] = k;
    vals_[i] = v;
  }
  int find(CellKey k) const {
    for (std::size_t i = slot(k);; i = (i + 1) & (keys_.size() - 1)) {
      if (keys_[i] == k) return vals_[i];
      if (keys_[i] == kEmpty) return -1;
    }
  }

 private:
  static constexpr CellKey kEmpty = ~CellKey(0);
  std::size_t slot(CellKey k) const { return std::size_t((k * 0x9E3779B97F4A7C15ULL) >> (64 - bits_)); }
  int bits_;
  std::vector<CellKey> keys_;
  std::vector<int> vals_;
};

// Connected components (26-neighbourhood) of `cells`, each sorted, ordered by first cell.
std::vector<std::vector<CellKey>> components26(std::vector<CellKey> cells) {
  std::sort(cells.begin(), cells.end());
  KeyIndex pos(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) pos.insert(cells[i], int(i));
  UnionFind uf(cells.size());
  // each neighbouring pair once: the 13 offsets after (0, 0, 0) in (dz, dy, dx) order
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (int o = 13; o < 26; ++o) {
      const auto& d = detail::kN26.d[o];
      CellKey n;
      if (!detail::neighbour(cells[i], d[0], d[1], d[2], n)) continue;
      int j = pos.find(n);
      if (j >= 0) uf.unite(int(i), j);
    }
  std::vector<int> root_to_comp(cells.size(), -1);
  std::vector<std::vector<CellKey>> out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    int r = uf.find(int(i));
    if (root_to_comp[r] < 0) {
      root_to_comp[r] = int(out.size());
      out.emplace_back();
    }
    out[root_to_comp[r]].push_back(cells[i]);
  }
  return out;  // cells were sorted, so each component is sorted and components are ordered by first cell
}

}  // namespace

// ---------------------------------------------------------------------------------------------

ExplorationMap::ExplorationMap(const ExplorationOptions& options) : options_(options) {
  if (!(options.resolution > 0) || !std::isfinite(options.resolution))
    throw std::invalid_argument("resolution must be a positive number of metres, got " +
                                std::to_string(options.resolution));
  if (!(options.void_fit_threshold >= 0))
    throw std::invalid_argument("void_fit_threshold must be >= 0, got " + std::to_string(options.void_fit_threshold));
  resolution_ = options.resolution;
  impl_ = std::make_unique<Impl>(resolution_);
}

ExplorationMap::~ExplorationMap() = default;

const octomap::OcTree& ExplorationMap::octree() const { return impl_->tree; }

CellKey ExplorationMap::key_of(const Eigen::Vector3d& p) const {
  octomap::OcTreeKey k;
  if (!p.allFinite() || !impl_->tree.coordToKeyChecked(octomap::point3d(float(p.x()), float(p.y()), float(p.z())), k))
    throw std::invalid_argument("point " + fmt_vec(p) + " is outside the map bounds");
  return to_cell(k);
}

Eigen::Vector3d ExplorationMap::center(CellKey k) const {
  const auto& t = impl_->tree;
  return {t.keyToCoord(octomap::key_type(key_x(k))), t.keyToCoord(octomap::key_type(key_y(k))),
          t.keyToCoord(octomap::key_type(key_z(k)))};
}

CellState ExplorationMap::state(CellKey key) const { return impl_->state(key); }
CellState ExplorationMap::state(const Eigen::Vector3d& p) const {
  octomap::OcTreeKey k;
  if (!p.allFinite() || !impl_->tree.coordToKeyChecked(octomap::point3d(float(p.x()), float(p.y()), float(p.z())), k))
    return CellState::Unknown;
  return impl_->state(to_cell(k));
}
bool ExplorationMap::is_frontier(CellKey key) const { return (impl_->grid.get(key) & kFrontierFlag) != 0; }
bool ExplorationMap::is_void(CellKey key) const { return (impl_->grid.get(key) & kVoidFlag) != 0; }

namespace {
bool frontier_test(const detail::GridReader& g, CellKey k) {
  if ((g.get(k) & kStateMask) != std::uint8_t(CellState::Free)) return false;
  for (const auto& d : detail::kN6) {
    CellKey n;
    if (detail::neighbour(k, d[0], d[1], d[2], n) && (g.get(n) & kStateMask) == std::uint8_t(CellState::Unknown))
      return true;
  }
  return false;
}

// Column intervals of the cells whose centres are inside the hull (planes: n.x + d <= 0).
detail::HullColumns hull_columns(const octomap::OcTree& tree, const std::vector<Eigen::Vector4d>& planes,
                                 const std::vector<Eigen::Vector3d>& vertices, int threads,
                                 const Eigen::Vector3d& s_lo, const Eigen::Vector3d& s_hi) {
  detail::HullColumns c;
  if (planes.empty() || vertices.empty()) return c;
  Eigen::Vector3d lo = vertices[0], hi = vertices[0];
  for (const auto& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // only the search space: cells whose centre lies in [s_lo, s_hi]
  const double res = tree.getResolution();
  lo = lo.cwiseMax(s_lo);
  hi = hi.cwiseMin(s_hi);
  if ((lo.array() > hi.array()).any()) return c;
  const double zcap_lo = std::ceil(s_lo.z() / res + 32767.5), zcap_hi = std::floor(s_hi.z() / res + 32767.5);
  octomap::OcTreeKey klo, khi;
  if (!tree.coordToKeyChecked(octomap::point3d(float(lo.x()), float(lo.y()), float(lo.z())), klo) ||
      !tree.coordToKeyChecked(octomap::point3d(float(hi.x()), float(hi.y()), float(hi.z())), khi))
    return c;
  c.x0 = klo[0] - 1;
  c.y0 = klo[1] - 1;
  c.nx = khi[0] - klo[0] + 3;
  c.ny = khi[1] - klo[1] + 3;
  c.lo.assign(std::size_t(c.nx) * c.ny, 1);
  c.hi.assign(std::size_t(c.nx) * c.ny, 0);
  const double eps = 1e-7 * res;
  const double half = 32768.0 - 0.5;  // key k has centre (k - half) * res (OctoMap: tree_max_val 32768)
  detail::parallel_for(std::size_t(c.ny), threads, [&](std::size_t yi, int) {
    double y = (double(c.y0 + int(yi)) - half) * res;
    if (y < s_lo.y() || y > s_hi.y()) return;
    for (int xi = 0; xi < c.nx; ++xi) {
      double x = (double(c.x0 + xi) - half) * res;
      if (x < s_lo.x() || x > s_hi.x()) continue;
      double zlo = -std::numeric_limits<double>::infinity(), zhi = std::numeric_limits<double>::infinity();
      bool empty = false;
      for (const auto& p : planes) {
        double a = p[2], b = -(p[3] + p[0] * x + p[1] * y);
        if (std::abs(a) < 1e-12) {
          if (b < -eps) {
            empty = true;
            break;
          }
        } else if (a > 0) {
          zhi = std::min(zhi, (b + eps) / a);
        } else {
          zlo = std::max(zlo, (b + eps) / a);
        }
        if (zlo > zhi) {
          empty = true;
          break;
        }
      }
      std::size_t i = yi * c.nx + xi;
      if (empty) continue;
      double klo_f = std::ceil(zlo / res + half), khi_f = std::floor(zhi / res + half);
      klo_f = std::max({klo_f, 0.0, zcap_lo});
      khi_f = std::min({khi_f, 65535.0, zcap_hi});
      if (klo_f > khi_f) continue;
      c.lo[i] = std::int32_t(klo_f);
      c.hi[i] = std::int32_t(khi_f);
    }
  }, 4);
  return c;
}
}  // namespace

InsertStats ExplorationMap::insert(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                   double max_range) {
  auto t_start = Clock::now();
  InsertStats st;
  if (!origin.allFinite()) throw std::invalid_argument("sensor_origin must be finite, got " + fmt_vec(origin));
  if (std::isnan(max_range)) throw std::invalid_argument("max_range must be a number (<= 0 or inf: unlimited), got nan");
  auto& tree = impl_->tree;
  const octomap::point3d o(float(origin.x()), float(origin.y()), float(origin.z()));
  octomap::OcTreeKey okey;
  if (!tree.coordToKeyChecked(o, okey))
    throw std::invalid_argument("sensor_origin " + fmt_vec(origin) + " is outside the map bounds (|coordinate| < " +
                                std::to_string(resolution_ * 32768) + " m)");
  changed_.clear();
  std::vector<octomap::point3d> pc;
  pc.reserve(points.size());
  for (const auto& p : points) {
    if (p.allFinite())
      pc.emplace_back(float(p.x()), float(p.y()), float(p.z()));
    else
      ++st.dropped;
  }
  st.points = pc.size();
  if (pc.empty()) {
    st.seconds_total = seconds_since(t_start);
    return st;
  }
  const bool unlimited = !(max_range > 0) || std::isinf(max_range);
  const int threads = detail::default_threads(options_.threads);

  // 1. Ray end points (exactly as computeUpdate forms them) and the key box they span.
  auto t0 = Clock::now();
  const std::size_t n = pc.size();
  std::vector<octomap::point3d> ends(n);
  std::vector<std::uint8_t> kind(n);  // 0 out of bounds, 1 hit, 2 max-range ray (free only)
  std::vector<std::array<int, 6>> boxes(threads, {okey[0], okey[1], okey[2], okey[0], okey[1], okey[2]});
  detail::parallel_for(n, threads, [&](std::size_t i, int tid) {
    const octomap::point3d& p = pc[i];
    if (unlimited || (p - o).norm() <= max_range) {
      ends[i] = p;
      kind[i] = 1;
    } else {
      octomap::point3d direction = (p - o).normalized();
      ends[i] = o + direction * float(max_range);
      kind[i] = 2;
    }
    octomap::OcTreeKey k;
    if (!tree.coordToKeyChecked(ends[i], k)) {
      kind[i] = 0;
      return;
    }
    auto& b = boxes[tid];
    for (int j = 0; j < 3; ++j) {
      b[j] = std::min(b[j], int(k[j]));
      b[3 + j] = std::max(b[3 + j], int(k[j]));
    }
  }, 1024);
  int lo[3] = {okey[0], okey[1], okey[2]}, hi[3] = {okey[0], okey[1], okey[2]};
  for (const auto& b : boxes)
    for (int j = 0; j < 3; ++j) {
      lo[j] = std::min(lo[j], b[j]);
      hi[j] = std::max(hi[j], b[3 + j]);
    }
  for (std::size_t i = 0; i < n; ++i) st.out_of_bounds += kind[i] == 0;
  // a walk may step one cell past its end cell by rounding: pad the bitmap's box
  for (int j = 0; j < 3; ++j) {
    lo[j] = std::max(lo[j] - 2, 0);
    hi[j] = std::min(hi[j] + 2, 0xffff);
  }
  double cells = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
  if (cells > 8.0e9)
    throw std::invalid_argument("the cloud spans " + std::to_string(cells) +
                                " cells; pass a max_range or a coarser resolution");

  // 2. Free cells of all rays in one bitmap per thread, occupied end cells per thread.
  std::vector<KeyBitmap> free_local;
  free_local.reserve(threads);
  for (int t = 0; t < threads; ++t) free_local.emplace_back(lo, hi);
  std::vector<std::vector<std::uint64_t>> occ_local(threads);
  // rays in pairs: two walks share the SSE registers (see walk_pair)
  detail::parallel_for((n + 1) / 2, threads, [&](std::size_t pair, int tid) {
    RayWalk w[2];
    int m = 0;
    for (std::size_t i = 2 * pair; i < std::min(n, 2 * pair + 2); ++i) {
      if (kind[i] == 0) continue;
      octomap::OcTreeKey kend = tree.coordToKey(ends[i]);
      if (w[m].init(tree, o, okey, ends[i], kend, free_local[tid])) ++m;
      if (kind[i] == 1) occ_local[tid].push_back((morton(kend[0], kend[1], kend[2]) << 1) | 1);
    }
    if (m == 2)
      walk_pair(w[0], w[1], free_local[tid].data());
    else if (m == 1)
      w[0].run(free_local[tid].data());
  }, 128);
  KeyBitmap& free_bits = free_local[0];
  {
    auto& w0 = free_bits.words();
    detail::parallel_for(w0.size(), threads, [&](std::size_t w, int) {
      for (int t = 1; t < threads; ++t) w0[w] |= free_local[t].words()[w];
    }, 4096);
  }
  std::vector<std::uint64_t> updates;
  for (auto& v : occ_local) updates.insert(updates.end(), v.begin(), v.end());
  occ_local.clear();
  radix_sort(updates, 50);
  updates.erase(std::unique(updates.begin(), updates.end()), updates.end());
  // occupied wins over free (computeUpdate makes the sets disjoint the same way)
  for (std::uint64_t u : updates) free_bits.clear(to_octo(key_from_morton(u >> 1)));
  st.occupied_cells = updates.size();
  std::vector<std::uint64_t> occ_codes = updates;  // kept for the hull
  free_bits.extract(updates);
  st.free_cells = updates.size() - st.occupied_cells;
  radix_sort(updates, 50);
  st.seconds_rays = seconds_since(t0);

  // 3. One batched descent of the tree.
  t0 = Clock::now();
  bool created_root = tree.root_node() == nullptr;
  octomap::OcTreeNode* root = tree.make_root();
  BatchUpdater up{tree,
                  tree.getProbHitLog(),
                  tree.getProbMissLog(),
                  tree.getClampingThresMinLog(),
                  tree.getClampingThresMaxLog(),
                  changed_};
  up.run(root, created_root, updates.data(), updates.data() + updates.size(), 0);
  detail::GridWriter gw3(impl_->grid);
  for (const auto& c : changed_) {
    std::uint8_t& cell = gw3.at(c.key);
    cell = std::uint8_t((cell & ~kStateMask) | std::uint8_t(c.after));
  }
  st.changed_cells = changed_.size();
  st.seconds_tree = seconds_since(t0);

  // 4. Frontiers: only changed cells and the 6-neighbours of cells that stopped being unknown
  //    can change status (a neighbour can only lose one: it has one unknown neighbour fewer).
  t0 = Clock::now();
  {
    auto& I = *impl_;
    std::vector<std::uint8_t> own(changed_.size());
    std::vector<detail::GridReader> readers(threads, detail::GridReader(I.grid));
    detail::parallel_for(changed_.size(), threads, [&](std::size_t i, int tid) {
      own[i] = frontier_test(readers[tid], changed_[i].key);
    }, 512);
    std::vector<CellKey> added;
    std::vector<std::pair<CellKey, int>> removed;
    detail::GridWriter gw(I.grid);  // every cell touched here already has its block
    auto remove = [&](CellKey k) {
      std::uint8_t& f = gw.at(k);
      f = std::uint8_t(f & ~kFrontierFlag);
      auto it = I.frontier_label.find(k);
      if (it != I.frontier_label.end()) {
        removed.emplace_back(k, it->second);
        I.frontier_label.erase(it);
      }
    };
    detail::GridReader g(I.grid);
    for (std::size_t i = 0; i < changed_.size(); ++i) {
      CellKey k = changed_[i].key;
      std::uint8_t& fk = gw.at(k);
      bool was = (fk & kFrontierFlag) != 0;
      if (own[i] && !was) {
        fk |= kFrontierFlag;
        added.push_back(k);
      } else if (!own[i] && was) {
        remove(k);
      }
      if (changed_[i].before != CellState::Unknown) continue;
      for (const auto& d : detail::kN6) {
        CellKey nb;
        if (!detail::neighbour(k, d[0], d[1], d[2], nb)) continue;
        if ((g.get(nb) & kFrontierFlag) && !frontier_test(g, nb)) remove(nb);
      }
    }
    st.frontier_added = added.size();
    st.frontier_removed = removed.size();
    // Recluster only the clusters touched: those that lost a cell or border a new cell.
    std::unordered_set<int> affected;
    for (const auto& r : removed) affected.insert(r.second);
    for (CellKey a : added)
      for (const auto& d : detail::kN26.d) {
        CellKey nb;
        if (!detail::neighbour(a, d[0], d[1], d[2], nb)) continue;
        auto it = I.frontier_label.find(nb);
        if (it != I.frontier_label.end()) affected.insert(it->second);
      }
    std::vector<CellKey> pool = added;
    std::vector<int> affected_sorted(affected.begin(), affected.end());
    std::sort(affected_sorted.begin(), affected_sorted.end());
    for (int label : affected_sorted) {
      auto it = I.frontier_members.find(label);
      if (it == I.frontier_members.end()) continue;
      for (CellKey k : it->second)
        if (I.grid.get(k) & kFrontierFlag) pool.push_back(k);
      I.frontier_members.erase(it);
    }
    for (auto& comp : components26(std::move(pool))) {
      int label = I.next_label++;
      for (CellKey k : comp) I.frontier_label[k] = label;
      I.frontier_members.emplace(label, std::move(comp));
    }
    std::lock_guard<std::mutex> lock(I.cache_mutex);
    I.clusters_dirty = true;
  }
  st.seconds_frontiers = seconds_since(t0);

  // 5. Hull from the previous hull's vertices plus the new occupied cells; void cells updated
  //    from the changed cells and from the hull's growth, column by column.
  if (options_.track_voids) {
    auto& I = *impl_;
    t0 = Clock::now();
    std::vector<Eigen::Vector3d> hull_in = I.hull_vertices;
    hull_in.reserve(hull_in.size() + occ_codes.size());
    for (std::uint64_t u : occ_codes) hull_in.push_back(center(key_from_morton(u >> 1)));
    std::vector<Eigen::Vector4d> planes;
    std::vector<Eigen::Vector3d> verts;
    bool have_hull = convex_hull(hull_in, planes, verts);
    st.seconds_hull = seconds_since(t0);
    t0 = Clock::now();
    detail::GridWriter gw(I.grid);
    // cells that became known are no longer voids
    for (const auto& c : changed_)
      if (c.before == CellState::Unknown && (gw.get(c.key) & kVoidFlag)) {
        gw.at(c.key) &= std::uint8_t(~kVoidFlag);
        I.void_set.erase(c.key);
        ++st.void_removed;
      }
    if (have_hull) {
      detail::HullColumns nc = hull_columns(tree, planes, verts, threads, options_.search_lo, options_.search_hi);
      const detail::HullColumns& oc = I.columns;
      // visit the union of both column boxes
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
            if ((f & kStateMask) == 0 && !(f & kVoidFlag)) {
              gw.at(k) |= kVoidFlag;
              I.void_set.insert(k);
              ++st.void_added;
            }
          }
          for (int z = ol; z <= oh; ++z) {  // cells that left the hull (numerical merging only)
            if (z >= nl && z <= nh) continue;
            CellKey k = pack_key(x, y, z);
            if (gw.get(k) & kVoidFlag) {
              gw.at(k) &= std::uint8_t(~kVoidFlag);
              I.void_set.erase(k);
              ++st.void_removed;
            }
          }
        }
      I.columns = std::move(nc);
      I.hull_planes = std::move(planes);
      I.hull_vertices = std::move(verts);
    }
    std::lock_guard<std::mutex> lock(I.cache_mutex);
    I.voids_dirty = true;
    st.seconds_voids = seconds_since(t0);
  }
  st.seconds_total = seconds_since(t_start);
  return st;
}

double ExplorationMap::insert_stock(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                    double max_range) {
  if (!origin.allFinite()) throw std::invalid_argument("sensor_origin must be finite, got " + fmt_vec(origin));
  octomap::Pointcloud pc;
  pc.reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) pc.push_back(float(p.x()), float(p.y()), float(p.z()));
  auto t0 = Clock::now();
  impl_->tree.insertPointCloud(pc, octomap::point3d(float(origin.x()), float(origin.y()), float(origin.z())),
                               max_range > 0 ? max_range : -1.0);
  return seconds_since(t0);
}

std::vector<CellKey> ExplorationMap::frontier_cells() const {
  std::vector<CellKey> out;
  out.reserve(impl_->frontier_label.size());
  for (const auto& kv : impl_->frontier_label) out.push_back(kv.first);
  std::sort(out.begin(), out.end());
  return out;
}

const std::vector<std::vector<CellKey>>& ExplorationMap::frontier_clusters() const {
  auto& I = *impl_;
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

std::vector<CellKey> ExplorationMap::void_cells() const {
  std::vector<CellKey> out(impl_->void_set.begin(), impl_->void_set.end());
  std::sort(out.begin(), out.end());
  return out;
}
std::size_t ExplorationMap::void_cell_count() const { return impl_->void_set.size(); }

std::vector<Eigen::Vector3d> ExplorationMap::hull_vertices() const { return impl_->hull_vertices; }
std::vector<Eigen::Vector4d> ExplorationMap::hull_planes() const { return impl_->hull_planes; }
bool ExplorationMap::inside_hull(const Eigen::Vector3d& p) const {
  if (impl_->hull_planes.empty()) return false;
  for (const auto& pl : impl_->hull_planes)
    if (pl.head<3>().dot(p) + pl[3] > 1e-7 * resolution_) return false;
  return true;
}

// Ellipsoid region growing (eq. 2, see VoidCluster) from seeded random start cells.
const std::vector<VoidCluster>& ExplorationMap::void_clusters() const {
  auto& I = *impl_;
  std::lock_guard<std::mutex> lock(I.cache_mutex);
  if (!I.voids_dirty) return I.void_clusters;
  I.void_clusters.clear();
  std::vector<CellKey> cells(I.void_set.begin(), I.void_set.end());
  std::sort(cells.begin(), cells.end());
  const std::size_t n = cells.size();
  std::unordered_map<CellKey, int> index;
  index.reserve(n * 2);
  for (std::size_t i = 0; i < n; ++i) index.emplace(cells[i], int(i));
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(options_.seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> assigned(n, -1), tried(n, -1);
  const double thr = options_.void_fit_threshold;
  const double res = resolution_;
  auto score_of = [](double cnt, const Eigen::Vector3d& s1, const Eigen::Matrix3d& s2) {
    Eigen::Vector3d mu = s1 / cnt;
    Eigen::Matrix3d cov = s2 / cnt - mu * mu.transpose();
    cov.diagonal().array() += 1.0 / 12.0;  // each cell is a unit cube, not a point
    double det = std::max(cov.determinant(), 1e-12);
    return cnt / (4.0 / 3.0 * M_PI * std::sqrt(125.0 * det));
  };
  std::vector<int> queue;
  for (int s : order) {
    if (assigned[s] >= 0) continue;
    int cid = int(I.void_clusters.size());
    const int sx = int(key_x(cells[s])), sy = int(key_y(cells[s])), sz = int(key_z(cells[s]));
    auto rel = [&](CellKey k) {
      return Eigen::Vector3d(int(key_x(k)) - sx, int(key_y(k)) - sy, int(key_z(k)) - sz);
    };
    double cnt = 1;
    Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
    Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero();
    assigned[s] = cid;
    queue.assign(1, s);
    std::vector<int> members{s};
    double score = score_of(cnt, s1, s2);
    for (std::size_t qi = 0; qi < queue.size(); ++qi) {
      CellKey k = cells[queue[qi]];
      for (const auto& d : detail::kN26.d) {
        CellKey nb;
        if (!detail::neighbour(k, d[0], d[1], d[2], nb)) continue;
        auto it = index.find(nb);
        if (it == index.end()) continue;
        int j = it->second;
        if (assigned[j] >= 0 || tried[j] == cid) continue;
        Eigen::Vector3d p = rel(nb);
        double sc = score_of(cnt + 1, s1 + p, s2 + p * p.transpose());
        if (sc >= thr) {
          cnt += 1;
          s1 += p;
          s2 += p * p.transpose();
          score = sc;
          assigned[j] = cid;
          queue.push_back(j);
          members.push_back(j);
        } else {
          tried[j] = cid;
        }
      }
    }
    VoidCluster vc;
    Eigen::Vector3d mu = s1 / cnt;
    Eigen::Matrix3d cov = s2 / cnt - mu * mu.transpose();
    cov.diagonal().array() += 1.0 / 12.0;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    for (int j = 0; j < 3; ++j) {
      vc.eigenvalues[j] = std::max(es.eigenvalues()[2 - j], 0.0) * res * res;
      vc.axes.col(j) = es.eigenvectors().col(2 - j);
    }
    if (vc.axes.determinant() < 0) vc.axes.col(2) *= -1;
    vc.semi_axes = (5.0 * vc.eigenvalues.array()).sqrt();
    vc.centroid = center(pack_key(sx, sy, sz)) + mu * res;
    vc.score = score;
    for (int m : members) vc.cells.push_back(cells[m]);
    std::sort(vc.cells.begin(), vc.cells.end());
    I.void_clusters.push_back(std::move(vc));
  }
  I.voids_dirty = false;
  return I.void_clusters;
}

std::vector<FrontierVoid> ExplorationMap::frontier_voids() const {
  const auto& fcs = frontier_clusters();
  const auto& vcs = void_clusters();
  (void)fcs;
  auto& I = *impl_;
  std::vector<FrontierVoid> out;
  detail::GridReader g(I.grid);
  for (std::size_t v = 0; v < vcs.size(); ++v) {
    FrontierVoid fv;
    fv.void_index = int(v);
    for (CellKey k : vcs[v].cells)
      for (const auto& d : detail::kN26.d) {
        CellKey nb;
        if (!detail::neighbour(k, d[0], d[1], d[2], nb)) continue;
        if (!(g.get(nb) & kFrontierFlag)) continue;
        fv.frontier_cells.push_back(nb);
        auto it = I.frontier_label.find(nb);
        if (it != I.frontier_label.end()) {
          auto jt = I.label_to_cluster.find(it->second);
          if (jt != I.label_to_cluster.end()) fv.frontier_clusters.push_back(jt->second);
        }
      }
    if (fv.frontier_cells.empty()) continue;
    std::sort(fv.frontier_cells.begin(), fv.frontier_cells.end());
    fv.frontier_cells.erase(std::unique(fv.frontier_cells.begin(), fv.frontier_cells.end()), fv.frontier_cells.end());
    std::sort(fv.frontier_clusters.begin(), fv.frontier_clusters.end());
    fv.frontier_clusters.erase(std::unique(fv.frontier_clusters.begin(), fv.frontier_clusters.end()),
                               fv.frontier_clusters.end());
    fv.utility = vcs[v].volume(resolution_);
    out.push_back(std::move(fv));
  }
  return out;
}

ExplorationSnapshot ExplorationMap::snapshot() const {
  ExplorationSnapshot s;
  s.frontier_cells = frontier_cells();
  s.frontier_clusters = frontier_clusters();
  s.void_cells = void_cells();
  return s;
}

ExplorationSnapshot ExplorationMap::recompute_from_scratch() const {
  ExplorationSnapshot s;
  auto& I = *impl_;
  // Every known leaf of the tree, expanded to the finest resolution, classified by the tree itself.
  std::unordered_map<CellKey, std::uint8_t> cls;
  const auto& tree = I.tree;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    std::uint8_t c = std::uint8_t(tree.isNodeOccupied(*it) ? CellState::Occupied : CellState::Free);
    for_each_covered_cell(it, [&](CellKey cell) { cls[cell] = c; });
  }
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
  s.frontier_clusters = components26(s.frontier_cells);
  if (!I.hull_planes.empty()) {
    detail::HullColumns c = hull_columns(tree, I.hull_planes, I.hull_vertices, options_.threads, options_.search_lo, options_.search_hi);
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
  std::size_t known = 0, unknown = 0;
  detail::GridReader g(impl_->grid);
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
  std::string tmp = path + ".tmp";
  if (!impl_->tree.writeBinaryConst(tmp)) {
    std::remove(tmp.c_str());
    throw FileError("cannot write OctoMap file '" + path + "'");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw FileError("cannot move '" + tmp + "' to '" + path + "'");
  }
}

std::unique_ptr<ExplorationMap> ExplorationMap::from_file(const std::string& path, const ExplorationOptions& options) {
  {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw FileError("cannot open OctoMap file '" + path + "'");
  }
  auto m = std::make_unique<ExplorationMap>(options);
  auto& I = *m->impl_;
  if (!I.tree.readBinary(path)) throw FileError("'" + path + "' is not a readable OctoMap binary (.bt) file");
  m->resolution_ = I.tree.getResolution();
  m->options_.resolution = m->resolution_;
  std::vector<Eigen::Vector3d> occupied;
  for (auto it = I.tree.begin_leafs(), end = I.tree.end_leafs(); it != end; ++it) {
    bool occ = I.tree.isNodeOccupied(*it);
    for_each_covered_cell(it, [&](CellKey c) {
      I.grid.at(c) = std::uint8_t(occ ? CellState::Occupied : CellState::Free);
      if (occ) occupied.push_back(m->center(c));
    });
  }
  ExplorationSnapshot s = m->recompute_from_scratch();  // frontiers only: no hull yet
  for (CellKey k : s.frontier_cells) I.grid.at(k) |= kFrontierFlag;
  for (auto& comp : s.frontier_clusters) {
    int label = I.next_label++;
    for (CellKey k : comp) I.frontier_label[k] = label;
    I.frontier_members.emplace(label, std::move(comp));
  }
  if (options.track_voids && convex_hull(occupied, I.hull_planes, I.hull_vertices)) {
    I.columns = hull_columns(I.tree, I.hull_planes, I.hull_vertices, options.threads, options.search_lo, options.search_hi);
    ExplorationSnapshot v = m->recompute_from_scratch();
    for (CellKey k : v.void_cells) {
      I.grid.at(k) |= kVoidFlag;
      I.void_set.insert(k);
    }
  }
  return m;
}

}  // namespace octoreach
