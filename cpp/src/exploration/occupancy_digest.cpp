// occupancy_digest: the order-independent digest of any OctoMap occupancy tree. A file of its own because
// the benchmark references compile it too (they compare a stock OctoMap tree with ExplorationMap's without
// linking the library).
#include <cstring>

#include "common/random_mix.hpp"
#include "exploration/exploration_state.hpp"
#include "octoreach/exploration.hpp"

namespace octoreach {

OccupancyDigest occupancy_digest(const octomap::OcTree& tree) {
  OccupancyDigest d;
  detail::for_each_leaf_cell(tree, [&](CellKey c, const auto& it) {
    bool occ = tree.isNodeOccupied(*it);
    float lo = it->getLogOdds();
    std::uint32_t lo_bits;
    std::memcpy(&lo_bits, &lo, 4);
    d.hash += detail::mix64(c ^ (std::uint64_t(lo_bits) << 48) ^ (std::uint64_t(occ) << 47), 0);
    (occ ? d.occupied : d.free)++;
  });
  return d;
}

}  // namespace octoreach
