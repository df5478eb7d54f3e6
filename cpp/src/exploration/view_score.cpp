// The visibility model of a view: what a camera pose is expected to see through unknown space
// (next_best_view.hpp, "Visibility model"), and the names of the gains.
#include "view_score.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "cell_sets.hpp"
#include "exploration_state.hpp"
#include "grid_ray.hpp"

namespace octoreach {

const char* gain_name(NbvGain g) {
  switch (g) {
    case NbvGain::FrontierVoid: return "frontier_void";
    case NbvGain::Frontiers: return "frontiers";
    case NbvGain::Unknown: return "unknown";
  }
  return "?";
}

NbvGain gain_from_name(const std::string& name) {
  for (NbvGain g : {NbvGain::FrontierVoid, NbvGain::Frontiers, NbvGain::Unknown})
    if (name == gain_name(g)) return g;
  throw std::invalid_argument("gain must be 'frontier_void', 'frontiers' or 'unknown', got '" + name + "'");
}

double ViewGains::gain(NbvGain g) const {
  switch (g) {
    case NbvGain::FrontierVoid: return expected_void;
    case NbvGain::Frontiers: return expected_frontier;
    case NbvGain::Unknown: return expected_unknown;
  }
  return 0;
}

namespace detail {

namespace {

// A cell met by the rays of one view: its largest weight and whether it is void / a frontier.
struct Met {
  float w = -1;
  std::uint8_t flags = 0;
};

}  // namespace

// Cells whose weight fell below this are left out of the expected sums (they still count raw).
constexpr double kMinWeight = 1e-4;

ViewGains view_gains_unlocked(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                              double p) {
  GridReader g(state(map).grid);
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d o = pose.translation();
  const double res = map.resolution();
  std::vector<Eigen::Vector3d> dirs(std::size_t(sw) * sh);
  // key box of the frustum (every walked cell lies within a cell of a ray's end points)
  Eigen::Vector3d lo = o, hi = o;
  for (int j = 0; j < sh; ++j)
    for (int i = 0; i < sw; ++i) {
      Eigen::Vector3d d = R * cam.ray((i + 0.5) * cam.width / sw, (j + 0.5) * cam.height / sh);
      dirs[std::size_t(j) * sw + i] = d;
      Eigen::Vector3d e = o + d.normalized() * cam.max_range;
      lo = lo.cwiseMin(e);
      hi = hi.cwiseMax(e);
    }
  std::int64_t klo[3], n[3];
  for (int a = 0; a < 3; ++a) {
    klo[a] = std::int64_t(std::floor(lo[a] / res + 32768.0)) - 2;
    n[a] = std::int64_t(std::floor(hi[a] / res + 32768.0)) + 2 - klo[a] + 1;
  }
  // raw distinct cells: one bit per cell of the box; weights of the cells seen with weight >= kMinWeight
  std::vector<std::uint64_t> seen(std::size_t((n[0] * n[1] * n[2] + 63) / 64), 0);
  KeyTable<Met> met(std::size_t(sw) * sh * 4);
  ViewGains v;
  for (const Eigen::Vector3d& d : dirs) {
    double w = 1.0;
    walk_cells(res, o, d, cam.max_range, [&](CellKey k) {
      const std::uint8_t f = g.get(k);
      const std::uint8_t s = f & kStateMask;
      if (s == std::uint8_t(CellState::Occupied)) return false;
      const bool unknown = s == std::uint8_t(CellState::Unknown);
      if (!unknown && !(f & kFrontierFlag)) return true;
      std::int64_t x = std::int64_t(key_x(k)) - klo[0], y = std::int64_t(key_y(k)) - klo[1],
                   z = std::int64_t(key_z(k)) - klo[2];
      if (x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) return false;  // cannot happen
      const std::size_t idx = std::size_t((z * n[1] + y) * n[0] + x);
      const std::uint64_t bit = std::uint64_t(1) << (idx & 63);
      if (!(seen[idx >> 6] & bit)) {
        seen[idx >> 6] |= bit;
        if (!unknown) ++v.frontier_cells;
        else {
          ++v.unknown_cells;
          if (f & kVoidFlag) ++v.void_cells;
        }
      }
      if (w >= kMinWeight) {
        Met& m = met.at(k);
        if (float(w) > m.w) m.w = float(w);
        m.flags = f;
      }
      if (unknown) w *= p;
      return true;
    });
  }
  met.for_each([&](CellKey, const Met& m) {
    if ((m.flags & kStateMask) == std::uint8_t(CellState::Unknown)) {
      v.expected_unknown += m.w;
      if (m.flags & kVoidFlag) v.expected_void += m.w;
    } else {
      v.expected_frontier += m.w;
    }
  });
  return v;
}

double pass_probability_of(const ExplorationMap& map, const NbvOptions& opt) {
  return opt.unknown_pass_probability >= 0 ? opt.unknown_pass_probability : map.pass_probability();
}

void score_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt, double p,
                ViewCandidate& v) {
  static_cast<ViewGains&>(v) = view_gains_unlocked(map, cam, v.pose, opt.score_width, opt.score_height, p);
  v.gain = v.ViewGains::gain(opt.gain);
  const double res = map.resolution();
  v.utility_dm3 = v.expected_void * res * res * res * 1000.0;
}

}  // namespace detail

ViewGains view_gains(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                     double p) {
  cam.validate();
  if (sw <= 0 || sh <= 0)
    throw std::invalid_argument("score grid must be positive, got " + std::to_string(sw) + " x " + std::to_string(sh));
  if (!(p >= 0 && p <= 1)) throw std::invalid_argument("pass probability must be in [0, 1], got " + std::to_string(p));
  if (!pose.matrix().allFinite()) throw std::invalid_argument("camera pose must be finite");
  auto guard = detail::read_guard(map);
  return detail::view_gains_unlocked(map, cam, pose, sw, sh, p);
}

std::pair<std::size_t, std::size_t> view_utility(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                 const Pose& pose, int sw, int sh) {
  ViewGains v = view_gains(map, cam, pose, sw, sh, 1.0);
  return {v.void_cells, v.unknown_cells};
}

}  // namespace octoreach
