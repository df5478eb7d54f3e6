#pragma once
// Internal: how enclosed each void cell is (the ranking weight of NbvOptions::enclosure_power).
#include <cstdint>
#include <memory>

#include "exploration/cell_sets.hpp"
#include "octoreach/exploration.hpp"

namespace octoreach::detail {

struct ExplorationState;
class GridReader;

// Per void cell, how many of the six axis directions are closed, in halves (0..12): from the cell, a
// direction walks up to `range` through unknown cells; it is closed (2) when it meets an occupied cell,
// open (0) when it meets a free cell, and half (1) when it stays in unknown space to the range. A cell
// inside a box whose walls have been seen counts 10-12, a shadow behind one object 2-5. Bit kExposed is set
// when one of the cell's 26 neighbours is observed free (the face of a void that observed space shows).
using EnclosureTable = KeyTable<std::uint8_t>;
constexpr std::uint8_t kExposed = 16;
constexpr std::uint8_t kHalvesMask = 15;
constexpr std::uint8_t kInTable = 128;  // a byte above the table's values: "the table holds the cell" (ScoreCells)

// True when one of k's 26 neighbours is observed free: k lies on the face of a void that observed space
// shows (the exposure of NbvOptions::unexposed_weight; public as exposed_cells).
bool has_free_neighbour(const GridReader& g, CellKey k);

// The void weights of one search: enclosure^power per void cell, times unexposed_weight for a cell with no
// observed free neighbour (cells not in the table: 1).
class VoidWeights {
 public:
  VoidWeights() = default;
  VoidWeights(std::shared_ptr<const EnclosureTable> table, double power, double unexposed_weight);
  // The weight of void cell k (1 without a table).
  double of(CellKey k) const {
    if (!table_) return 1.0;
    const std::uint8_t* h = table_->find(k);
    return h ? weight_[*h & (kExposed | kHalvesMask)] : 1.0;
  }
  // The same from the cell's table byte with kInTable set (without kInTable: not in the table).
  double of_mark(std::uint8_t mark) const { return (mark & kInTable) ? weight_[mark & (kExposed | kHalvesMask)] : 1.0; }
  explicit operator bool() const { return bool(table_); }
  const std::shared_ptr<const EnclosureTable>& table() const { return table_; }

 private:
  std::shared_ptr<const EnclosureTable> table_;
  double weight_[32] = {};
};

// The enclosure of the map's void cells for `range` (m), with the exposed bit when `exposure` (else the
// bit may or may not be set): cached until the next insert (the caller holds the map's lock, shared or
// exclusive).
std::shared_ptr<const EnclosureTable> cached_void_enclosure(const ExplorationState& s, double resolution,
                                                            double range, bool exposure = false);

// The weights of a search with `power`, `range` and `unexposed_weight` (power 0 and unexposed_weight 1: none,
// every void cell weighs 1).
VoidWeights void_weights(const ExplorationState& s, double resolution, double power, double range,
                         double unexposed_weight);

}  // namespace octoreach::detail
