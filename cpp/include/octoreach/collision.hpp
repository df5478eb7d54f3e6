#pragma once
/// \file collision.hpp
/// \brief Environment obstacles: shapes (shape.hpp) in the world frame, checked for contact.
///
/// FCL and OctoMap types appear only as forward declarations, so this header (and robot.hpp,
/// chain.hpp) compiles with Eigen alone; code that builds or inspects FCL geometry includes
/// <fcl/fcl.h> itself.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/shape.hpp"
#include "octoreach/types.hpp"

namespace fcl {
template <typename S>
class CollisionObject;
using CollisionObjectd = CollisionObject<double>;
}  // namespace fcl

namespace octomap {
class OcTree;
}  // namespace octomap

namespace octoreach {

namespace detail {
struct Obb;
}  // namespace detail

/// \brief A set of environment objects in the world frame: shapes (boxes, cylinders, spheres, meshes and
/// OctoMap octrees), each kept as its description (shapes()) and as an FCL object.
///
/// Built by the add calls, then only read: the const checks may run from many threads at once
/// (they move no shared object); adding while another thread checks is not safe.
class Obstacles {
 public:
  /// \brief Adds a shape (world frame); a shape without geometry gets it built from its description.
  /// \throws std::invalid_argument for a non-finite pose, FileError for a mesh file that cannot be read
  void add(const Shape& shape, const std::string& name = "");
  /// \brief Adds an axis-aligned (in its own frame) box of extents `size` at `pose`.
  void add_box(const Eigen::Vector3d& size, const Pose& pose, const std::string& name = "");
  /// \brief Adds a sphere.
  void add_sphere(double radius, const Pose& pose, const std::string& name = "");
  /// \brief Adds a cylinder along its local z axis.
  void add_cylinder(double radius, double length, const Pose& pose, const std::string& name = "");
  /// \brief Adds a mesh file (STL, DAE ...).
  void add_mesh_file(const std::string& path, const Pose& pose, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                     const std::string& name = "");
  /// \brief Adds an already built geometry (described by Shape::of).
  void add_geometry(std::shared_ptr<fcl::CollisionGeometryd> geometry, const Pose& pose, const std::string& name = "");
  /// \brief Adds an OctoMap: its occupied cells are obstacles.
  void add_octree(std::shared_ptr<const octomap::OcTree> tree, const Pose& pose = Pose::Identity(),
                  const std::string& name = "");
  /// \brief Adds the occupied cells of an OctoMap file (.ot: any OcTree; otherwise a binary .bt).
  /// \throws FileError when the file cannot be read or is not an OcTree
  void add_octree_file(const std::string& path, const Pose& pose = Pose::Identity(), const std::string& name = "");
  /// \brief Adds occupied cells at the given points (N x 3, world frame) as an OctoMap of `resolution` metres.
  /// \throws std::invalid_argument for a non-positive resolution or a non-finite point
  void add_points(const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& points, double resolution,
                  const std::string& name = "");

  /// \brief Adds every obstacle of `other` (the FCL objects are shared, never changed; the sets stay independent).
  void add(const Obstacles& other);
  /// \brief Number of obstacles.
  std::size_t size() const { return objects_.size(); }
  /// \brief True when there is no obstacle.
  bool empty() const { return objects_.empty(); }
  /// \brief The obstacles' shapes (world frame), in the order they were added.
  const std::vector<Shape>& shapes() const { return shapes_; }
  /// \brief Obstacle names, in the order they were added ("obstacle_<i>" when none was given).
  const std::vector<std::string>& names() const { return names_; }
  /// \brief The FCL objects (world frame, AABBs computed).
  const std::vector<std::shared_ptr<fcl::CollisionObjectd>>& objects() const { return objects_; }
  /// \brief Internal: obstacle `i`'s local AABB placed at its pose (world frame), the exact pre-test collides uses.
  const detail::Obb& oriented_box(std::size_t i) const { return *obbs_[i]; }
  /// \brief True when `geometry` at `pose` (world frame) touches any obstacle.
  /// \throws std::invalid_argument unless `pose` is a finite rigid transform (check_rigid).
  bool collides(const fcl::CollisionGeometryd& geometry, const Pose& pose) const;
  /// \brief True when `object` (world frame, AABB computed) touches any obstacle; AABBs reject first.
  /// \throws std::invalid_argument unless the object's transform is a finite rigid transform (check_rigid).
  bool collides(const fcl::CollisionObjectd& object) const;
  /// \brief Largest box extent collides_box accepts, metres.
  static constexpr double kMaxBoxSize = limits::kCoordinate;
  /// \brief True when a box of extents `size` at `pose` (world frame) touches any obstacle.
  /// \throws std::invalid_argument for a non-finite, negative or larger than kMaxBoxSize extent or a non-finite pose.
  bool collides_box(const Eigen::Vector3d& size, const Pose& pose) const;

 private:
  std::vector<std::shared_ptr<fcl::CollisionObjectd>> objects_;
  std::vector<std::string> names_;
  std::vector<Shape> shapes_;
  // Per object: its local AABB placed at its pose, for an exact pre-test before FCL (shared, never changed).
  std::vector<std::shared_ptr<const detail::Obb>> obbs_;
};

}  // namespace octoreach
