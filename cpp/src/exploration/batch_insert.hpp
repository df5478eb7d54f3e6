#pragma once
// Internal: batched point-cloud insertion with the same result as OctoMap's insertPointCloud.
//
// The cloud's rays are walked into one bitmap of free cells (grid_ray.hpp), their end cells
// collected as occupied, both sorted in Morton order (the tree's child order), and the tree is
// updated in one descent that shares every common key prefix.
#include <cstdint>
#include <vector>

#include <octomap/OcTree.h>

#include "exploration/exploration_state.hpp"

namespace octoreach::detail {

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

// The cell updates of one cloud: sorted, distinct ((morton << 1) | occupied), occupied winning over
// free as in computeUpdate, and the occupied cells alone (Morton order) for the hull.
struct CloudUpdates {
  std::vector<std::uint64_t> updates;
  std::vector<CellKey> occupied;
};

// Steps 1-2 of an insert: the cells the rays from `origin` (inside the map) to `cloud` free and
// occupy, exactly as OcTree::computeUpdate finds them (max_range <= 0 or inf: unlimited). Counts
// points out of bounds, free and occupied cells in `stats`.
CloudUpdates cloud_updates(const octomap::OcTree& tree, const std::vector<octomap::point3d>& cloud,
                           const octomap::point3d& origin, double max_range, int threads, InsertStats& stats);

// Step 3: applies `updates` to the tree as OccupancyOcTreeBase::updateNode would one key at a time
// and appends every cell whose class changed to `changed` (Morton order).
void apply_updates(MapTree& tree, const std::vector<std::uint64_t>& updates, std::vector<CellChange>& changed);

}  // namespace octoreach::detail
