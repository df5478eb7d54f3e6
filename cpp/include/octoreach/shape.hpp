#pragma once
/// \file shape.hpp
/// \brief The one shape vocabulary: boxes, cylinders, spheres, triangle meshes and OctoMaps, each with a pose.
///
/// A robot link's collision and visual shapes, Obstacles (collision checks), Scene (ray casting) and room files
/// all describe what stands somewhere with a Shape, so a solid added in one place is the same solid in the
/// others. FCL and OctoMap types appear only as forward declarations.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/types.hpp"

namespace fcl {
template <typename S>
class CollisionGeometry;
using CollisionGeometryd = CollisionGeometry<double>;
}  // namespace fcl

namespace octomap {
class OcTree;
}  // namespace octomap

namespace octoreach {

/// \brief Vertices (N x 3) of a triangle mesh, row per vertex.
using MeshVertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// \brief Triangles (M x 3) of a triangle mesh, three vertex indices per row.
using MeshTriangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// \brief A solid: a box, cylinder, sphere, triangle mesh or OctoMap, with its pose in its parent frame (a
/// link's frame for a robot's shapes, the world frame for obstacles, scenes and rooms).
///
/// The description (type, sizes, mesh file, pose) says what the shape is; `geometry` is its FCL collision
/// geometry (local AABB computed), built by the factories and shared, never changed. Shapes that are only
/// drawn (a robot's visuals) carry no geometry; with_geometry() builds it from the description.
struct Shape {
  /// \brief Kind of shape (URDF box, cylinder, sphere or mesh; an OctoMap's occupied cells).
  enum class Type { Box, Cylinder, Sphere, Mesh, Octree };
  Type type = Type::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();   ///< box extents (x, y, z), centred on the pose
  double radius = 0.0;                              ///< cylinder or sphere radius
  double length = 0.0;                              ///< cylinder length along its local z axis, centred
  std::string mesh_path;                            ///< mesh file ("" for triangles given in memory)
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  ///< mesh scale, per axis
  Pose origin = Pose::Identity();                   ///< pose in the parent frame
  std::shared_ptr<fcl::CollisionGeometryd> geometry;  ///< FCL geometry, local AABB computed; shared, never changed
  std::shared_ptr<const octomap::OcTree> octree;      ///< an Octree shape's map (its occupied cells are solid)

  /// \brief A box of extents `size` centred at `pose`. \throws std::invalid_argument for a size that is not
  /// three positive numbers or a non-finite pose.
  static Shape box(const Eigen::Vector3d& size, const Pose& pose = Pose::Identity());
  /// \brief A cylinder along the local z axis of `pose`, centred there.
  static Shape cylinder(double radius, double length, const Pose& pose = Pose::Identity());
  /// \brief A sphere centred at `pose`.
  static Shape sphere(double radius, const Pose& pose = Pose::Identity());
  /// \brief A mesh file (STL, DAE, OBJ ... through assimp), scaled per axis. \throws FileError when it cannot be read.
  static Shape mesh_file(const std::string& path, const Pose& pose = Pose::Identity(),
                         const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());
  /// \brief A triangle mesh from vertices (N x 3) and triangles (M x 3 indices), in the frame of `pose`.
  static Shape triangle_mesh(const MeshVertices& vertices, const MeshTriangles& triangles,
                             const Pose& pose = Pose::Identity());
  /// \brief The occupied cells of an OctoMap, placed at `pose`.
  static Shape from_octree(std::shared_ptr<const octomap::OcTree> tree, const Pose& pose = Pose::Identity());
  /// \brief The occupied cells of an OctoMap file (.ot: any OcTree; otherwise a binary .bt).
  /// \throws FileError when the file cannot be read or is not an OcTree
  static Shape octree_file(const std::string& path, const Pose& pose = Pose::Identity());
  /// \brief The description of an FCL geometry (box, cylinder, sphere, BVH or convex mesh, OcTree) at `pose`;
  /// an OcTree described this way has no `octree` (ray casting cannot see it: use from_octree).
  /// \throws std::invalid_argument for a null or another kind of geometry, or a non-finite pose
  static Shape of(std::shared_ptr<fcl::CollisionGeometryd> geometry, const Pose& pose);

  /// \brief "box", "cylinder", "sphere", "mesh" or "octree".
  const char* type_name() const;
  /// \brief This shape with its collision geometry: itself when it has one, else built from the description
  /// (a mesh read from mesh_path). \throws FileError for a mesh file that cannot be read,
  /// std::invalid_argument for an Octree shape without its map or a mesh without a file.
  Shape with_geometry() const;
  /// \brief The triangles of a mesh shape in its own frame (before `origin`), from its geometry or else read
  /// from mesh_path. \throws std::invalid_argument for a shape that is not a mesh.
  void mesh_triangles(std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& triangles) const;
};

/// \brief Loads a triangle mesh (STL, DAE, OBJ ... through assimp) as an FCL BVH model.
/// \param path mesh file \param scale per-axis scale
/// \throws std::runtime_error when the file cannot be read or holds no triangles
std::shared_ptr<fcl::CollisionGeometryd> load_mesh(const std::string& path,
                                                    const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

/// \brief Builds an FCL BVH model from vertices (N x 3) and triangles (M x 3 indices).
std::shared_ptr<fcl::CollisionGeometryd> make_mesh(const MeshVertices& vertices, const MeshTriangles& triangles);

}  // namespace octoreach
