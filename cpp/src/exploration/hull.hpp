#pragma once
// Internal: the cells whose centre the convex hull of the occupied cells contains (the hull: common/convex_hull.hpp).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/convex_hull.hpp"
#include "octoreach/exploration.hpp"

namespace octomap {
class OcTree;
}

namespace octoreach::detail {

// Per (x, y) column of cells, the key interval [lo, hi] of cells whose centre is inside the hull
// (lo > hi: empty).
struct HullColumns {
  int x0 = 0, y0 = 0, nx = 0, ny = 0;
  std::vector<std::int32_t> lo, hi;
  bool column(int x, int y, int& l, int& h) const {
    if (x < x0 || y < y0 || x >= x0 + nx || y >= y0 + ny) return false;
    std::size_t i = std::size_t(y - y0) * nx + (x - x0);
    l = lo[i];
    h = hi[i];
    return l <= h;
  }
};

// Cells of the box [lo, hi] (the bounding box of the hull's points) clipped to the search space, at
// `resolution`: an upper bound of the cells hull_columns visits and of the voids inside the hull (0 when
// the box misses the search space).
double hull_box_cells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double resolution,
                      const Eigen::Vector3d& search_lo, const Eigen::Vector3d& search_hi);

// Column intervals of the cells of `tree`'s grid whose centres are inside `hull` and inside the
// search space [search_lo, search_hi].
HullColumns hull_columns(const octomap::OcTree& tree, const Hull& hull, int threads, const Eigen::Vector3d& search_lo,
                         const Eigen::Vector3d& search_hi);

// The columns of the void cells: hull_columns, or with options.voids_fill_search_space the whole search space
// (every column of its box, from its floor to its top).
HullColumns void_columns(const octomap::OcTree& tree, const Hull& hull, int threads, const ExplorationOptions& options);

}  // namespace octoreach::detail
