#pragma once
// Private: the cells of one voxel record of a capability map as a build produces them, and as map files
// (format 2) and the block build's results carry them: reachable bits, mixed bits and, with solutions, one
// joint solution and one CellQuality per reachable bit and one configuration per mixed bit, in bit order.
#include <cstdint>
#include <vector>

#include "octoreach/capability_map.hpp"
#include "maps/map_io.hpp"

namespace octoreach::detail {

struct VoxelCellData {
  std::vector<std::uint64_t> bits, mixed;  // words each
  std::vector<float> solutions;            // dof per reachable bit
  std::vector<CellQuality> quality;        // per reachable bit
  std::vector<float> mixed_solutions;      // dof per mixed bit

  /// Empties the record for `words` words per bit set.
  void clear(int words);
  bool empty() const;
  std::size_t reachable_count() const;
  std::size_t mixed_count() const;
  /// Writes the bits, the mixed bits and (with_solutions) the solutions, the quality and the mixed configurations;
  /// cell_data false: a format-1 record (the bits and the solutions), for a map loaded from such a file.
  void write(ByteWriter& w, bool with_solutions, bool cell_data = true) const;
  /// Reads what write() wrote (cell_data false: a format-1 record, reachable bits and solutions only), checking
  /// that the record holds a cell, fits `orientations` and that nothing ends early.
  void read(ByteReader& r, int words, int orientations, int dof, bool with_solutions, bool cell_data);
};

}  // namespace octoreach::detail
