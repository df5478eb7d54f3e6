// Convex hull of the occupied cells (libqhull_r) and the columns of cells inside it.
#include "hull.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <octomap/OcTree.h>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "common/thread_pool.hpp"

namespace octoreach::detail {

// Convex hull with libqhull_r: facet planes (outward unit normal n, offset d; inside n.x + d <= 0)
// and vertices. Returns false when the points are degenerate (fewer than 4, coplanar ...).
bool convex_hull(const std::vector<Eigen::Vector3d>& pts, Hull& hull) {
  if (pts.size() < 4) return false;
  std::vector<coordT> coords(pts.size() * 3);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int j = 0; j < 3; ++j) coords[3 * i + j] = pts[i][j];
  qhT qh_qh;
  qhT* qh = &qh_qh;
  FILE* devnull = std::fopen("/dev/null", "w");
  qh_zero(qh, devnull);
  char flags[] = "qhull Qt";
  int exitcode = qh_new_qhull(qh, 3, int(pts.size()), coords.data(), False, flags, nullptr, devnull);
  bool ok = exitcode == 0;
  std::vector<Eigen::Vector4d> planes;
  std::vector<Eigen::Vector3d> vertices;
  if (ok) {
    facetT* facet;
    FORALLfacets {
      planes.emplace_back(facet->normal[0], facet->normal[1], facet->normal[2], facet->offset);
    }
    vertexT* vertex;
    FORALLvertices {
      vertices.emplace_back(vertex->point[0], vertex->point[1], vertex->point[2]);
    }
    std::sort(vertices.begin(), vertices.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    std::sort(planes.begin(), planes.end(), [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
      return std::lexicographical_compare(a.data(), a.data() + 4, b.data(), b.data() + 4);
    });
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (devnull) std::fclose(devnull);
  if (!ok || planes.size() < 4) return false;
  hull.planes = std::move(planes);
  hull.vertices = std::move(vertices);
  return true;
}

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
}  // namespace octoreach::detail
