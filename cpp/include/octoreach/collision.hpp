#pragma once
/// \file collision.hpp
/// \brief Collision geometry (link shapes, meshes) and environment obstacles.
///
/// FCL and OctoMap types appear only as forward declarations, so this header (and robot.hpp,
/// chain.hpp) compiles with Eigen alone; code that builds or inspects FCL geometry includes
/// <fcl/fcl.h> itself.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/types.hpp"

namespace fcl {
template <typename S>
class CollisionGeometry;
template <typename S>
class CollisionObject;
using CollisionGeometryd = CollisionGeometry<double>;
using CollisionObjectd = CollisionObject<double>;
}  // namespace fcl

namespace octomap {
class OcTree;
}  // namespace octomap

namespace octoreach {

namespace detail {
struct Obb;
}  // namespace detail

/// \brief One collision shape of a link, with its pose in the link frame.
struct Shape {
  /// \brief Kind of shape (URDF box, cylinder, sphere or mesh).
  enum class Type { Box, Cylinder, Sphere, Mesh };
  Type type = Type::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box extents (x, y, z)
  double radius = 0.0;                             ///< cylinder or sphere radius
  double length = 0.0;                             ///< cylinder length
  std::string mesh_path;                           ///< resolved mesh file
  Eigen::Vector3d scale = Eigen::Vector3d::Ones(); ///< mesh scale
  Pose origin = Pose::Identity();                  ///< pose in the link frame
  std::shared_ptr<fcl::CollisionGeometryd> geometry;  ///< FCL geometry, local AABB computed; shared, never changed
};

/// \brief Loads a triangle mesh (STL, DAE, OBJ ... through assimp) as an FCL BVH model.
/// \param path mesh file \param scale per-axis scale
/// \throws std::runtime_error when the file cannot be read or holds no triangles
std::shared_ptr<fcl::CollisionGeometryd> load_mesh(const std::string& path,
                                                    const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

/// \brief Builds an FCL BVH model from vertices (N x 3) and triangles (M x 3 indices).
std::shared_ptr<fcl::CollisionGeometryd> make_mesh(const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& vertices,
                                                    const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>& triangles);

/// \brief A set of environment objects in the world frame: boxes, meshes and OctoMap octrees.
///
/// Built by the add_* calls, then only read: the const checks may run from many threads at once
/// (they move no shared object); adding while another thread checks is not safe.
class Obstacles {
 public:
  /// \brief Adds an axis-aligned (in its own frame) box of extents `size` at `pose`.
  void add_box(const Eigen::Vector3d& size, const Pose& pose, const std::string& name = "");
  /// \brief Adds a sphere.
  void add_sphere(double radius, const Pose& pose, const std::string& name = "");
  /// \brief Adds a cylinder along its local z axis.
  void add_cylinder(double radius, double length, const Pose& pose, const std::string& name = "");
  /// \brief Adds a mesh file (STL, DAE ...).
  void add_mesh_file(const std::string& path, const Pose& pose, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                     const std::string& name = "");
  /// \brief Adds an already built geometry.
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
  /// \brief Obstacle names, in the order they were added ("obstacle_<i>" when none was given).
  const std::vector<std::string>& names() const { return names_; }
  /// \brief The FCL objects (world frame, AABBs computed).
  const std::vector<std::shared_ptr<fcl::CollisionObjectd>>& objects() const { return objects_; }
  /// \brief Internal: obstacle `i`'s local AABB placed at its pose (world frame), the exact pre-test collides uses.
  const detail::Obb& oriented_box(std::size_t i) const { return *obbs_[i]; }
  /// \brief True when `geometry` at `pose` (world frame) touches any obstacle.
  bool collides(const fcl::CollisionGeometryd& geometry, const Pose& pose) const;
  /// \brief True when `object` (world frame, AABB computed) touches any obstacle; AABBs reject first.
  bool collides(const fcl::CollisionObjectd& object) const;
  /// \brief Largest box extent collides_box accepts, metres.
  static constexpr double kMaxBoxSize = limits::kCoordinate;
  /// \brief True when a box of extents `size` at `pose` (world frame) touches any obstacle.
  /// \throws std::invalid_argument for a non-finite, negative or larger than kMaxBoxSize extent or a non-finite pose.
  bool collides_box(const Eigen::Vector3d& size, const Pose& pose) const;

 private:
  std::vector<std::shared_ptr<fcl::CollisionObjectd>> objects_;
  std::vector<std::string> names_;
  // Per object: its local AABB placed at its pose, for an exact pre-test before FCL (shared, never changed).
  std::vector<std::shared_ptr<const detail::Obb>> obbs_;
};

}  // namespace octoreach
