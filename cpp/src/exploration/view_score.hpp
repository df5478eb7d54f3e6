#pragma once
// Internal: the visibility model of a view (view_score.cpp), the checks that make a camera pose a view
// (view_check.cpp) and the aimed looks' scoring (score_views.cpp), shared by next_best_view and score_views.
#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "octoreach/capability_map.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/next_best_view.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/void_enclosure.hpp"

namespace octomap {
class OcTree;
}

namespace octoreach::detail {

struct ExplorationState;
struct ExpectedCell;
class ScoreCells;

// Where a view's rays can still meet a cell that counts for the gain (map frame, cell bounds): with the
// FrontierVoid gain, the box of the map's void cells; cells count only up to where a ray leaves it (it cannot
// meet a void cell beyond) and a ray that misses it is not walked. Empty: no void cell at all.
struct RayClip {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = -Eigen::Vector3d::Ones();
  // Past the clip a ray is walked only to learn what ends it (an occupied cell, or an unknown cell of the search
  // space or the voids); outside the reach box there is neither, so the walk ends where the ray leaves it. Outside
  // the known box (the cell cache's blocks) every cell is unknown, and only the search space's cells there can
  // stop a ray (1 - p each: none when p is 1).
  Eigen::Vector3d reach_lo = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Vector3d reach_hi = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d known_lo = Eigen::Vector3d::Zero(), known_hi = -Eigen::Vector3d::Ones();
  bool empty() const { return (hi.array() < lo.array()).any(); }
};
// The box of the map's void cells, and the box of its known cells and search space as the reach (the caller holds
// the map's lock).
RayClip void_box(const ExplorationMap& map);

// view_gains without taking the map's lock: the caller holds it (pool workers of next_best_view must
// not lock again: a writer waiting in between would deadlock them against their caller).
// `learned`: ray weights from the map's learned visibility curve (with the geometric weight of p and
// p_void as its prior), else the geometric weight alone. With `unknown_met`, also lists every unknown
// cell a ray met with its largest ray weight w (before seeability), that ray's unknown depth and its class.
// With `clip`, cells count up to where rays leave it and the rest of a ray only says whether it returns (the
// void and enclosed-void figures stay those of whole rays; the unknown and frontier figures count what the rays
// met up to there; unknown figures count the search space's cells only, and every unknown cell counts by the
// chance that its ray returns at or behind it: count_view). With `cells` (made with
// void_weights' table), the cells are read through it: the same values, faster.
ViewGains view_gains_unlocked(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                              double p, double p_void, bool learned,
                              std::vector<ExpectedCell>* unknown_met = nullptr,
                              const VoidWeights* void_weights = nullptr, const RayClip* clip = nullptr,
                              const ScoreCells* cells = nullptr);

// After an insert: each cell the view announced by expect_view expected (weight w), left unknown and
// still met by the view's rays in the updated map (no surface seen in between) has its seeability
// multiplied by (1 - w), and a void cell or an unknown cell of the search space with no surface behind it
// within range keeps the line of sight when the insert had points (`returned`; blind_lines.hpp); every
// announced cell the view did not count 0 for a line teaches the visibility curve (seen or not, at its depth
// and class); the announcement is cleared. S is map's state; the caller holds the write lock
// (view_learning.cpp).
void learn_from_missed(const ExplorationMap& map, ExplorationState& S, bool returned);

// Throws std::invalid_argument naming the first bad option (or camera value).
void validate_options(const CameraIntrinsics& cam, const NbvOptions& opt);

// p (unknown cells outside the voids) and p_void of a search: the fixed option or the map's learned values.
std::pair<double, double> pass_probabilities(const ExplorationMap& map, const NbvOptions& opt);

// What every view score of one search shares: p and p_void, the void weights (enclosure_power), the map's cells
// in flat form and, with the FrontierVoid gain, the box the rays are clipped to (the void cells').
struct ScoreModel {
  std::pair<double, double> p{1.0, 1.0};
  VoidWeights void_weights;
  std::optional<RayClip> clip;
  std::shared_ptr<const ScoreCells> cells;  // the map's cells for void_weights (made once per map version)
};
// The model of a search on `map` with `opt` (the caller holds the map's lock).
ScoreModel score_model(const ExplorationMap& map, const NbvOptions& opt);

// Fills the gains, expected_gain (of opt.gain) and utility_dm3 of `v` (its pose set): the one place a view is
// scored; ranks_before (next_best_view.hpp) is the one order of scored views. `step` > 1: every step-th ray of
// the score grid across and down (rounded up), the first score of many poses (NbvOptions::rescore_best: 2).
void score_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt, const ScoreModel& m,
                ViewCandidate& v, int step = 1);

// The verdict of opt.workspace.filter on each position (all true without a filter, which is then not called): the
// one call of the caller's filter. \throws std::invalid_argument when it returns another number of values.
std::vector<bool> filter_verdicts(const NbvOptions& opt, const std::vector<Eigen::Vector3d>& pos);

// The capability map's verdict on a camera position p (map frame; `to_arm` the inverse of opt.capability_base): true
// without a map, else when one of the 8 voxels around p (CapabilityMap::corners) has D > opt.min_reachability; as
// CapabilityLookup::any, a no only where the map is sure: IK decides between the voxels.
inline bool position_reachable(const NbvOptions& opt, const Pose& to_arm, const Eigen::Vector3d& p) {
  if (!opt.capability_map) return true;
  std::uint32_t records[8];
  double weights[8];
  opt.capability_map->corners(to_arm * p, records, weights);
  for (const std::uint32_t r : records)
    if (opt.capability_map->record_reachability(r) > opt.min_reachability) return true;
  return false;
}

// score_views(map, cam, poses, opt, false) for a choice by `key`, with opt.rescore_best = n > 0 unless the chain
// only aims its camera (then score_views itself): the checks before IK for every pose, then for those that pass
// a coarse score and IK and the arm's collisions in the coarse order until n are valid, those n scored with the
// full grid. When more than 16 n pass, a score with every fourth ray ranks them first and they go through those
// steps in chunks of 16 n in that order. Holds the poses checked up to the n-th valid one (without a chain, the
// n best by the coarse score), in their order in `poses`: the same views for any thread count. Takes the map's
// lock.
ScoredViews rescored_views(const ExplorationMap& map, const CameraIntrinsics& cam, const std::vector<Pose>& poses,
                           const NbvOptions& opt, RankKey key);

// The indices (ascending) of the n best of `views` by each ranking key (ranks_before; ties: the lower index):
// the ones a coarse first score keeps for the full score (NbvOptions::rescore_best).
std::vector<std::size_t> best_by_each_key(const std::vector<const ViewCandidate*>& views, std::size_t n);

// The size of the next batch of poses checked until `wanted` more are valid, when `valid` of the `tried` so far
// were: the poses expected to give them at the rate seen so far, at least `least` (a few per thread), at most
// twice `last` (the batch before: a rate measured on few poses grows it step by step) and 16 x least. Poses
// past the last one needed are checked and scored for nothing: a fixed small batch wastes threads on its
// slowest pose, one too large the scoring of valid poses that are not needed.
inline std::size_t next_batch(std::size_t wanted, std::size_t valid, std::size_t tried, std::size_t least,
                              std::size_t last) {
  const double rate = double(valid + 1) / double(tried + 1);
  const double expected = double(wanted) / rate;
  return std::size_t(std::clamp(expected, double(least), double(std::min(2 * last, 16 * least))));
}

// The checks of one search that make a pose a view: camera clearance, the capability map's axis,
// IK and the arm's collisions. Built once per search (the obstacles: the map's occupied cells and,
// with unknown_is_obstacle, a tree of the unknown cells of the search space); const methods may run
// from many threads. The caller holds the map's lock.
class ViewChecker {
 public:
  ViewChecker(const ExplorationMap& map, const NbvOptions& opt);
  ~ViewChecker();
  // Camera cell free, no point of an occupied cell within min_distance of it, and (unknown_is_obstacle) no point of
  // an unknown cell of the search space within unknown_margin (a cell no insert has reached is unknown).
  bool camera_clear(const Eigen::Vector3d& p) const;
  // The capability map's verdict on the pose's optical axis at its position, CapabilityLookup::any (a no only
  // where every cell around the pose says no: IK decides where they disagree); true without a map or when its
  // approach axis is not the camera's +z.
  bool axis_reachable(const Pose& pose) const;
  // The capability map's directions (map frame) at most `max_turn` radians from `axis` (unit, map frame),
  // nearest first; none without a capability map that checks axes (see axis_reachable).
  std::vector<Eigen::Vector3d> turned_axes(const Eigen::Vector3d& axis, double max_turn) const;
  // An optical axis for a camera at `eye` meant to look along `axis`: `axis` itself when axis_reachable (at
  // roll 0, as score_views checks a pose), else the first of `turned` (turned_axes of `axis`) that is; none
  // otherwise.
  std::optional<Eigen::Vector3d> reachable_axis(const Eigen::Vector3d& eye, const Eigen::Vector3d& axis,
                                                const std::vector<Eigen::Vector3d>& turned) const;
  // IK (seed ik.seed + seed_offset) and the arm's collision check; on success the pose becomes the
  // one the arm reaches and q is set. Needs a chain.
  ViewStatus reach(Pose& pose, Eigen::VectorXd& q, std::size_t seed_offset) const;
  // The arm's collision check of joints q (the links it moves against the map, the robot against itself).
  // Needs a chain.
  ViewStatus arm_clear(const Eigen::VectorXd& q) const;
  // Unknown cells of the search space turned into obstacles (0 without unknown_is_obstacle).
  std::size_t unknown_obstacle_cells() const { return unknown_cells_; }

 private:
  // False when no cell the arm's map obstacles hold (an occupied cell; with unknown_is_obstacle, an unknown cell of
  // the search space) lies in the world box of `shape` at `world`: then those obstacles cannot touch it.
  bool cells_near(const Shape& shape, const Pose& world) const;
  // The capability map's joint solution of the cell of camera pose `pose` (map frame), a start for IK after the first
  // random one: a configuration that reaches the cell's centre lies near one that reaches the pose. None without one.
  std::optional<Eigen::VectorXd> map_seed(const Pose& pose) const;
  // For a pose the capability map's vote rules out though a cell around it is reachable (axis_reachable let it
  // through): the joint solutions of the reachable cells among the 8 around it (CapabilityMap::corners), the
  // largest trilinear weight first. Empty for a pose the vote admits, and without the map's solutions.
  std::vector<Eigen::VectorXd> between_cells_seeds(const Pose& pose) const;
  const ExplorationMap& map_;
  const NbvOptions& opt_;
  IkOptions ik_;
  Pose base_inv_, cap_inv_, robot_root_ = Pose::Identity();
  bool cap_orient_ = false;
  bool map_seeds_ = false;  // see map_seed
  std::optional<Obstacles> obstacles_;
  std::optional<Obstacles> ground_;  // ground_is_obstacle: a slab whose top is the ground (view_check.cpp)
  std::vector<int> moved_links_;     // collision links the chain moves (tested against the map and ground_)
  std::shared_ptr<octomap::OcTree> unknown_tree_;
  std::size_t unknown_cells_ = 0;
  Eigen::VectorXd reference_;
  // The key box of the whole search space: the camera's margin counts every unknown cell of it, those beyond the
  // known cells too (before the first insert every cell is one).
  SpaceKeys space_;
  // The key box whose unknown cells are the arm's obstacles (view_check.cpp, arm_cells): space_, or for an unbounded
  // (or very large) search space, space_ clipped to the known cells; empty without unknown_is_obstacle.
  SpaceKeys arm_box_ = SpaceKeys::none();
};

}  // namespace octoreach::detail
