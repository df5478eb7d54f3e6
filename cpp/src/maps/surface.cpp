#include "octoreach/surface.hpp"

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include <fcl/fcl.h>

namespace octoreach {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

bool on_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double eps) {
  return std::abs(cross2(b - a, p - a)) <= eps * (b - a).norm() && (p - a).dot(p - b) <= eps * eps;
}

// True when the closed segments touch or cross (eps: a length tolerance).
bool segments_intersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, const Eigen::Vector2d& q1,
                        const Eigen::Vector2d& q2, double eps) {
  double d1 = cross2(p2 - p1, q1 - p1), d2 = cross2(p2 - p1, q2 - p1);
  double d3 = cross2(q2 - q1, p1 - q1), d4 = cross2(q2 - q1, p2 - q1);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return on_segment(q1, p1, p2, eps) || on_segment(q2, p1, p2, eps) || on_segment(p1, q1, q2, eps) ||
         on_segment(p2, q1, q2, eps);
}

bool point_in_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       const Eigen::Vector2d& c) {
  double d1 = cross2(b - a, p - a), d2 = cross2(c - b, p - b), d3 = cross2(a - c, p - c);
  return d1 >= 0 && d2 >= 0 && d3 >= 0;
}

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

// Throws unless the 2D polygon is simple: no spike of zero width, no edges crossing or touching.
void check_simple(const std::vector<Eigen::Vector2d>& polygon, double eps) {
  const std::size_t N = polygon.size();
  for (std::size_t i = 0; i < N; ++i) {
    // Adjacent edges folding back onto each other make a spike of zero width.
    Eigen::Vector2d e0 = polygon[(i + 1) % N] - polygon[i], e1 = polygon[(i + 2) % N] - polygon[(i + 1) % N];
    if (std::abs(cross2(e0, e1)) <= eps * e0.norm() && e0.dot(e1) < 0)
      throw std::invalid_argument("surface polygon is self-intersecting: edges " + std::to_string(i) + " and " +
                                  std::to_string((i + 1) % N) + " fold back onto each other");
    for (std::size_t j = i + 1; j < N; ++j) {
      if (j == i + 1 || (i == 0 && j == N - 1)) continue;
      if (segments_intersect(polygon[i], polygon[(i + 1) % N], polygon[j], polygon[(j + 1) % N], eps))
        throw std::invalid_argument("surface polygon is self-intersecting: edges " + std::to_string(i) + " and " +
                                    std::to_string(j) + " cross or touch");
    }
  }
}

// Triangles (vertex indices) of a simple 2D polygon by ear clipping; `clockwise` polygons are
// walked backwards so that ears are convex corners.
std::vector<std::array<int, 3>> ear_clip(const std::vector<Eigen::Vector2d>& polygon, bool clockwise) {
  const std::size_t N = polygon.size();
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> idx(N);
  for (std::size_t i = 0; i < N; ++i) idx[i] = static_cast<int>(i);
  if (clockwise) std::reverse(idx.begin(), idx.end());
  while (idx.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      int ia = idx[(k + idx.size() - 1) % idx.size()], ib = idx[k], ic = idx[(k + 1) % idx.size()];
      const auto &a = polygon[ia], &b = polygon[ib], &c = polygon[ic];
      if (cross2(b - a, c - b) <= 1e-15) continue;  // reflex or flat corner
      bool ear = true;
      for (int other : idx)
        if (other != ia && other != ib && other != ic && point_in_triangle(polygon[other], a, b, c)) {
          ear = false;
          break;
        }
      if (!ear) continue;
      triangles.push_back({ia, ib, ic});
      idx.erase(idx.begin() + k);
      clipped = true;
      break;
    }
    if (!clipped) throw std::invalid_argument("surface polygon could not be triangulated (degenerate shape)");
  }
  triangles.push_back({idx[0], idx[1], idx[2]});
  return triangles;
}

}  // namespace

Surface::Surface(const std::vector<Eigen::Vector3d>& vertices, double thickness) : thickness_(thickness) {
  if (vertices.size() < 3)
    throw std::invalid_argument("a surface needs at least three vertices, got " + std::to_string(vertices.size()));
  if (!(thickness > 0) || !std::isfinite(thickness))
    throw std::invalid_argument("surface thickness must be positive, got " + std::to_string(thickness));
  for (const auto& v : vertices)
    if (!v.allFinite()) throw std::invalid_argument("surface vertices must be finite");
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
  check_simple(polygon_, 1e-9 * std::max(1.0, scale));
  // Signed area; orient the 2D polygon counter-clockwise for ear clipping.
  double a2 = 0;
  for (std::size_t i = 0; i < N; ++i) a2 += cross2(polygon_[i], polygon_[(i + 1) % N]);
  area_ = std::abs(a2) / 2;
  if (area_ < 1e-9) throw std::invalid_argument("degenerate surface polygon: zero area");
  triangles_ = ear_clip(polygon_, a2 < 0);
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
  if (!(sx > 0) || !(sy > 0)) throw std::invalid_argument("rectangle sides must be positive");
  Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<Eigen::Vector3d> v;
  for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    v.push_back(Eigen::Vector3d(x, y, height) + R * Eigen::Vector3d(a * sx / 2, b * sy / 2, 0));
  return Surface(v, thickness);
}

void Surface::add_box(const Eigen::Vector3d& size, const Pose& pose) {
  if (!(size.array() > 0).all() || !size.allFinite()) throw std::invalid_argument("box size must be positive");
  if (!pose.matrix().allFinite()) throw std::invalid_argument("box pose must be finite");
  boxes_.emplace_back(size, pose);
}

void Surface::add_legs(double width) {
  if (!(width > 0)) throw std::invalid_argument("leg width must be positive");
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
  if (!(res > 0) || !std::isfinite(res)) throw std::invalid_argument("sampling resolution must be positive");
  Eigen::Vector2d lo = polygon_[0], hi = polygon_[0];
  for (const auto& p : polygon_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
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
