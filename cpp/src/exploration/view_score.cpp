// The visibility model of a view: what a camera pose is expected to see through unknown space
// (next_best_view.hpp, "Visibility model"), and the names of the gains.
#include "exploration/view_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/cancel.hpp"
#include "exploration/cell_sets.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/grid_ray.hpp"
#include "exploration/met_cells.hpp"
#include "exploration/score_cells.hpp"

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
    case NbvGain::FrontierVoid: return expected_enclosed_void;
    case NbvGain::Frontiers: return expected_frontier;
    case NbvGain::Unknown: return expected_unknown;
  }
  return 0;
}

const char* rank_key_name(RankKey k) { return k == RankKey::Gain ? "expected_gain" : "expected_void"; }

RankKey rank_key_from_name(const std::string& name) {
  for (RankKey k : {RankKey::Gain, RankKey::ExpectedVoid})
    if (name == rank_key_name(k)) return k;
  throw std::invalid_argument("views are ranked by 'expected_gain' or 'expected_void', got '" + name + "'");
}

bool ranks_before(const ViewCandidate& a, const ViewCandidate& b, RankKey key) {
  const double ka = key == RankKey::Gain ? a.expected_gain : a.expected_void;
  const double kb = key == RankKey::Gain ? b.expected_gain : b.expected_void;
  if (ka != kb) return ka > kb;
  return a.expected_unknown > b.expected_unknown;
}

const ViewCandidate* NbvResult::best(RankKey key) const {
  const ViewCandidate* top = nullptr;
  for (const ViewCandidate& v : ranked)
    if (!top || ranks_before(v, *top, key)) top = &v;
  return top;
}

const ScoredView* ScoredViews::best(RankKey key) const {
  const ScoredView* top = nullptr;
  for (const ScoredView& v : views)
    if (v.valid() && (!top || ranks_before(v, *top, key))) top = &v;
  return top;
}

namespace detail {

namespace {

// The part of the ray o + t dir (dir unit), t in [0, range], that can meet a cell of the box [lo, hi]: its length up
// to the exit (plus half a cell, so the exit cell is walked), or -1 when it misses the box.
double clipped_length(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double res, const Eigen::Vector3d& o,
                      const Eigen::Vector3d& dir, double range) {
  double t0 = 0, t1 = range;
  for (int i = 0; i < 3; ++i) {
    if (dir[i] == 0) {
      if (o[i] < lo[i] || o[i] > hi[i]) return -1;
      continue;
    }
    double a = (lo[i] - o[i]) / dir[i], b = (hi[i] - o[i]) / dir[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1 ? std::min(range, t1 + 0.5 * res) : -1;
}

}  // namespace

RayClip void_box(const ExplorationMap& map) {
  const ExplorationState& S = state(map);
  RayClip c;
  if (S.void_set.empty()) return c;
  std::uint32_t lo[3] = {0xffff, 0xffff, 0xffff}, hi[3] = {0, 0, 0};
  for (CellKey k : S.void_set) {
    const std::uint32_t x[3] = {key_x(k), key_y(k), key_z(k)};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], x[a]), hi[a] = std::max(hi[a], x[a]);
  }
  const double half = 0.5 * map.resolution();
  const Eigen::Vector3d clo = S.center(pack_key(lo[0], lo[1], lo[2])), chi = S.center(pack_key(hi[0], hi[1], hi[2]));
  c.lo = clo.array() - half;
  c.hi = chi.array() + half;
  // the reach: the cell cache's blocks (every known cell lies in one) and the search space, where bounded
  std::uint32_t blo[3] = {0xffff, 0xffff, 0xffff}, bhi[3] = {0, 0, 0};
  S.grid.for_each_block([&](CellKey b, const StateGrid::Block&) {
    const std::uint32_t x[3] = {key_x(b), key_y(b), key_z(b)};
    for (int a = 0; a < 3; ++a) blo[a] = std::min(blo[a], x[a] << 4), bhi[a] = std::max(bhi[a], (x[a] << 4) | 15u);
  });
  c.known_lo = S.center(pack_key(blo[0], blo[1], blo[2])).array() - half;
  c.known_hi = S.center(pack_key(bhi[0], bhi[1], bhi[2])).array() + half;
  // the search space's cells are those whose centre lies in it (space_keys): their bounds, not the space's own
  const ExplorationOptions& o = map.options();
  const SpaceKeys space = space_keys(o);
  const Eigen::Vector3d slo = S.center(pack_key(space.lo[0], space.lo[1], space.lo[2])).array() - half;
  const Eigen::Vector3d shi = S.center(pack_key(space.hi[0], space.hi[1], space.hi[2])).array() + half;
  for (int a = 0; a < 3; ++a) {
    if (!open_below(o.search_lo[a])) c.reach_lo[a] = std::min({c.known_lo[a], slo[a], c.lo[a]});
    if (!open_above(o.search_hi[a])) c.reach_hi[a] = std::max({c.known_hi[a], shi[a], c.hi[a]});
  }
  return c;
}

namespace {

// The cell reads of a view score straight from the map's tables (an announcement, and its check after the insert).
struct MapCells {
  const ExplorationState& S;
  const VoidWeights* weights;
  const StateGrid::Block* block(CellKey b) const { return S.grid.find_block(b); }
  double seeability(CellKey k, std::uint8_t&) const { return S.seeability(k); }
  bool blind(CellKey k, std::uint8_t, const Eigen::Vector3d& eye) const {
    return !S.blind.empty() && S.blind.covers(k, S.center(k), eye);
  }
  bool crossed_empty(CellKey k) const { return S.blind.holds(k); }
  double void_weight(CellKey k, std::uint8_t) const { return weights->of(k); }
};

// The same reads through a search's ScoreCells (the same values: the map's tables, flat).
struct FlatCells {
  ScoreCells::Reader r;
  const VoidWeights* weights;
  const StateGrid::Block* block(CellKey b) const { return r.block(b); }
  double seeability(CellKey k, std::uint8_t& mark) const { return r.seeability(k, mark); }
  bool blind(CellKey k, std::uint8_t mark, const Eigen::Vector3d& eye) const { return r.blind(k, mark, eye); }
  bool crossed_empty(CellKey k) const { return r.crossed_empty(k); }
  double void_weight(CellKey, std::uint8_t mark) const { return weights->of_mark(mark); }
};

// The score grid's ray directions in the camera frame (cam.ray at the grid cells' centres), kept per thread
// for the last camera and grid: a search scores every view with one.
const std::vector<Eigen::Vector3d>& grid_rays(const CameraIntrinsics& cam, int sw, int sh) {
  struct Grid {
    int width = -1, height = -1, sw = -1, sh = -1;
    double fov = -1;
    std::vector<Eigen::Vector3d> rays;
  };
  thread_local Grid g;
  if (g.width != cam.width || g.height != cam.height || g.fov != cam.fov || g.sw != sw || g.sh != sh) {
    g.rays.resize(std::size_t(sw) * sh);
    for (int j = 0; j < sh; ++j)
      for (int i = 0; i < sw; ++i)
        g.rays[std::size_t(j) * sw + i] = cam.ray((i + 0.5) * cam.width / sw, (j + 0.5) * cam.height / sh);
    g.width = cam.width, g.height = cam.height, g.fov = cam.fov, g.sw = sw, g.sh = sh;
  }
  return g.rays;
}

// One view's rays: directions (map frame), lengths (-1: the ray misses the clip box) and the frustum's key box.
struct ViewRays {
  std::vector<Eigen::Vector3d> dirs;
  std::vector<double> lengths;
  std::vector<double> reach;  // how far each ray is walked (at least its length): the clip's reach, else the range
  std::vector<double> known;  // where each ray leaves the clip's known box (-1: it misses it; the range: no clip)
  std::int64_t klo[3], n[3];
};

void view_rays(const CameraIntrinsics& cam, const Pose& pose, int sw, int sh, double res, const RayClip* clip,
               ViewRays& v) {
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d o = pose.translation();
  const std::vector<Eigen::Vector3d>& rays = grid_rays(cam, sw, sh);
  v.dirs.resize(rays.size());
  v.lengths.assign(rays.size(), cam.max_range);
  v.reach.assign(rays.size(), cam.max_range);
  v.known.assign(rays.size(), cam.max_range);
  // key box of the frustum (every walked cell lies within a cell of a ray's end points)
  Eigen::Vector3d lo = o, hi = o;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const Eigen::Vector3d d = R * rays[r];
    v.dirs[r] = d;
    if (clip) {
      v.lengths[r] = clipped_length(clip->lo, clip->hi, res, o, d.normalized(), cam.max_range);
      v.reach[r] = std::max(v.lengths[r], clipped_length(clip->reach_lo, clip->reach_hi, res, o, d.normalized(),
                                                         cam.max_range));
      v.known[r] = clipped_length(clip->known_lo, clip->known_hi, res, o, d.normalized(), cam.max_range);
    }
    if (v.lengths[r] < 0) continue;
    Eigen::Vector3d e = o + d.normalized() * v.lengths[r];
    lo = lo.cwiseMin(e);
    hi = hi.cwiseMax(e);
  }
  for (int a = 0; a < 3; ++a) {
    v.klo[a] = std::int64_t(std::floor(lo[a] / res + 32768.0)) - 2;
    v.n[a] = std::int64_t(std::floor(hi[a] / res + 32768.0)) + 2 - v.klo[a] + 1;
  }
}

// What one view's rays meet (see view_gains_unlocked), its cells read through `cells`, met cells kept in `met`.
template <class Met, class Cells>
ViewGains count_view(const ExplorationState& S, const CameraIntrinsics& cam, const Eigen::Vector3d& o, double res,
                     int sw, int sh, const ViewRays& rays, double p, double p_void, const VisibilityCurve* curve,
                     const Cells& cells, bool weighted, std::vector<ExpectedCell>* unknown_met,
                     const SpaceKeys& space) {
  Met met(rays.klo, rays.n);
  // A depth camera clears only the cells in front of the surface a ray returns from. An unknown cell, void or not,
  // counts with the chance that its ray returns at or behind it: 1 when the ray ends on an occupied cell, else the
  // chance that an unknown cell of the search space or of the voids from there on holds a surface (1 - p each,
  // where p is the pass probability of its class; none on a cell a ray that returned nothing has crossed,
  // blind_lines.hpp). The hull that makes a cell void is not a surface: between tall objects on a table it holds
  // open air, and a ray through it that meets no surface behind returns nothing and clears nothing. Outside the
  // search space the views so far are taken to have seen what there is.
  struct Pending {
    CellKey key;
    std::uint8_t f;
    double w;
    int depth;
  };
  thread_local std::vector<Pending> pending;
  // The chance that an unknown cell (flags f) lets a ray through, in the chance of a return: p of its class for a
  // void cell or one of the search space that no ray which returned nothing has crossed; 1 for any other.
  const auto pass = [&](std::uint8_t f, CellKey k) {
    const bool v = f & kVoidFlag;
    return (v || space.contains(k)) && !cells.crossed_empty(k) ? (v ? p_void : p) : 1.0;
  };
  for (std::size_t r = 0; r < rays.dirs.size(); ++r) {
    if ((r & 1023) == 1023) poll_cancel("view scoring cancelled");  // a fine score grid takes long per view
    if (rays.lengths[r] < 0) continue;  // misses the clip box
    double w = 1.0;  // the geometric weight: the product of the pass probabilities so far
    int depth = 0;   // unknown cells crossed so far
    // walk_cells' walk, reading the cell cache block by block (a new block only where the ray crosses into one).
    // Cells count up to the clip (`counted`, in key units); past it the walk goes on, while a counted cell waits
    // for it, only to learn whether the ray returns: a whole ray's chance, so clipped and whole rays agree.
    GridRay ray;
    if (!key_unit_ray(res, o, rays.dirs[r], rays.reach[r], ray)) continue;
    const double counted = rays.lengths[r] / res;
    // past the known box nothing but the search space's unknown cells is left, and with p 1 they stop nothing
    const double known = p == 1.0 ? std::max(counted, rays.known[r] / res) : std::numeric_limits<double>::infinity();
    double entry = 0;      // the ray parameter at which it entered the current cell
    double behind = 1.0;   // past the clip: the chance that no unknown cell there stops the ray
    ScalarRay g(ray);
    CellKey block_key = g.block();
    const StateGrid::Block* block = cells.block(block_key);
    pending.clear();
    bool surface = false;  // the ray ends on an occupied cell
    for (;;) {
      const std::uint8_t f = block ? (*block)[g.offset()] : 0;
      const std::uint8_t s = f & kStateMask;
      if (s == std::uint8_t(CellState::Occupied)) {
        // (a ray past the part of the cell its surface fills goes on: surface_extents.hpp)
        if (surface_meets_line(S, g.cell(), o, rays.dirs[r])) {
          surface = true;
          break;
        }
      } else if (entry > counted) {
        // nothing counted waits for the rest of the ray, or nothing further changes a weight by 1e-12
        if (pending.empty() || behind < 1e-12 || entry > known) break;
        if (s == std::uint8_t(CellState::Unknown))
          behind *= pass(f, g.cell());
      } else if (s == std::uint8_t(CellState::Unknown)) {
        const bool v = f & kVoidFlag;
        const bool inside = v || space.contains(g.kx, g.ky, g.kz);
        const double wc = curve ? curve->weight(v, depth, w) : w;
        if (unknown_met || inside) {
          // (one outside the search space and the voids counts for nothing in a score, nor in the chance of a return)
          pending.push_back({g.cell(), f, wc, depth});
        }
        // Outside the search space the views so far are taken to have seen what there is: such a cell lets the ray
        // through (else a view over space no capture has reached, as after a first capture that returned nothing,
        // would expect nothing of the search space behind it).
        if (inside) {
          w *= v ? p_void : p;
          ++depth;
        }
      } else if (f & kFrontierFlag) {
        met.touch(g.kx, g.ky, g.kz, f, curve ? curve->weight(0, depth, w) : w, depth);
      }
      if (!g.step(entry)) break;
      const CellKey bk = g.block();
      if (bk != block_key) block = cells.block(block_key = bk);
    }
    double through = behind;  // the chance that no unknown cell from here on stops the ray
    for (auto c = pending.rbegin(); c != pending.rend(); ++c) {
      if (!surface) through *= pass(c->f, c->key);
      met.touch(int(key_x(c->key)), int(key_y(c->key)), int(key_z(c->key)), c->f,
                surface ? c->w : c->w * (1.0 - through), c->depth);
    }
  }
  // A ray of the coarse grid stands for the pixels of its grid cell: at distance t its beam covers
  // t^2 du dv / res^2 cells across (at least 1), the cells the camera's pixels see there.
  const double beam = (double(cam.width) / sw / cam.focal()) * (double(cam.height) / sh / cam.focal()) / (res * res);
  // with the learned curve, the beam's cells are calibrated too (per class: outside the voids, void)
  const double scales[2] = {curve ? curve->beam_scale(0) : 1.0, curve ? curve->beam_scale(1) : 1.0};
  ViewGains v;
  met.for_each([&](CellKey k, std::uint8_t f, double w, int depth) {
    const bool unknown = (f & kStateMask) == std::uint8_t(CellState::Unknown);
    const double n = std::max(1.0, (S.center(k) - o).squaredNorm() * beam);
    if (unknown && unknown_met)
      unknown_met->push_back({k, float(w), float(n), std::uint16_t(std::min(depth, 65535)),
                              std::uint8_t((f & kVoidFlag) ? 1 : 0)});
    if (unknown && !(f & kVoidFlag) && !space.contains(k)) return;
    // unknown cells count with their seeability (lowered by views that expected them and missed)
    const double scale = scales[(f & kVoidFlag) ? 1 : 0];
    std::uint8_t mark = 0;
    double s = unknown ? cells.seeability(k, mark) : 1.0;
    if (s > 0 && unknown && cells.blind(k, mark, o)) s = 0;  // a line that returned nothing (blind_lines.hpp)
    const double e = w * s * n * scale;
    if (unknown) {
      ++v.unknown_cells;
      v.expected_unknown += e;
      if (f & kVoidFlag) {
        ++v.void_cells;
        v.expected_void += e;
        v.expected_enclosed_void += weighted ? e * cells.void_weight(k, mark) : e;
      }
    } else {
      ++v.frontier_cells;
      v.expected_frontier += e;
    }
  });
  return v;
}

}  // namespace

ViewGains view_gains_unlocked(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                              double p, double p_void, bool learned, std::vector<ExpectedCell>* unknown_met,
                              const VoidWeights* void_weights, const RayClip* clip, const ScoreCells* score_cells) {
  const ExplorationState& S = state(map);
  if (clip && clip->empty()) return {};  // no void cell: nothing counts
  // (a curve no announced view taught is the geometric weight itself: skip it)
  const VisibilityCurve* curve = learned && S.curve.taught ? &S.curve : nullptr;
  const double res = map.resolution();
  thread_local ViewRays rays;
  view_rays(cam, pose, sw, sh, res, clip, rays);
  const Eigen::Vector3d o = pose.translation();
  const bool weighted = void_weights != nullptr;
  const SpaceKeys space = space_keys(map.options());  // unknown cells outside it are not counted
  // depths only for an announcement
  if (unknown_met)
    return count_view<MetCells<std::uint32_t>>(S, cam, o, res, sw, sh, rays, p, p_void, curve,
                                               MapCells{S, void_weights}, weighted, unknown_met, space);
  std::shared_ptr<const ScoreCells> own;  // without the search's cells for these weights: the map's, made once
  if (!score_cells || (weighted && score_cells->enclosure() != void_weights->table().get())) {
    own = detail::score_cells(S, weighted ? void_weights->table() : nullptr);
    score_cells = own.get();
  }
  return count_view<MetCells<std::uint16_t>>(S, cam, o, res, sw, sh, rays, p, p_void, curve,
                                             FlatCells{ScoreCells::Reader(*score_cells), void_weights}, weighted,
                                             nullptr, space);
}

std::pair<double, double> pass_probabilities(const ExplorationMap& map, const NbvOptions& opt) {
  if (opt.unknown_pass_probability >= 0) return {opt.unknown_pass_probability, opt.unknown_pass_probability};
  const RayStatistics r = map.ray_statistics();
  return {r.pass_probability(), r.void_pass_probability()};
}

ScoreModel score_model(const ExplorationMap& map, const NbvOptions& opt) {
  ScoreModel m;
  m.p = pass_probabilities(map, opt);
  if (opt.gain == NbvGain::FrontierVoid) {
    m.void_weights =
        void_weights(state(map), map.resolution(), opt.enclosure_power, opt.enclosure_range, opt.unexposed_weight);
    m.clip = void_box(map);
  }
  m.cells = score_cells(state(map), m.void_weights.table());
  return m;
}

void score_view(const ExplorationMap& map, const CameraIntrinsics& cam, const NbvOptions& opt, const ScoreModel& m,
                ViewCandidate& v, int step) {
  const int sw = (opt.score_width + step - 1) / step, sh = (opt.score_height + step - 1) / step;
  static_cast<ViewGains&>(v) =
      view_gains_unlocked(map, cam, v.pose, sw, sh, m.p.first, m.p.second,
                          opt.unknown_pass_probability < 0, nullptr, m.void_weights ? &m.void_weights : nullptr,
                          m.clip ? &*m.clip : nullptr, m.cells.get());
  v.expected_gain = v.gain(opt.gain);
  const double res = map.resolution();
  v.utility_dm3 = v.expected_void * res * res * res * 1000.0;
}

std::vector<std::size_t> best_by_each_key(const std::vector<const ViewCandidate*>& views, std::size_t n) {
  std::vector<char> keep(views.size(), 0);
  std::vector<std::size_t> order(views.size());
  for (RankKey key : {RankKey::Gain, RankKey::ExpectedVoid}) {
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const std::size_t m = std::min(n, order.size());
    std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(m), order.end(), [&](std::size_t a, std::size_t b) {
      if (ranks_before(*views[a], *views[b], key)) return true;
      if (ranks_before(*views[b], *views[a], key)) return false;
      return a < b;
    });
    for (std::size_t i = 0; i < m; ++i) keep[order[i]] = 1;
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) out.push_back(i);
  return out;
}

}  // namespace detail

ViewGains view_gains(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                     double p, double p_void, bool learned) {
  cam.validate();
  if (sw <= 0 || sh <= 0)
    throw std::invalid_argument("score grid must be positive, got " + std::to_string(sw) + " x " + std::to_string(sh));
  if (!(p >= 0 && p <= 1) || !(p_void >= 0 && p_void <= 1))
    throw std::invalid_argument("pass probabilities must be in [0, 1], got " + std::to_string(p) + " and " +
                                std::to_string(p_void));
  check_rigid(pose, "camera pose");
  auto guard = detail::read_guard(map);
  return detail::view_gains_unlocked(map, cam, pose, sw, sh, p, p_void, learned);
}

ViewGainsResult view_gains(const ExplorationMap& map, const CameraIntrinsics& cam, const Pose& pose, int sw, int sh,
                           std::optional<double> pass_probability) {
  ViewGainsResult r;
  const bool learned = !pass_probability;
  if (learned) {
    const RayStatistics s = map.ray_statistics();
    r.pass_probability = s.pass_probability();
    r.void_pass_probability = s.void_pass_probability();
  } else {
    r.pass_probability = r.void_pass_probability = *pass_probability;
  }
  static_cast<ViewGains&>(r) = view_gains(map, cam, pose, sw, sh, r.pass_probability, r.void_pass_probability, learned);
  return r;
}

std::pair<std::size_t, std::size_t> view_utility(const ExplorationMap& map, const CameraIntrinsics& cam,
                                                 const Pose& pose, int sw, int sh) {
  ViewGains v = view_gains(map, cam, pose, sw, sh, 1.0, 1.0);
  return {v.void_cells, v.unknown_cells};
}

}  // namespace octoreach
