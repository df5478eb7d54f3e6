#include "common/octree_file.hpp"

#include <sys/stat.h>

#include <cmath>
#include <fstream>

#include <octomap/OcTree.h>

#include "common/format.hpp"
#include "octoreach/types.hpp"

namespace octoreach::detail {

std::uint64_t finest_cell_count(const octomap::OcTree& tree, std::uint64_t stop_above) {
  std::uint64_t n = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const unsigned levels = 16 - it.getDepth();  // a leaf covers (2^levels)^3 cells, at most 2^48
    n += std::uint64_t(1) << (3 * levels);
    if (n > stop_above) return n;
  }
  return n;
}

void read_bt(octomap::OcTree& tree, const std::string& path, const std::string& what, std::uint64_t max_cells) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) throw FileNotFound("no " + what + " '" + path + "'");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw FileError("cannot open " + what + " '" + path + "'");
  if (!tree.readBinary(f)) throw FileError("'" + path + "' is not a readable OctoMap binary (.bt) file");
  const double res = tree.getResolution();
  if (!(res >= kMinOctreeResolution && res <= kMaxOctreeResolution))
    throw FileError("'" + path + "' states a resolution of " + format_number(res) + " m, outside [" +
                    format_number(kMinOctreeResolution) + ", " + format_number(kMaxOctreeResolution) + "] (damaged?)");
  if (max_cells > 0) {
    const std::uint64_t n = finest_cell_count(tree, max_cells);
    if (n > max_cells)
      throw FileError("'" + path + "' covers more than " + std::to_string(max_cells) +
                      " cells at its finest resolution (the limit; damaged or too large a map)");
  }
}

}  // namespace octoreach::detail
