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

// The cells (unknown or frontier) the rays of one view met, each with its largest weight: a dense
// array over the frustum's key box (thread-local, reset through the list of touched cells, so a view
// costs what its rays walk) or, for a box of more than kMaxDense cells, a hash table. Weights are kept
// as 16-bit fractions (1 + w * 65534; 0: not met).
class MetCells {
 public:
  static constexpr std::int64_t kMaxDense = std::int64_t(1) << 25;
  MetCells(const std::int64_t klo[3], const std::int64_t n[3]) : dense_(n[0] * n[1] * n[2] <= kMaxDense) {
    for (int a = 0; a < 3; ++a) klo_[a] = klo[a], n_[a] = n[a];
    if (dense_) {
      auto& b = buffer();
      if (b.size() < std::size_t(n[0] * n[1] * n[2])) b.assign(std::size_t(n[0] * n[1] * n[2]), 0);
    }
  }
  ~MetCells() {
    if (!dense_) return;
    auto& b = buffer();
    for (const auto& t : touched_) b[t.first] = 0;
  }
  MetCells(const MetCells&) = delete;
  MetCells& operator=(const MetCells&) = delete;
  void touch(CellKey k, double w) {
    const std::uint16_t q = std::uint16_t(1 + std::lround(std::min(std::max(w, 0.0), 1.0) * 65534.0));
    if (!dense_) {
      std::uint16_t& v = table_.at(k);
      if (!v) touched_.emplace_back(0, k);
      v = std::max(v, q);
      return;
    }
    const std::int64_t x = std::int64_t(key_x(k)) - klo_[0], y = std::int64_t(key_y(k)) - klo_[1],
                       z = std::int64_t(key_z(k)) - klo_[2];
    if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) return;  // cannot happen
    const std::size_t idx = std::size_t((z * n_[1] + y) * n_[0] + x);
    std::uint16_t& v = buffer()[idx];
    if (!v) touched_.emplace_back(idx, k);
    v = std::max(v, q);
  }
  // f(key, weight) once per cell met.
  template <class F>
  void for_each(F&& f) const {
    for (const auto& t : touched_) {
      const std::uint16_t v = dense_ ? buffer()[t.first] : *table_.find(t.second);
      f(t.second, double(v - 1) / 65534.0);
    }
  }

 private:
  static std::vector<std::uint16_t>& buffer() {
    thread_local std::vector<std::uint16_t> b;
    return b;
  }
  bool dense_;
  std::int64_t klo_[3], n_[3];
  std::vector<std::pair<std::size_t, CellKey>> touched_;
  KeyTable<std::uint16_t> table_{dense_ ? std::size_t(0) : std::size_t(1) << 16};
};

}  // namespace

ViewGains view_gains_unlocked(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                              double p, double p_void, std::vector<std::pair<CellKey, float>>* unknown_met) {
  const ExplorationState& S = state(map);
  GridReader g(S.grid);
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
  MetCells met(klo, n);
  for (const Eigen::Vector3d& d : dirs) {
    double w = 1.0;
    walk_cells(res, o, d, cam.max_range, [&](CellKey k) {
      const std::uint8_t f = g.get(k);
      const std::uint8_t s = f & kStateMask;
      if (s == std::uint8_t(CellState::Occupied)) return false;
      if (s == std::uint8_t(CellState::Unknown)) {
        met.touch(k, w);
        w *= (f & kVoidFlag) ? p_void : p;
      } else if (f & kFrontierFlag) {
        met.touch(k, w);
      }
      return true;
    });
  }
  // A ray of the coarse grid stands for the pixels of its grid cell: at distance t its beam covers
  // t^2 du dv / res^2 cells across (at least 1), the cells the camera's pixels see there.
  const double beam = (double(cam.width) / sw / cam.focal()) * (double(cam.height) / sh / cam.focal()) / (res * res);
  ViewGains v;
  met.for_each([&](CellKey k, double w) {
    const std::uint8_t f = g.get(k);
    const bool unknown = (f & kStateMask) == std::uint8_t(CellState::Unknown);
    if (unknown && unknown_met) unknown_met->emplace_back(k, float(w));
    // unknown cells count with their seeability (lowered by views that expected them and missed)
    const double e = w * (unknown ? S.seeability(k) : 1.0) * std::max(1.0, (S.center(k) - o).squaredNorm() * beam);
    if (unknown) {
      ++v.unknown_cells;
      v.expected_unknown += e;
      if (f & kVoidFlag) {
        ++v.void_cells;
        v.expected_void += e;
      }
    } else {
      ++v.frontier_cells;
      v.expected_frontier += e;
    }
  });
  return v;
}

std::pair<double, double> pass_probabilities(const ExplorationMap& map, const NbvOptions& opt) {
  if (opt.unknown_pass_probability >= 0) return {opt.unknown_pass_probability, opt.unknown_pass_probability};
  const RayStatistics r = map.ray_statistics();
  return {r.pass_probability(), r.void_pass_probability()};
}

void score_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt,
                std::pair<double, double> p, ViewCandidate& v) {
  static_cast<ViewGains&>(v) =
      view_gains_unlocked(map, cam, v.pose, opt.score_width, opt.score_height, p.first, p.second);
  v.gain = v.ViewGains::gain(opt.gain);
  const double res = map.resolution();
  v.utility_dm3 = v.expected_void * res * res * res * 1000.0;
}

void learn_from_missed(ExplorationState& S) {
  for (const auto& [k, w] : S.expected_by_view) {
    if (S.state(k) != CellState::Unknown) continue;
    float& h = S.hidden.at(k);  // s' = s (1 - w), kept as h = 1 - s
    h = float(1.0 - (1.0 - double(h)) * (1.0 - std::min(std::max(double(w), 0.0), 1.0)));
  }
  S.expected_by_view.clear();
}

}  // namespace detail

void expect_view(ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, const NbvOptions& opt) {
  detail::validate_options(cam, opt);
  if (!pose.matrix().allFinite()) throw std::invalid_argument("camera pose must be finite");
  detail::ExplorationState& S = detail::mutable_state(map);
  detail::MapGuard guard(S, true);
  const auto p = detail::pass_probabilities(map, opt);
  S.expected_by_view.clear();
  detail::view_gains_unlocked(map, cam, pose, opt.score_width, opt.score_height, p.first, p.second,
                              &S.expected_by_view);
}

std::size_t missed_cells(const ExplorationMap& map) {
  auto guard = detail::read_guard(map);
  return detail::state(map).hidden.size();
}

ViewGains view_gains(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                     double p, double p_void) {
  cam.validate();
  if (sw <= 0 || sh <= 0)
    throw std::invalid_argument("score grid must be positive, got " + std::to_string(sw) + " x " + std::to_string(sh));
  if (!(p >= 0 && p <= 1) || !(p_void >= 0 && p_void <= 1))
    throw std::invalid_argument("pass probabilities must be in [0, 1], got " + std::to_string(p) + " and " +
                                std::to_string(p_void));
  if (!pose.matrix().allFinite()) throw std::invalid_argument("camera pose must be finite");
  auto guard = detail::read_guard(map);
  return detail::view_gains_unlocked(map, cam, pose, sw, sh, p, p_void);
}

std::pair<std::size_t, std::size_t> view_utility(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                 const Pose& pose, int sw, int sh) {
  ViewGains v = view_gains(map, cam, pose, sw, sh, 1.0, 1.0);
  return {v.void_cells, v.unknown_cells};
}

}  // namespace octoreach
