// Simulated scenes: boxes, crates, closed boxes, meshes or an OctoMap world, and ray casting into them.
#include "octoreach/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <mutex>
#include <random>
#include <sstream>

#include <octomap/OcTree.h>

#include "common/format.hpp"
#include "common/shared_mutex.hpp"
#include "common/octree_file.hpp"

namespace octoreach {

namespace {
void check_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const char* what) {
  if (!lo.allFinite() || !hi.allFinite() || (lo.array() > hi.array()).any())
    throw std::invalid_argument(std::string(what) + ": need finite lo <= hi, got lo " + detail::format_point(lo) + ", hi " + detail::format_point(hi));
}

// Slab test; t in [0, tmax]. `axis`: the slab the ray entered last (-1 when it starts inside).
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

// Unit normal of the face of a box a ray with direction d entered through `axis` (-d from inside).
inline Eigen::Vector3d box_normal(const Eigen::Vector3d& d, int axis) {
  if (axis < 0) return -d.normalized();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[axis] = d[axis] > 0 ? -1.0 : 1.0;
  return n;
}

// Moller-Trumbore.
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
}  // namespace

struct Scene::Bvh {
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1, right = -1, first = 0, count = 0;
  };
  std::vector<Node> nodes;
  std::vector<Eigen::Vector3d> tris;  // reordered

  explicit Bvh(const std::vector<Eigen::Vector3d>& t) {
    std::size_t n = t.size() / 3;
    std::vector<int> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    std::vector<Eigen::Vector3d> cent(n);
    for (std::size_t i = 0; i < n; ++i) cent[i] = (t[3 * i] + t[3 * i + 1] + t[3 * i + 2]) / 3.0;
    build(t, idx, cent, 0, int(n));
    tris.reserve(t.size());
    for (int i : idx)
      for (int j = 0; j < 3; ++j) tris.push_back(t[3 * i + j]);
  }
  int build(const std::vector<Eigen::Vector3d>& t, std::vector<int>& idx, const std::vector<Eigen::Vector3d>& cent,
            int first, int count) {
    Node node;
    node.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    node.hi = -node.lo;
    for (int i = first; i < first + count; ++i)
      for (int j = 0; j < 3; ++j) {
        node.lo = node.lo.cwiseMin(t[3 * idx[i] + j]);
        node.hi = node.hi.cwiseMax(t[3 * idx[i] + j]);
      }
    int id = int(nodes.size());
    nodes.push_back(node);
    if (count <= 4) {
      nodes[id].first = first;
      nodes[id].count = count;
      return id;
    }
    int axis;
    (node.hi - node.lo).maxCoeff(&axis);
    int mid = first + count / 2;
    std::nth_element(idx.begin() + first, idx.begin() + mid, idx.begin() + first + count,
                     [&](int a, int b) { return cent[a][axis] < cent[b][axis]; });
    int l = build(t, idx, cent, first, mid - first);
    int r = build(t, idx, cent, mid, first + count - mid);
    nodes[id].left = l;
    nodes[id].right = r;
    return id;
  }
  bool raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& inv, double& best,
               int* best_tri = nullptr) const {
    bool hit = false;
    int stack[128];
    int sp = 0;
    stack[sp++] = 0;
    while (sp) {
      const Node& n = nodes[stack[--sp]];
      double tb;
      if (!ray_box(o, inv, n.lo, n.hi, best, tb)) continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          double t;
          if (ray_triangle(o, d, tris[3 * i], tris[3 * i + 1], tris[3 * i + 2], t) && t < best) {
            best = t;
            hit = true;
            if (best_tri) *best_tri = i;
          }
        }
      } else if (sp < 126) {
        stack[sp++] = n.left;
        stack[sp++] = n.right;
      }
    }
    return hit;
  }
};

struct Scene::Lock : detail::SharedMutex {};

Scene::Scene() : lock_(std::make_shared<Lock>()) {}
void Scene::lock_shared_() const { lock_->lock_shared(); }
void Scene::unlock_shared_() const { lock_->unlock_shared(); }
Scene::~Scene() = default;
Scene::Scene(const Scene&) = default;
Scene& Scene::operator=(const Scene&) = default;

void Scene::add_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::unique_lock<Lock> lock(*lock_);
  add_box_(lo, hi);
}
void Scene::add_box_(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  check_box(lo, hi, "box");
  boxes_.push_back({lo, hi});
}

void Scene::add_interior(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::unique_lock<Lock> lock(*lock_);
  add_interior_(lo, hi);
}
void Scene::add_interior_(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  check_box(lo, hi, "interior");
  interiors_.push_back({lo, hi});
}

void Scene::add_crate(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double th) {
  std::unique_lock<Lock> lock(*lock_);
  check_box(lo, hi, "crate");
  if (!(th > 0) || 2 * th >= (hi - lo).head<2>().minCoeff() || th >= hi.z() - lo.z())
    throw std::invalid_argument("crate wall thickness must be positive and smaller than half the crate, got " +
                                std::to_string(th));
  const Eigen::Vector3d t(th, th, th);
  add_box_(lo, {hi.x(), hi.y(), lo.z() + th});                       // floor
  add_box_({lo.x(), lo.y(), lo.z()}, {lo.x() + th, hi.y(), hi.z()});  // -x
  add_box_({hi.x() - th, lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()});  // +x
  add_box_({lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y() + th, hi.z()});  // -y
  add_box_({lo.x(), hi.y() - th, lo.z()}, {hi.x(), hi.y(), hi.z()});  // +y
  add_interior_(lo + t, {hi.x() - th, hi.y() - th, hi.z()});
}

void Scene::add_closed_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double th, const std::string& face,
                           double ow, double oh) {
  std::unique_lock<Lock> lock(*lock_);
  check_box(lo, hi, "closed box");
  if (!(th > 0) || 2 * th >= (hi - lo).minCoeff())
    throw std::invalid_argument("closed box wall thickness must be positive and smaller than half the box, got " +
                                std::to_string(th));
  int axis, sign;
  if (face == "+x") axis = 0, sign = 1;
  else if (face == "-x") axis = 0, sign = -1;
  else if (face == "+y") axis = 1, sign = 1;
  else if (face == "-y") axis = 1, sign = -1;
  else if (face == "+z") axis = 2, sign = 1;
  else throw std::invalid_argument("opening face must be '+x', '-x', '+y', '-y' or '+z', got '" + face + "'");
  // the two in-face axes: (u, v); for side faces v is z (height)
  int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
  double fu = hi[u] - lo[u] - 2 * th, fv = hi[v] - lo[v] - 2 * th;
  if (!(ow > 0) || !(oh > 0) || ow >= fu || oh >= fv)
    throw std::invalid_argument("opening_width x opening_height " + std::to_string(ow) + " x " + std::to_string(oh) +
                                " must be positive and fit inside the face (" + std::to_string(fu) + " x " +
                                std::to_string(fv) + ")");
  for (int a = 0; a < 3; ++a)
    for (int s = -1; s <= 1; s += 2) {
      Eigen::Vector3d wlo = lo, whi = hi;
      if (s < 0)
        whi[a] = lo[a] + th;
      else
        wlo[a] = hi[a] - th;
      if (a != axis || s != sign) {
        add_box_(wlo, whi);
        continue;
      }
      // the wall with the opening: four boards around a centred hole
      double cu = 0.5 * (lo[u] + hi[u]), cv = 0.5 * (lo[v] + hi[v]);
      double u0 = cu - ow / 2, u1 = cu + ow / 2, v0 = cv - oh / 2, v1 = cv + oh / 2;
      Eigen::Vector3d a0 = wlo, a1 = whi;
      a1[u] = u0;
      add_box_(a0, a1);  // left of the hole, full height
      a0 = wlo, a1 = whi;
      a0[u] = u1;
      add_box_(a0, a1);  // right
      a0 = wlo, a1 = whi;
      a0[u] = u0, a1[u] = u1, a1[v] = v0;
      add_box_(a0, a1);  // below
      a0 = wlo, a1 = whi;
      a0[u] = u0, a1[u] = u1, a0[v] = v1;
      add_box_(a0, a1);  // above
    }
  add_interior_(lo + Eigen::Vector3d::Constant(th), hi - Eigen::Vector3d::Constant(th));
}

void Scene::add_mesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles) {
  for (const auto& v : vertices)
    if (!v.allFinite()) throw std::invalid_argument("mesh vertices must be finite");
  for (const auto& t : triangles)
    for (int j = 0; j < 3; ++j)
      if (t[j] < 0 || t[j] >= int(vertices.size()))
        throw std::invalid_argument("triangle index " + std::to_string(t[j]) + " out of range [0, " +
                                    std::to_string(vertices.size()) + ")");
  std::unique_lock<Lock> lock(*lock_);
  for (const auto& t : triangles)
    for (int j = 0; j < 3; ++j) tris_.push_back(vertices[t[j]]);
  rebuild_bvh_();
}

void Scene::rebuild_bvh_() { bvh_ = tris_.empty() ? nullptr : std::make_shared<const Bvh>(tris_); }

void Scene::load_octomap(const std::string& path) {
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  detail::read_bt(*tree, path, "OctoMap scene file", 0);  // not expanded: the resolution check bounds raycasts
  std::unique_lock<Lock> lock(*lock_);
  octree_ = tree;
}

Aabb Scene::bounds() const {
  Aabb b;
  b.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  b.hi = -b.lo;
  for (const auto& x : boxes_) {
    b.lo = b.lo.cwiseMin(x.lo);
    b.hi = b.hi.cwiseMax(x.hi);
  }
  for (const auto& v : tris_) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  if (octree_) {
    double x0, y0, z0, x1, y1, z1;
    octree_->getMetricMin(x0, y0, z0);
    octree_->getMetricMax(x1, y1, z1);
    b.lo = b.lo.cwiseMin(Eigen::Vector3d(x0, y0, z0));
    b.hi = b.hi.cwiseMax(Eigen::Vector3d(x1, y1, z1));
  }
  if (!b.lo.allFinite()) b.lo = b.hi = Eigen::Vector3d::Zero();
  return b;
}

bool Scene::solid(const Eigen::Vector3d& p) const {
  for (const auto& b : boxes_)
    if (b.contains(p)) return true;
  return false;
}

bool Scene::raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, double& t) const {
  return raycast(o, d, max_range, t, nullptr);
}

bool Scene::raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, double& t,
                    Eigen::Vector3d* normal) const {
  if (!o.allFinite() || !d.allFinite() || std::isnan(max_range))
    throw std::invalid_argument("raycast: origin, direction and max_range must be numbers, got origin " +
                                detail::format_point(o) + ", direction " + detail::format_point(d));
  Eigen::Vector3d inv = d.cwiseInverse();
  double best = max_range;
  bool hit = false;
  Eigen::Vector3d n = -d;
  for (const auto& b : boxes_) {
    double tb;
    int axis;
    if (ray_box(o, inv, b.lo, b.hi, best, tb, &axis) && tb <= best) {
      best = tb;
      hit = true;
      if (normal) n = box_normal(d, axis);
    }
  }
  int tri = -1;
  if (bvh_ && bvh_->raycast(o, d, inv, best, &tri)) {
    hit = true;
    if (normal && tri >= 0) {
      const auto& T = bvh_->tris;
      n = (T[3 * tri + 1] - T[3 * tri]).cross(T[3 * tri + 2] - T[3 * tri]).normalized();
      if (n.dot(d) > 0) n = -n;
    }
  }
  if (octree_) {
    octomap::point3d end;
    octomap::point3d oo(float(o.x()), float(o.y()), float(o.z())), dd(float(d.x()), float(d.y()), float(d.z()));
    if (octree_->castRay(oo, dd, end, true, best)) {
      double tt = (Eigen::Vector3d(end.x(), end.y(), end.z()) - o).dot(d) - 0.5 * octree_->getResolution();
      tt = std::max(tt, 0.0);
      if (tt <= best) {
        best = tt;
        hit = true;
        if (normal) {  // the face of the hit cell the ray entered
          const octomap::point3d c = octree_->keyToCoord(octree_->coordToKey(end));
          const Eigen::Vector3d h = Eigen::Vector3d::Constant(0.5 * octree_->getResolution());
          const Eigen::Vector3d cc(c.x(), c.y(), c.z());
          double tc;
          int axis = -1;
          ray_box(o, inv, cc - h, cc + h, std::numeric_limits<double>::infinity(), tc, &axis);
          n = box_normal(d, axis);
        }
      }
    }
  }
  t = best;
  if (normal) *normal = n;
  return hit;
}

}  // namespace octoreach
