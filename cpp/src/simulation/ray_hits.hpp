#pragma once
// Internal: where a ray o + t d (t in [0, tmax]) first meets a box, a triangle, a sphere or a cylinder, each
// in its own frame, and the unit normal there facing the ray. A ray that starts inside a solid meets it at
// t = 0 with the normal -d.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace octoreach::detail {

/// Slab test; t in [0, tmax]. `axis`: the slab the ray entered last (-1 when it starts inside).
inline bool ray_box(const Eigen::Vector3d& o, const Eigen::Vector3d& inv, const Eigen::Vector3d& lo,
                    const Eigen::Vector3d& hi, double tmax, double& t, int* axis = nullptr) {
  double t0 = 0, t1 = tmax;
  int entered = -1;
  for (int i = 0; i < 3; ++i) {
    double a = (lo[i] - o[i]) * inv[i], b = (hi[i] - o[i]) * inv[i];
    if (std::isnan(a)) a = -std::numeric_limits<double>::infinity();  // 0 * inf: origin on the slab
    if (std::isnan(b)) b = std::numeric_limits<double>::infinity();
    if (a > b) std::swap(a, b);
    if (a > t0) {
      t0 = a;
      entered = i;
    }
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  t = t0;
  if (axis) *axis = entered;
  return true;
}

/// Unit normal of the face of a box a ray with direction d entered through `axis` (-d from inside).
inline Eigen::Vector3d box_normal(const Eigen::Vector3d& d, int axis) {
  if (axis < 0) return -d.normalized();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[axis] = d[axis] > 0 ? -1.0 : 1.0;
  return n;
}

/// Moller-Trumbore.
inline bool ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c, double& t) {
  Eigen::Vector3d e1 = b - a, e2 = c - a, p = d.cross(e2);
  double det = e1.dot(p);
  if (std::abs(det) < 1e-14) return false;
  double inv = 1.0 / det;
  Eigen::Vector3d s = o - a;
  double u = s.dot(p) * inv;
  if (u < 0 || u > 1) return false;
  Eigen::Vector3d q = s.cross(e1);
  double v = d.dot(q) * inv;
  if (v < 0 || u + v > 1) return false;
  t = e2.dot(q) * inv;
  return t > 0;
}

/// A sphere of radius r centred at the origin (o in its frame); `n` gets the normal.
inline bool ray_sphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double tmax, double& t,
                       Eigen::Vector3d& n) {
  const double a = d.squaredNorm(), b = o.dot(d), c = o.squaredNorm() - r * r;
  if (c <= 0) {  // inside
    t = 0;
    n = -d.normalized();
    return true;
  }
  const double disc = b * b - a * c;
  if (b >= 0 || disc < 0) return false;  // moving away, or missing
  t = (-b - std::sqrt(disc)) / a;
  if (t > tmax) return false;
  n = (o + t * d) / r;
  return true;
}

/// A cylinder of radius r along z from -h to h (o, d in its frame); `n` gets the normal in that frame.
inline bool ray_cylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double h, double tmax,
                         double& t, Eigen::Vector3d& n) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  double r0 = -inf, r1 = inf;  // inside the infinite cylinder
  const double a = d.x() * d.x() + d.y() * d.y(), b = o.x() * d.x() + o.y() * d.y();
  const double c = o.x() * o.x() + o.y() * o.y() - r * r;
  if (a > 0) {
    const double disc = b * b - a * c;
    if (disc < 0) return false;
    const double s = std::sqrt(disc);
    r0 = (-b - s) / a;
    r1 = (-b + s) / a;
  } else if (c > 0) {
    return false;  // parallel to the axis, outside
  }
  double z0 = -inf, z1 = inf;  // between the caps
  if (d.z() != 0) {
    z0 = (-h - o.z()) / d.z();
    z1 = (h - o.z()) / d.z();
    if (z0 > z1) std::swap(z0, z1);
  } else if (std::abs(o.z()) > h) {
    return false;
  }
  const double enter = std::max(r0, z0), leave = std::min({r1, z1, tmax});
  if (std::max(enter, 0.0) > leave) return false;
  if (enter <= 0) {  // inside
    t = 0;
    n = -d.normalized();
    return true;
  }
  t = enter;
  if (z0 >= r0) {
    n = Eigen::Vector3d(0, 0, d.z() > 0 ? -1.0 : 1.0);
  } else {
    const Eigen::Vector3d p = o + t * d;
    n = Eigen::Vector3d(p.x(), p.y(), 0) / r;
  }
  return true;
}

}  // namespace octoreach::detail
