#pragma once
// Internal: per-cell values of an exploration map kept in dense blocks of 16^3 cells: the cell cache of the
// tree's classes (StateGrid) and the seeability memory of missed views (HiddenCells).
#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>

#include "octoreach/exploration.hpp"

namespace octoreach::detail {

// Blocks of 16^3 cells (block key: a cell key's coordinates >> 4) in a hash map, made zeroed on first write
// and never moved or freed while the map lives (a pointer to one stays valid as others are made).
template <class B>
class BlockMap {
 public:
  using Block = B;
  static CellKey block_of(CellKey k) { return pack_key(key_x(k) >> 4, key_y(k) >> 4, key_z(k) >> 4); }
  static int offset(CellKey k) {
    return int(key_x(k) & 15) | (int(key_y(k) & 15) << 4) | (int(key_z(k) & 15) << 8);
  }
  Block& block(CellKey block) {
    auto& b = blocks_[block];
    if (!b) b = std::make_unique<Block>();  // value-initialised: zero
    return *b;
  }
  const Block* find_block(CellKey block) const {
    auto it = blocks_.find(block);
    return it == blocks_.end() ? nullptr : it->second.get();
  }
  // f(block key, block) for every block, in no particular order.
  template <class F>
  void for_each_block(F&& f) const {
    for (const auto& [k, b] : blocks_) f(k, *b);
  }

 private:
  std::unordered_map<CellKey, std::unique_ptr<Block>> blocks_;
};

// A finest-resolution cache of the tree's cell classes, written from the exact list of changed cells, so
// neighbour queries avoid tree descents.
class StateGrid : public BlockMap<std::array<std::uint8_t, 4096>> {
 public:
  std::uint8_t get(CellKey k) const {
    const Block* b = find_block(block_of(k));
    return b ? (*b)[offset(k)] : 0;
  }
  std::uint8_t& at(CellKey k) { return block(block_of(k))[offset(k)]; }
};

struct HiddenBlock {
  std::array<float, 4096> value;
  std::array<std::uint8_t, 4096> held;  // 1: the cell has an entry (its value may still be 0)
};

// A float per cell in blocks laid out as the cell cache's (ExplorationState::hidden): a view score reads a
// block's values in place (ScoreCells), so nothing proportional to the cells held is copied per map version.
class HiddenCells : public BlockMap<HiddenBlock> {
 public:
  // The value of k, 0 when k has none.
  float get(CellKey k) const {
    const Block* b = find_block(block_of(k));
    return b ? b->value[std::size_t(offset(k))] : 0.0f;
  }
  // The value of k, made 0 when k is new.
  float& at(CellKey k) {
    Block& b = block(block_of(k));
    const std::size_t i = std::size_t(offset(k));
    if (!b.held[i]) b.held[i] = 1, ++size_;
    return b.value[i];
  }
  std::size_t size() const { return size_; }  // cells with an entry

 private:
  std::size_t size_ = 0;
};

}  // namespace octoreach::detail
