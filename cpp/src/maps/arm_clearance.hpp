#pragma once
// Private: does an arm pass below a working surface? Witness points of the arm links (at the joint
// solutions a capability map stored) that lie below the surface, per capability cell, for the
// surface map's arm check.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "octoreach/arm.hpp"
#include "octoreach/capability_map.hpp"
#include "maps/cell_slots.hpp"

namespace octoreach::detail {

/// The arm's witness points below the surface for one capability cell (relative to the reached
/// voxel centre, arm frame), nearest to the target first, with a summary for a quick "all outside
/// one edge" test: for kDirs horizontal directions phi_k the smallest projection of the points on
/// (cos phi_k, sin phi_k), and the largest horizontal radius.
struct LowSet {
  static constexpr int kDirs = 32;
  std::vector<Eigen::Vector3f> points;
  std::array<float, kDirs> min_proj{};
  float r_max = 0;
  void summarise();
};

/// A low set read in place (a LowSet, or one of the shared low sets stored flat).
struct LowSetRef {
  const Eigen::Vector3f* points;
  std::uint32_t count;
  const float* min_proj;  // LowSet::kDirs values
  float r_max;
  static LowSetRef of(const LowSet& l) { return {l.points.data(), static_cast<std::uint32_t>(l.points.size()), l.min_proj.data(), l.r_max}; }
};

/// Low sets of capability cells. Thread-safe for const use once the shared layers are computed.
class ArmClearance {
 public:
  ArmClearance(const Robot& robot, const CapabilityMap& capability, const ArmPlacement& place, double grasp_height);
  /// Low set of cell (record, orientation) reached at `centre` for a surface with normal `n_arm` (arm frame).
  void compute(std::uint32_t rec, int orient, const Eigen::Vector3d& centre, const Eigen::Vector3d& n_arm,
               std::vector<Pose>& poses, LowSet& low) const;
  /// For an upright arm frame and a horizontal surface the normal in the arm frame is z whatever
  /// the yaw: computes the low sets once for every cell of `slots`, in parallel, and stores them flat
  /// in slot order (the points of neighbouring cells side by side in memory).
  void compute_shared(const CellSlots& slots, int threads);
  /// The shared low set of a slot of the CellSlots given to compute_shared.
  LowSetRef shared(std::int32_t slot) const {
    const auto s = static_cast<std::size_t>(slot);
    return {points_.data() + start_[s], start_[s + 1] - start_[s], summary_.data() + s * kSummary,
            summary_[s * kSummary + LowSet::kDirs]};
  }
  /// Where the shared low set of a slot starts in the flat point array, and how many points it has.
  std::uint32_t shared_start(std::int32_t slot) const { return start_[static_cast<std::size_t>(slot)]; }
  std::uint32_t shared_count(std::int32_t slot) const {
    return start_[static_cast<std::size_t>(slot) + 1] - start_[static_cast<std::size_t>(slot)];
  }
  const Eigen::Vector3f* shared_points() const { return points_.data(); }
  std::uint64_t key(std::uint32_t rec, int orient) const { return static_cast<std::uint64_t>(rec) * orientations_ + orient; }

 private:
  const Robot& robot_;
  const CapabilityMap& cap_;
  Chain arm_;
  Eigen::VectorXd reference_;
  std::vector<int> arm_links_;
  std::vector<int> placing_;  // the joints that place arm_links_ (forward kinematics of those only)
  std::vector<std::vector<Eigen::Vector3d>> link_witness_;
  Pose root_from_arm_base_;
  double grasp_height_;
  int orientations_;
  // The shared low sets, flat by slot: points [start_[s], start_[s + 1]), then per slot the kDirs
  // smallest projections and r_max (kSummary floats from s * kSummary).
  static constexpr int kSummary = LowSet::kDirs + 1;
  std::vector<Eigen::Vector3f> points_;
  std::vector<std::uint32_t> start_;
  std::vector<float> summary_;
};

}  // namespace octoreach::detail
