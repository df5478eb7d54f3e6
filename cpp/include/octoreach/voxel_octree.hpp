#pragma once
/// \file voxel_octree.hpp
/// \brief An OctoMap octree whose leaves carry an index into a map's payload (reachability data).

#include <cstdint>
#include <limits>
#include <vector>

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTreeBaseImpl.h>
#include <octomap/OcTreeDataNode.h>

namespace octoreach {

/// \brief Octree node: `value` holds the largest reachability below it (the leaf's own value
/// at the finest level); `payload` indexes the owning map's per-voxel record (leaves only).
class VoxelNode : public octomap::OcTreeDataNode<float> {
 public:
  VoxelNode() : octomap::OcTreeDataNode<float>(0.0f) {}
  std::uint32_t payload = std::numeric_limits<std::uint32_t>::max();
  void copyData(const VoxelNode& from) {
    value = from.value;
    payload = from.payload;
  }
};

/// \brief The reachability octree (an extension of octomap::OcTreeBaseImpl).
///
/// Lookups cost O(depth): a key computation and a descent of at most 16 levels.
class VoxelOcTree : public octomap::OcTreeBaseImpl<VoxelNode, octomap::AbstractOcTree> {
 public:
  explicit VoxelOcTree(double resolution) : octomap::OcTreeBaseImpl<VoxelNode, octomap::AbstractOcTree>(resolution) {}
  VoxelOcTree* create() const override { return new VoxelOcTree(resolution); }
  std::string getTreeType() const override { return "OctoreachVoxelOcTree"; }

  /// \brief The root node, created if the tree is empty.
  VoxelNode* ensure_root() {
    if (!root) {
      root = new VoxelNode();
      ++tree_size;
    }
    return root;
  }

  /// \brief Leaf at `key` at the finest depth, created with its parents if absent.
  VoxelNode* touch(const octomap::OcTreeKey& key) {
    VoxelNode* node = ensure_root();
    for (int depth = static_cast<int>(tree_depth) - 1; depth >= 0; --depth) {
      unsigned idx = octomap::computeChildIdx(key, depth);
      node = nodeChildExists(node, idx) ? getNodeChild(node, idx) : createNodeChild(node, idx);
    }
    return node;
  }

  /// \brief Leaf containing (x, y, z), or nullptr when the point is outside the tree or no leaf is there.
  const VoxelNode* find(double x, double y, double z) const {
    octomap::OcTreeKey key;
    if (!coordToKeyChecked(x, y, z, key)) return nullptr;
    const VoxelNode* n = search(key);
    return n && !nodeHasChildren(n) ? n : nullptr;
  }

  /// \brief Sets each inner node's value to the largest value of its children.
  void update_inner_values() {
    if (root) update_recurs(root);
  }

 private:
  float update_recurs(VoxelNode* node) {
    if (!nodeHasChildren(node)) return node->getValue();
    float best = 0.0f;
    for (unsigned i = 0; i < 8; ++i)
      if (nodeChildExists(node, i)) best = std::max(best, update_recurs(getNodeChild(node, i)));
    node->setValue(best);
    return best;
  }
};

/// \brief A dense key -> record table over the bounding box of a tree's leaves: a lookup is a key
/// computation and one array access instead of an octree descent. Built after a map is complete;
/// maps whose box would need more than `max_cells` entries keep using the octree.
class DenseIndex {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  void build(const VoxelOcTree& tree, std::size_t max_cells = std::size_t(1) << 26) {
    records_.clear();
    for (int a = 0; a < 3; ++a) lo_[a] = 0, hi_[a] = -1;
    bool first = true;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
      if (it->payload == kNone) continue;
      for (int a = 0; a < 3; ++a) {
        int k = it.getKey()[a];
        lo_[a] = first ? k : std::min(lo_[a], k);
        hi_[a] = first ? k : std::max(hi_[a], k);
      }
      first = false;
    }
    if (first) return;
    std::size_t leaves = 0;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) leaves += it->payload != kNone;
    // Sparse maps with a large box (two tables far apart) keep the octree rather than a mostly empty table.
    max_cells = std::min(max_cells, 16 * leaves + (std::size_t(1) << 20));
    std::size_t cells = 1;
    for (int a = 0; a < 3; ++a) {
      dim_[a] = hi_[a] - lo_[a] + 1;
      cells *= dim_[a];
    }
    if (cells > max_cells) return;
    records_.assign(cells, kNone);
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it)
      if (it->payload != kNone) records_[offset(it.getKey())] = it->payload;
  }
  bool active() const { return !records_.empty(); }
  /// \brief The key box of the leaves with a record (inclusive), also when the table is not kept; false when
  /// there is none.
  bool key_box(int lo[3], int hi[3]) const {
    for (int a = 0; a < 3; ++a) lo[a] = lo_[a], hi[a] = hi_[a];
    return hi_[0] >= lo_[0];
  }
  /// \brief Record of the voxel holding (x, y, z), or kNone; the caller checks active() first.
  std::uint32_t find(const VoxelOcTree& tree, double x, double y, double z) const {
    octomap::OcTreeKey key;
    if (!tree.coordToKeyChecked(x, y, z, key)) return kNone;
    return find(key);
  }
  /// \brief Record of the voxel with octree key `key`, or kNone; the caller checks active() first.
  std::uint32_t find(const octomap::OcTreeKey& key) const {
    for (int a = 0; a < 3; ++a)
      if (key[a] < lo_[a] || key[a] > hi_[a]) return kNone;
    return records_[offset(key)];
  }

 private:
  std::size_t offset(const octomap::OcTreeKey& k) const {
    return (static_cast<std::size_t>(k[0] - lo_[0]) * dim_[1] + (k[1] - lo_[1])) * dim_[2] + (k[2] - lo_[2]);
  }
  int lo_[3] = {0, 0, 0}, hi_[3] = {-1, -1, -1};
  std::size_t dim_[3] = {0, 0, 0};
  std::vector<std::uint32_t> records_;
};

}  // namespace octoreach
