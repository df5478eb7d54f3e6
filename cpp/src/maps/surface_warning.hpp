#pragma once
// Internal: the check of a surface map build that the surface's height is within the arm's comfortable
// reach (map_warnings.hpp states the rule).
#include <string>

#include "maps/surface_bin.hpp"

namespace octoreach::detail {

/// "" or one line: the best share of the grasp set the arm reaches at the targets' heights (over the base
/// heights of the build) is below kEdgeOfReach times its best share at any height. `best_rs` is the map's
/// best R_S, quoted in the line.
std::string surface_height_warning(const SurfaceBuild& b, double best_rs);

}  // namespace octoreach::detail
