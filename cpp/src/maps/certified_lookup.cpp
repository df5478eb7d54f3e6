#include "octoreach/certified_lookup.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "octoreach/arm.hpp"
#include "maps/batch.hpp"

namespace octoreach {
namespace {

const CapabilityMap& usable(const CapabilityMap& map, const Robot& robot) {
  if (!map.has_cell_data() || !map.has_solutions())
    throw std::invalid_argument(
        std::string("CertifiedLookup needs a capability map that marks its mixed cells and keeps its joint solutions; "
                    "this one ") +
        (map.has_cell_data() ? "was built or saved without solutions" : "was written by an older octoreach") +
        ": rebuild it with arms.capability_map(robot, arm, ...) (keep_solutions=True, the default) and save it with "
        "save(path, with_solutions=True)");
  if (map.model_hash() != 0 && robot.model_hash() != map.model_hash())
    throw std::invalid_argument("the capability map was built for another robot model than '" + robot.name() +
                                "' (model hashes differ: another URDF or allowed-collision matrix)");
  return map;
}

}  // namespace

CertifiedLookup::CertifiedLookup(const CapabilityMap& map, const Robot& robot, const Eigen::VectorXd& reference,
                                 const CertifiedLookupOptions& options)
    : map_(usable(map, robot)), chain_(robot.chain(map.base_link(), map.tip_link())), options_(options) {
  if (options.seeds < 1 || options.seeds > kMaxSeeds)
    throw std::invalid_argument("seeds must be in [1, " + std::to_string(kMaxSeeds) + "], got " +
                                std::to_string(options.seeds));
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
  int n = 0;
  return cells(T, nullptr, n) != Cells::mixed;
}

bool CertifiedLookup::reachable(const Pose& T, Eigen::VectorXd* solution) const {
  const float* seeds[kMaxSeeds];
  int n = 0;
  const Cells answer = cells(T, seeds, n);
  if (answer != Cells::mixed) return answer == Cells::reachable;
  Eigen::VectorXd q0(chain_.dof());
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < chain_.dof(); ++j) q0[j] = seeds[i][j];
    if (auto q = chain_.ik(T, ik_, &q0)) {
      if (solution) *solution = *q;
      return true;
    }
  }
  return false;
}

void CertifiedLookup::reachable(const double* poses, std::size_t n, bool* out, int threads) const {
  detail::batch_lookup_finite(poses, n, 16, "pose", " (NaN or inf)", [&](std::size_t i) {
    Pose T;
    T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses + 16 * i);
    out[i] = reachable(T);
  }, threads, 64);
}

void CertifiedLookup::certain(const double* poses, std::size_t n, bool* out) const {
  detail::batch_lookup_finite(poses, n, 16, "pose", " (NaN or inf)", [&](std::size_t i) {
    Pose T;
    T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses + 16 * i);
    out[i] = certain(T);
  });
}

}  // namespace octoreach
