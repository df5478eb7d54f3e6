#pragma once
// Private: a dense numbering of the capability cells (record, orientation) a surface-map build reads,
// so the per-cell data of the arm checks (low sets, arm boxes, link poses) sit in flat arrays and a
// lookup is one array read instead of a hash-map probe.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "octoreach/capability_map.hpp"

namespace octoreach::detail {

/// The cells of the records whose voxel centre height (arm frame) lies in [za_lo, za_hi] widened by one
/// capability voxel, for the orientations marked in `wanted` (size: the orientation count), that hold a
/// stored solution; numbered record by record in the capability map's voxel order (deterministic).
class CellSlots {
 public:
  static constexpr std::int32_t kNone = -1;
  struct Cell {
    std::uint32_t rec;
    int orient;
  };
  CellSlots(const CapabilityMap& cap, const std::vector<char>& wanted, double za_lo = -1e9, double za_hi = 1e9);
  /// The slot of (rec, orient), or kNone when the cell is not covered (other band, orientation, no solution).
  std::int32_t slot(std::uint32_t rec, int orient) const {
    if (rec >= local_.size()) return kNone;
    const std::int32_t r = local_[rec];
    return r < 0 ? kNone : table_[static_cast<std::size_t>(r) * orientations_ + orient];
  }
  /// Index into records() of record `rec`, or -1 when the record is not covered.
  std::int32_t local(std::uint32_t rec) const { return rec < local_.size() ? local_[rec] : -1; }
  std::size_t size() const { return cells_.size(); }
  const Cell& cell(std::size_t slot) const { return cells_[slot]; }
  /// Records covered, each with its voxel centre and its slots [first, last).
  struct Record {
    std::uint32_t rec;
    Eigen::Vector3d centre;
    std::uint32_t first, last;
  };
  const std::vector<Record>& records() const { return records_; }

 private:
  int orientations_;
  std::vector<std::int32_t> local_;  // record -> index into records_, or -1
  std::vector<std::int32_t> table_;  // (local record, orientation) -> slot
  std::vector<Cell> cells_;
  std::vector<Record> records_;
};

}  // namespace octoreach::detail
