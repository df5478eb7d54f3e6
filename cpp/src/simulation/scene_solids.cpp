// Ray casting into a scene's oriented boxes, spheres, cylinders and posed OctoMaps (scene_solids.hpp).
#include "simulation/scene_solids.hpp"

#include <cmath>
#include <limits>

#include <octomap/OcTree.h>

#include "simulation/ray_hits.hpp"

namespace octoreach {
namespace {

// The ray in a solid's own frame (local -> world: rotation R, origin c).
struct LocalRay {
  Eigen::Vector3d o, d;
  LocalRay(const Eigen::Matrix3d& R, const Eigen::Vector3d& c, const Eigen::Vector3d& o_world,
           const Eigen::Vector3d& d_world)
      : o(R.transpose() * (o_world - c)), d(R.transpose() * d_world) {}
};

// An OctoMap's first occupied cell along the ray (o, d, inv in the tree's frame): the distance to the cell's
// near face, and the normal of the face it entered.
bool ray_octree(const octomap::OcTree& tree, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                const Eigen::Vector3d& inv, double& best, Eigen::Vector3d* normal) {
  octomap::point3d end;
  octomap::point3d oo(float(o.x()), float(o.y()), float(o.z())), dd(float(d.x()), float(d.y()), float(d.z()));
  if (!tree.castRay(oo, dd, end, true, best)) return false;
  double tt = (Eigen::Vector3d(end.x(), end.y(), end.z()) - o).dot(d) - 0.5 * tree.getResolution();
  tt = std::max(tt, 0.0);
  if (tt > best) return false;
  best = tt;
  if (normal) {  // the face of the hit cell the ray entered
    const octomap::point3d c = tree.keyToCoord(tree.coordToKey(end));
    const Eigen::Vector3d h = Eigen::Vector3d::Constant(0.5 * tree.getResolution());
    const Eigen::Vector3d cc(c.x(), c.y(), c.z());
    double tc;
    int axis = -1;
    detail::ray_box(o, inv, cc - h, cc + h, std::numeric_limits<double>::infinity(), tc, &axis);
    *normal = detail::box_normal(d, axis);
  }
  return true;
}

}  // namespace

bool Scene::Solids::add(const Shape& s) {
  auto placed = [&s](const Eigen::Vector3d& half) { return Placed{s.origin.linear(), s.origin.translation(), half}; };
  switch (s.type) {
    case Shape::Type::Box: boxes.push_back(placed(s.size / 2)); return true;
    case Shape::Type::Sphere: spheres.push_back(placed(Eigen::Vector3d::Constant(s.radius))); return true;
    case Shape::Type::Cylinder:
      cylinders.push_back(placed(Eigen::Vector3d(s.radius, s.radius, s.length / 2)));
      return true;
    case Shape::Type::Octree: {
      Octree t{s.octree, s.origin, s.origin.matrix() == Eigen::Matrix4d::Identity(), {}, {}};
      s.octree->getMetricMin(t.lo.x(), t.lo.y(), t.lo.z());
      s.octree->getMetricMax(t.hi.x(), t.hi.y(), t.hi.z());
      octrees.push_back(std::move(t));
      return true;
    }
    case Shape::Type::Mesh: return false;
  }
  return false;
}

bool Scene::Solids::raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& best,
                            Eigen::Vector3d* normal) const {
  bool hit = false;
  double t;
  Eigen::Vector3d n;
  for (const Placed& b : boxes) {
    const LocalRay r(b.R, b.c, o, d);
    int axis;
    if (detail::ray_box(r.o, r.d.cwiseInverse(), -b.half, b.half, best, t, &axis) && t <= best) {
      best = t;
      hit = true;
      if (normal) *normal = b.R * detail::box_normal(r.d, axis);
    }
  }
  for (const Placed& s : spheres)
    if (detail::ray_sphere(o - s.c, d, s.half.x(), best, t, n) && t <= best) {
      best = t;
      hit = true;
      if (normal) *normal = n;
    }
  for (const Placed& c : cylinders) {
    const LocalRay r(c.R, c.c, o, d);
    if (detail::ray_cylinder(r.o, r.d, c.half.x(), c.half.z(), best, t, n) && t <= best) {
      best = t;
      hit = true;
      if (normal) *normal = c.R * n;
    }
  }
  return hit;
}

bool Scene::Solids::raycast_octrees(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& inv,
                                    double& best, Eigen::Vector3d* normal) const {
  bool hit = false;
  for (const Octree& tree : octrees) {
    if (tree.identity) {
      hit = ray_octree(*tree.tree, o, d, inv, best, normal) || hit;
      continue;
    }
    const Eigen::Matrix3d Rt = tree.pose.linear().transpose();
    const Eigen::Vector3d ol = Rt * (o - tree.pose.translation()), dl = Rt * d;
    Eigen::Vector3d n;
    if (ray_octree(*tree.tree, ol, dl, dl.cwiseInverse(), best, normal ? &n : nullptr)) {
      hit = true;
      if (normal) *normal = tree.pose.linear() * n;
    }
  }
  return hit;
}

bool Scene::Solids::contains(const Eigen::Vector3d& p) const {
  for (const Placed& b : boxes)
    if (((b.R.transpose() * (p - b.c)).cwiseAbs() - b.half).maxCoeff() <= 0) return true;
  for (const Placed& s : spheres)
    if ((p - s.c).norm() <= s.half.x()) return true;
  for (const Placed& c : cylinders) {
    const Eigen::Vector3d l = c.R.transpose() * (p - c.c);
    if (std::abs(l.z()) <= c.half.z() && l.head<2>().norm() <= c.half.x()) return true;
  }
  return false;
}

void Scene::Solids::extend(Aabb& b) const {
  auto grow = [&b](const Eigen::Vector3d& c, const Eigen::Vector3d& e) {
    b.lo = b.lo.cwiseMin(c - e);
    b.hi = b.hi.cwiseMax(c + e);
  };
  for (const Placed& x : boxes) grow(x.c, x.R.cwiseAbs() * x.half);
  for (const Placed& x : spheres) grow(x.c, x.half);
  for (const Placed& x : cylinders) {  // the rim circles' extent plus the axis' extent, per world axis
    const Eigen::Vector3d a = x.R.col(2);
    const Eigen::Vector3d rim = (Eigen::Vector3d::Ones() - a.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt() * x.half.x();
    grow(x.c, rim + a.cwiseAbs() * x.half.z());
  }
  for (const Octree& t : octrees)
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d corner(k & 1 ? t.hi.x() : t.lo.x(), k & 2 ? t.hi.y() : t.lo.y(), k & 4 ? t.hi.z() : t.lo.z());
      grow(t.pose * corner, Eigen::Vector3d::Zero());
    }
}

}  // namespace octoreach
