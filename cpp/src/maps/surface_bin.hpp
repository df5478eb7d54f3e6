#pragma once
// Private: the state a surface map build shares with its theta bins, and the evaluation of one bin.
#include <cstddef>
#include <memory>
#include <vector>

#include "maps/arm_clearance.hpp"
#include "maps/arm_obstacles.hpp"
#include "maps/cell_slots.hpp"
#include "octoreach/surface_map.hpp"

namespace octoreach::detail {

// Base-position grid of a surface map: the octree keys kmin + (ix, iy, iz), T theta bins per cell,
// values [((ix * ny + iy) * nz + iz) * T + k].
struct SurfaceGrid {
  octomap::OcTreeKey kmin;
  int nx = 0, ny = 0, nz = 0, T = 0;
  std::vector<float> values;
  std::size_t cells() const { return static_cast<std::size_t>(nx) * ny * nz; }
  octomap::OcTreeKey key(int ix, int iy, int iz) const { return octomap::OcTreeKey(kmin[0] + ix, kmin[1] + iy, kmin[2] + iz); }
};

// What every theta bin of a build reads.
struct SurfaceBuild {
  const Robot& robot;
  const CapabilityMap& cap;
  const Surface& surface;
  const SurfaceMapOptions& o;
  const ArmPlacement& place;
  const VoxelOcTree& tree;          // of the map being built: key <-> coordinate
  std::vector<Eigen::Vector3d> targets;  // grasp points, grasp_height above the surface
  std::vector<Eigen::Vector2d> target_uv;
  Pose arm_from_reference;
  bool upright = false;             // arm frame upright and surface horizontal
  ArmClearance* clearance = nullptr;
  std::shared_ptr<Obstacles> slab;        // the surface, its boxes and the rest of the room: the body check
  const ArmObstacles* obstacles = nullptr;  // its boxes and the rest of the room: the arm check
  const CellSlots* slots = nullptr;  // the cells the arm checks read (check_arm only)
};

// What a theta bin counted: candidate and valid (base pose, target) pairs, base poses rejected for the
// body, grasps rejected for the arm.
struct BinCounts {
  std::size_t candidates = 0, valid = 0, body = 0, arm = 0;
};

// The arm-frame orientations the grasps map to at theta bin k.
std::vector<int> bin_orientations(const SurfaceBuild& b, int k);

// R_S of every base position of the grid at theta bin k, into g.values (that bin's values only, so bins
// may run in parallel).
BinCounts evaluate_bin(const SurfaceBuild& b, int k, SurfaceGrid& g);

}  // namespace octoreach::detail
