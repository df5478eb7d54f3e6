#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "octoreach/capability_blocks.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {

std::string file_bytes(const CapabilityMap& m, const std::string& name) {
  const std::string path = ::testing::TempDir() + "octoreach_blocks_" + name;
  m.save(path, true);
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

}  // namespace

// Blocks built in any order, each from its own seeds, merge into the bytes of the one-process block build.
TEST(CapabilityBlocks, MergeOfBlocksInAnyOrderIsTheBlockBuild) {
  auto robot = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  const Chain chain = robot->chain("base_link", "tool0");
  CapabilityMapOptions o;
  o.resolution = 0.15;
  o.directions = 16;
  o.seed = 5;
  o.block_size = 3;
  const CapabilityMap whole = CapabilityMap::build(chain, o);
  const CapabilityBlocks plan(chain, o);
  ASSERT_GT(plan.count(), 8u);
  const std::vector<std::string> seeds = plan.sample();
  std::vector<std::string> results(plan.count());
  for (std::size_t b = plan.count(); b-- > 0;) results[b] = plan.build_block(b, seeds[b]);
  const CapabilityMap merged = plan.merge(results);
  EXPECT_GT(whole.voxel_count(), 0u);
  EXPECT_EQ(file_bytes(merged, "merged"), file_bytes(whole, "whole"));
  // a block built again gives the same bytes; a block's seeds are refused by another block
  const std::size_t busy = static_cast<std::size_t>(
      std::max_element(seeds.begin(), seeds.end(), [](const std::string& a, const std::string& b) {
        return CapabilityBlocks::seed_count(a) < CapabilityBlocks::seed_count(b);
      }) - seeds.begin());
  EXPECT_EQ(plan.build_block(busy, seeds[busy]), results[busy]);
  EXPECT_THROW(plan.build_block((busy + 1) % plan.count(), seeds[busy]), FileError);
  results.pop_back();
  EXPECT_THROW(plan.merge(results), std::invalid_argument);
}
