#pragma once
// Internal: GJK (Gilbert-Johnson-Keerthi) on the Minkowski difference of two convex sets given by
// their support functions, used only to find a separating plane; the plane is then certified by the
// support functions themselves (apart_along), so an answer "apart" rests on that check alone, never on
// GJK's arithmetic. Shared by the mesh-pair check (hull against hull) and the mesh-box check (hull
// against box).
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace octoreach::detail::gjk {

// Closest point to the origin of the triangle (a, b, c) (Ericson, Real-Time Collision Detection
// 5.1.5); out/m: the vertices of the feature it lies on.
inline Eigen::Vector3d closest_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                 Eigen::Vector3d* out, int& m) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) {
    out[0] = a;
    m = 1;
    return a;
  }
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) {
    out[0] = b;
    m = 1;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    out[0] = a;
    out[1] = b;
    m = 2;
    return a + d1 / (d1 - d3) * ab;
  }
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) {
    out[0] = c;
    m = 1;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    out[0] = a;
    out[1] = c;
    m = 2;
    return a + d2 / (d2 - d6) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    out[0] = b;
    out[1] = c;
    m = 2;
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  out[0] = a;
  out[1] = b;
  out[2] = c;
  m = 3;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// True when the origin and d lie on opposite sides of the plane through a, b, c.
inline bool origin_outside(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  const Eigen::Vector3d nrm = (b - a).cross(c - a);
  return (-a).dot(nrm) * (d - a).dot(nrm) < 0;
}

// Closest point to the origin of the simplex W[0..n), W reduced to the feature it lies on. A
// tetrahedron holding the origin gives zero.
inline Eigen::Vector3d closest(Eigen::Vector3d* W, int& n) {
  if (n == 1) return W[0];
  if (n == 2) {
    const Eigen::Vector3d ab = W[1] - W[0];
    const double t = -W[0].dot(ab) / ab.squaredNorm();
    if (!(t > 0)) {
      n = 1;
      return W[0];
    }
    if (t >= 1) {
      W[0] = W[1];
      n = 1;
      return W[0];
    }
    return W[0] + t * ab;
  }
  Eigen::Vector3d out[3];
  int m = 0;
  if (n == 3) {
    const Eigen::Vector3d p = closest_triangle(W[0], W[1], W[2], out, m);
    for (int i = 0; i < m; ++i) W[i] = out[i];
    n = m;
    return p;
  }
  // Tetrahedron: the closest of the faces the origin lies outside of.
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), keep[3];
  int kept = 4;
  for (const auto& f : kFaces) {
    if (!origin_outside(W[f[0]], W[f[1]], W[f[2]], W[f[3]])) continue;
    const Eigen::Vector3d q = closest_triangle(W[f[0]], W[f[1]], W[f[2]], out, m);
    if (q.squaredNorm() < best) {
      best = q.squaredNorm();
      p = q;
      for (int i = 0; i < m; ++i) keep[i] = out[i];
      kept = m;
    }
  }
  if (kept == 4) return Eigen::Vector3d::Zero();  // inside every face: the hulls overlap
  for (int i = 0; i < kept; ++i) W[i] = keep[i];
  n = kept;
  return p;
}

// z = a - b over both sets: w (out) minimises z . d, so z . d >= w . d everywhere. When w . d exceeds
// the margin times |d|, the plane normal to d separates the sets: this test is the certificate.
// A and B have support(d): a point of the set farthest along world direction d.
template <class A, class B>
bool apart_along(const A& a, const B& b, const Eigen::Vector3d& d, double margin, Eigen::Vector3d& w) {
  w = a.support(-d) - b.support(d);
  return w.dot(d) > margin * d.norm();
}

// GJK on the Minkowski difference a - b, started along d (non-zero): v, the point of the simplex W
// nearest the origin, approaches the difference's nearest point; each step adds the support point w
// against v. True (axis: unit v, from b to a) when some v certifies the separation by more than
// `margin` (apart_along); false when the sets come closer than that.
template <class A, class B>
bool apart(const A& a, const B& b, const Eigen::Vector3d& d, double margin, Eigen::Vector3d& axis) {
  Eigen::Vector3d w;
  if (apart_along(a, b, d, margin, w)) {
    axis = d.normalized();
    return true;
  }
  Eigen::Vector3d W[4] = {w};
  int n = 1;
  Eigen::Vector3d v = w;
  for (int it = 0; it < 64; ++it) {
    const double vv = v.squaredNorm();
    if (!(vv > 1e-24)) return false;  // the origin is in the difference: the sets overlap
    if (apart_along(a, b, v, margin, w)) {
      axis = v / std::sqrt(vv);
      return true;
    }
    if (vv - w.dot(v) <= 1e-12 * vv) return false;  // converged closer than the margin
    for (int i = 0; i < n; ++i)
      if (W[i] == w) return false;  // no progress
    W[n++] = w;
    v = closest(W, n);
  }
  return false;
}

}  // namespace octoreach::detail::gjk
