#include "octoreach/collision.hpp"

#include <optional>

#include <fcl/fcl.h>
#include <octomap/OcTree.h>

#include "collision/detail.hpp"
#include "collision/obb.hpp"

namespace octoreach {
namespace {

using detail::geometry_collide;
using detail::world_aabb;

// Obstacles::collides of a pose already checked: world AABBs first, then an exact pre-test (the oriented boxes of
// the geometry and of the obstacle, their local AABBs placed, clearly apart means no contact), and FCL (whose every
// call fits a bounding volume to the obstacle) only for the rest.
bool touches(const Obstacles& obstacles, const fcl::CollisionGeometryd& geometry, const Pose& pose) {
  const fcl::AABBd box = world_aabb(geometry, pose);
  std::optional<detail::Obb> shape;
  const auto& objects = obstacles.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto& o = objects[i];
    if (!o->getAABB().overlap(box)) continue;
    if (!shape) shape = detail::Obb::of(geometry, pose);
    if (shape->apart(obstacles.oriented_box(i))) continue;
    if (geometry_collide(&geometry, pose, o->collisionGeometry().get(), Pose(o->getTransform().matrix())))
      return true;
  }
  return false;
}

}  // namespace

void Obstacles::add(const Shape& shape, const std::string& name) {
  Shape s = shape.with_geometry();
  check_rigid(s.origin, "obstacle pose");
  auto obj = std::make_shared<fcl::CollisionObjectd>(s.geometry, fcl::Transform3d(s.origin.matrix()));
  obj->computeAABB();
  objects_.push_back(obj);
  obbs_.push_back(std::make_shared<const detail::Obb>(detail::Obb::of(*s.geometry, s.origin)));
  names_.push_back(name.empty() ? "obstacle_" + std::to_string(objects_.size() - 1) : name);
  shapes_.push_back(std::move(s));
}

void Obstacles::add_geometry(std::shared_ptr<fcl::CollisionGeometryd> geometry, const Pose& pose,
                             const std::string& name) {
  add(Shape::of(std::move(geometry), pose), name);
}

void Obstacles::add_box(const Eigen::Vector3d& size, const Pose& pose, const std::string& name) {
  add(Shape::box(size, pose), name);
}

void Obstacles::add_sphere(double radius, const Pose& pose, const std::string& name) {
  add(Shape::sphere(radius, pose), name);
}

void Obstacles::add_cylinder(double radius, double length, const Pose& pose, const std::string& name) {
  add(Shape::cylinder(radius, length, pose), name);
}

void Obstacles::add_mesh_file(const std::string& path, const Pose& pose, const Eigen::Vector3d& scale,
                              const std::string& name) {
  add(Shape::mesh_file(path, pose, scale), name.empty() ? path : name);
}

void Obstacles::add_octree(std::shared_ptr<const octomap::OcTree> tree, const Pose& pose, const std::string& name) {
  add(Shape::from_octree(std::move(tree), pose), name);
}

void Obstacles::add_octree_file(const std::string& path, const Pose& pose, const std::string& name) {
  add(Shape::octree_file(path, pose), name.empty() ? path : name);
}

void Obstacles::add_points(const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& points,
                           double resolution, const std::string& name) {
  if (!(resolution > 0) || !std::isfinite(resolution))
    throw std::invalid_argument("resolution must be a positive finite number of metres, got " + std::to_string(resolution));
  auto tree = std::make_shared<octomap::OcTree>(resolution);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) throw std::invalid_argument("points row " + std::to_string(i) + " is not finite");
    tree->updateNode(octomap::point3d(points(i, 0), points(i, 1), points(i, 2)), true);
  }
  tree->updateInnerOccupancy();
  add_octree(tree, Pose::Identity(), name);
}

void Obstacles::add(const Obstacles& other) {
  if (&other == this) throw std::invalid_argument("cannot add obstacles to themselves");
  objects_.insert(objects_.end(), other.objects_.begin(), other.objects_.end());
  names_.insert(names_.end(), other.names_.begin(), other.names_.end());
  obbs_.insert(obbs_.end(), other.obbs_.begin(), other.obbs_.end());
  shapes_.insert(shapes_.end(), other.shapes_.begin(), other.shapes_.end());
}

bool Obstacles::collides_box(const Eigen::Vector3d& size, const Pose& pose) const {
  if (!size.allFinite() || (size.array() < 0).any() || size.maxCoeff() > kMaxBoxSize)
    throw std::invalid_argument("collides_box: size must be finite, >= 0 and at most " + std::to_string(kMaxBoxSize) +
                                " m per axis");
  check_rigid(pose, "collides_box: pose");
  fcl::Boxd box(size);
  box.computeLocalAABB();
  return touches(*this, box, pose);
}

bool Obstacles::collides(const fcl::CollisionGeometryd& geometry, const Pose& pose) const {
  check_rigid(pose, "collides: pose");
  return touches(*this, geometry, pose);
}

bool Obstacles::collides(const fcl::CollisionObjectd& object) const {
  check_rigid(Pose(object.getTransform().matrix()), "collides: object pose");
  for (const auto& o : objects_) {
    if (!o->getAABB().overlap(object.getAABB())) continue;
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    if (fcl::collide(&object, o.get(), request, result) > 0) return true;
  }
  return false;
}

}  // namespace octoreach
