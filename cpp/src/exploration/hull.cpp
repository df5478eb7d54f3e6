// The columns of cells inside the convex hull of the occupied cells.
#include "exploration/hull.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <octomap/OcTree.h>

#include "common/thread_pool.hpp"

namespace octoreach::detail {

double hull_box_cells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double resolution,
                      const Eigen::Vector3d& search_lo, const Eigen::Vector3d& search_hi) {
  double cells = 1;
  for (int j = 0; j < 3; ++j) {
    const double a = std::max(lo[j], search_lo[j]), b = std::min(hi[j], search_hi[j]);
    if (a > b) return 0;
    cells *= std::floor((b - a) / resolution) + 1;
  }
  return cells;
}

// Column intervals of the cells whose centres are inside the hull (planes: n.x + d <= 0).
HullColumns hull_columns(const octomap::OcTree& tree, const Hull& hull, int threads, const Eigen::Vector3d& s_lo,
                         const Eigen::Vector3d& s_hi) {
  const auto& planes = hull.planes;
  const auto& vertices = hull.vertices;
  HullColumns c;
  if (planes.empty() || vertices.empty()) return c;
  Eigen::Vector3d lo = vertices[0], hi = vertices[0];
  for (const auto& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // only the search space: cells whose centre lies in [s_lo, s_hi]
  const double res = tree.getResolution();
  lo = lo.cwiseMax(s_lo);
  hi = hi.cwiseMin(s_hi);
  if ((lo.array() > hi.array()).any()) return c;
  const double zcap_lo = std::ceil(s_lo.z() / res + 32767.5), zcap_hi = std::floor(s_hi.z() / res + 32767.5);
  octomap::OcTreeKey klo, khi;
  if (!tree.coordToKeyChecked(octomap::point3d(float(lo.x()), float(lo.y()), float(lo.z())), klo) ||
      !tree.coordToKeyChecked(octomap::point3d(float(hi.x()), float(hi.y()), float(hi.z())), khi))
    return c;
  c.x0 = klo[0] - 1;
  c.y0 = klo[1] - 1;
  c.nx = khi[0] - klo[0] + 3;
  c.ny = khi[1] - klo[1] + 3;
  c.lo.assign(std::size_t(c.nx) * c.ny, 1);
  c.hi.assign(std::size_t(c.nx) * c.ny, 0);
  const double eps = 1e-7 * res;
  const double half = 32768.0 - 0.5;  // key k has centre (k - half) * res (OctoMap: tree_max_val 32768)
  parallel_for(std::size_t(c.ny), threads, [&](std::size_t yi, int) {
    double y = (double(c.y0 + int(yi)) - half) * res;
    if (y < s_lo.y() || y > s_hi.y()) return;
    for (int xi = 0; xi < c.nx; ++xi) {
      double x = (double(c.x0 + xi) - half) * res;
      if (x < s_lo.x() || x > s_hi.x()) continue;
      double zlo = -std::numeric_limits<double>::infinity(), zhi = std::numeric_limits<double>::infinity();
      bool empty = false;
      for (const auto& p : planes) {
        double a = p[2], b = -(p[3] + p[0] * x + p[1] * y);
        if (std::abs(a) < 1e-12) {
          if (b < -eps) {
            empty = true;
            break;
          }
        } else if (a > 0) {
          zhi = std::min(zhi, (b + eps) / a);
        } else {
          zlo = std::max(zlo, (b + eps) / a);
        }
        if (zlo > zhi) {
          empty = true;
          break;
        }
      }
      std::size_t i = yi * c.nx + xi;
      if (empty) continue;
      double klo_f = std::ceil(zlo / res + half), khi_f = std::floor(zhi / res + half);
      klo_f = std::max({klo_f, 0.0, zcap_lo});
      khi_f = std::min({khi_f, 65535.0, zcap_hi});
      if (klo_f > khi_f) continue;
      c.lo[i] = std::int32_t(klo_f);
      c.hi[i] = std::int32_t(khi_f);
    }
  }, 4);
  return c;
}

HullColumns void_columns(const octomap::OcTree& tree, const Hull& hull, int threads, const ExplorationOptions& o) {
  if (!o.voids_fill_search_space || hull.planes.empty())
    return hull_columns(tree, hull, threads, o.search_lo, o.search_hi);
  HullColumns c;
  octomap::OcTreeKey klo, khi;
  if (!tree.coordToKeyChecked(octomap::point3d(float(o.search_lo.x()), float(o.search_lo.y()), float(o.search_lo.z())), klo) ||
      !tree.coordToKeyChecked(octomap::point3d(float(o.search_hi.x()), float(o.search_hi.y()), float(o.search_hi.z())), khi))
    return c;
  // cells whose centre lies in the box, as hull_columns counts them
  const double res = tree.getResolution(), half = 32768.0 - 0.5;
  const auto first = [&](double v) { return std::int32_t(std::ceil(v / res + half - 1e-9)); };
  const auto last = [&](double v) { return std::int32_t(std::floor(v / res + half + 1e-9)); };
  const std::int32_t x0 = first(o.search_lo.x()), x1 = last(o.search_hi.x()), y0 = first(o.search_lo.y()),
                     y1 = last(o.search_hi.y()), z0 = first(o.search_lo.z()), z1 = last(o.search_hi.z());
  if (x0 > x1 || y0 > y1 || z0 > z1) return c;
  c.x0 = x0;
  c.y0 = y0;
  c.nx = x1 - x0 + 1;
  c.ny = y1 - y0 + 1;
  c.lo.assign(std::size_t(c.nx) * c.ny, z0);
  c.hi.assign(std::size_t(c.nx) * c.ny, z1);
  return c;
}

}  // namespace octoreach::detail
