#pragma once
// Private: the steps of CapabilityMap::build. A dense box of cells (voxel x orientation) around the
// arm's workspace; forward-kinematics sampling proposes cells and IK seeds; IK at the voxel centres
// settles them in waves, flooding from reachable cells to their neighbours.
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "octoreach/capability_map.hpp"
#include "octoreach/chain.hpp"
#include "maps/capability_cells.hpp"

namespace octoreach::detail {

/// The cells of the build: voxels of the workspace's bounding box times the orientations.
/// Cell index = voxel * O + orientation; voxel = (ix * ny + iy) * nz + iz.
struct CellBox {
  const VoxelOcTree* tree = nullptr;
  octomap::OcTreeKey kmin;
  int nx = 0, ny = 0, nz = 0, O = 0;
  std::size_t voxels = 0, cells = 0;

  /// Box around `samples` forward-kinematics positions of `chain`, 1.5 voxels of margin.
  static CellBox around_workspace(const Chain& chain, const VoxelOcTree& tree, int orientations, std::uint64_t seed);
  bool voxel_of(const Eigen::Vector3d& p, std::size_t& v) const;
  octomap::OcTreeKey key(std::size_t v) const;
  Eigen::Vector3d centre(std::size_t v) const;
  /// The 6 spatial neighbours with the same orientation, the neighbouring directions with the same
  /// roll, and (several rolls) the neighbouring rolls.
  void neighbours(std::uint32_t cell, const OrientationSet& set, std::vector<std::uint32_t>& out) const;
};

/// Runs the sampling and IK stages; the result is a status and (if reachable) a solution per cell.
class CapabilityBuilder {
 public:
  enum : std::uint8_t { kUntried = 0, kQueued = 1, kFailed = 2, kReachable = 3 };
  CapabilityBuilder(const Chain& chain, const CapabilityMapOptions& options, const OrientationSet& set,
                    const Eigen::Vector3d& approach_axis, const Eigen::VectorXd& reference, const CellBox& box,
                    const ProgressCallback& progress);
  /// Stage 1: forward-kinematics samples (deterministic: fixed chunks merged in order) give each
  /// cell they hit a seed configuration. Returns the number of samples.
  std::size_t sample();
  /// Stage 2: floods over neighbours (IK at the voxel centres, seeded with a reachable neighbour's solution)
  /// started from a sparse share of the sampled cells, retries of the failed cells (their own sample where at
  /// least a quarter of their neighbours are reachable, then another neighbour's solution where most are), and
  /// (exhaustive) random restarts on every untried cell.
  void solve();

  /// Stage 3: the quality of every reachable cell's solution (keep_solutions), on every core.
  void rate();
  /// The cells of voxel v (box index) as a map record holds them: reachable cells, mixed cells (a forward-
  /// kinematics sample landed in them, IK at their centre failed) and, with keep_solutions, their solutions,
  /// quality (after rate()) and the mixed cells' samples.
  void collect(std::size_t v, VoxelCellData& out) const;

  bool reachable(std::size_t cell) const { return status_[cell] == kReachable; }
  /// The solution (dof floats) of a reachable cell.
  const float* solution(std::size_t cell) const { return sol_pool_.data() + static_cast<std::size_t>(sol_row_[cell]) * dof_; }
  std::size_t ik_calls() const { return ik_calls_; }
  /// The block build's hooks (maps/capability_blocks.cpp): a cell's seed from sample() (dof floats, or
  /// nullptr), and a seed given to a cell before solve(), as sample() gives them (first one kept).
  const float* seed(std::size_t cell) const {
    return seed_row_[cell] < 0 ? nullptr : seed_pool_.data() + static_cast<std::size_t>(seed_row_[cell]) * dof_;
  }
  void add_seed(std::uint32_t cell, const float* q) {
    if (seed_row_[cell] >= 0) return;
    seed_row_[cell] = static_cast<std::int32_t>(seed_pool_.size() / dof_);
    seed_pool_.insert(seed_pool_.end(), q, q + dof_);
  }
  /// Reports progress: this stage starts at `start` (fraction of the build) and owns `share` of it.
  void report(double start, double share, double fraction) const;
  /// With OCTOREACH_DEBUG set: `what` and the seconds since the builder was made, on stderr (the build's stages).
  void stage(const std::string& what) const;

 private:
  struct Item {
    std::uint32_t cell;
    std::int32_t seed;  // row in seed_pool_ (wave 0) or sol_pool_ (flood, retry); -1 none
  };
  void run_wave(const std::vector<Item>& wave, const std::vector<float>& pool, int attempts,
                std::vector<std::uint32_t>& newly);
  void flood(std::vector<std::uint32_t> frontier);
  void start_floods();
  std::vector<Item> retry_items(bool samples) const;
  static constexpr std::size_t kStartShare = 16, kStartMin = 16384, kPassMin = 1024;  // start_floods()

  const Chain& chain_;
  const CapabilityMapOptions& o_;
  const OrientationSet& set_;
  const CellBox& box_;
  const ProgressCallback& progress_;
  const int dof_;
  IkOptions base_ik_;
  std::vector<Eigen::Matrix3d> rotations_;  // tool rotation per orientation
  std::vector<std::int32_t> seed_row_;
  std::vector<float> seed_pool_;
  std::vector<std::uint8_t> status_;
  std::vector<std::uint8_t> started_;  // per cell: a descent started from its sample (a flood's start)
  std::vector<std::int32_t> sol_row_;
  std::vector<float> sol_pool_;
  std::vector<CellQuality> quality_;  // per sol_pool_ row (rate())
  std::size_t ik_calls_ = 0;
  std::size_t reachable_ = 0;  // cells with status kReachable
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();  // stage()
  const bool debug_ = std::getenv("OCTOREACH_DEBUG") != nullptr;
};

}  // namespace octoreach::detail
