#include "shape_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace octoreach::detail {
namespace {

constexpr double kGrid = 0.03;       // grid spacing (m) of the distance grids
constexpr double kGridMargin = 0.06; // the grid covers the local AABB and this much around it (m)
constexpr double kCell = 0.02;       // edge (m) of the cover's cells, at most
constexpr double kMargin = 1e-4;     // FCL's distance and its collision test need not agree to the last bit
constexpr std::size_t kMaxNodes = std::size_t(1) << 21;

// Distance from p to the box [lo, hi] (0 inside): a lower bound of the distance to anything inside it.
double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

}  // namespace

ShapeClearance::ShapeClearance(const Robot& robot)
    : fields_(robot.links().size()), ready_(robot.links().size()) {}

ShapeClearance::Field& ShapeClearance::field(const Robot& robot, int link, std::size_t shape) {
  auto& fs = fields_[link];
  auto& rd = ready_[link];
  const auto& shapes = robot.links()[link].shapes;
  if (fs.size() != shapes.size()) {
    fs.assign(shapes.size(), Field());
    rd.assign(shapes.size(), 0);
  }
  Field& f = fs[shape];
  if (rd[shape]) return f;
  rd[shape] = 1;
  const fcl::CollisionGeometryd& g = *shapes[shape].geometry;
  f.geometry = &g;
  f.box_lo = g.aabb_local.min_;
  f.box_hi = g.aabb_local.max_;
  const Eigen::Vector3d extent = (f.box_hi - f.box_lo).cwiseMax(0.0);
  f.centre = 0.5 * (f.box_lo + f.box_hi);
  f.radius = 0.5 * extent.norm();
  // The grid (coarser for a large shape, so that it stays within kMaxNodes).
  f.h = kGrid;
  for (;;) {
    std::size_t total = 1;
    for (int a = 0; a < 3; ++a) {
      f.n[a] = static_cast<int>(std::ceil((extent[a] + 2 * kGridMargin) / f.h)) + 1;
      total *= static_cast<std::size_t>(f.n[a]);
    }
    if (total <= kMaxNodes) {
      f.d.assign(total, std::numeric_limits<float>::quiet_NaN());
      break;
    }
    f.h *= 1.5;
  }
  f.lo = f.box_lo.array() - kGridMargin;
  // The cover: cells of the local AABB that hold some of the shape.
  int m[3];
  Eigen::Vector3d e;
  for (int a = 0; a < 3; ++a) {
    m[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / kCell)));
    e[a] = extent[a] / m[a];
  }
  f.cover_radius = 0.5 * e.norm();
  std::vector<char> keep(static_cast<std::size_t>(m[0]) * m[1] * m[2], 0);
  auto cell_index = [&](int a, double v) {
    if (!(e[a] > 0)) return 0;
    return std::clamp(static_cast<int>(std::floor((v - f.box_lo[a]) / e[a])), 0, m[a] - 1);
  };
  const auto* mesh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(&g);
  if (mesh && mesh->vertices && mesh->tri_indices && mesh->num_tris > 0) {
    for (int t = 0; t < mesh->num_tris; ++t) {
      const fcl::Triangle& tri = mesh->tri_indices[t];
      Eigen::Vector3d lo = mesh->vertices[tri[0]], hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = lo.cwiseMin(mesh->vertices[tri[k]]);
        hi = hi.cwiseMax(mesh->vertices[tri[k]]);
      }
      int c0[3], c1[3];
      for (int a = 0; a < 3; ++a) {
        c0[a] = cell_index(a, lo[a] - 1e-9);
        c1[a] = cell_index(a, hi[a] + 1e-9);
      }
      for (int i = c0[0]; i <= c1[0]; ++i)
        for (int j = c0[1]; j <= c1[1]; ++j)
          for (int k = c0[2]; k <= c1[2]; ++k) keep[(static_cast<std::size_t>(i) * m[1] + j) * m[2] + k] = 1;
    }
  } else {
    std::fill(keep.begin(), keep.end(), 1);  // a primitive: its whole box
  }
  // Cells grouped in blocks of up to 3 x 3 x 3: a block whose sphere is clear needs no cell tests.
  for (int bi = 0; bi < m[0]; bi += 3)
    for (int bj = 0; bj < m[1]; bj += 3)
      for (int bk = 0; bk < m[2]; bk += 3) {
        Field::Block blk{Eigen::Vector3d::Zero(), 0.0, static_cast<std::uint32_t>(f.cover.size()), 0};
        const int ei = std::min(m[0], bi + 3), ej = std::min(m[1], bj + 3), ek = std::min(m[2], bk + 3);
        for (int i = bi; i < ei; ++i)
          for (int j = bj; j < ej; ++j)
            for (int k = bk; k < ek; ++k)
              if (keep[(static_cast<std::size_t>(i) * m[1] + j) * m[2] + k])
                f.cover.push_back(f.box_lo + Eigen::Vector3d((i + 0.5) * e[0], (j + 0.5) * e[1], (k + 0.5) * e[2]));
        blk.end = static_cast<std::uint32_t>(f.cover.size());
        if (blk.end == blk.begin) continue;
        const Eigen::Vector3d lo = f.box_lo + Eigen::Vector3d(bi * e[0], bj * e[1], bk * e[2]);
        const Eigen::Vector3d hi = f.box_lo + Eigen::Vector3d(ei * e[0], ej * e[1], ek * e[2]);
        blk.centre = 0.5 * (lo + hi);
        blk.radius = 0.5 * (hi - lo).norm();
        f.blocks.push_back(blk);
      }
  f.inv_h = 1.0 / f.h;
  return f;
}

double ShapeClearance::lower_bound(Field& f, const Eigen::Vector3d& p) {
  const double outside = box_distance(p, f.box_lo, f.box_hi);
  int idx[3];
  for (int a = 0; a < 3; ++a) {
    const double u = (p[a] - f.lo[a]) * f.inv_h;
    if (!(u >= 0.0 && u <= f.n[a] - 1)) return outside;  // off the grid: the box's bound only
    idx[a] = static_cast<int>(u + 0.5);
  }
  const std::size_t at = (static_cast<std::size_t>(idx[0]) * f.n[1] + idx[1]) * f.n[2] + idx[2];
  const Eigen::Vector3d node = f.lo + f.h * Eigen::Vector3d(idx[0], idx[1], idx[2]);
  if (std::isnan(f.d[at])) {
    // One FCL distance query: a tiny sphere at the node against the shape (both in the shape's frame).
    static const fcl::Sphered probe(1e-6);
    fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    fcl::Transform3d tp = fcl::Transform3d::Identity();
    tp.translation() = node;
    fcl::distance(&probe, tp, f.geometry, fcl::Transform3d::Identity(), request, result);
    const double d = result.min_distance > 0 ? result.min_distance : 0.0;
    f.d[at] = static_cast<float>(d * (1.0 - 1e-6));  // rounded down to a float
  }
  return std::max(outside, static_cast<double>(f.d[at]) - (p - node).norm());
}

bool ShapeClearance::apart(const Robot& robot, int a, std::size_t sa, const Pose& ta, int b, std::size_t sb,
                           const Pose& tb) {
  Field& fa = field(robot, a, sa);
  Field& fb = field(robot, b, sb);
  const Pose a_in_b = tb.inverse() * ta;
  // One sphere around the whole of either shape.
  if (lower_bound(fb, a_in_b * fa.centre) > fa.radius + kMargin) return true;
  const Pose b_in_a = a_in_b.inverse();
  if (lower_bound(fa, b_in_a * fb.centre) > fb.radius + kMargin) return true;
  // The cover of the shape with fewer cells against the other's grid.
  const bool a_covers = fa.cover.size() <= fb.cover.size();
  Field& coverer = a_covers ? fa : fb;
  Field& other = a_covers ? fb : fa;
  const Pose& into = a_covers ? a_in_b : b_in_a;
  const double need = coverer.cover_radius + kMargin;
  for (const Field::Block& blk : coverer.blocks) {
    if (lower_bound(other, into * blk.centre) > blk.radius + kMargin) continue;
    for (std::uint32_t i = blk.begin; i < blk.end; ++i)
      if (!(lower_bound(other, into * coverer.cover[i]) > need)) return false;
  }
  return true;
}

}  // namespace octoreach::detail
