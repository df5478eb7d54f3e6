#include "octoreach/surface.hpp"

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include <fcl/fcl.h>

#include "common/cancel.hpp"
#include "common/checks.hpp"
#include "maps/polygon.hpp"

namespace octoreach {
namespace {

using detail::cross2;

std::string vec(const Eigen::Vector3d& v) {
  return "(" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) + ")";
}

// Unit normal of a planar polygon, z >= 0: Newell's normal, robust for non-convex polygons.
Eigen::Vector3d plane_normal(const std::vector<Eigen::Vector3d>& vertices) {
  const std::size_t N = vertices.size();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < N; ++i) {
    const auto& a = vertices[i];
    const auto& b = vertices[(i + 1) % N];
    n.x() += (a.y() - b.y()) * (a.z() + b.z());
    n.y() += (a.z() - b.z()) * (a.x() + b.x());
    n.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  if (n.norm() < 1e-12) {
    // No net area (a bow tie, or collinear points): fall back to the best-fit plane so that the
    // checks below can say what is wrong.
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& v : vertices) mean += v;
    mean /= static_cast<double>(N);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& v : vertices) cov += (v - mean) * (v - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    if (eig.eigenvalues()[1] < 1e-18) throw std::invalid_argument("degenerate surface polygon: its vertices are collinear");
    n = eig.eigenvectors().col(0);
  }
  n.normalize();
  if (n.z() < -1e-9) n = -n;
  return n;
}

}  // namespace

Surface::Surface(const std::vector<Eigen::Vector3d>& vertices, double thickness) : thickness_(thickness) {
  if (vertices.size() < 3)
    throw std::invalid_argument("a surface needs at least three vertices, got " + std::to_string(vertices.size()));
  if (vertices.size() > limits::kPolygonVertices)
    throw std::invalid_argument("a surface polygon has at most " + std::to_string(limits::kPolygonVertices) +
                                " vertices, got " + std::to_string(vertices.size()));
  detail::check_positive(thickness, "thickness");
  detail::check_coordinate(thickness, "thickness");
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite() || vertices[i].cwiseAbs().maxCoeff() > limits::kCoordinate)
      throw std::invalid_argument("surface vertices[" + std::to_string(i) + "] " + detail::format_point(vertices[i]) +
                                  (vertices[i].allFinite() ? " is out of range (coordinates at most " +
                                                                 detail::format_number(limits::kCoordinate) + " m in magnitude)"
                                                           : " is not finite"));
  detail::CancellableScope cancellable;  // the checks below take a while on polygons of many vertices
  vertices_ = vertices;
  const std::size_t N = vertices.size();
  const Eigen::Vector3d n = plane_normal(vertices);
  normal_ = n;
  origin_ = Eigen::Vector3d::Zero();
  for (const auto& v : vertices) origin_ += v;
  origin_ /= N;
  double scale = 0;
  for (const auto& v : vertices) {
    double d = (v - origin_).dot(n);
    scale = std::max(scale, (v - origin_).norm());
    if (std::abs(d) > 1e-6 + 1e-6 * scale)
      throw std::invalid_argument("surface polygon is not planar: vertex " + vec(v) + " is " + std::to_string(d) +
                                  " m off the plane");
  }
  // u along the first non-degenerate edge.
  for (std::size_t i = 0; i < N; ++i) {
    Eigen::Vector3d e = vertices[(i + 1) % N] - vertices[i];
    e -= e.dot(n) * n;
    if (e.norm() > 1e-9) {
      u_ = e.normalized();
      break;
    }
  }
  v_ = n.cross(u_);
  for (const auto& p : vertices) polygon_.push_back(project(p));
  for (std::size_t i = 0; i < N; ++i)
    if ((polygon_[i] - polygon_[(i + 1) % N]).norm() < 1e-9)
      throw std::invalid_argument("surface polygon has repeated vertex " + vec(vertices[i]));
  detail::check_simple(polygon_, 1e-9 * std::max(1.0, scale));
  // Signed area; orient the 2D polygon counter-clockwise for ear clipping.
  double a2 = 0;
  for (std::size_t i = 0; i < N; ++i) a2 += cross2(polygon_[i], polygon_[(i + 1) % N]);
  area_ = std::abs(a2) / 2;
  if (area_ < 1e-9) throw std::invalid_argument("degenerate surface polygon: zero area");
  triangles_ = detail::ear_clip(polygon_, a2 < 0);
  // Convex polygons get a half-plane test (the hot loop of surface-map builds).
  std::vector<Eigen::Vector2d> ccw;
  for (std::size_t i = 0; i < N; ++i) ccw.push_back(polygon_[a2 < 0 ? N - 1 - i : i]);
  convex_ = true;
  for (std::size_t i = 0; i < N && convex_; ++i)
    if (cross2(ccw[(i + 1) % N] - ccw[i], ccw[(i + 2) % N] - ccw[(i + 1) % N]) < -1e-12) convex_ = false;
  if (convex_)
    for (std::size_t i = 0; i < N; ++i) {
      Eigen::Vector2d e = ccw[(i + 1) % N] - ccw[i];
      Eigen::Vector2d out(e.y(), -e.x());  // outward normal of a counter-clockwise polygon
      halfplanes_.emplace_back(out.x(), out.y(), out.dot(ccw[i]));
    }
}

Surface Surface::rectangle(double sx, double sy, double height, double x, double y, double yaw, double thickness) {
  detail::check_positive(sx, "size_x");
  detail::check_positive(sy, "size_y");
  detail::check_coordinate(sx, "size_x");
  detail::check_coordinate(sy, "size_y");
  detail::check_coordinate(height, "height");
  detail::check_coordinate(x, "x");
  detail::check_coordinate(y, "y");
  detail::check_finite(yaw, "yaw");
  Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<Eigen::Vector3d> v;
  for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    v.push_back(Eigen::Vector3d(x, y, height) + R * Eigen::Vector3d(a * sx / 2, b * sy / 2, 0));
  return Surface(v, thickness);
}

void Surface::add_box(const Eigen::Vector3d& size, const Pose& pose) {
  detail::check_coordinates(size, "size");
  if (!(size.array() > 0).all()) throw std::invalid_argument("box size must be positive, got " + detail::format_point(size));
  check_rigid(pose, "pose");
  detail::check_coordinates(pose.translation(), "pose translation");
  boxes_.emplace_back(size, pose);
}

void Surface::add_legs(double width) {
  detail::check_positive(width, "width");
  detail::check_coordinate(width, "width");
  for (const auto& v : vertices_) {
    double h = v.z() - thickness_;
    if (h <= 0) continue;
    Eigen::Vector3d inward = (origin_ - v);
    inward.z() = 0;
    if (inward.norm() > 1e-9) inward = inward.normalized() * width;
    Pose p = Pose::Identity();
    p.translation() = Eigen::Vector3d(v.x() + inward.x(), v.y() + inward.y(), h / 2);
    add_box(Eigen::Vector3d(width, width, h), p);
  }
}

bool Surface::contains_even_odd(const Eigen::Vector2d& p) const {
  if (!p.allFinite()) return false;
  bool inside = false;
  const std::size_t N = polygon_.size();
  for (std::size_t i = 0, j = N - 1; i < N; j = i++) {
    const auto &a = polygon_[i], &b = polygon_[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

std::vector<Eigen::Vector3d> Surface::sample_points(double res) const {
  detail::check_positive(res, "resolution");
  Eigen::Vector2d lo = polygon_[0], hi = polygon_[0];
  for (const auto& p : polygon_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double grid = std::ceil((hi.x() - lo.x()) / res) * std::ceil((hi.y() - lo.y()) / res);
  if (!(grid <= double(limits::kSurfacePoints)))
    throw std::invalid_argument("resolution " + detail::format_number(res) + " m gives " + detail::format_number(grid) +
                                " grid points over the surface, more than the limit of " +
                                std::to_string(limits::kSurfacePoints) + ": use a coarser resolution");
  std::vector<Eigen::Vector3d> out;
  const double eps = 1e-9;
  for (double u = lo.x() + res / 2; u < hi.x() - eps; u += res)
    for (double v = lo.y() + res / 2; v < hi.y() - eps; v += res)
      if (contains({u, v})) out.push_back(origin_ + u * u_ + v * v_);
  return out;
}

std::shared_ptr<Obstacles> Surface::obstacles() const {
  auto obs = std::make_shared<Obstacles>();
  for (const auto& t : triangles_) {
    auto verts = std::make_shared<std::vector<Eigen::Vector3d>>();
    for (int k : t) verts->push_back(vertices_[k]);
    for (int k : t) verts->push_back(vertices_[k] - thickness_ * normal_);
    // Faces: top (0 1 2 seen from +n after orienting), bottom, three sides.
    Eigen::Vector3d tn = ((*verts)[1] - (*verts)[0]).cross((*verts)[2] - (*verts)[0]);
    bool ccw = tn.dot(normal_) > 0;
    std::vector<int> f;
    auto face = [&](std::initializer_list<int> ids) {
      f.push_back(static_cast<int>(ids.size()));
      for (int i : ids) f.push_back(i);
    };
    if (ccw) {
      face({0, 1, 2});
      face({5, 4, 3});
      face({0, 3, 4, 1});
      face({1, 4, 5, 2});
      face({2, 5, 3, 0});
    } else {
      face({2, 1, 0});
      face({3, 4, 5});
      face({1, 4, 3, 0});
      face({2, 5, 4, 1});
      face({0, 3, 5, 2});
    }
    auto faces = std::make_shared<std::vector<int>>(f);
    obs->add_geometry(std::make_shared<fcl::Convexd>(verts, 5, faces), Pose::Identity(), "surface");
  }
  for (const auto& [size, pose] : boxes_) obs->add_box(size, pose, "surface_box");
  return obs;
}

}  // namespace octoreach
