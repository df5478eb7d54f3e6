// The warnings of map builds (map_warnings.hpp): figures of the finished map against what the arm's geometry
// promises, in one line with what to try.
#include "octoreach/map_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iomanip>
#include <sstream>
#include <vector>

#include "octoreach/capability_map.hpp"
#include "common/format.hpp"
#include "maps/surface_warning.hpp"

namespace octoreach {

namespace {

std::string percent(double share) {
  if (share > 0 && share < 0.005) return "under 1 %";
  std::ostringstream s;
  s << static_cast<int>(std::lround(100.0 * share)) << " %";
  return s.str();
}

}  // namespace

std::string capability_map_warning(const CapabilityMap& cap) {
  const std::string arm = "capability map of " + cap.base_link() + " -> " + cap.tip_link();
  // The certified lookup needs the map's joint solutions.
  const std::string certified = std::string("CertifiedLookup(map, robot)") +
                                (cap.has_solutions() ? "" : " (after a build with keep_solutions=True)");
  const bool none_reachable = cap.stats().voxels == 0;  // voxels with a reachable cell
  // Voxel records but none reachable: every record holds mixed cells only (the arm's configurations land in
  // them, IK at their centres fails), the mark of a reach thinner than a voxel.
  if (none_reachable && cap.voxel_count() > 0)
    return arm + ": no voxel centre is reachable, though the arm's configurations reach " +
           std::to_string(cap.voxel_count()) + " voxels: its reach is thinner than a cell, in position or in "
           "direction (an arm of " + std::to_string(cap.dof()) + " joints; one with no joint that turns it about the "
           "vertical reaches a single plane, one that holds its tool in one direction, as a SCARA pointing down, "
           "reaches no direction's centre" + (cap.orientations().poles() ? "" : " unless the map has poles=True") +
           "), so IK at the cell centres fails and the map's own lookups answer no everywhere: " + certified +
           " answers its poses by IK from the configurations the map keeps; or check the joint axes and the "
           "approach axis, or give the arm the joints it lacks";
  if (none_reachable)
    return arm + ": no voxel is reachable: check the arm's joint limits, its collision model (`octoreach robot` "
                 "counts its self-collisions) and the reference posture";
  if (cap.dof() >= 6) {
    std::vector<Eigen::Vector3d> centres;
    std::vector<double> values;
    cap.voxels(centres, values);
    const double best = *std::max_element(values.begin(), values.end());
    if (best < kFewDirections)
      return arm + ": its best voxel reaches only " + percent(best) + " of the approach directions (a 6-DOF wrist "
             "turning +-90 degrees reaches " + percent(kFewDirections) + "): self-collision (`octoreach robot` shows "
             "how often the arm collides with itself and which links), joint limits or an approach axis that is not "
             "the tool's (--approach-axis) block the wrist";
  }
  const std::size_t mixed = cap.stats().mixed_cells, reachable = cap.stats().reachable_cells;
  if (static_cast<double>(mixed) <= kMixedPerReachable * static_cast<double>(reachable)) return "";
  return arm + ": the arm's configurations land in " + std::to_string(mixed) + " cells whose centre IK does not "
         "reach (mixed cells), more than " + detail::format_number(kMixedPerReachable) + " times the " +
         std::to_string(reachable) + " it reaches: its reach is thin in position or direction (few joints, narrow "
         "joint ranges), so the plain lookups (map.reachable) and surface maps, which read only the reachable cells, "
         "miss much of it: " + certified + " answers the mixed cells by IK";
}

namespace detail {

std::string surface_height_warning(const SurfaceBuild& b, double best_rs) {
  if (b.targets.empty() || !(b.o.z_max - b.o.z_min < 1e6)) return "";  // a floating base reaches any height
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> values;
  b.cap.voxels(centres, values);
  const std::vector<int> grasps = bin_orientations(b, 0);
  if (centres.empty() || grasps.empty()) return "";
  double tz_lo = std::numeric_limits<double>::infinity(), tz_hi = -tz_lo;
  for (const auto& t : b.targets) {
    tz_lo = std::min(tz_lo, t.z());
    tz_hi = std::max(tz_hi, t.z());
  }
  // A voxel centre stands (reference_to_arm * c).z above the base's reference frame whatever the base's x,
  // y and yaw; it meets the targets for some base height in [z_min, z_max] within half a voxel.
  const double half = 0.5 * b.cap.resolution();
  double best = 0.0, here = 0.0, best_height = 0.0;
  for (const auto& c : centres) {
    const std::int64_t rec = b.cap.record_at(c);
    if (rec < 0) continue;
    int n = 0;
    for (int o : grasps) n += b.cap.record_has(static_cast<std::uint32_t>(rec), o);
    const double share = static_cast<double>(n) / grasps.size();
    const double h = (b.place.reference_to_arm * c).z();
    if (share > best) {
      best = share;
      best_height = h;
    }
    if (h + b.o.z_max >= tz_lo - half && h + b.o.z_min <= tz_hi + half) here = std::max(here, share);
  }
  if (best <= 0.0 || here >= kEdgeOfReach * best) return "";
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << "surface with grasp points at " << tz_lo << " m (best R_S " << std::setprecision(3) << best_rs
    << "): at that height the arm reaches at most " << percent(here) << " of the grasps, against "
    << percent(best) << " at its best height (" << std::setprecision(2) << best_height + b.o.z_min
    << " m): the surface lies at the edge of the arm's reach; try another reference posture (a torso lift, "
       "reference=), the torso's joints in the arm (--base LINK), or another grasp set";
  return s.str();
}

}  // namespace detail
}  // namespace octoreach
