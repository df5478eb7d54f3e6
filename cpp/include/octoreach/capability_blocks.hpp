#pragma once
/// \file capability_blocks.hpp
/// \brief A capability-map build cut into blocks of voxels that can be built anywhere and merged.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "octoreach/capability_map.hpp"

namespace octoreach {

/// \brief The block build of a capability map (CapabilityMapOptions::block_size = n > 0).
///
/// The workspace box of the plain build is cut into cubes of n x n x n voxels. One forward-kinematics
/// sampling over the whole box (the plain build's, the same samples) gives the cells their seeds; then
/// each block runs the IK stages on its own cells only: seeded IK, a flood fill that stays inside the
/// block, the retry pass. A block's result is a function of its seeds alone, so blocks built on any
/// machine, in any order, any number of times, merge into the same map; CapabilityMap::build with the
/// same options runs exactly these three steps in one process, so its file has the same bytes.
///
/// The steps pass byte strings (seeds, block results) that a task system can move between machines;
/// each carries a fingerprint of the plan (robot model, options, reference posture, box) and is refused
/// by a plan it does not belong to. Every machine must run the same octoreach build.
class CapabilityBlocks {
 public:
  /// Plans the build of `chain` (block_size 0 in the options becomes `default_block_size`).
  CapabilityBlocks(const Chain& chain, const CapabilityMapOptions& options);
  /// Plans the build of a robot's arm with the arm's approach axis (as CapabilityMap::build).
  CapabilityBlocks(const Robot& robot, const Arm& arm, const CapabilityMapOptions& options);

  static constexpr int default_block_size = 16;

  /// Number of blocks (some may hold no seed: their result is empty).
  std::size_t count() const;
  /// Voxels per block edge.
  int block_size() const;
  /// The options of the map this plan builds (block_size set).
  const CapabilityMapOptions& options() const;
  /// Fingerprint of the plan that seeds and results carry.
  std::uint64_t fingerprint() const;

  /// Step 1: the forward-kinematics sampling of the whole box, one seed list per block (in block order).
  std::vector<std::string> sample(const ProgressCallback& progress = nullptr) const;
  /// Number of seeds in a seed list of sample() (how much work its block is).
  static std::size_t seed_count(const std::string& seeds);
  /// Step 2: block `block` from its seed list: its reachable cells (and solutions, if kept).
  std::string build_block(std::size_t block, const std::string& seeds, const ProgressCallback& progress = nullptr) const;
  /// Step 3: the map from the results of every block, in block order.
  CapabilityMap merge(const std::vector<std::string>& results) const;
  /// The three steps in this process (what CapabilityMap::build does for block_size > 0).
  CapabilityMap build(const ProgressCallback& progress = nullptr) const;

  struct Plan;

 private:
  std::shared_ptr<const Plan> plan_;
};

}  // namespace octoreach
