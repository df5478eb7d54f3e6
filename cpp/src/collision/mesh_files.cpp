// Triangle meshes as FCL BVH models: read from files through assimp (load_mesh) or built from arrays
// (make_mesh). Each model also keeps its convex hull (mesh_pair_check.hpp).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcl/fcl.h>

#include "octoreach/shape.hpp"
#include "octoreach/types.hpp"
#include "collision/mesh_pair_check.hpp"
#include "common/checks.hpp"
#include "common/file_read.hpp"
#include "octoreach/limits.hpp"

namespace octoreach {
namespace {

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
  for (const auto& p : points)  // a scale of 1e300 gives vertices no collision check can place
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > limits::kCoordinate)
      throw std::invalid_argument("mesh '" + path + "' scaled by " + detail::format_point(scale) + " has a vertex at " +
                                  detail::format_point(p) + ", out of range (at most " +
                                  detail::format_number(limits::kCoordinate) + " m in magnitude)");
  return bvh_from(points, triangles);
}

std::shared_ptr<fcl::CollisionGeometryd> make_mesh(const MeshVertices& vertices, const MeshTriangles& triangles) {
  if (vertices.rows() == 0 || triangles.rows() == 0)
    throw std::invalid_argument("a mesh needs at least one vertex and one triangle");
  if (!vertices.allFinite()) throw std::invalid_argument("mesh vertices must be finite");
  detail::check_coordinates(vertices, "mesh vertices");
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

}  // namespace octoreach
