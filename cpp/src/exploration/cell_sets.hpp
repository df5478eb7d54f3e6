#pragma once
// Internal: sets of cells. Neighbourhoods, union-find, the one open-addressing key table and
// 26-connected components.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "octoreach/exploration.hpp"

namespace octoreach::detail {

// Neighbour of k by (dx, dy, dz); false when it would leave the key range.
inline bool neighbour(CellKey k, int dx, int dy, int dz, CellKey& out) {
  int x = int(key_x(k)) + dx, y = int(key_y(k)) + dy, z = int(key_z(k)) + dz;
  if (x < 0 || y < 0 || z < 0 || x > 0xffff || y > 0xffff || z > 0xffff) return false;
  out = pack_key(x, y, z);
  return true;
}

constexpr int kN6[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// The 26 neighbour offsets in (dz, dy, dx) order; the 13 after (0, 0, 0) visit each pair once.
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

// Union-find with path halving; the smaller index becomes the root.
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

// Open-addressing table CellKey -> V (power-of-two capacity, multiplicative hash, linear probing,
// at most half full): lookups of a few hundred thousand cells millions of times.
template <class V>
class KeyTable {
 public:
  static constexpr CellKey kEmpty = ~CellKey(0);
  // Room for `expected` keys without growing.
  explicit KeyTable(std::size_t expected = 0) {
    int b = 4;
    while ((std::size_t(1) << b) < 2 * expected + 16) ++b;
    rehash(b);
  }
  // The value of k, default-constructed when k is new.
  V& at(CellKey k) {
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = slot(k);; i = (i + 1) & mask) {
      if (keys_[i] == k) return vals_[i];
      if (keys_[i] == kEmpty) {
        if (2 * (used_ + 1) > keys_.size()) {
          rehash(bits_ + 1);
          return at(k);
        }
        keys_[i] = k;
        ++used_;
        return vals_[i];
      }
    }
  }
  // The value of k, or nullptr when k is not in the table.
  const V* find(CellKey k) const {
    for (std::size_t i = slot(k);; i = (i + 1) & (keys_.size() - 1)) {
      if (keys_[i] == k) return &vals_[i];
      if (keys_[i] == kEmpty) return nullptr;
    }
  }
  V* find(CellKey k) { return const_cast<V*>(static_cast<const KeyTable&>(*this).find(k)); }
  std::size_t size() const { return used_; }
  // f(key, value) for every entry, in slot order.
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kEmpty) f(keys_[i], vals_[i]);
  }

 private:
  std::size_t slot(CellKey k) const { return std::size_t((k * 0x9E3779B97F4A7C15ULL) >> (64 - bits_)); }
  void rehash(int b) {
    std::vector<CellKey> old_keys = std::move(keys_);
    std::vector<V> old_vals = std::move(vals_);
    bits_ = b;
    keys_.assign(std::size_t(1) << b, kEmpty);
    vals_.assign(std::size_t(1) << b, V());
    used_ = 0;
    for (std::size_t i = 0; i < old_keys.size(); ++i)
      if (old_keys[i] != kEmpty) at(old_keys[i]) = old_vals[i];
  }
  int bits_ = 0;
  std::size_t used_ = 0;
  std::vector<CellKey> keys_;
  std::vector<V> vals_;
};

// Connected components (26-neighbourhood) of `cells`, each sorted, ordered by first cell.
std::vector<std::vector<CellKey>> components26(std::vector<CellKey> cells);

}  // namespace octoreach::detail
