#pragma once
/// \file map_warnings.hpp
/// \brief One line saying why a freshly built map looks wrong and what to try: a capability map whose best
/// voxel reaches few approach directions (a collision model that blocks the arm), a surface at a height the
/// arm barely reaches. The thresholds follow from the arm's geometry, not from one robot.

#include <string>

namespace octoreach {

class CapabilityMap;

/// \brief Least reachability index D a 6-DOF or longer arm reaches at its best voxel. Why one half: at a
/// voxel the wrist centre can reach with some slack, a spherical wrist whose middle joint turns +-90 degrees
/// points the tool along every direction of the hemisphere around the forearm, which alone is half of the
/// directions (a free wrist, and the freedom of the arm's other joints, add more). A best voxel below it
/// means the wrist is blocked: by self-collision, by joint limits or by an approach axis that is not the tool's.
inline constexpr double kFewDirections = 0.5;

/// \brief Mixed cells per reachable cell above which a capability map warns that its plain lookups miss much of
/// the arm's reach. Why two: above it fewer than a third of the cells the arm's configurations land in are
/// reachable at their centre, where the plain lookups are measured to fail: the 5-joint so101 arm has 13 mixed cells
/// per reachable one at 0.05 m and its plain lookups agree with IK on 56-59 % of the check poses, the 6- and 7-joint
/// arms of the panel have 0.05 to 0.4 and agree on 89-97 %; between them, the tests' own 6-joint arm (1.3 at 0.1 m
/// and 50 directions, 88 %) stays under it.
inline constexpr double kMixedPerReachable = 2.0;

/// \brief Share of its best grasp share (over every height) that an arm must keep at a surface's height. Why
/// one half: below it the surface's height alone costs the arm more than half the grasps it has where it
/// reaches best: the surface lies at the bottom or top edge of the arm's reach.
inline constexpr double kEdgeOfReach = 0.5;

/// \brief "" when the map looks right, else one line saying what is wrong and what to try: no reachable voxel
/// (with or without mixed cells), its best voxel's D below kFewDirections (arms of 6 or more joints only; fewer
/// joints cannot point the tool along every direction), or more mixed cells than reachable ones (the plain
/// lookups miss most of the arm's reach; the certified lookup answers it).
std::string capability_map_warning(const CapabilityMap& capability);

}  // namespace octoreach
