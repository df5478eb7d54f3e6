// Convex hull of 3D points with libqhull_r.
#include "common/convex_hull.hpp"

#include <algorithm>
#include <cstdio>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

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

}  // namespace octoreach::detail
