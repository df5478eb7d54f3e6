#pragma once
// Internal: walking the cells of a ray through the key grid (Amanatides & Woo).
//
// A ray steps along the axis whose next cell border is nearest (next_axis, the tie-breaks of
// OctoMap's computeRayKeys). Its set-up (GridRay) comes in two kinds, on purpose:
// - octomap_ray reproduces computeRayKeys exactly (metric t, float direction, OctoMap's border
//   arithmetic), so that insertion (RayWalk, the batched SSE form of the same walk) yields the
//   very cells stock insertPointCloud updates;
// - key_unit_ray works in key units from a double-precision origin and direction (ScalarRay's walk:
//   walk_cells, view scoring and utility rays, which have no OctoMap counterpart).
// Changing either set-up would change which cells a ray meets and so the maps or the views.
#include <cmath>
#include <cstdint>
#include <limits>

#include <Eigen/Core>
#include <octomap/OcTree.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "octoreach/exploration.hpp"

namespace octoreach::detail {

// computeRayKeys' choice: t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2), without branches (the
// axis of a ray's next step is what a branch predictor cannot guess).
inline int next_axis(const double t[3]) {
  const bool a = t[0] < t[1], b = t[0] < t[2], c = t[1] < t[2];
  return 2 - 2 * int(a & b) - int(!a & c);
}

// The set-up of one ray through the key grid: the first cell, the step along each axis, the ray parameter t
// at which it crosses the next cell border on each axis and the increment of t per cell.
struct GridRay {
  int key[3] = {0, 0, 0}, step[3] = {0, 0, 0};
  double t[3], d[3];
  double length = 0;  // in the units of t
};

// The walk of a GridRay, its state in scalars, which a compiler keeps in registers (arrays indexed by the axis
// of each step stay in memory): t[axis] += d[axis] along next_axis's choice, so the cells computeRayKeys' walk
// meets.
struct ScalarRay {
  int kx, ky, kz;
  const int sx, sy, sz;
  double tx, ty, tz;
  const double dx, dy, dz, length;
  explicit ScalarRay(const GridRay& g)
      : kx(g.key[0]), ky(g.key[1]), kz(g.key[2]), sx(g.step[0]), sy(g.step[1]), sz(g.step[2]), tx(g.t[0]),
        ty(g.t[1]), tz(g.t[2]), dx(g.d[0]), dy(g.d[1]), dz(g.d[2]), length(g.length) {}
  // Steps to the next cell; `exit` is where the ray left the current one. False when that lies past the length
  // or the step leaves the key range (the state is then spent).
  bool step(double& exit) {
    const bool a = tx < ty, on_x = a & (tx < tz), on_y = !a & (ty < tz), on_z = !(on_x | on_y);
    exit = on_x ? tx : on_y ? ty : tz;
    if (exit > length) return false;
    kx += on_x ? sx : 0;
    ky += on_y ? sy : 0;
    kz += on_z ? sz : 0;
    if ((unsigned(kx) | unsigned(ky) | unsigned(kz)) > 0xffffu) return false;
    tx += on_x ? dx : 0.0;  // (t + 0.0 is t: every t is >= 0 or inf)
    ty += on_y ? dy : 0.0;
    tz += on_z ? dz : 0.0;
    return true;
  }
  CellKey cell() const { return pack_key(std::uint32_t(kx), std::uint32_t(ky), std::uint32_t(kz)); }
  // The key of the cell cache's 16^3 block holding the current cell.
  CellKey block() const { return pack_key(std::uint32_t(kx >> 4), std::uint32_t(ky >> 4), std::uint32_t(kz >> 4)); }
  // The current cell's index in its block.
  int offset() const { return (kx & 15) | ((ky & 15) << 4) | ((kz & 15) << 8); }
};

// computeRayKeys' set-up for the ray from `origin` (in the cell key_origin) to `end`: t in metres
// along the float direction, borders computed as OctoMap does. Keys are left at zero: the batched
// walk keeps bitmap indices instead.
inline GridRay octomap_ray(const octomap::OcTree& tree, const octomap::point3d& origin,
                           const octomap::OcTreeKey& key_origin, const octomap::point3d& end) {
  GridRay r;
  octomap::point3d direction = (end - origin);
  float length = (float)direction.norm();
  direction /= length;
  const double res = tree.getResolution();
  for (unsigned i = 0; i < 3; ++i) {
    if (direction(i) > 0.0)
      r.step[i] = 1;
    else if (direction(i) < 0.0)
      r.step[i] = -1;
    else
      r.step[i] = 0;
    if (r.step[i] != 0) {
      double border = tree.keyToCoord(key_origin[i]);
      border += (float)(r.step[i] * res * 0.5);
      r.t[i] = (border - origin(i)) / direction(i);
      r.d[i] = res / std::fabs(direction(i));
    } else {
      r.t[i] = std::numeric_limits<double>::max();
      r.d[i] = std::numeric_limits<double>::max();
    }
  }
  r.length = length;
  return r;
}

// The segment o + s dir, s in [0, length] metres (dir unit), in key units (cell k covers
// [k, k + 1)); false when o is outside the key range.
inline bool key_unit_ray(double res, const Eigen::Vector3d& o, const Eigen::Vector3d& dir, double length, GridRay& r) {
  Eigen::Vector3d u = o / res + Eigen::Vector3d::Constant(32768.0);
  if ((u.array() < 0).any() || (u.array() >= 65536).any()) return false;
  for (int i = 0; i < 3; ++i) {
    r.key[i] = int(std::floor(u[i]));
    if (dir[i] > 0) {
      r.step[i] = 1;
      r.t[i] = (r.key[i] + 1 - u[i]) / dir[i];
      r.d[i] = 1.0 / dir[i];
    } else if (dir[i] < 0) {
      r.step[i] = -1;
      r.t[i] = (r.key[i] - u[i]) / dir[i];
      r.d[i] = -1.0 / dir[i];
    } else {
      r.step[i] = 0;
      r.t[i] = r.d[i] = std::numeric_limits<double>::infinity();
    }
  }
  r.length = length / res;
  return true;
}

// Visits the cells of the segment o + s dir, s in [0, length] (dir unit), in order; `visit(key)`
// returns false to stop (view scoring and utility rays).
template <class Visit>
void walk_cells(double res, const Eigen::Vector3d& o, const Eigen::Vector3d& dir, double length, Visit&& visit) {
  GridRay g;
  if (!key_unit_ray(res, o, dir, length, g)) return;
  ScalarRay r(g);
  double exit;
  do {
    if (!visit(r.cell())) return;
  } while (r.step(exit));
}

// The cells OcTreeBaseImpl::computeRayKeys(origin, end) returns, written straight into a bitmap
// instead of a KeyRay. The set-up (RayWalk::init) is computeRayKeys' code; the walk does the
// same double arithmetic in the same order (t_max[dim] += t_delta[dim], the same comparisons and
// tie-breaks), so it yields the same cells. It is written without data-dependent branches: the
// axis is picked with SSE masks, and the cell is kept as its bit index in the bitmap (a step
// along an axis adds a constant) and compared with the end cell's index. Both keys are known to
// be inside the map and the bitmap's box is padded, so a walk that overshoots the end cell by
// rounding stays inside. Two rays are walked side by side in the two lanes of the SSE registers,
// which hides the latency of each step's compare-select-add chain.
struct RayWalk {
  double t[3], d[3], len;
  std::size_t idx, target;
  std::size_t inc[4];  // by the chosen axis: [m0 | m1 << 1] -> 0: z, 1: x, 2: y
  // false when there is nothing to walk (origin and end in one cell)
  // Bitmap: set(key), index(key) and size(axis) of the bitmap the walk writes into (KeyBitmap).
  template <class Bitmap>
  bool init(const octomap::OcTree& tree, const octomap::point3d& origin, const octomap::OcTreeKey& key_origin,
            const octomap::point3d& end, const octomap::OcTreeKey& key_end, Bitmap& bits) {
    if (key_origin == key_end) return false;
    bits.set(key_origin);
    const GridRay r = octomap_ray(tree, origin, key_origin, end);
    // an end a denormal distance away (1e-38 m) has no direction in float: NaN steps walked off the bitmap
    if (!(r.length > 0) || std::isnan(r.t[0] + r.t[1] + r.t[2]) || std::isnan(r.d[0] + r.d[1] + r.d[2])) return false;
    for (int i = 0; i < 3; ++i) {
      t[i] = r.t[i];
      d[i] = r.d[i];
    }
    len = r.length;
    const int* step = r.step;
    idx = bits.index(key_origin);
    target = bits.index(key_end);
    const std::int64_t nx = std::int64_t(bits.size(0)), nxy = nx * std::int64_t(bits.size(1));
    inc[0] = std::size_t(std::int64_t(step[2]) * nxy);
    inc[1] = std::size_t(std::int64_t(step[0]));
    inc[2] = std::size_t(std::int64_t(step[1]) * nx);
    inc[3] = 0;
    return true;
  }
  // One step; false when the walk ends (the cell is then not free space of this ray).
  bool step(std::uint64_t* words) {
    static constexpr int kIncOf[3] = {1, 2, 0};  // inc[] slot of axis x, y, z
    const int dim = next_axis(t);
    idx += inc[kIncOf[dim]];
    t[dim] += d[dim];
    if (idx == target) return false;
    if (std::min(std::min(t[0], t[1]), t[2]) > len) return false;
    words[idx >> 6] |= std::uint64_t(1) << (idx & 63);
    return true;
  }
  void run(std::uint64_t* words) {
#if defined(__SSE2__)
    __m128d t0 = _mm_set_sd(t[0]), t1 = _mm_set_sd(t[1]), t2 = _mm_set_sd(t[2]);
    const __m128d d0 = _mm_set_sd(d[0]), d1 = _mm_set_sd(d[1]), d2 = _mm_set_sd(d[2]);
    for (;;) {
      // computeRayKeys: t0 < t1 ? (t0 < t2 ? 0 : 2) : (t1 < t2 ? 1 : 2); adding (mask & d) adds
      // d or +0.0, and t + 0.0 == t
      const __m128d lt01 = _mm_cmplt_sd(t0, t1);
      const __m128d m0 = _mm_and_pd(lt01, _mm_cmplt_sd(t0, t2));
      const __m128d m1 = _mm_andnot_pd(lt01, _mm_cmplt_sd(t1, t2));
      idx += inc[_mm_movemask_pd(_mm_unpacklo_pd(m0, m1))];
      t0 = _mm_add_sd(t0, _mm_and_pd(m0, d0));
      t1 = _mm_add_sd(t1, _mm_and_pd(m1, d1));
      t2 = _mm_add_sd(t2, _mm_andnot_pd(_mm_or_pd(m0, m1), d2));
      if (idx == target) return;
      if (_mm_cvtsd_f64(_mm_min_sd(_mm_min_sd(t0, t1), t2)) > len) return;
      words[idx >> 6] |= std::uint64_t(1) << (idx & 63);
    }
#else
    while (step(words)) {
    }
#endif
  }
};

// Walks two rays side by side (lane 0: a, lane 1: b) until one ends, then finishes the other.
inline void walk_pair(RayWalk& a, RayWalk& b, std::uint64_t* words) {
#if defined(__SSE2__)
  __m128d t0 = _mm_set_pd(b.t[0], a.t[0]), t1 = _mm_set_pd(b.t[1], a.t[1]), t2 = _mm_set_pd(b.t[2], a.t[2]);
  const __m128d d0 = _mm_set_pd(b.d[0], a.d[0]), d1 = _mm_set_pd(b.d[1], a.d[1]), d2 = _mm_set_pd(b.d[2], a.d[2]);
  const __m128d len = _mm_set_pd(b.len, a.len);
  bool a_on = true, b_on = true;
  for (;;) {
    const __m128d lt01 = _mm_cmplt_pd(t0, t1);
    const __m128d m0 = _mm_and_pd(lt01, _mm_cmplt_pd(t0, t2));
    const __m128d m1 = _mm_andnot_pd(lt01, _mm_cmplt_pd(t1, t2));
    a.idx += a.inc[_mm_movemask_pd(_mm_unpacklo_pd(m0, m1))];
    b.idx += b.inc[_mm_movemask_pd(_mm_unpackhi_pd(m0, m1))];
    t0 = _mm_add_pd(t0, _mm_and_pd(m0, d0));
    t1 = _mm_add_pd(t1, _mm_and_pd(m1, d1));
    t2 = _mm_add_pd(t2, _mm_andnot_pd(_mm_or_pd(m0, m1), d2));
    const int past = _mm_movemask_pd(_mm_cmpgt_pd(_mm_min_pd(_mm_min_pd(t0, t1), t2), len));
    a_on = a.idx != a.target && !(past & 1);
    b_on = b.idx != b.target && !(past & 2);
    if (!(a_on & b_on)) break;
    words[a.idx >> 6] |= std::uint64_t(1) << (a.idx & 63);
    words[b.idx >> 6] |= std::uint64_t(1) << (b.idx & 63);
  }
  alignas(16) double v[2];
  _mm_store_pd(v, t0);
  a.t[0] = v[0];
  b.t[0] = v[1];
  _mm_store_pd(v, t1);
  a.t[1] = v[0];
  b.t[1] = v[1];
  _mm_store_pd(v, t2);
  a.t[2] = v[0];
  b.t[2] = v[1];
  // the lane still walking: this step's cell is free, then it goes on alone
  RayWalk* rest = a_on ? &a : b_on ? &b : nullptr;
  if (rest) {
    words[rest->idx >> 6] |= std::uint64_t(1) << (rest->idx & 63);
    rest->run(words);
  }
#else
  a.run(words);
  b.run(words);
#endif
}

}  // namespace octoreach::detail
