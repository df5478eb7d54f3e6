// What makes a camera pose a view: camera clearance (observed-free space), the capability map's axis,
// IK and the arm's collisions against the occupied and (safe views) unknown cells; the loop's options'
// checks and the names of statuses and aimings.
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

#include <octomap/OcTree.h>

#include "collision/detail.hpp"
#include "exploration/cell_sets.hpp"
#include "common/thread_pool.hpp"
#include "exploration/exploration_state.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/orientation_set.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/simulation.hpp"
#include "exploration/view_score.hpp"
#include "exploration/look_at_views.hpp"

namespace octoreach {

namespace detail {

namespace {

// The key of the cell that holds coordinate x along an axis (OctoMap's: floor(x / res) + 32768), clamped into the
// key range; in doubles, so that a coordinate far outside the map cannot overflow an integer.
std::uint32_t clamped_key(double x, double res) {
  return std::uint32_t(std::clamp(std::floor(x / res) + 32768.0, 0.0, 65535.0));
}

// Key box of the search space: the cells that share volume with it (a cell that only touches a face is out), every
// key along an unbounded axis. Empty for a space thinner than a cell between two faces.
SpaceKeys space_cells(double res, const ExplorationOptions& o) {
  SpaceKeys box;
  for (int a = 0; a < 3; ++a) {
    if (!open_below(o.search_lo[a])) box.lo[a] = clamped_key(o.search_lo[a], res);
    if (open_above(o.search_hi[a])) continue;
    const double top = std::ceil(o.search_hi[a] / res) - 1.0 + 32768.0;  // (below the key range: no cell)
    if (top < 0) return SpaceKeys::none();
    box.hi[a] = std::uint32_t(std::min(top, 65535.0));
  }
  return box;
}

// A bounded search space's box of more cells than this is clipped to the known cells for the arm's obstacles, as an
// unbounded one is: turning the box's unknown cells into an octree takes about 0.3 s per million cells (before the
// first insert, when all are unknown), at every map version.
constexpr double kArmBoxCells = 1e7;

// The key box of the search space's cells whose unknown ones are the arm's obstacles: the whole of `space` (the
// search space's cells) when the search space is bounded and not larger than kArmBoxCells, else `space` clipped to
// the bounding box of the known cells (an unbounded search space would hold infinitely many unknown cells).
SpaceKeys arm_cells(const ExplorationState& s, const ExplorationOptions& o, const SpaceKeys& space) {
  if (space.empty()) return space;
  double cells = 1;
  for (int a = 0; a < 3; ++a) cells *= double(space.hi[a]) - double(space.lo[a]) + 1.0;
  if (bounded_search_space(o) && cells <= kArmBoxCells) return space;
  if (s.tree.size() == 0) return SpaceKeys::none();
  double b[6];
  {
    std::lock_guard<std::mutex> lock(s.cache_mutex);
    if (s.bounds_generation != s.generation) {
      s.tree.getMetricMin(s.tree_bounds[0], s.tree_bounds[1], s.tree_bounds[2]);
      s.tree.getMetricMax(s.tree_bounds[3], s.tree_bounds[4], s.tree_bounds[5]);
      s.bounds_generation = s.generation;
    }
    std::copy(s.tree_bounds, s.tree_bounds + 6, b);
  }
  SpaceKeys box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = std::max<std::uint32_t>(space.lo[a], s.tree.coordToKey(b[a]));
    box.hi[a] = std::min<std::uint32_t>(space.hi[a], s.tree.coordToKey(b[a + 3]));
  }
  return box;
}

// The unknown cells of the key box lo..hi as an octree, and their count: made once per map version (every
// search of a choice checks its arm against the same cells).
std::pair<std::shared_ptr<octomap::OcTree>, std::size_t> unknown_cells_tree(const ExplorationState& S, double res,
                                                                            const std::uint32_t lo[3],
                                                                            const std::uint32_t hi[3]) {
  std::lock_guard<std::mutex> lock(S.cache_mutex);
  const std::uint32_t box[6] = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
  if (S.unknown_tree_generation == S.generation && std::equal(box, box + 6, S.unknown_tree_box))
    return {S.unknown_tree, S.unknown_tree_cells};
  auto tree = std::make_shared<octomap::OcTree>(res);
  std::size_t cells = 0;
  GridReader g(S.grid);
  for (std::uint32_t z = lo[2]; z <= hi[2]; ++z)
    for (std::uint32_t y = lo[1]; y <= hi[1]; ++y)
      for (std::uint32_t x = lo[0]; x <= hi[0]; ++x)
        if ((g.get(pack_key(x, y, z)) & kStateMask) == std::uint8_t(CellState::Unknown)) {
          tree->updateNode(octomap::OcTreeKey(octomap::key_type(x), octomap::key_type(y), octomap::key_type(z)), true,
                           true);
          ++cells;
        }
  if (cells) {
    tree->updateInnerOccupancy();
    tree->prune();
  }
  S.unknown_tree = tree;
  S.unknown_tree_cells = cells;
  std::copy(box, box + 6, S.unknown_tree_box);
  S.unknown_tree_generation = S.generation;
  return {tree, cells};
}

}  // namespace

void validate_options(const CameraIntrinsics& cam, const NbvOptions& opt) {
  cam.validate();
  check_rigid(opt.chain_base, "chain_base");
  check_rigid(opt.capability_base, "capability_base");
  if (opt.chain && opt.chain->dof() == 0)
    throw std::invalid_argument("chain " + opt.chain->base_link() + " -> " + opt.chain->tip_link() +
                                " has no movable joint: it can neither move nor aim the camera (pass no chain for a "
                                "camera placed freely, or a chain that ends at the camera link)");
  if (opt.max_valid_poses <= 0 || opt.orientations_per_cell <= 0 || opt.max_candidate_cells <= 0)
    throw std::invalid_argument("max_valid_poses, orientations_per_cell and max_candidate_cells must be positive");
  const std::uint64_t poses = std::uint64_t(opt.max_candidate_cells) * std::uint64_t(opt.orientations_per_cell);
  if (poses > limits::kViewCandidates || std::uint64_t(opt.max_valid_poses) > limits::kViewCandidates)
    throw std::invalid_argument("max_candidate_cells x orientations_per_cell (" + std::to_string(poses) +
                                ") and max_valid_poses (" + std::to_string(opt.max_valid_poses) +
                                ") must be at most " + std::to_string(limits::kViewCandidates));
  if (opt.rescore_best < 0)
    throw std::invalid_argument("rescore_best must be >= 0 (0: every valid pose scored with the full grid), got " +
                                std::to_string(opt.rescore_best));
  if (!(opt.orientation_spread >= 0) || !std::isfinite(opt.orientation_spread))
    throw std::invalid_argument("orientation_spread must be a finite number >= 0, got " +
                                std::to_string(opt.orientation_spread));
  if (!(opt.min_distance >= 0) || !std::isfinite(opt.min_distance))
    throw std::invalid_argument("min_distance must be a finite number of metres >= 0, got " +
                                std::to_string(opt.min_distance));
  if (!(opt.min_reachability >= 0 && opt.min_reachability < 1))
    throw std::invalid_argument("min_reachability must be in [0, 1), got " + std::to_string(opt.min_reachability));
  if (opt.unknown_pass_probability > 1 || std::isnan(opt.unknown_pass_probability))
    throw std::invalid_argument("unknown_pass_probability must be in [0, 1] (or < 0: learned by the map), got " +
                                std::to_string(opt.unknown_pass_probability));
  if (!(opt.unknown_margin >= 0) || !std::isfinite(opt.unknown_margin))
    throw std::invalid_argument("unknown_margin must be a non-negative number of metres");
  if (!(opt.enclosure_power >= 0) || !std::isfinite(opt.enclosure_power))
    throw std::invalid_argument("enclosure_power must be a finite number >= 0, got " + std::to_string(opt.enclosure_power));
  if (!(opt.unexposed_weight >= 0 && opt.unexposed_weight <= 1))
    throw std::invalid_argument("unexposed_weight must be a number in [0, 1], got " + std::to_string(opt.unexposed_weight));
  if (!(opt.enclosure_range > 0) || !std::isfinite(opt.enclosure_range))
    throw std::invalid_argument("enclosure_range must be a positive number of metres, got " +
                                std::to_string(opt.enclosure_range));
  if (!(opt.ik.position_tolerance > 0) || !std::isfinite(opt.ik.position_tolerance) ||
      !(opt.ik.orientation_tolerance > 0) || !std::isfinite(opt.ik.orientation_tolerance))
    throw std::invalid_argument("ik_position_tolerance and ik_orientation_tolerance must be positive finite numbers, "
                                "got " + std::to_string(opt.ik.position_tolerance) + " and " +
                                std::to_string(opt.ik.orientation_tolerance));
  if (!(opt.look_at_tolerance > 0 && opt.look_at_tolerance < kPi))
    throw std::invalid_argument("look_at_tolerance must be a number of radians in (0, pi), got " +
                                std::to_string(opt.look_at_tolerance));
  if (opt.score_width <= 0 || opt.score_height <= 0)
    throw std::invalid_argument("score_width and score_height must be positive");
  if (std::uint64_t(opt.score_width) * std::uint64_t(opt.score_height) > limits::kImagePixels)
    throw std::invalid_argument("score_width x score_height must be at most " + std::to_string(limits::kImagePixels) +
                                " rays, got " + std::to_string(opt.score_width) + " x " + std::to_string(opt.score_height));
}

ViewChecker::ViewChecker(const ExplorationMap& map, const NbvOptions& opt) : map_(map), opt_(opt) {
  ik_ = opt.ik;
  ik_.mode = IkMode::Approach;
  ik_.approach_axis = Eigen::Vector3d::UnitZ();
  base_inv_ = opt.chain_base.inverse();
  cap_inv_ = opt.capability_base.inverse();
  // The map's directions are the camera's optical axis (+z of the tip frame) when its approach axis is +z.
  const bool optical_axis =
      opt.capability_map && opt.capability_map->approach_axis().isApprox(Eigen::Vector3d::UnitZ(), 1e-9);
  cap_orient_ = optical_axis && opt.capability_orientations;
  // The map's solutions seed IK when they are the chain's (the same links, the optical axis as the approach
  // axis) and its frame is the chain's base.
  map_seeds_ = optical_axis && opt.chain && opt.capability_map->has_solutions() &&
               opt.capability_map->base_link() == opt.chain->base_link() &&
               opt.capability_map->tip_link() == opt.chain->tip_link() &&
               opt.capability_map->dof() == opt.chain->dof() && opt.capability_base.isApprox(opt.chain_base, 1e-12);
  const ExplorationState& S = state(map);
  space_ = space_cells(map.resolution(), map.options());
  arm_box_ = opt.unknown_is_obstacle ? arm_cells(S, map.options(), space_) : SpaceKeys::none();
  if (!opt.chain || !opt.arm_collisions) return;
  const Robot& robot = opt.chain->robot();
  obstacles_.emplace();  // with no cell known yet, the arm is still checked against itself
  // the joints off the chain stand where its IK checks self-collision: ik.reference, else home
  reference_ = opt.ik.reference.size() ? opt.ik.reference : robot.home();
  if (reference_.size() != robot.dof())
    throw std::invalid_argument("reference must hold the robot's " + std::to_string(robot.dof()) +
                                " joint values, got " + std::to_string(reference_.size()));
  robot_root_ = opt.chain_base * robot.link_poses(reference_)[robot.link_index(opt.chain->base_link())].inverse();
  // Only the links the chain moves are tested against the map (as the loop's physical check and the oracle
  // do): the others do not move with the view, and a base standing on the floor touches the floor's
  // occupied cells in every configuration (example-robot-data's xArm 7: no valid view once a view had seen
  // the floor under it).
  moved_links_ = opt.chain->moved_collision_links();
  const ExplorationOptions& mo = map.options();
  if (opt.ground_is_obstacle) {
    // The ground lies at or below the robot's root link (the robot stands on it) and at or below the search
    // space's floor (the space searched lies above it; -1e9: no search space): the lower of the two. A slab
    // 1 m deep with that top, 100 m across around the chain's base.
    const double search_floor =
        open_below(mo.search_lo.z()) ? std::numeric_limits<double>::infinity() : mo.search_lo.z();
    const double top = std::min(robot_root_.translation().z(), search_floor);
    constexpr double kSide = 100.0, kDepth = 1.0;
    Pose slab = Pose::Identity();
    slab.translation() = Eigen::Vector3d(opt.chain_base.translation().x(), opt.chain_base.translation().y(),
                                         top - kDepth / 2);
    ground_.emplace();
    ground_->add_box(Eigen::Vector3d(kSide, kSide, kDepth), slab);
  }
  // The map's occupied cells (the tree is not copied: the map outlives the search).
  if (S.tree.size() != 0)
    obstacles_->add_octree(std::shared_ptr<const octomap::OcTree>(&map.octree(), [](const octomap::OcTree*) {}));
  if (!arm_box_.empty()) {
    std::tie(unknown_tree_, unknown_cells_) = unknown_cells_tree(S, map.resolution(), arm_box_.lo, arm_box_.hi);
    if (unknown_cells_) obstacles_->add_octree(unknown_tree_);
  }
}

ViewChecker::~ViewChecker() = default;

bool ViewChecker::camera_clear(const Eigen::Vector3d& p) const {
  const double res = map_.resolution();
  CellKey c;
  try {
    c = map_.key_of(p);
  } catch (const std::invalid_argument&) {
    return false;
  }
  GridReader g(state(map_).grid);
  const std::uint8_t own = g.get(c) & kStateMask;
  if (own == std::uint8_t(CellState::Occupied)) return false;
  if (own == std::uint8_t(CellState::Unknown) && opt_.unknown_is_obstacle && space_.contains(c)) return false;
  // A cell is within a margin of the camera when any point of it is: the map knows only that a surface (or unseen
  // space) lies somewhere in the cell, so this is the rule that keeps the margin to every surface the cells allow,
  // at any cell size. The whole cube of cells around the camera's cell would keep it up to sqrt(3) times the margin
  // rounded up to whole cells from some surfaces and refuse the views through a box's opening that the rule allows.
  const double occ2 = opt_.min_distance * opt_.min_distance;
  const double unk2 = opt_.unknown_is_obstacle ? opt_.unknown_margin * opt_.unknown_margin : 0.0;
  // a cell k steps away along an axis is at least (k - 1) cells from any point of the camera's cell
  const int m = int(std::ceil(std::sqrt(std::max(occ2, unk2)) / res - 1e-9));
  const Eigen::Vector3d off = p - map_.center(c);
  for (int dz = -m; dz <= m; ++dz)
    for (int dy = -m; dy <= m; ++dy)
      for (int dx = -m; dx <= m; ++dx) {
        // the camera's distance to the cell (dx, dy, dz): to the nearest point of its cube
        const Eigen::Vector3d gap = ((Eigen::Vector3d(dx, dy, dz) * res - off).cwiseAbs().array() - res / 2).max(0.0);
        const double d2 = gap.squaredNorm();
        if (!(d2 < occ2) && !(d2 < unk2)) continue;
        CellKey nb;
        if (!neighbour(c, dx, dy, dz, nb)) continue;
        const std::uint8_t s = g.get(nb) & kStateMask;
        if (s == std::uint8_t(CellState::Occupied) && d2 < occ2) return false;
        if (s == std::uint8_t(CellState::Unknown) && d2 < unk2 && space_.contains(nb)) return false;
      }
  return true;
}

bool ViewChecker::axis_reachable(const Pose& pose) const {
  return !cap_orient_ || opt_.capability_map->reachable(cap_inv_ * pose, CapabilityLookup::any);
}

std::vector<Eigen::Vector3d> ViewChecker::turned_axes(const Eigen::Vector3d& axis, double max_turn) const {
  if (!cap_orient_ || !(max_turn > 0)) return {};
  const OrientationSet& set = opt_.capability_map->orientations();
  const Eigen::Vector3d a = cap_inv_.linear() * axis;
  const double min_cos = std::cos(max_turn);
  std::vector<std::pair<double, int>> near;
  for (int d = 0; d < set.directions(); ++d)
    if (const double c = set.direction(d).dot(a); c >= min_cos) near.emplace_back(-c, d);
  std::sort(near.begin(), near.end());
  std::vector<Eigen::Vector3d> out;
  out.reserve(near.size());
  for (const auto& [c, d] : near) out.push_back(opt_.capability_base.linear() * set.direction(d));
  return out;
}

std::optional<Eigen::Vector3d> ViewChecker::reachable_axis(const Eigen::Vector3d& eye, const Eigen::Vector3d& axis,
                                                           const std::vector<Eigen::Vector3d>& turned) const {
  if (axis_reachable(camera_pose(eye, axis, 0.0))) return axis;
  for (const Eigen::Vector3d& w : turned)
    if (axis_reachable(camera_pose(eye, w, 0.0))) return w;
  return std::nullopt;
}

std::optional<Eigen::VectorXd> ViewChecker::map_seed(const Pose& pose) const {
  if (!map_seeds_) return std::nullopt;
  const CapabilityMap& m = *opt_.capability_map;
  const Pose P = cap_inv_ * pose;
  return m.solution(P.translation(), m.orientations().nearest(P.linear(), m.approach_axis()));
}

std::vector<Eigen::VectorXd> ViewChecker::between_cells_seeds(const Pose& pose) const {
  if (!map_seeds_ || !cap_orient_) return {};
  const CapabilityMap& m = *opt_.capability_map;
  const Pose P = cap_inv_ * pose;
  if (m.reachable(P, CapabilityLookup::vote)) return {};
  const int o = m.orientations().nearest(P.linear(), m.approach_axis());
  std::uint32_t records[8];
  double weights[8];
  m.corners(P.translation(), records, weights);
  std::vector<std::pair<double, const float*>> found;
  for (int k = 0; k < 8; ++k)
    if (records[k] != DenseIndex::kNone)
      if (const float* q = m.record_solution(records[k], o)) found.emplace_back(-weights[k], q);
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Eigen::VectorXd> out;
  for (const auto& f : found) out.push_back(Eigen::Map<const Eigen::VectorXf>(f.second, m.dof()).cast<double>());
  return out;
}

ViewStatus ViewChecker::reach(Pose& pose, Eigen::VectorXd& q_out, std::size_t seed_offset) const {
  IkOptions o = ik_;
  o.seed = ik_.seed + seed_offset;
  const Pose target = base_inv_ * pose;
  std::optional<Eigen::VectorXd> q;
  // Between the map's cells where its vote says no (the cells around the pose disagree): one descent from each
  // reachable cell's solution, nearest first, up to ik.attempts descents, decides, as CertifiedLookup does. Random
  // restarts there cost a failed descent each for poses the arm mostly cannot reach.
  const std::vector<Eigen::VectorXd> between = between_cells_seeds(pose);
  if (!between.empty()) {
    IkOptions one = o;
    one.attempts = 1;
    const std::size_t tries = std::min(between.size(), std::size_t(std::max(1, o.attempts)));
    for (std::size_t i = 0; i < tries && !q; ++i) q = opt_.chain->ik(target, one, &between[i]);
  } else if (std::optional<Eigen::VectorXd> start = map_seed(pose); start && o.attempts > 1) {
    // The first random start, then (when it fails) the capability map's solution of the pose's cell before the
    // other random starts: a first start that succeeds finds what an unseeded call finds, so the IK branches the
    // random starts reach (some clear of the surfaces where the map's is not) stay on offer.
    IkOptions first = o;
    first.attempts = 1;
    q = opt_.chain->ik(target, first);
    if (!q) {
      IkOptions rest = o;
      rest.attempts = o.attempts - 1;
      rest.seed = o.seed ^ 0x5EEDULL;  // restarts other than the first start's
      q = opt_.chain->ik(target, rest, &*start);
    }
  } else {
    q = opt_.chain->ik(target, o);
  }
  if (!q) return ViewStatus::NoIk;
  const ViewStatus st = arm_clear(*q);
  if (st != ViewStatus::Valid) return st;
  q_out = *q;
  pose = opt_.chain_base * opt_.chain->fk(*q);  // the roll the arm actually reaches
  return ViewStatus::Valid;
}

bool ViewChecker::cells_near(const Shape& shape, const Pose& world) const {
  // The obstacles are octrees of those cells, and FCL tests only their occupied leaves, each a box of whole cells,
  // against the shape: a box can touch it only where it meets the shape's world box, widened by 0.1 mm for the
  // narrow phase's tolerance (1e-6 m) and the rounding of the keys.
  constexpr double kMargin = 1e-4;
  constexpr std::uint64_t kMaxCells = 8192;  // a larger box: FCL's own traversal decides
  const fcl::AABBd box = world_aabb(*shape.geometry, world);
  const double res = map_.resolution();
  std::uint32_t lo[3], hi[3];
  std::uint64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double l = box.min_[a] - kMargin, h = box.max_[a] + kMargin;
    if (!(l <= h)) return true;  // not a box (NaN): FCL's own check decides
    lo[a] = clamped_key(l, res);  // (no cell lies beyond the key range)
    hi[a] = clamped_key(h, res);
    cells *= hi[a] - lo[a] + 1;
  }
  if (cells > kMaxCells) return true;
  GridReader g(state(map_).grid);
  for (std::uint32_t z = lo[2]; z <= hi[2]; ++z)
    for (std::uint32_t y = lo[1]; y <= hi[1]; ++y)
      for (std::uint32_t x = lo[0]; x <= hi[0]; ++x) {
        const CellKey k = pack_key(x, y, z);
        const std::uint8_t s = g.get(k) & kStateMask;
        if (s == std::uint8_t(CellState::Occupied)) return true;
        if (s == std::uint8_t(CellState::Unknown) && unknown_cells_ && arm_box_.contains(k)) return true;
      }
  return false;
}

ViewStatus ViewChecker::arm_clear(const Eigen::VectorXd& q) const {
  // The links the arm moves against the map's occupied (and, safe views, unknown) cells; the robot against itself.
  if (!obstacles_ && !ground_) return ViewStatus::Valid;
  const Robot& robot = opt_.chain->robot();
  thread_local std::vector<Pose> poses;
  robot.link_poses(opt_.chain->to_robot_configuration(q, reference_), poses);
  if (obstacles_) {
    // FCL only for the shapes with one of the obstacles' cells in their box: a link away from every such cell needs
    // none.
    for (int li : moved_links_)
      for (const Shape& s : robot.links()[li].shapes) {
        const Pose world = robot_root_ * poses[li] * s.origin;
        if (cells_near(s, world) && obstacles_->collides(*s.geometry, world)) return ViewStatus::ArmCollision;
      }
    if (robot.in_self_collision_poses(poses)) return ViewStatus::ArmCollision;
  }
  if (ground_ && robot.links_in_collision(poses, *ground_, robot_root_, &moved_links_))
    return ViewStatus::ArmCollision;
  return ViewStatus::Valid;
}

}  // namespace detail

const char* aiming_name(CameraAiming a) {
  switch (a) {
    case CameraAiming::Auto: return "auto";
    case CameraAiming::Pose: return "pose";
    case CameraAiming::LookAt: return "look_at";
  }
  return "?";
}

CameraAiming aiming_from_name(const std::string& name) {
  for (CameraAiming a : {CameraAiming::Auto, CameraAiming::Pose, CameraAiming::LookAt})
    if (name == aiming_name(a)) return a;
  throw std::invalid_argument("unknown aiming '" + name + "'; choose one of auto, pose, look_at");
}

bool looks_at(const NbvOptions& o) {
  if (!o.chain) return false;
  // 3 position and 2 axis constraints place a camera (any roll): fewer joints can only aim it
  return o.aiming == CameraAiming::LookAt || (o.aiming == CameraAiming::Auto && o.chain->dof() < 5);
}

void ExploreOptions::validate() const {
  const auto bad = [](const std::string& what, const std::string& got) {
    throw std::invalid_argument(what + ", got " + got);
  };
  if (max_views < 1) bad("max_views must be an integer >= 1", std::to_string(max_views));
  if (min_utility && (!(*min_utility >= 0) || !std::isfinite(*min_utility)))
    bad("min_utility must be a finite number >= 0 (or None: derived from the sensor)", std::to_string(*min_utility));
  if (patience < 1) bad("patience must be an integer >= 1", std::to_string(patience));
  if (sampled_poses < 1) bad("sampled_poses (explore's candidates) must be an integer >= 1", std::to_string(sampled_poses));
  if (aimed_poses < 0 || low_aimed_poses < 0 || last_poses < 0 || last_directions < 1 || max_ray_cells < 1)
    bad("aimed_poses, low_aimed_poses and last_poses must be >= 0, last_directions and max_ray_cells >= 1",
        std::to_string(aimed_poses) + ", " + std::to_string(low_aimed_poses) + ", " + std::to_string(last_poses) +
            ", " + std::to_string(last_directions) + ", " + std::to_string(max_ray_cells));
  if (!(unexposed_share >= 0 && unexposed_share <= 1))
    bad("unexposed_share must be in [0, 1]", std::to_string(unexposed_share));
  for (const auto& [name, d] : {std::pair{"aimed_distance", aimed_distance}, std::pair{"last_distance", last_distance}})
    if (!(d.first >= 0 && d.first <= d.second) || !std::isfinite(d.second))
      bad(std::string(name) + " must be (min, max) metres with 0 <= min <= max",
          "(" + std::to_string(d.first) + ", " + std::to_string(d.second) + ")");
  if (!(failed_view_radius >= 0) || !std::isfinite(failed_view_radius))
    bad("failed_view_radius must be a finite number of metres >= 0", std::to_string(failed_view_radius));
  if (!std::isfinite(min_camera_height)) bad("min_camera_height must be finite", std::to_string(min_camera_height));
}

double ExploreOptions::stop_threshold(const CameraIntrinsics& camera, double resolution) const {
  if (!(resolution > 0) || !std::isfinite(resolution))
    throw std::invalid_argument("resolution must be a positive finite number of metres, got " + std::to_string(resolution));
  if (min_utility) return *min_utility;
  return double(search.score_width) * double(search.score_height) * resolution / camera.max_range;
}

const char* status_name(ViewStatus s) {
  switch (s) {
    case ViewStatus::Valid: return "valid";
    case ViewStatus::OutsideWorkspace: return "outside_workspace";
    case ViewStatus::NotReachable: return "not_reachable";
    case ViewStatus::CameraNotClear: return "camera_not_clear";
    case ViewStatus::NoIk: return "no_ik";
    case ViewStatus::ArmCollision: return "arm_collision";
  }
  return "?";
}

}  // namespace octoreach
