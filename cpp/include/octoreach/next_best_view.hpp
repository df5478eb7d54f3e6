#pragma once
/// \file next_best_view.hpp
/// \brief Next best view (Dornhege & Kleiner, Algorithm 1 and section IV-C).
///
/// 1. Utility vectors: for every frontier-void, from the void's centre and its six extremes
///    (centroid +- semi-axis along each eigenvector) through each frontier cell touching the void.
/// 2. Each vector is ray-traced from its frontier cell through free cells, and through the unknown
///    cells outside the map's search space that are not below its floor (not obstacles for the
///    safe-view rule either), up to the sensor range and the workspace's edge (stopping at any other
///    cell), adding the void's volume to every cell.
/// 3. Cells outside the sensor's workspace are pruned: a box, a sphere, a user callback and/or a
///    capability map of the arm carrying the sensor (cells where each of the 8 voxels around them has a
///    reachability index at or below a threshold go). The arm's IK stays the final check of each pose (step 4).
/// 4. At the cells of highest utility, camera orientations are sampled around the mean direction
///    back along the vectors that reached the cell; each is scored by casting a coarse grid of rays
///    through the camera frustum (view_score.cpp: the visibility model below). A pose counts when
///    the camera sits in observed-free space and the arm (if given) has an IK solution for it whose
///    links are clear of the occupied (and, by default, the unknown) cells; the search stops after
///    `max_valid_poses` valid poses, ranked by the expected gain of NbvOptions::gain.
///
/// Visibility model: a ray's geometric weight starts at 1 and is multiplied by p after each unknown
/// cell it passes (a void cell, or an unknown cell of the search space: outside it the views so far
/// are taken to have seen what there is, so space no capture has reached there hides nothing), the
/// probability that an unknown cell lets the ray through: learned by the map from
/// what earlier rays did (ExplorationMap::void_pass_probability for void cells,
/// ExplorationMap::pass_probability for the other unknown cells), or fixed for both by
/// NbvOptions::unknown_pass_probability. With learned p (the default), the weight of a cell at
/// unknown depth d (d unknown cells crossed before it) is calibrated on what the views announced with
/// expect_view actually saw: the share of the cells at depth d (per class: void or not) that their
/// inserts turned known, non-increasing in d, blended with the geometric weight as the prior (worth
/// 30 cells per depth). Unknown space is not a medium of independent cells (an empty box lets rays
/// through all the way, a solid stops them at once), so the geometric weight alone under-expected
/// what views saw (median seen/expected 2.35). The ray stops at the first occupied cell. A depth camera
/// clears only the cells in front of the surface a ray returns from, so an unknown cell, void or not,
/// also counts with the chance that its ray returns at or behind it: 1 when the ray ends on an occupied
/// cell, else the chance that a void cell or an unknown cell of the search space from there on holds a
/// surface (1 - p for each, p of its class; none for a cell a ray that returned nothing has crossed); the
/// hull that makes a cell void is no surface (between objects on a table it holds open air). A cell met
/// by several rays counts once, with the largest weight: its expected visibility, times the cell's
/// seeability (1 unless views announced with expect_view expected it and missed, see there). Free
/// cells do not reduce the weight.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "octoreach/simulation.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

class Chain;
class CapabilityMap;

/// \brief What a view is scored by (and, for Frontiers and Unknown, where the search looks).
enum class NbvGain {
  FrontierVoid,  ///< the paper's: expected void cells (candidate cells from Algorithm 1)
  Frontiers,     ///< expected frontier cells in view (candidate cells traced back from the frontiers)
  Unknown,       ///< expected unknown cells of the search space in view, as nbvplanner's gain but counted only as
                 ///< far as a ray can return (ViewGains::expected_unknown; candidates as for Frontiers)
};
/// \brief "frontier_void", "frontiers" or "unknown".
const char* gain_name(NbvGain g);
/// \brief The gain of a name; \throws std::invalid_argument naming the three choices.
NbvGain gain_from_name(const std::string& name);

/// \brief How the search places a camera its chain carries.
enum class CameraAiming {
  Auto,    ///< LookAt for a chain of fewer than 5 joints (a camera position and optical axis are 5 constraints), else Pose
  Pose,    ///< IK of each candidate pose's position and optical axis (any roll): the camera goes where the search says
  LookAt,  ///< the chain aims the optical axis (+z) at target points (void or frontier cells); the position follows
};
/// \brief "auto", "pose" or "look_at".
const char* aiming_name(CameraAiming a);
/// \brief The aiming of a name; \throws std::invalid_argument naming the three choices.
CameraAiming aiming_from_name(const std::string& name);

/// \brief Where the sensor can be (map frame). Empty: everywhere.
struct SensorWorkspace {
  std::optional<Aabb> box;                                  ///< sensor positions inside this box
  std::optional<Eigen::Vector3d> sphere_center;             ///< and within sphere_radius of this point
  double sphere_radius = 0;
  /// Filter: one bool per position, each judged on its own (a batch of positions per call; a search may call it
  /// several times: with its candidate cells, and the loop's aimed looks with their eyes in chunks).
  std::function<std::vector<bool>(const std::vector<Eigen::Vector3d>&)> filter;
  /// \brief True when p (map frame) is inside the box and the sphere that are set (the filter is not asked).
  bool contains(const Eigen::Vector3d& p) const;
};

/// \brief Options of the next-best-view search.
struct NbvOptions {
  /// \brief The search's IK defaults: 8 restarts, 1 mm, 0.01 rad (a view need not be exact).
  static IkOptions default_ik() {
    IkOptions ik;
    ik.attempts = 8;
    ik.position_tolerance = 1e-3;
    ik.orientation_tolerance = 1e-2;
    return ik;
  }
  /// \brief The exploration loop's search (docs/design/next_best_view.md says why each value): 100 valid
  /// poses from the best 800 candidate cells, the best 16 by a coarse score scored in full (rescore_best), the
  /// camera 5 cm clear of surfaces, enclosed voids first (enclosure_power 2), the faces of voids that observed
  /// space shows first (unexposed_weight 0.2) and the ground an obstacle for the arm (ground_is_obstacle).
  static NbvOptions exploration_loop() {
    NbvOptions o;
    o.ground_is_obstacle = true;
    o.rescore_best = 16;
    o.max_valid_poses = 100;
    o.max_candidate_cells = 800;
    o.min_distance = 0.05;
    o.enclosure_power = 2.0;
    o.unexposed_weight = 0.2;
    return o;
  }
  int max_valid_poses = 50;          ///< N of the paper
  int orientations_per_cell = 8;     ///< sampled orientations per candidate cell
  double orientation_spread = 0.35;  ///< radians: cone around the mean utility direction
  int max_candidate_cells = 400;     ///< cells tried, best utility first (up to 8 such batches while no pose is valid)
  int score_width = 48, score_height = 36;  ///< coarse ray grid for scoring (not every pixel)
  /// With n > 0, next_best_view first scores every valid pose with a grid of half as many rays across and down
  /// (rounded up; a quarter of the ray casting) and only the n best by each ranking key (ranks_before) with the
  /// full grid: `ranked` holds those. choose_view's aimed looks do the same, checking IK in the coarse order
  /// until n are valid; more than 16 n poses are ranked first with every fourth ray and go on in chunks of
  /// 16 n in that order. 0 (the default): every valid pose is scored with the full grid, as in the paper. A
  /// chain that only aims its camera (looks_at), score_views and the baselines' sampled poses always score in
  /// full; frontier-void's views beyond the voids (ExploreOptions::beyond_voids) rank their sampled poses as the
  /// aimed looks do, with at most 2 scored in full.
  int rescore_best = 0;
  double min_distance = 0.0;         ///< keep the camera this far (m) from every point of an occupied cell
  std::uint64_t seed = 0;
  int threads = 0;
  SensorWorkspace workspace;
  /// Arm carrying the camera: its tip frame is the camera frame (+z forward); IK in Approach mode
  /// (position and optical axis; the roll the arm reaches is scored).
  const Chain* chain = nullptr;
  Pose chain_base = Pose::Identity();  ///< chain base frame -> map frame
  /// IK of each sampled pose (mode and approach axis are set by the search; restart seeds are
  /// ik.seed + the pose's index).
  IkOptions ik = default_ik();
  /// With a chain: reject IK solutions where a link the chain moves (its collision shapes; the rest of
  /// the robot at ik.reference, else at home, the robot placed so the chain base sits at chain_base) touches an occupied cell
  /// of the map (and, with unknown_is_obstacle, an unknown cell of the search space), or any link touches
  /// another link of the robot (self-collision, the robot's allowed pairs excepted). The links the chain
  /// does not move are not tested against the map: they do not move with the view, and a base standing on
  /// the floor touches the floor's cells in every configuration.
  bool arm_collisions = true;
  /// How views of a chain's camera are found: Auto (the default) aims a chain of fewer than 5 joints (a pan/tilt
  /// head, a torso lift under it) at target points and places the camera of any other by IK (looks_at).
  CameraAiming aiming = CameraAiming::Auto;
  /// LookAt: radians an aimed optical axis may miss its target by (a head at a joint limit still sees a target
  /// this near the image centre; the aim solver's own tolerance is 1 mrad).
  double look_at_tolerance = 0.1;
  /// Capability map of the arm carrying the camera (positions in its base link frame): candidate
  /// cells where each of the 8 voxels around them has reachability index D <= min_reachability are pruned
  /// before any IK (the map says no only where it is sure; IK decides between its voxels).
  const CapabilityMap* capability_map = nullptr;
  Pose capability_base = Pose::Identity();  ///< capability map base link frame -> map frame
  double min_reachability = 0.0;            ///< keep cells with a voxel around them of D > this (0: any reachable orientation)
  /// Also skip IK for sampled poses whose optical axis none of the 8 cells around them reaches
  /// (CapabilityLookup::any; only when the map's approach axis is the camera's +z).
  bool capability_orientations = true;
  /// What the views are ranked by (and, for Frontiers / Unknown, where candidate cells come from).
  NbvGain gain = NbvGain::FrontierVoid;
  /// p of the visibility model: the chance that an unknown cell lets a ray through. < 0: learned by
  /// the map (ExplorationMap::void_pass_probability() for void cells, pass_probability() for the
  /// others); in [0, 1]: fixed for both (1: unknown space is transparent, a ray returns only from a known
  /// surface).
  double unknown_pass_probability = -1.0;
  /// Safe views: unknown cells inside the map's search space (ExplorationOptions::search_lo/hi)
  /// count as obstacles for the arm's collision check (with arm_collisions) and the camera must sit
  /// in observed-free space: no unknown cell of the search space within unknown_margin of it. A cell no
  /// insert has reached is unknown (before the first insert, every cell of the search space); for the arm, a
  /// search space unbounded along some axis, or of more than 10^7 cells, counts only those within the box of
  /// the cells inserts have reached. The search space's cells are those that share volume with it. Unknown cells outside the search space (the robot's own body, space the camera never looks at)
  /// are not obstacles.
  bool unknown_is_obstacle = true;
  double unknown_margin = 0.05;  ///< metres around the camera that no unknown cell may reach into
  /// With a chain and arm_collisions: the ground is an obstacle for the links the chain moves (the links it
  /// does not move, a base standing on the floor, are not tested against it). The ground is the horizontal
  /// plane at the lower of the robot's root link (the robot stands on the ground) and the map's search
  /// space floor (ExplorationOptions::search_lo's z; the space searched lies above the ground). Unknown
  /// cells outside the search space are no obstacles otherwise, and a camera looking down could take the
  /// arm's wrist into a floor the map has not seen. On in exploration_loop().
  bool ground_is_obstacle = false;
  /// Enclosed voids first (gain FrontierVoid): each void cell also counts with e^enclosure_power in the
  /// ranking gain (ViewGains::expected_enclosed_void) and in its void's utility (step 1), e its
  /// enclosure: the share of the six axis directions that, walking from the cell through unknown
  /// cells up to enclosure_range, meet an occupied cell (1) rather than a free one (0; unknown to the
  /// range: 1/2). The inside of a box whose walls have been seen counts more than the shadow behind an
  /// object, where victims and objects do not hide. 0: the paper's plain count (every void cell 1).
  double enclosure_power = 0.0;
  double enclosure_range = 0.5;  ///< metres walked from a void cell per direction (enclosure_power > 0)
  /// Exposed voids first (gain FrontierVoid): a void cell none of whose 26 neighbours is observed free
  /// counts with this factor (in [0, 1]) in the ranking gain and in its void's utility, on top of its
  /// enclosure weight. A cell next to observed free space lies on the face of the void that observed space
  /// shows (the last slivers of an open crate: 83 % of them in paper scene 1 after the first view); one
  /// with no free neighbour lies behind other unknown cells (16 % of the inside of that scene's solid
  /// computer tower is exposed). 1: no such weight (the paper's count).
  double unexposed_weight = 1.0;
};

/// \brief True when the search aims options.chain at target points (CameraAiming::LookAt, or Auto and a chain of
/// fewer than 5 joints); false without a chain.
bool looks_at(const NbvOptions& options);

/// \brief What one camera pose sees under the visibility model (see the file comment).
struct ViewGains {
  std::size_t void_cells = 0;     ///< distinct void cells met before the first occupied cell (raw)
  std::size_t unknown_cells = 0;  ///< distinct unknown cells of the search space met (void cells included; raw)
  std::size_t frontier_cells = 0; ///< distinct frontier cells met (raw)
  /// void cells weighted by their expected visibility, each also by the chance that its ray returns at or behind
  /// it (a depth camera clears only the cells in front of what a ray returns from): 1 when the ray ends on an
  /// occupied cell, else the chance that an unknown cell of the voids or the search space from there on (not
  /// crossed by a ray that returned nothing) holds a surface, 1 - p_void for a void cell and 1 - p for another
  double expected_void = 0;
  /// unknown cells of the search space weighted likewise (void cells included)
  double expected_unknown = 0;
  double expected_frontier = 0;   ///< frontier cells weighted likewise
  /// expected_void with each void cell also weighted by its enclosure (NbvOptions::enclosure_power;
  /// equal to expected_void at power 0): the gain FrontierVoid ranks by.
  double expected_enclosed_void = 0;
  /// \brief The expected gain of kind g (expected_void, expected_frontier or expected_unknown).
  double gain(NbvGain g) const;
};

/// \brief One scored sensor configuration.
struct ViewCandidate : ViewGains {
  Pose pose = Pose::Identity();  ///< camera -> map
  double expected_gain = 0;      ///< the expected gain of NbvOptions::gain (the ranking key)
  double utility_dm3 = 0;        ///< expected_void as a volume, dm^3
  double cell_utility = 0;       ///< accumulated utility (m^3 summed over vectors) at its cell
  Eigen::VectorXd q;             ///< arm joints when a chain was given
};

/// \brief What views are ranked by: the expected gain of NbvOptions::gain (RankKey::Gain), or the plain
/// expected void cells (RankKey::ExpectedVoid, the figure the exploration loop stops on).
enum class RankKey { Gain, ExpectedVoid };
/// \brief "expected_gain" or "expected_void" (the ViewCandidate field ranked by).
const char* rank_key_name(RankKey k);
/// \brief The key of a name; \throws std::invalid_argument naming the two choices.
RankKey rank_key_from_name(const std::string& name);

/// \brief The one order of views: true when `a` ranks before `b`, by more of `key`, then by more expected
/// unknown cells (equal views keep their order). next_best_view ranks by it, and every choice among scored
/// views (NbvResult::best, ScoredViews::best) takes its first.
bool ranks_before(const ViewCandidate& a, const ViewCandidate& b, RankKey key = RankKey::Gain);

/// \brief Result of a search: valid poses ranked by ranks_before (the expected gain, then expected unknown
/// cells, then the order they were sampled in); with NbvOptions::rescore_best, only the ones scored in full.
struct NbvResult {
  std::vector<ViewCandidate> ranked;
  NbvGain gain = NbvGain::FrontierVoid;  ///< the gain the views are ranked by (NbvOptions::gain)
  double pass_probability = 1;      ///< p the visibility model used for unknown cells outside the voids
  double void_pass_probability = 1; ///< p it used for void cells
  std::size_t utility_vectors = 0;
  std::size_t utility_cells = 0;    ///< cells of the workspace's box and sphere with utility > 0 before pruning
  std::size_t candidate_cells = 0;  ///< after workspace and capability-map pruning (before the clearance check)
  std::size_t capability_pruned = 0;  ///< cells the capability map removed
  /// Poses checked and why they failed. The search checks poses in parallel batches and stops after the batch that
  /// completes max_valid_poses, so these counts (not the ranked views) depend on the number of threads.
  std::size_t poses_scored = 0, ik_failures = 0;
  std::size_t arm_collisions = 0;   ///< IK solutions rejected because the arm touches an occupied (or unknown) cell or itself
  std::size_t camera_not_clear = 0; ///< sampled poses whose camera is not in observed-free space
  std::size_t capability_rejected = 0;  ///< sampled poses the capability map ruled out before IK
  double seconds = 0;
  double seconds_vectors = 0, seconds_prune = 0, seconds_score = 0;  ///< parts: steps 1-2, 3, 4
  /// \brief Void cells (raw) of the best pose (0 when there is none).
  std::size_t best_void_cells() const { return ranked.empty() ? 0 : ranked.front().void_cells; }
  /// \brief Expected gain of the best pose (0 when there is none).
  double best_gain() const { return ranked.empty() ? 0.0 : ranked.front().expected_gain; }
  /// \brief Volume of the best pose's expected void cells, dm^3 (0 when there is none).
  double best_utility_dm3() const { return ranked.empty() ? 0.0 : ranked.front().utility_dm3; }
  /// \brief The first of the ranked views by ranks_before with `key` (nullptr when there is none).
  const ViewCandidate* best(RankKey key = RankKey::Gain) const;
};

/// \brief Accumulated utility per free cell (steps 1-2), before pruning.
std::vector<std::pair<CellKey, double>> accumulate_utility(const ExplorationMap& map, double sensor_range,
                                                           std::size_t* vectors = nullptr);

/// \brief Distinct void and unknown cells a camera at `pose` sees before the first occupied cell,
/// casting a score_width x score_height grid of rays over the field of view.
std::pair<std::size_t, std::size_t> view_utility(const ExplorationMap& map, const CameraIntrinsics& camera,
                                                 const Pose& pose, int score_width, int score_height);

/// \brief The gains of a camera at `pose` under the visibility model with pass probability p for
/// unknown cells outside the voids and p_void for void cells (score_width x score_height rays); with
/// `learned`, the map's learned visibility curve too (as next_best_view with unknown_pass_probability < 0,
/// p and p_void its prior).
/// \throws std::invalid_argument for a bad grid or a probability outside [0, 1].
ViewGains view_gains(const ExplorationMap& map, const CameraIntrinsics& camera, const Pose& pose, int score_width,
                     int score_height, double pass_probability, double void_pass_probability, bool learned = false);

/// \brief view_gains' answer with the pass probabilities the visibility model used.
struct ViewGainsResult : ViewGains {
  double pass_probability = 1;       ///< p for unknown cells outside the voids
  double void_pass_probability = 1;  ///< p for void cells
};
/// \brief The gains of a camera at `pose`: with `pass_probability`, that p for every unknown cell; without,
/// the map's learned model (its p, p_void and visibility curve, as next_best_view by default).
/// \throws std::invalid_argument for a bad grid or a probability outside [0, 1].
ViewGainsResult view_gains(const ExplorationMap& map, const CameraIntrinsics& camera, const Pose& pose,
                           int score_width, int score_height, std::optional<double> pass_probability);

/// \brief Announces the view the map's next insert comes from (the visibility model's memory of
/// misses): the unknown cells a camera at `pose` is expected to see (options' score grid and pass
/// probability) are recorded with their ray weights w; the next ExplorationMap::insert multiplies the
/// seeability s of each of them it leaves unknown by (1 - w). Every later view score counts an unknown
/// cell with w * s, so voids that views aimed at and did not see (behind unseen surfaces, inside
/// solids, in gaps too narrow for the rays) stop drawing views, and the loop can end. A void cell (or an
/// unknown cell of the search space) left
/// unknown though the rays still meet it in the updated map, with no occupied cell behind it within range
/// (the rays ended on nothing), also keeps the line of sight: later views from an eye within the angle one
/// cell spans from this one, and no nearer to it, count it 0. A second call replaces the announcement.
/// \throws std::invalid_argument for a bad option or a non-finite pose.
void expect_view(ExplorationMap& map, const CameraIntrinsics& camera, const Pose& pose, const NbvOptions& options);
/// \brief Unknown cells whose seeability a missed view has lowered (some may be known by now).
std::size_t missed_cells(const ExplorationMap& map);

/// \brief The enclosure e in [0, 1] of every void cell (sorted by key), as NbvOptions::enclosure_power
/// weighs it: the share of the six axis directions that, walking from the cell through unknown cells up
/// to `range` metres, meet an occupied cell (1) rather than a free cell (0); a direction that stays in
/// unknown space to the range counts 1/2. \throws std::invalid_argument for a range that is not > 0.
std::vector<std::pair<CellKey, double>> void_enclosure(const ExplorationMap& map, double range = 0.5);

/// \brief For each cell key, whether one of its 26 neighbours is observed free: the exposure that
/// NbvOptions::unexposed_weight weighs (a void cell on the face of the void that observed space shows).
std::vector<bool> exposed_cells(const ExplorationMap& map, const std::vector<CellKey>& keys);

/// \brief The visibility curve a map learned from its announced views (see the file comment), per
/// class (index 0: unknown cells outside the voids, 1: void cells) and unknown depth d (the last
/// entry holds the deeper cells too): the cells views expected (weighted by their seeability; a cell a
/// view counted 0 for a line that returned nothing is left out), the
/// ones their inserts turned known, and the learned non-increasing share.
struct VisibilityCurveTable {
  std::vector<double> expected[2], seen[2], share[2];
};
VisibilityCurveTable visibility_curve(const ExplorationMap& map);

/// \brief The full search (steps 1-4).
NbvResult next_best_view(const ExplorationMap& map, const CameraIntrinsics& camera, const NbvOptions& options);

/// \brief Why score_views counts a pose as a view or not (the checks in this order).
enum class ViewStatus {
  Valid,
  OutsideWorkspace,  ///< the camera position is outside workspace box / sphere / filter
  NotReachable,      ///< the capability map rules out the position (D <= min_reachability) or the axis
  CameraNotClear,    ///< camera cell not free, an occupied cell within min_distance, or (unknown_is_obstacle)
                     ///< an unknown cell of the search space within unknown_margin
  NoIk,              ///< the chain has no IK solution (a chain that aims: it cannot aim at the pose's point)
  ArmCollision,      ///< every IK solution found touches an occupied (or unknown, see NbvOptions) cell
};
/// \brief "valid", "outside_workspace", "not_reachable", "camera_not_clear", "no_ik", "arm_collision".
const char* status_name(ViewStatus s);

/// \brief One pose scored by score_views: its gains (of the pose the arm reaches when it does, else of
/// the given pose), the ranking gain, the joints (with a chain and IK) and the status.
struct ScoredView : ViewCandidate {
  ViewStatus status = ViewStatus::Valid;
  bool valid() const { return status == ViewStatus::Valid; }
};

/// \brief What score_views returns: one ScoredView per given pose, in their order.
struct ScoredViews {
  std::vector<ScoredView> views;
  NbvGain gain = NbvGain::FrontierVoid;  ///< the gain expected_gain is of (NbvOptions::gain)
  double pass_probability = 1;           ///< p the visibility model used for unknown cells outside the voids
  double void_pass_probability = 1;      ///< p it used for void cells
  std::size_t dof = 0;                   ///< joints of the chain (0: no chain)
  /// \brief The first valid view by ranks_before with `key` (nullptr when none is valid).
  const ScoredView* best(RankKey key = RankKey::Gain) const;
};

/// \brief The gains and validity of given camera poses (camera -> map), with the very checks and ray
/// casting of next_best_view (workspace, capability map, camera clearance, IK with the chain at
/// chain_base, arm collisions; samples, candidate counts, max_valid_poses and rescore_best play no part). Poses are
/// scored in parallel; pose i uses IK seed ik.seed + i. A chain that can only aim its camera (looks_at)
/// aims it at the point half the camera's range along pose i's optical axis (aim seed seed + i; NoIk, checked
/// first, when it cannot) and the checks and the score are of the pose it reaches, which is the view's pose
/// and q whenever the aim succeeds, valid or not. `score_invalid` false: the poses that
/// fail a check are not ray cast (their cell counts 0, expected gains NaN), far less work when most fail.
/// \throws std::invalid_argument for a non-finite pose.
ScoredViews score_views(const ExplorationMap& map, const CameraIntrinsics& camera, const std::vector<Pose>& poses,
                        const NbvOptions& options, bool score_invalid = true);

/// \brief The exploration loop's settings (octoreach.exploration.explore; docs/design/next_best_view.md says
/// why each value): the search of every view, the budget and stopping rule, and how the loop chooses a view
/// beyond the search (the second look, the last chance, the baselines' sampled poses).
struct ExploreOptions {
  /// The search of every view; its seed is the run's (the map's; view k searches with seed + k).
  NbvOptions search = NbvOptions::exploration_loop();
  /// View budget: a safety net; the stop rule ends a run (the longest benchmark runs end after about 65 views).
  int max_views = 100;
  /// Stop when the chosen view's utility (its strategy's gain) has been <= min_utility for `patience`
  /// views in a row, or is 0. Unset (the default): the threshold follows from the sensor and the cell size
  /// (stop_threshold). 0 with patience 1 is the paper's rule (utility 0).
  std::optional<double> min_utility;
  int patience = 3;
  bool second_look = true;     ///< frontier_void: aimed poses are scored on every view too, the better view taken
  bool learn_misses = true;    ///< each view is announced before its insert (expect_view)
  bool physical_check = true;  ///< with a robot: a view whose arm touches the scene is not taken
  double failed_view_radius = 0.1;  ///< metres: no view is chosen this near the camera of a view not taken
  int sampled_poses = 200;          ///< baselines: camera poses sampled per view and base
  double min_camera_height = 0.05;  ///< metres: sampled and aimed cameras stay above this height
  int aimed_poses = 400;            ///< second look: poses aimed at void cells, per base
  std::pair<double, double> aimed_distance{0.3, 1.0};  ///< metres from an aimed pose's eye to its void cell
  double unexposed_share = 0.25;    ///< share of the void cells with no observed free neighbour among the aims
  int low_aimed_poses = 1200;       ///< before a low view is taken: this many more, aimed at any void cell
  /// last chance (the choice would end the loop): rays out of each void cell, half of them through the voids'
  /// gates (observed-free cells with a void cell across a face)
  int last_directions = 128;
  /// last chance: poses kept from those rays (most of its cost: the rays walked until it has them, then a score
  /// and IK each in rank order until rescore_best are valid)
  int last_poses = 1000;
  std::pair<double, double> last_distance{0.15, 1.0};  ///< metres from a last-chance eye to its void cell
  /// last chance: void cells the rays leave from, and gates they pass (each at most; drawn at random)
  int max_ray_cells = 4096;
  /// frontier_void: a view beyond the voids (toward the unknown cells of the search space outside the hull of the
  /// occupied cells; ViewChoice::beyond) where it expects more unknown cells of the search space (void cells
  /// included) than frontier-void's view expects void cells, and where frontier-void's own choice would end the
  /// loop. On (the default): a table top's layer above the objects is seen, as the rest of the search space is;
  /// off: the paper's voids only, and the loop ends when they are spent.
  bool beyond_voids = true;
  /// \brief The exploration benchmark's settings: the defaults (the stop rule every entry point uses).
  static ExploreOptions benchmark() { return ExploreOptions(); }
  /// \brief The paper's rule: stop at the first chosen view with utility 0.
  static ExploreOptions paper_stop() {
    ExploreOptions o;
    o.min_utility = 0.0;
    o.patience = 1;
    return o;
  }
  /// \brief min_utility, or when unset the void cells a view must be expected to see to be worth taking:
  /// score_width x score_height x resolution / max_range, the cells its score rays would meet if one cell in
  /// every max_range / resolution cells along them were void (10.8 for the default 48 x 36 grid, 2.5 cm
  /// cells and a 4 m sensor).
  double stop_threshold(const CameraIntrinsics& camera, double resolution) const;
  /// \brief \throws std::invalid_argument naming the first bad setting (the search's are checked by the search).
  void validate() const;
};

}  // namespace octoreach
