#pragma once
// Internal: what view scoring reads per cell (its flags, its seeability, its enclosure), in flat form for one
// version of the map. A view's rays read these for every cell they cross and a search scores thousands of
// views on one map: a directory of the cell cache's 16^3 blocks, with the map's own block of seeability values
// and a companion block of the sealed, lines-that-returned-nothing and enclosure entries beside each block that
// has some, replaces a hash lookup per block and per cell. The values are the map tables' own
// (ExplorationState::seeability, its lines, the enclosure table), so a score is the same.
#include <cstdint>
#include <memory>
#include <vector>

#include "exploration/exploration_state.hpp"
#include "exploration/void_enclosure.hpp"

namespace octoreach::detail {

class ScoreCells {
 public:
  static constexpr std::uint8_t kSealed = 0x40;    // mark: the cell is sealed (seeability 0)
  static constexpr std::uint8_t kBlind = 0x20;     // mark: the cell has lines that returned nothing
  static constexpr std::uint8_t kEnclosed = kInTable;  // mark: the enclosure table holds the cell (low bits: its byte)
  static_assert(((kSealed | kBlind) & (kEnclosed | kExposed | kHalvesMask)) == 0 && (kSealed & kBlind) == 0,
                "the mark byte's flags and the enclosure byte must not share bits");
  // The sealed, lines-that-returned-nothing and enclosure entries of one block's cells.
  struct Extra {
    std::uint8_t mark[4096];
  };
  struct Entry {
    const StateGrid::Block* grid = nullptr;
    const Extra* extra = nullptr;
    const HiddenCells::Block* hidden = nullptr;  // the map's own block of 1 - seeability values
  };

  // The cells of S with the entries of `enclosure` (may be null); the caller holds the map's lock.
  ScoreCells(const ExplorationState& S, std::shared_ptr<const EnclosureTable> enclosure);
  const EnclosureTable* enclosure() const { return enclosure_.get(); }
  Entry entry(CellKey block) const;

  // Reads cells with a one-block cache (one per thread and view).
  class Reader {
   public:
    explicit Reader(const ScoreCells& c) : c_(c) {}
    // The cell cache's block of block key b (null: all its cells unknown, no flag).
    const StateGrid::Block* block(CellKey b) const { return c_.entry(b).grid; }
    // ExplorationState::seeability(k), and the cell's mark: the enclosure byte (with kEnclosed; 0: not in the
    // table) and the kSealed and kBlind flags.
    double seeability(CellKey k, std::uint8_t& mark) const {
      const Entry& e = at(k);
      const int i = StateGrid::offset(k);
      mark = e.extra ? e.extra->mark[i] : 0;
      if (mark & kSealed) return 0.0;
      return e.hidden ? 1.0 - double(e.hidden->value[std::size_t(i)]) : 1.0;
    }
    // True when a view from `eye` looks at cell k (marked `mark`) along a line that returned nothing.
    bool blind(CellKey k, std::uint8_t mark, const Eigen::Vector3d& eye) const {
      return (mark & kBlind) && c_.state_->blind.covers(k, c_.state_->center(k), eye);
    }
    // True when cell k has a line of sight that returned nothing (BlindLines::holds).
    bool crossed_empty(CellKey k) const {
      const Entry& e = at(k);
      return e.extra && (e.extra->mark[StateGrid::offset(k)] & kBlind);
    }

   private:
    const Entry& at(CellKey k) const {
      const CellKey b = StateGrid::block_of(k);
      if (b != last_) {
        last_ = b;
        entry_ = c_.entry(b);
      }
      return entry_;
    }
    const ScoreCells& c_;
    mutable CellKey last_ = ~CellKey(0);
    mutable Entry entry_;
  };

 private:
  static constexpr std::size_t kOutside = ~std::size_t(0);
  // The directory index of block key b, or kOutside when b lies outside the directory's box.
  std::size_t slot(CellKey b) const;

  std::shared_ptr<const EnclosureTable> enclosure_;
  const StateGrid* grid_;
  std::uint32_t lo_[3] = {0, 0, 0}, n_[3] = {0, 0, 0};  // directory box (block keys); n 0: no directory
  std::vector<Entry> dir_;
  const HiddenCells* hidden_;
  const ExplorationState* state_;  // the lines that returned nothing (blind), read for marked cells only
  KeyTable<const Extra*> extra_of_;  // block key -> its extra block (outside the directory)
  std::vector<std::unique_ptr<Extra>> extras_;
};

// The ScoreCells of `map` for `enclosure` (null: no enclosure entries), made once per map version and
// shared by every search on it (the caller holds the map's lock).
std::shared_ptr<const ScoreCells> score_cells(const ExplorationState& S, std::shared_ptr<const EnclosureTable> enclosure);

}  // namespace octoreach::detail
