// Shape: the one description of a solid (box, cylinder, sphere, mesh, OctoMap) with its pose, and its FCL
// collision geometry.
#include "octoreach/shape.hpp"

#include <cmath>
#include <sstream>

#include <fcl/fcl.h>
#include <octomap/OcTree.h>

#include "common/checks.hpp"
#include "common/file_read.hpp"
#include "common/octree_file.hpp"
#include "octoreach/limits.hpp"

namespace octoreach {
namespace {

using BVH = fcl::BVHModel<fcl::OBBRSSd>;

// A rigid pose (check_rigid) whose position lies within limits::kCoordinate (far beyond, the millimetres the
// collision checks work in are lost, and extents add up to infinity).
void check_pose(const Pose& pose, const char* what) {
  check_rigid(pose, std::string(what) + " pose");
  detail::check_coordinates(pose.translation(), (std::string(what) + " position").c_str());
}

Shape with_geometry_at(Shape s, std::shared_ptr<fcl::CollisionGeometryd> geometry, const Pose& pose) {
  check_pose(pose, "shape");
  geometry->computeLocalAABB();
  s.geometry = std::move(geometry);
  s.origin = pose;
  return s;
}

// An OctoMap file: .ot holds any AbstractOcTree (it must be an OcTree), anything else is read as .bt.
std::shared_ptr<octomap::OcTree> read_octree(const std::string& path) {
  if (path.size() >= 3 && path.substr(path.size() - 3) == ".ot") {
    std::istringstream f(detail::read_file_bounded(path, "octree file", limits::kOctreeFileBytes));
    std::unique_ptr<octomap::AbstractOcTree> t(octomap::AbstractOcTree::read(f));
    auto* tree = dynamic_cast<octomap::OcTree*>(t.get());
    if (!tree) throw FileError("'" + path + "' is not an OcTree .ot file");
    t.release();
    return std::shared_ptr<octomap::OcTree>(tree);
  }
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  detail::read_bt(*tree, path, "octree file", 0);
  return tree;
}

}  // namespace

Shape Shape::box(const Eigen::Vector3d& size, const Pose& pose) {
  if (!(size.array() > 0).all() || !size.allFinite())
    throw std::invalid_argument("box size must be three positive numbers");
  detail::check_coordinates(size, "box size");
  Shape s;
  s.type = Type::Box;
  s.size = size;
  return with_geometry_at(std::move(s), std::make_shared<fcl::Boxd>(size), pose);
}

Shape Shape::cylinder(double radius, double length, const Pose& pose) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw std::invalid_argument("cylinder radius must be a positive finite number, got " + std::to_string(radius));
  if (!(length > 0) || !std::isfinite(length))
    throw std::invalid_argument("cylinder length must be a positive finite number, got " + std::to_string(length));
  detail::check_coordinate(radius, "cylinder radius");
  detail::check_coordinate(length, "cylinder length");
  Shape s;
  s.type = Type::Cylinder;
  s.radius = radius;
  s.length = length;
  return with_geometry_at(std::move(s), std::make_shared<fcl::Cylinderd>(radius, length), pose);
}

Shape Shape::sphere(double radius, const Pose& pose) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("sphere radius must be positive");
  detail::check_coordinate(radius, "sphere radius");
  Shape s;
  s.type = Type::Sphere;
  s.radius = radius;
  return with_geometry_at(std::move(s), std::make_shared<fcl::Sphered>(radius), pose);
}

Shape Shape::mesh_file(const std::string& path, const Pose& pose, const Eigen::Vector3d& scale) {
  Shape s;
  s.type = Type::Mesh;
  s.mesh_path = path;
  s.scale = scale;
  return with_geometry_at(std::move(s), load_mesh(path, scale), pose);
}

Shape Shape::triangle_mesh(const MeshVertices& vertices, const MeshTriangles& triangles, const Pose& pose) {
  Shape s;
  s.type = Type::Mesh;
  return with_geometry_at(std::move(s), make_mesh(vertices, triangles), pose);
}

Shape Shape::from_octree(std::shared_ptr<const octomap::OcTree> tree, const Pose& pose) {
  if (!tree) throw std::invalid_argument("octree is null");
  Shape s;
  s.type = Type::Octree;
  s.octree = tree;
  return with_geometry_at(std::move(s), std::make_shared<fcl::OcTreed>(tree), pose);
}

Shape Shape::octree_file(const std::string& path, const Pose& pose) { return from_octree(read_octree(path), pose); }

Shape Shape::of(std::shared_ptr<fcl::CollisionGeometryd> geometry, const Pose& pose) {
  if (!geometry) throw std::invalid_argument("obstacle geometry is null");
  Shape s;
  switch (geometry->getNodeType()) {
    case fcl::GEOM_BOX:
      s.type = Type::Box;
      s.size = static_cast<const fcl::Boxd&>(*geometry).side;
      break;
    case fcl::GEOM_CYLINDER: {
      const auto& c = static_cast<const fcl::Cylinderd&>(*geometry);
      s.type = Type::Cylinder;
      s.radius = c.radius;
      s.length = c.lz;
      break;
    }
    case fcl::GEOM_SPHERE:
      s.type = Type::Sphere;
      s.radius = static_cast<const fcl::Sphered&>(*geometry).radius;
      break;
    case fcl::GEOM_CONVEX:
    case fcl::BV_OBBRSS: s.type = Type::Mesh; break;
    case fcl::GEOM_OCTREE: s.type = Type::Octree; break;
    default:
      throw std::invalid_argument("unsupported FCL geometry (node type " + std::to_string(geometry->getNodeType()) +
                                  "): a shape is a box, cylinder, sphere, BVH or convex mesh, or OcTree");
  }
  check_rigid(pose, "obstacle pose");
  return with_geometry_at(std::move(s), std::move(geometry), pose);
}

const char* Shape::type_name() const {
  switch (type) {
    case Type::Box: return "box";
    case Type::Cylinder: return "cylinder";
    case Type::Sphere: return "sphere";
    case Type::Mesh: return "mesh";
    case Type::Octree: return "octree";
  }
  return "?";
}

Shape Shape::with_geometry() const {
  if (geometry) return *this;
  switch (type) {
    case Type::Box: return box(size, origin);
    case Type::Cylinder: return cylinder(radius, length, origin);
    case Type::Sphere: return sphere(radius, origin);
    case Type::Mesh:
      if (mesh_path.empty()) throw std::invalid_argument("a mesh shape without geometry needs its mesh file");
      return mesh_file(mesh_path, origin, scale);
    case Type::Octree:
      if (!octree) throw std::invalid_argument("an OctoMap shape needs its map");
      return from_octree(octree, origin);
  }
  return *this;
}

void Shape::mesh_triangles(std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& triangles) const {
  if (type != Type::Mesh) throw std::invalid_argument(std::string("a ") + type_name() + " is not a triangle mesh");
  vertices.clear();
  triangles.clear();
  std::shared_ptr<fcl::CollisionGeometryd> g = geometry ? geometry : load_mesh(mesh_path, scale);
  if (const auto* bvh = dynamic_cast<const BVH*>(g.get())) {
    for (int i = 0; i < bvh->num_vertices; ++i) vertices.push_back(bvh->vertices[i]);
    for (int i = 0; i < bvh->num_tris; ++i) {
      const fcl::Triangle& t = bvh->tri_indices[i];
      triangles.emplace_back(int(t[0]), int(t[1]), int(t[2]));
    }
  } else if (const auto* convex = dynamic_cast<const fcl::Convexd*>(g.get())) {
    vertices = convex->getVertices();
    const std::vector<int>& faces = convex->getFaces();  // per face: its vertex count, then its vertices
    for (std::size_t k = 0; k < faces.size(); k += std::size_t(faces[k]) + 1)
      for (int j = 2; j < faces[k]; ++j)  // a convex face is a fan from its first vertex
        triangles.emplace_back(faces[k + 1], faces[k + std::size_t(j)], faces[k + std::size_t(j) + 1]);
  }
}

}  // namespace octoreach
