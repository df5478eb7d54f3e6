#pragma once
// Private: does an arm, at the joint solution a capability map stored, touch an obstacle of the
// room (boxes, meshes, OctoMaps, other surfaces)? Cheapest test first: the obstacles near the arm's
// whole reach at a base pose, then the arm's bounding box at that solution, then each link's box, then
// each shape's oriented box against each near obstacle, then FCL's answer for that pair (the mesh-box
// check with witnesses for a mesh against a box, mesh_box_check.hpp; FCL for the rest).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <fcl/math/bv/AABB.h>

#include "octoreach/arm.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/collision.hpp"
#include "collision/mesh_box_check.hpp"
#include "maps/cell_slots.hpp"
#include "collision/obb.hpp"

namespace octoreach::detail {

/// The obstacles near the arm at one base pose, as boxes in the arm frame: in centimetres, lo rounded
/// up and hi rounded down (lo x y z, hi x y z), so an integer box of the arm meets one exactly when it
/// meets the unrounded box; clamped to the int16 range (the arm boxes lie within +-32000 cm, so no
/// answer changes).
struct NearObstacles {
  std::vector<std::array<std::int16_t, 6>> cm;
  std::vector<Obb> obb;  // the same obstacles' oriented boxes (local AABB placed), arm frame
  std::vector<std::uint32_t> index;  // the same obstacles' indices in the Obstacles
  bool empty() const { return cm.empty(); }
};

/// Scratch of one thread of a build: link poses (arm frame, float 3 x 4 per shaped link) and their
/// shapes' oriented boxes (centre, axes) of the cells checked so far, so a cell met again from another
/// base position needs no forward kinematics.
struct ArmScratch {
  std::vector<Pose> poses;
  std::vector<std::uint32_t> at;  // by slot: offset into pool, or kNotYet
  std::vector<float> pool;
  std::vector<float> spare;       // a cell met once the pool is full
  std::vector<std::int32_t> hit;  // by shaped link (lane): its box meets a near obstacle's (-1) or not (0)
  std::vector<MeshBoxWitness> box_witness;  // by (link shape, obstacle): what decided their last check
  static constexpr std::uint32_t kNotYet = 0xffffffffu;
};

/// Arm boxes of the capability cells of a CellSlots and the checks against a set of obstacles.
/// Thread-safe for const use.
class ArmObstacles {
 public:
  /// Computes the arm boxes of every cell of `slots` (shared: the cells are numbered by it), in parallel.
  ArmObstacles(const Robot& robot, const CapabilityMap& capability, const ArmPlacement& place,
               std::shared_ptr<const Obstacles> obstacles, std::shared_ptr<const CellSlots> slots, int threads);
  bool empty() const { return !obstacles_ || obstacles_->empty(); }
  /// Obstacles whose world box meets the arm's whole reach when the arm base is at `world_from_arm`.
  void near(const Pose& world_from_arm, NearObstacles& out) const;
  /// True when the arm at the stored solution of the cell of `slot` touches an obstacle; the arm base
  /// link at `world_from_arm`.
  bool collides(std::int32_t slot, const NearObstacles& near, const Pose& world_from_arm, ArmScratch& scratch) const;

 private:
  const Robot& robot_;
  const CapabilityMap& cap_;
  Chain arm_;
  Eigen::VectorXd reference_;
  std::vector<int> links_;          // links moved by the arm (arm and tool roles)
  std::vector<int> placing_;        // the joints that place them (forward kinematics of those only)
  std::vector<int> shaped_;         // those of them with collision shapes
  std::vector<std::size_t> shape_id_;  // by shaped link: the number of its first shape among all shaped links' shapes
  std::size_t shapes_ = 0;
  std::vector<Eigen::Vector3d> shape_half_;  // by shape number: half extents of its local AABB
  // Per slot: the box of the whole arm (lo x y z, hi x y z), then the boxes of the shaped links as six
  // rows of lanes_ values (lo x, lo y, lo z, hi x, hi y, hi z; link j in lane j, the spare lanes never
  // meet), arm frame, in centimetres rounded outwards: stride_ = 6 (1 + lanes_) int16 from slot * stride_.
  // The rows let one pass test every link against an obstacle (the compiler vectorises it).
  std::vector<std::int16_t> boxes_cm_;
  std::size_t stride_ = 0, lanes_ = 0;
  std::shared_ptr<const CellSlots> slots_;
  Pose arm_from_root_;
  const float* link_poses(std::int32_t slot, ArmScratch& scratch) const;
  std::shared_ptr<const Obstacles> obstacles_;
  std::vector<fcl::AABBd> boxes_;   // world boxes of the obstacles
  Eigen::Vector3d reach_lo_, reach_hi_;  // union of the arm boxes (arm frame)
  void compute(int threads);
};

}  // namespace octoreach::detail
