#include "octoreach/collision.hpp"

#include <cerrno>
#include <fstream>
#include <optional>
#include <sstream>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcl/fcl.h>
#include <octomap/OcTree.h>

#include "collision/detail.hpp"
#include "collision/mesh_pair_check.hpp"
#include "common/file_read.hpp"
#include "common/octree_file.hpp"
#include "octoreach/limits.hpp"
#include "collision/obb.hpp"

namespace octoreach {
namespace {

using detail::geometry_collide;
using detail::world_aabb;

using BVH = fcl::BVHModel<fcl::OBBRSSd>;

void collect_triangles(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent,
                       std::vector<fcl::Vector3d>& points, std::vector<fcl::Triangle>& triangles,
                       const Eigen::Vector3d& scale) {
  aiMatrix4x4 transform = parent * node->mTransformation;
  for (unsigned mi = 0; mi < node->mNumMeshes; ++mi) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[mi]];
    std::size_t offset = points.size();
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      aiVector3D p = transform * mesh->mVertices[v];
      points.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      triangles.emplace_back(offset + face.mIndices[0], offset + face.mIndices[1], offset + face.mIndices[2]);
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collect_triangles(scene, node->mChildren[c], transform, points, triangles, scale);
}

std::shared_ptr<fcl::CollisionGeometryd> bvh_from(const std::vector<fcl::Vector3d>& points,
                                                  const std::vector<fcl::Triangle>& triangles) {
  auto model = std::make_shared<detail::HullMesh>();  // a BVH that also keeps its hull (mesh_pair_check.hpp)
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
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

std::shared_ptr<fcl::CollisionGeometryd> load_mesh(const std::string& path, const Eigen::Vector3d& scale) {
  if (!scale.allFinite() || (scale.array() == 0).any())  // negative: mirrored, as URDFs may give it
    throw std::invalid_argument("mesh scale must be finite and non-zero, got (" + std::to_string(scale.x()) + ", " +
                                std::to_string(scale.y()) + ", " + std::to_string(scale.z()) + ")");
  detail::check_file_bounded(path, "mesh file", limits::kMeshFileBytes);  // assimp opens it itself
  Assimp::Importer importer;
  // Keep the file's own units; URDF meshes carry their scale in the <mesh scale> attribute.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                     aiProcess_SortByPType);
  if (!scene || !scene->mRootNode)
    throw FileError("cannot read mesh '" + path + "': " + importer.GetErrorString());
  std::vector<fcl::Vector3d> points;
  std::vector<fcl::Triangle> triangles;
  collect_triangles(scene, scene->mRootNode, aiMatrix4x4(), points, triangles, scale);
  if (triangles.empty()) throw FileError("mesh '" + path + "' holds no triangles");
  return bvh_from(points, triangles);
}

std::shared_ptr<fcl::CollisionGeometryd> make_mesh(
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& vertices,
    const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>& triangles) {
  if (vertices.rows() == 0 || triangles.rows() == 0)
    throw std::invalid_argument("a mesh needs at least one vertex and one triangle");
  if (!vertices.allFinite()) throw std::invalid_argument("mesh vertices must be finite");
  std::vector<fcl::Vector3d> points;
  std::vector<fcl::Triangle> tris;
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) points.emplace_back(vertices.row(i).transpose());
  for (Eigen::Index i = 0; i < triangles.rows(); ++i) {
    for (int k = 0; k < 3; ++k)
      if (triangles(i, k) < 0 || triangles(i, k) >= vertices.rows())
        throw std::invalid_argument("triangle " + std::to_string(i) + " refers to vertex " +
                                    std::to_string(triangles(i, k)) + ", outside [0, " +
                                    std::to_string(vertices.rows()) + ")");
    tris.emplace_back(triangles(i, 0), triangles(i, 1), triangles(i, 2));
  }
  return bvh_from(points, tris);
}

void Obstacles::add_geometry(std::shared_ptr<fcl::CollisionGeometryd> geometry, const Pose& pose,
                             const std::string& name) {
  if (!geometry) throw std::invalid_argument("obstacle geometry is null");
  if (!pose.matrix().allFinite()) throw std::invalid_argument("obstacle pose must be finite");
  geometry->computeLocalAABB();
  auto obj = std::make_shared<fcl::CollisionObjectd>(geometry, fcl::Transform3d(pose.matrix()));
  obj->computeAABB();
  objects_.push_back(obj);
  obbs_.push_back(std::make_shared<const detail::Obb>(detail::Obb::of(*geometry, pose)));
  names_.push_back(name.empty() ? "obstacle_" + std::to_string(objects_.size() - 1) : name);
}

void Obstacles::add_box(const Eigen::Vector3d& size, const Pose& pose, const std::string& name) {
  if (!(size.array() > 0).all() || !size.allFinite())
    throw std::invalid_argument("box size must be three positive numbers");
  add_geometry(std::make_shared<fcl::Boxd>(size), pose, name);
}

void Obstacles::add_sphere(double radius, const Pose& pose, const std::string& name) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("sphere radius must be positive");
  add_geometry(std::make_shared<fcl::Sphered>(radius), pose, name);
}

void Obstacles::add_cylinder(double radius, double length, const Pose& pose, const std::string& name) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw std::invalid_argument("cylinder radius must be a positive finite number, got " + std::to_string(radius));
  if (!(length > 0) || !std::isfinite(length))
    throw std::invalid_argument("cylinder length must be a positive finite number, got " + std::to_string(length));
  add_geometry(std::make_shared<fcl::Cylinderd>(radius, length), pose, name);
}

void Obstacles::add_mesh_file(const std::string& path, const Pose& pose, const Eigen::Vector3d& scale,
                              const std::string& name) {
  add_geometry(load_mesh(path, scale), pose, name.empty() ? path : name);
}

void Obstacles::add_octree(std::shared_ptr<const octomap::OcTree> tree, const Pose& pose, const std::string& name) {
  if (!tree) throw std::invalid_argument("octree is null");
  add_geometry(std::make_shared<fcl::OcTreed>(tree), pose, name);
}

void Obstacles::add_octree_file(const std::string& path, const Pose& pose, const std::string& name) {
  add_octree(read_octree(path), pose, name.empty() ? path : name);
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
}

bool Obstacles::collides_box(const Eigen::Vector3d& size, const Pose& pose) const {
  if (!size.allFinite() || (size.array() < 0).any() || size.maxCoeff() > kMaxBoxSize)
    throw std::invalid_argument("collides_box: size must be finite, >= 0 and at most " + std::to_string(kMaxBoxSize) +
                                " m per axis");
  if (!pose.matrix().allFinite()) throw std::invalid_argument("collides_box: pose must be finite");
  fcl::Boxd box(size);
  box.computeLocalAABB();
  return collides(box, pose);
}

// World AABBs first, then an exact pre-test: the oriented boxes of the geometry and of the obstacle
// (their local AABBs placed) clearly apart means no contact, and FCL (whose every call fits a bounding
// volume to the obstacle) is skipped.
bool Obstacles::collides(const fcl::CollisionGeometryd& geometry, const Pose& pose) const {
  const fcl::AABBd box = world_aabb(geometry, pose);
  std::optional<detail::Obb> shape;
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const auto& o = objects_[i];
    if (!o->getAABB().overlap(box)) continue;
    if (!shape) shape = detail::Obb::of(geometry, pose);
    if (shape->apart(*obbs_[i])) continue;
    if (geometry_collide(&geometry, pose, o->collisionGeometry().get(), Pose(o->getTransform().matrix())))
      return true;
  }
  return false;
}

bool Obstacles::collides(const fcl::CollisionObjectd& object) const {
  for (const auto& o : objects_) {
    if (!o->getAABB().overlap(object.getAABB())) continue;
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    if (fcl::collide(&object, o.get(), request, result) > 0) return true;
  }
  return false;
}

}  // namespace octoreach
