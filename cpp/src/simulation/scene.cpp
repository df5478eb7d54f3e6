// Simulated scenes: shapes (boxes with a pose, cylinders, spheres, meshes, OctoMaps), crates, closed boxes and
// boards made of boxes, and ray casting into them.
#include "octoreach/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include <octomap/OcTree.h>

#include "common/format.hpp"
#include "common/shared_mutex.hpp"
#include "common/octree_file.hpp"
#include "simulation/ray_hits.hpp"
#include "simulation/scene_solids.hpp"
#include "simulation/triangle_bvh.hpp"

namespace octoreach {

namespace {
void check_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const char* what) {
  if (!lo.allFinite() || !hi.allFinite() || (lo.array() > hi.array()).any())
    throw std::invalid_argument(std::string(what) + ": need finite lo <= hi, got lo " + detail::format_point(lo) + ", hi " + detail::format_point(hi));
}

// The shape with its geometry, checked: ray casting needs an OctoMap's map.
Shape seen(const Shape& shape) {
  Shape s = shape.with_geometry();
  if (s.type == Shape::Type::Octree && !s.octree)
    throw std::invalid_argument("an OctoMap shape without its map cannot be seen (use Shape::from_octree)");
  return s;
}

}  // namespace

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
// The box as given stays the ray-casting box (its bounds exactly lo and hi); its shape is centred between them.
// A flat box (lo = hi on an axis) has no volume and so no shape: it is seen, never touched.
void Scene::add_box_(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  check_box(lo, hi, "box");
  if ((hi - lo).minCoeff() > 0) {
    Pose centre = Pose::Identity();
    centre.translation() = (lo + hi) / 2;
    shapes_.push_back(Shape::box(hi - lo, centre));
  }
  boxes_.push_back({lo, hi});
}

void Scene::add(const Shape& shape) {
  const Shape s = seen(shape);
  std::unique_lock<Lock> lock(*lock_);
  const std::size_t triangles = tris_.size();
  add_(s);
  if (tris_.size() != triangles) rebuild_bvh_();
}

void Scene::add(const Obstacles& obstacles) {
  std::vector<Shape> shapes;
  for (const Shape& s : obstacles.shapes()) shapes.push_back(seen(s));
  std::unique_lock<Lock> lock(*lock_);
  const std::size_t triangles = tris_.size();
  for (const Shape& s : shapes) add_(s);
  if (tris_.size() != triangles) rebuild_bvh_();
}

// Axis-aligned boxes join the boxes, meshes the triangles (the caller rebuilds their hierarchy), every other
// kind the solids.
void Scene::add_(const Shape& s) {
  if (s.type == Shape::Type::Box && s.origin.linear() == Eigen::Matrix3d::Identity()) {
    boxes_.push_back({s.origin.translation() - s.size / 2, s.origin.translation() + s.size / 2});
  } else if (s.type == Shape::Type::Mesh) {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Eigen::Vector3i> triangles;
    s.mesh_triangles(vertices, triangles);
    for (const auto& t : triangles)
      for (int j = 0; j < 3; ++j) tris_.push_back(s.origin * vertices[std::size_t(t[j])]);
  } else {
    auto solids = solids_ ? std::make_shared<Solids>(*solids_) : std::make_shared<Solids>();
    solids->add(s);
    solids_ = std::move(solids);
  }
  shapes_.push_back(s);
}

Obstacles Scene::obstacles() const {
  Obstacles out;
  for (const Shape& s : shapes_) out.add(s);
  return out;
}

bool Scene::has_octomap() const { return solids_ && !solids_->octrees.empty(); }

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
  if (triangles.empty()) return;
  MeshVertices v(Eigen::Index(vertices.size()), 3);
  MeshTriangles f(Eigen::Index(triangles.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) v.row(Eigen::Index(i)) = vertices[i].transpose();
  for (std::size_t i = 0; i < triangles.size(); ++i) f.row(Eigen::Index(i)) = triangles[i].transpose();
  Shape shape = Shape::triangle_mesh(v, f);
  std::unique_lock<Lock> lock(*lock_);
  for (const auto& t : triangles)  // as given: the vertices are already in the world frame
    for (int j = 0; j < 3; ++j) tris_.push_back(vertices[t[j]]);
  shapes_.push_back(std::move(shape));
  rebuild_bvh_();
}

void Scene::rebuild_bvh_() { bvh_ = tris_.empty() ? nullptr : std::make_shared<const Bvh>(tris_); }

void Scene::load_octomap(const std::string& path) {
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  detail::read_bt(*tree, path, "OctoMap scene file", 0);  // not expanded: the resolution check bounds raycasts
  add(Shape::from_octree(tree));
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
  if (solids_) solids_->extend(b);
  if (!b.lo.allFinite()) b.lo = b.hi = Eigen::Vector3d::Zero();
  return b;
}

std::vector<char> Scene::solid(const std::vector<Eigen::Vector3d>& points) const {
  std::vector<char> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())  // named by its row here; solid(p) alone could not say which
      throw std::invalid_argument("solid: points row " + std::to_string(i) + " is not finite: " +
                                  detail::format_point(points[i]));
    out[i] = solid(points[i]);
  }
  return out;
}

bool Scene::solid(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) throw std::invalid_argument("solid: the point " + detail::format_point(p) + " is not finite");
  for (const auto& b : boxes_)
    if (b.contains(p)) return true;
  return solids_ && solids_->contains(p);
}

bool Scene::raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, double& t) const {
  return raycast(o, d, max_range, t, nullptr);
}

bool Scene::raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, double& t,
                    Eigen::Vector3d* normal) const {
  if (!o.allFinite() || !d.allFinite() || !std::isfinite(max_range))
    throw std::invalid_argument("raycast: origin, direction and max_range must be finite, got origin " +
                                detail::format_point(o) + ", direction " + detail::format_point(d) +
                                ", max_range " + detail::format_number(max_range));
  // The distance is along d, so a direction of another length would scale every answer. The margin is what a
  // rotation passing as one (R^T R within 1e-6 of the identity per entry) leaves of a unit ray: at most 3e-6.
  if (d.squaredNorm() == 0) throw std::invalid_argument("raycast: the direction must be non-zero");
  if (!(std::abs(d.squaredNorm() - 1.0) <= 1e-5))
    throw std::invalid_argument("raycast: the direction must be a unit vector, got " + detail::format_point(d) +
                                " of length " + detail::format_number(d.norm()));
  Eigen::Vector3d inv = d.cwiseInverse();
  double best = max_range;
  bool hit = false;
  Eigen::Vector3d n = -d;
  for (const auto& b : boxes_) {
    double tb;
    int axis;
    if (detail::ray_box(o, inv, b.lo, b.hi, best, tb, &axis) && tb <= best) {
      best = tb;
      hit = true;
      if (normal) n = detail::box_normal(d, axis);
    }
  }
  if (solids_ && solids_->raycast(o, d, best, normal ? &n : nullptr)) hit = true;
  int tri = -1;
  if (bvh_ && bvh_->raycast(o, d, inv, best, &tri)) {
    hit = true;
    if (normal && tri >= 0) {
      const auto& T = bvh_->tris;
      n = (T[3 * tri + 1] - T[3 * tri]).cross(T[3 * tri + 2] - T[3 * tri]).normalized();
      if (n.dot(d) > 0) n = -n;
    }
  }
  if (solids_ && solids_->raycast_octrees(o, d, inv, best, normal ? &n : nullptr)) hit = true;
  t = best;
  if (normal) *normal = n;
  return hit;
}

}  // namespace octoreach
