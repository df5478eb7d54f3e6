#pragma once
// Internal: the one reader of OctoMap binary (.bt) files, bounded in time and memory by the file's size
// and a stated cell limit.
#include <cstdint>
#include <string>

#include "octoreach/limits.hpp"

namespace octomap {
class OcTree;
}

namespace octoreach::detail {

/// \brief Resolutions a .bt file may state, metres (outside: the file is rejected as damaged).
constexpr double kMinOctreeResolution = limits::kMinOctreeResolution, kMaxOctreeResolution = limits::kMaxOctreeResolution;

/// \brief Reads the .bt file at `path` into `tree` (`what` names it in messages).
/// \throws FileNotFound if it does not exist, FileError if it cannot be parsed, states a resolution outside
/// [kMinOctreeResolution, kMaxOctreeResolution], or (max_cells > 0) its leaves cover more than max_cells
/// finest-resolution cells.
void read_bt(octomap::OcTree& tree, const std::string& path, const std::string& what, std::uint64_t max_cells);

}  // namespace octoreach::detail
