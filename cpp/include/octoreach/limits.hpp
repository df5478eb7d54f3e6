#pragma once
/// \file limits.hpp
/// \brief Every numeric limit octoreach checks its inputs against, in one place (Python:
/// `octoreach._core.limits`, a read-only mapping of the same values; the limits tables of docs/guides/limits.md).
///
/// A limit is checked before any work or allocation it bounds, at full width (a count is compared
/// as a 64-bit or wider number before it is narrowed), and an input beyond it raises
/// std::invalid_argument (a bad argument) or FileError (a file) naming the value and the limit.
/// Each value is far above what a real robot, room or sensor needs (the comment says why) and low
/// enough that the work it bounds stays within memory and within seconds to minutes (every long
/// loop also stops on Ctrl-C).

#include <cstdint>

namespace octoreach::limits {

// ---- files read: each must be a regular file (no FIFO, device or directory) of at most ----

/// URDF and SRDF text files: expanded xacro models of whole humanoids are a few MB.
inline constexpr std::uint64_t kRobotFileBytes = std::uint64_t(64) << 20;
/// Mesh files (STL, DAE, OBJ, ...): scanned high-resolution meshes reach tens of MB; assimp holds a
/// few copies in memory while it converts.
inline constexpr std::uint64_t kMeshFileBytes = std::uint64_t(512) << 20;
/// OctoMap .bt and .ot files (read whole into memory before the tree is built): published city-scale
/// maps are tens to a few hundred MB.
inline constexpr std::uint64_t kOctreeFileBytes = std::uint64_t(1) << 30;
/// octoreach map files (.orcm, .orsm, .orpm), compressed.
inline constexpr std::uint64_t kMapFileBytes = std::uint64_t(4) << 30;
/// Decompressed contents of a map file; a file's contents are also bounded by the counts its header
/// declares (voxels times the record size) before anything is inflated. With solutions, a voxel of a
/// 7-joint arm's map at 200 directions takes up to 5.6 kB: 8 GiB hold 1.5 million voxels, a 0.02 m map of
/// a sphere of 1.2 m radius.
inline constexpr std::uint64_t kMapPayloadBytes = std::uint64_t(8) << 30;
/// Voxels a map file may declare (octree records are numbered with 32 bits).
inline constexpr std::uint64_t kMapVoxels = std::uint64_t(1) << 31;

// ---- geometry ----

/// |coordinate| and extents in metres of surfaces and obstacle boxes (1,000 km: any room, building or
/// campus; far beyond, doubles lose the millimetres the maps work in).
inline constexpr double kCoordinate = 1e6;
/// Resolutions an OctoMap file may state, metres (outside: the file is refused as damaged).
inline constexpr double kMinOctreeResolution = 1e-4;
inline constexpr double kMaxOctreeResolution = 1e4;
/// Map resolutions (voxel or cell edges, metres) of capability, point and surface maps, in builds
/// and in files alike.
inline constexpr double kMinMapResolution = 1e-3;
inline constexpr double kMaxMapResolution = 100.0;
/// Vertices of a surface polygon: a table top traced from a scan has hundreds; the simplicity check is
/// O(n log n), the triangulation O(n r) for r reflex corners (about half a second at the limit for a comb
/// of 5,000 long teeth, milliseconds for a convex outline).
inline constexpr std::uint64_t kPolygonVertices = 20000;
/// Grid points over a surface (Surface.points, the positions of a surface map build): a 4 x 4 m
/// table at 1 mm.
inline constexpr std::uint64_t kSurfacePoints = std::uint64_t(1) << 24;

// ---- counts of work ----

/// Directions and rolls of an orientation set (also in map headers): 100,000 directions are 0.6 degrees
/// apart; 360 rolls are 1 degree apart.
inline constexpr std::int64_t kDirections = 100000;
inline constexpr int kRolls = 360;
/// Values (positions x yaw bins) of the dense grid a point or surface map build fills: 8 GiB of floats;
/// a 0.01 m point map of an arm reaching 1.3 m at 64 bins takes 1.1e9.
inline constexpr std::uint64_t kMapGridValues = std::uint64_t(1) << 31;
/// Yaw bins of point and surface maps (1 degree apart).
inline constexpr int kThetaBins = 360;
/// Cells (voxels x orientations) of the workspace box of a capability map build: a byte of state and two
/// 32-bit rows per cell, 19 GB at the limit.
inline constexpr std::uint64_t kCapabilityCells = std::uint64_t(1) << 31;
/// Cells ExplorationMap.count_known visits (finest resolution).
inline constexpr std::uint64_t kCountKnownCells = std::uint64_t(1) << 30;

/// Pixels of a depth image (width x height; 4096 x 4096, above every depth sensor sold) and of the
/// ray grid that scores a view.
inline constexpr std::uint64_t kImagePixels = std::uint64_t(1) << 24;
/// Forward-kinematics samples of a capability map build (given or 40 per voxel of the workspace box): a
/// 2.4 m box at 0.01 m takes 5.5e8.
inline constexpr std::uint64_t kFkSamples = std::uint64_t(1) << 32;
/// Poses one next-best-view search may score: max_candidate_cells x orientations_per_cell (and
/// max_valid_poses); the paper's search scores 400 x 8.
inline constexpr std::uint64_t kViewCandidates = std::uint64_t(1) << 20;
/// Candidates per pose sample of a PoseSampler, and poses per sample(k) call.
inline constexpr std::uint64_t kSamplerCandidates = std::uint64_t(1) << 20;

}  // namespace octoreach::limits
