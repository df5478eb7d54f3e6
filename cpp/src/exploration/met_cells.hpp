#pragma once
// Internal: the cells the rays of one view met (view_score.cpp), each with its largest ray weight.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exploration/cell_sets.hpp"

namespace octoreach::detail {

// The cells (unknown or frontier) the rays of one view met, each with its largest weight and that
// ray's unknown depth: a dense array over the frustum's key box, in bricks of 16^3 cells (thread-local,
// reset through the list of touched cells, so a view costs what its rays walk) or, for a box of more
// than kMaxDense cells, a hash table. With V = uint32_t a value is (1 + w * 65534) << 16 | (65535 -
// depth) (0: not met): the largest is the largest weight, on ties the smallest depth; with V = uint16_t
// (scoring, which needs no depth: half the memory traffic) it is 1 + w * 65534.
template <class V>
class MetCells {
  static constexpr bool kDepth = sizeof(V) == 4;

 public:
  static constexpr std::int64_t kMaxDense = std::int64_t(1) << (kDepth ? 24 : 25);  // 64 MB per thread
  MetCells(const std::int64_t klo[3], const std::int64_t n[3])
      : dense_(bricks(n[0]) * bricks(n[1]) * bricks(n[2]) * kBrick <= kMaxDense) {
    for (int a = 0; a < 3; ++a) klo_[a] = klo[a], n_[a] = n[a], nb_[a] = bricks(n[a]);
    if (dense_) {
      const std::size_t size = std::size_t(nb_[0] * nb_[1] * nb_[2] * kBrick);
      auto& b = buffer();
      if (b.size() < size) b.assign(size, 0);
      dense_cells_ = b.data();  // once: the thread-local lookup costs a call per touch in a shared library
    }
  }
  ~MetCells() {
    if (dense_)
      for (const Touched& t : touched_) dense_cells_[t.index] = 0;
    touched_.clear();
  }
  MetCells(const MetCells&) = delete;
  MetCells& operator=(const MetCells&) = delete;
  // Cell (kx, ky, kz) (its flags f) met with weight w at unknown depth `depth`.
  void touch(int kx, int ky, int kz, std::uint8_t f, double w, int depth) {
    // w * 65534 + 0.5 rounded down: lround for w in [0, 1], without its library call
    const std::uint32_t wq = 1 + std::uint32_t(std::min(std::max(w, 0.0), 1.0) * 65534.0 + 0.5);
    const V q = kDepth ? V((wq << 16) | std::uint32_t(65535 - std::min(depth, 65535))) : V(wq);
    if (!dense_) {
      const CellKey k = pack_key(std::uint32_t(kx), std::uint32_t(ky), std::uint32_t(kz));
      V& v = table_.at(k);
      if (!v) touched_.push_back({0, k, f});
      v = std::max(v, q);
      return;
    }
    const std::int64_t x = kx - klo_[0], y = ky - klo_[1], z = kz - klo_[2];
    if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) return;  // cannot happen
    const std::size_t idx = std::size_t((((z >> 4) * nb_[1] + (y >> 4)) * nb_[0] + (x >> 4)) * kBrick) |
                            std::size_t(((z & 15) << 8) | ((y & 15) << 4) | (x & 15));
    V& v = dense_cells_[idx];
    if (!v) touched_.push_back({idx, pack_key(std::uint32_t(kx), std::uint32_t(ky), std::uint32_t(kz)), f});
    v = std::max(v, q);
  }
  // f(key, flags, weight, depth) once per cell met.
  template <class F>
  void for_each(F&& f) const {
    for (const Touched& t : touched_) {
      const std::uint32_t v = dense_ ? dense_cells_[t.index] : *table_.find(t.key);
      if (kDepth)
        f(t.key, t.flags, double((v >> 16) - 1) / 65534.0, int(65535 - (v & 0xffffu)));
      else
        f(t.key, t.flags, double(v - 1) / 65534.0, 0);
    }
  }

 private:
  static std::vector<V>& buffer() {
    thread_local std::vector<V> b;
    return b;
  }
  // The dense array holds the box in bricks of 16^3 cells (a brick's cells contiguous): the cells a ray meets in
  // a row share a few pages, where a row-major box puts every step along z in another page.
  static constexpr std::int64_t kBrick = 4096;
  static std::int64_t bricks(std::int64_t n) { return (n + 15) >> 4; }
  bool dense_;
  V* dense_cells_ = nullptr;
  std::int64_t klo_[3], n_[3], nb_[3];
  struct Touched {
    std::size_t index;  // in the dense array
    CellKey key;
    std::uint8_t flags;
  };
  static std::vector<Touched>& touched_list() {  // kept per thread: a view's list grows to its size once
    thread_local std::vector<Touched> t;
    return t;
  }
  std::vector<Touched>& touched_ = touched_list();
  KeyTable<V> table_{dense_ ? std::size_t(0) : std::size_t(1) << 16};
};

}  // namespace octoreach::detail
