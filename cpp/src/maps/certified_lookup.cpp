#include "octoreach/certified_lookup.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "octoreach/arm.hpp"
#include "kinematics/chain_checks.hpp"
#include "maps/batch.hpp"

namespace octoreach {
namespace {

// Two configurations within this of each other in every joint (rad; continuous joints compared modulo 2 pi, metres
// for a prismatic joint) descend into the same IK branch: a seed that close to one already tried adds nothing.
constexpr double kSameBranch = 1.0;
// The directions whose cells may store other branches: within this many direction spacings (sqrt(4 pi / K) for K
// directions) of the pose's approach direction.
constexpr double kBranchCone = 2.0;

const CapabilityMap& usable(const CapabilityMap& map, const Robot& robot) {
  if (!map.has_cell_data() || !map.has_solutions())
    throw std::invalid_argument(
        std::string("CertifiedLookup needs a capability map that marks its mixed cells and keeps its joint solutions; "
                    "this one ") +
        (map.has_cell_data() ? "was built or saved without solutions" : "was written by an older octoreach") +
        ": rebuild it with arms.capability_map(robot, arm, ...) (keep_solutions=True, the default) and save it with "
        "save(path, with_solutions=True)");
  if (map.model_hash() != 0 && robot.model_hash() != map.model_hash())
    throw std::invalid_argument(
        "the capability map was built for another robot model than '" + robot.name() +
        "' (model hashes differ: another URDF or allowed-collision matrix; robots.from_urdf samples the allowed "
        "collisions of a robot without a complete SRDF, Robot.from_urdf does not): pass the robot the map was built "
        "for, or build a map for this one");
  return map;
}

}  // namespace

CertifiedLookup::CertifiedLookup(const CapabilityMap& map, const Robot& robot, const Eigen::VectorXd& reference,
                                 const CertifiedLookupOptions& options)
    : map_(usable(map, robot)), chain_(robot.chain(map.base_link(), map.tip_link())), options_(options) {
  if (options.seeds < 1 || options.seeds > kMaxSeeds)
    throw std::invalid_argument("seeds must be in [1, " + std::to_string(kMaxSeeds) + "], got " +
                                std::to_string(options.seeds));
  if (options.branch_seeds < 0)
    throw std::invalid_argument("branch_seeds must be at least 0, got " + std::to_string(options.branch_seeds));
  if (options.collided_branch_seeds < 0)
    throw std::invalid_argument("collided_branch_seeds must be at least 0, got " +
                                std::to_string(options.collided_branch_seeds));
  if (options.max_iterations < 1)
    throw std::invalid_argument("max_iterations must be at least 1, got " + std::to_string(options.max_iterations));
  if (chain_.dof() != map.dof())
    throw std::invalid_argument("the chain '" + map.base_link() + "' -> '" + map.tip_link() + "' of this robot has " +
                                std::to_string(chain_.dof()) + " joints, the map's has " + std::to_string(map.dof()));
  const Eigen::VectorXd& stored = map.reference();
  ik_.reference = reference_or_default(robot, chain_, reference.size() ? reference : stored);
  ik_.mode = map.orientations().rolls() > 1 ? IkMode::Full : IkMode::Approach;
  ik_.approach_axis = map.approach_axis();
  ik_.position_tolerance = map.position_tolerance();
  ik_.orientation_tolerance = map.orientation_tolerance();
  ik_.check_self_collision = map.self_collision();
  ik_.max_iterations = options.max_iterations;
  ik_.stall_window = 3;  // as the build: a descent that stalls far from the pose does not reach it
  ik_.attempts = 1;
  if (map.self_collision()) {
    // The links the chain never moves stand at the reference: checked once here, not in every descent.
    std::vector<std::pair<int, int>> moving, fixed;
    chain_.split_collision_pairs(moving, fixed);
    if (robot.in_self_collision_poses(robot.link_poses(ik_.reference), fixed))
      throw std::invalid_argument("the reference posture puts links the chain does not move in self-collision");
    ik_.check_fixed_pairs = false;
  }
  reach_ik_ = ik_;
  reach_ik_.check_self_collision = false;
}

CertifiedLookup::Cells CertifiedLookup::cells(const Pose& T, const float** seeds, int& n_seeds) const {
  const CapabilityMap& m = map_;
  const int o = m.orientations().nearest(T.linear(), m.approach_axis());
  std::uint32_t records[8];
  double weights[8];
  m.corners(T.translation(), records, weights);
  struct Corner {
    double weight;
    std::uint32_t rec;
  };
  std::array<Corner, 8> corners;
  int reachable = 0, mixed = 0;
  for (int k = 0; k < 8; ++k) {
    corners[k] = {weights[k], records[k]};
    if (records[k] == DenseIndex::kNone) continue;
    if (m.record_has(records[k], o)) ++reachable;
    else if (m.record_mixed(records[k], o)) ++mixed;
  }
  n_seeds = 0;
  if (reachable == 8) return Cells::reachable;
  if (reachable == 0 && mixed == 0) return Cells::unreachable;
  if (!seeds) return Cells::mixed;
  std::stable_sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.weight > b.weight; });
  for (const Corner& c : corners) {
    if (c.rec == DenseIndex::kNone || n_seeds >= options_.seeds) continue;
    const float* q = m.record_solution(c.rec, o);
    if (!q) q = m.record_mixed_solution(c.rec, o);
    if (q) seeds[n_seeds++] = q;
  }
  return Cells::mixed;
}

bool CertifiedLookup::certain(const Pose& T) const {
  check_rigid(T, "pose");
  int n = 0;
  return cells(T, nullptr, n) != Cells::mixed;
}

bool CertifiedLookup::reachable(const Pose& T, Eigen::VectorXd* solution) const {
  check_rigid(T, "pose");
  return answer(T, solution);
}

bool CertifiedLookup::near(const float* a, const float* b, double gap_max) const {
  const int dof = chain_.dof();
  const std::vector<bool>& continuous = chain_.continuous();
  for (int j = 0; j < dof; ++j) {
    const double gap = double(a[j]) - double(b[j]);
    const double wrapped = continuous[j] ? gap - 2.0 * M_PI * std::nearbyint(gap / (2.0 * M_PI)) : gap;
    if (std::abs(wrapped) > gap_max) return false;
  }
  return true;
}

bool CertifiedLookup::answer(const Pose& T, Eigen::VectorXd* solution) const {
  const float* seeds[kMaxSeeds];
  int n = 0;
  const Cells verdict = cells(T, seeds, n);
  if (verdict != Cells::mixed) return verdict == Cells::reachable;
  Eigen::VectorXd q0(chain_.dof());
  bool collided = false;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < chain_.dof(); ++j) q0[j] = seeds[i][j];
    if (descend(T, q0, solution, collided)) return true;
  }
  return other_branches(T, seeds, n, solution, collided);
}

// A single-attempt IK with the collision check is the descent, then the check of its solution: split, so that a
// solution that collides is known as such.
bool CertifiedLookup::descend(const Pose& T, const Eigen::VectorXd& q0, Eigen::VectorXd* solution,
                              bool& collided) const {
  auto q = chain_.ik(T, reach_ik_, &q0);
  if (!q) return false;
  if (ik_.check_self_collision && detail::ik_solution_collides(chain_, *q, ik_)) {
    collided = true;
    return false;
  }
  if (solution) *solution = *q;
  return true;
}

bool CertifiedLookup::other_branches(const Pose& T, const float* const* tried, int n_tried,
                                     Eigen::VectorXd* solution, bool collided) const {
  if (options_.branch_seeds == 0) return false;  // no other branches at all
  auto budget = [&] {
    return collided ? std::max(options_.branch_seeds, options_.collided_branch_seeds) : options_.branch_seeds;
  };
  const CapabilityMap& m = map_;
  const OrientationSet& set = m.orientations();
  const Eigen::Vector3d& axis = m.approach_axis();
  const int rolls = set.rolls();
  const Eigen::Vector3d d = T.linear() * axis.normalized();
  const double spacing = std::sqrt(4.0 * M_PI / set.directions());
  const double cos_cone = std::cos(std::min(M_PI, kBranchCone * spacing));
  struct Candidate {
    double distance;  // voxels from the position plus direction spacings from the approach direction
    std::uint32_t rec;
    int o;
    int order;  // gathering order: equal distances are taken in it
  };
  thread_local std::vector<std::pair<int, double>> directions;  // (orientation, direction spacings away)
  thread_local std::vector<Candidate> candidates;
  directions.clear();
  candidates.clear();
  for (int i = 0; i < set.directions(); ++i) {
    const double c = set.direction(i).dot(d);
    if (c < cos_cone) continue;
    int o = i * rolls;
    if (rolls > 1) {  // the roll of this direction nearest the pose's (roll indices do not line up across directions)
      double best = -std::numeric_limits<double>::infinity();
      for (int r = 0; r < rolls; ++r) {
        const double t = (set.rotation(i * rolls + r, axis).transpose() * T.linear()).trace();
        if (t > best) best = t, o = i * rolls + r;
      }
    }
    directions.emplace_back(o, std::acos(std::min(1.0, c)) / spacing);
  }
  // The 4 x 4 x 4 voxels around the position: its 8 corners (grid coordinates from the centre of key 0, as
  // CapabilityMap::corners) and one voxel further; a cell's configuration is read only when its turn comes.
  constexpr double kOffset = 32768.0;
  const double res = m.resolution();
  double low[3];
  const double inv = 1.0 / res;
  for (int a = 0; a < 3; ++a) low[a] = std::floor(T.translation()[a] * inv - 0.5);
  for (int dx = -1; dx <= 2; ++dx)
    for (int dy = -1; dy <= 2; ++dy)
      for (int dz = -1; dz <= 2; ++dz) {
        const double g[3] = {low[0] + dx, low[1] + dy, low[2] + dz};
        octomap::OcTreeKey key;
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
          inside &= g[a] + kOffset >= 0.0 && g[a] + kOffset <= 65535.0;
          key[a] = inside ? static_cast<octomap::key_type>(g[a] + kOffset) : 0;
        }
        if (!inside) continue;
        const std::uint32_t rec = m.record_of_key(key);
        if (rec == DenseIndex::kNone) continue;
        const double voxels = (Eigen::Vector3d(g[0] + 0.5, g[1] + 0.5, g[2] + 0.5) * res - T.translation()).norm() / res;
        for (const auto& [o, angle] : directions)
          if (m.record_has(rec, o) || m.record_mixed(rec, o))
            candidates.push_back({voxels + angle, rec, o, static_cast<int>(candidates.size())});
      }
  // Nearest first, taken from a heap as the descents need them (a few of hundreds of candidates).
  auto farther = [](const Candidate& a, const Candidate& b) {
    return a.distance > b.distance || (a.distance == b.distance && a.order > b.order);
  };
  std::make_heap(candidates.begin(), candidates.end(), farther);
  const int dof = chain_.dof();
  thread_local std::vector<const float*> used;
  used.assign(tried, tried + n_tried);
  Eigen::VectorXd q0(dof);
  int descents = 0;
  for (auto end = candidates.end(); end != candidates.begin(); --end) {
    if (descents >= budget()) break;
    std::pop_heap(candidates.begin(), end, farther);
    const Candidate& c = *(end - 1);
    const float* q = m.record_solution(c.rec, c.o);
    if (!q) q = m.record_mixed_solution(c.rec, c.o);
    if (!q) continue;
    bool same = false;
    for (const float* u : used) same = same || near(q, u, kSameBranch);
    if (same) continue;
    used.push_back(q);
    ++descents;
    for (int j = 0; j < dof; ++j) q0[j] = q[j];
    if (descend(T, q0, solution, collided)) return true;
  }
  return false;
}

void CertifiedLookup::reachable(const double* poses, std::size_t n, bool* out, int threads) const {
  detail::batch_lookup_valid(poses, n, 16, "pose", "", [&](std::size_t i) {  // (rows checked as they are read)
    Pose T;
    T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses + 16 * i);
    out[i] = answer(T, nullptr);
  }, threads, 64);
}

void CertifiedLookup::certain(const double* poses, std::size_t n, bool* out) const {
  detail::batch_lookup_valid(poses, n, 16, "pose", "", [&](std::size_t i) {
    Pose T;
    T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses + 16 * i);
    int seeds = 0;
    out[i] = cells(T, nullptr, seeds) != Cells::mixed;
  });
}

}  // namespace octoreach
