#pragma once
// Internal: views of a camera whose chain can only aim it (NbvOptions::aiming, looks_at): the chain points
// the optical axis at target points (aim.hpp) and the poses it reaches are checked and scored as any view.
#include <cstdint>
#include <vector>

#include "octoreach/aim.hpp"
#include "octoreach/next_best_view.hpp"

namespace octoreach::detail {

class ViewChecker;
struct ScoreModel;

// Target points (map frame) of a look-at search: up to n void cells drawn as the aims draw them (exposed ones
// first, unexposed ones with probability unexposed_share), or, for the Frontiers and Unknown gains and on a
// map without void cells, up to n frontier cells at random. Deterministic for the seed; the caller holds the
// map's lock.
std::vector<Eigen::Vector3d> look_at_targets(const ExplorationMap& map, NbvGain gain, std::size_t n,
                                             double unexposed_share, std::uint64_t seed);

// What a look-at search found: the distinct aims (in target order) with their status, the valid ones scored.
struct LookAtViews {
  ScoredViews scored;
  std::size_t aim_failures = 0;    // targets the chain cannot aim at within opt.look_at_tolerance
  std::size_t camera_not_clear = 0, arm_collisions = 0, capability_rejected = 0;
};

// The chain (at opt.chain_base) aims its camera at `target` (map frame): aim() from a random configuration drawn
// from opt.seed + index, tolerance opt.look_at_tolerance.
AimResult aim_camera(const NbvOptions& opt, const Eigen::Vector3d& target, std::size_t index);

// The chain aims its camera at each target (aim_camera with the target's index); aims whose joints round to the same
// 0.02 rad (or m) steps as an earlier one are dropped; the others get score_views' checks in its order
// (workspace and its filter, capability map, camera clearance, the arm's collisions) and, up to `max_valid`
// of them in target order, the valid ones are scored. With full_best > 0 a coarse score (a quarter of the rays)
// ranks them by the gain and only the best full_best are kept, scored in full. The caller holds the map's lock.
LookAtViews look_at_views(const ExplorationMap& map, const CameraIntrinsics& cam,
                          const std::vector<Eigen::Vector3d>& targets, const NbvOptions& opt,
                          const ViewChecker& checker, const ScoreModel& model, std::size_t max_valid,
                          std::size_t full_best = 0);

// next_best_view with looks_at(opt): look_at_views of opt.max_candidate_cells targets (look_at_targets with
// the second look's unexposed share 0.25), up to opt.max_valid_poses valid, ranked by ranks_before.
NbvResult look_at_search(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt);

}  // namespace octoreach::detail
