#include "octoreach/collision.hpp"

#include <algorithm>
#include <random>
#include <set>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "octoreach/robot.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {
namespace {

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
  auto model = std::make_shared<BVH>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

// World-frame AABB of a geometry at a pose, from its local AABB (cheap and conservative).
fcl::AABBd world_aabb(const fcl::CollisionGeometryd& g, const Pose& T) {
  const fcl::AABBd& local = g.aabb_local;
  Eigen::Vector3d c = T * local.center();
  Eigen::Vector3d h = 0.5 * (local.max_ - local.min_);
  Eigen::Vector3d e = T.linear().cwiseAbs() * h;
  return fcl::AABBd(c - e, c + e);
}

bool geometry_collide(const fcl::CollisionGeometryd* a, const Pose& ta, const fcl::CollisionGeometryd* b,
                      const Pose& tb) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::Transform3d fa(ta.matrix()), fb(tb.matrix());
  return fcl::collide(a, fa, b, fb, request, result) > 0;
}

}  // namespace

std::shared_ptr<fcl::CollisionGeometryd> load_mesh(const std::string& path, const Eigen::Vector3d& scale) {
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
  if (!(radius > 0) || !(length > 0)) throw std::invalid_argument("cylinder radius and length must be positive");
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

bool Obstacles::collides(const fcl::CollisionGeometryd& geometry, const Pose& pose) const {
  fcl::AABBd box = world_aabb(geometry, pose);
  for (const auto& o : objects_) {
    if (!o->getAABB().overlap(box)) continue;
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

// ---------------------------------------------------------------- robot collisions

bool Robot::in_self_collision_poses(const std::vector<Pose>& poses) const {
  return in_self_collision_poses(poses, checked_);
}

bool Robot::in_self_collision_poses(const std::vector<Pose>& poses, const std::vector<std::pair<int, int>>& pairs) const {
  // AABBs of every shape first, so most pairs are rejected without FCL.
  thread_local std::vector<std::vector<fcl::AABBd>> boxes;
  thread_local std::vector<std::vector<Pose>> shape_poses;
  boxes.resize(links_.size());
  shape_poses.resize(links_.size());
  // Only the links named by `pairs` need their boxes.
  thread_local std::vector<char> needed;
  needed.assign(links_.size(), 0);
  for (const auto& [a, b] : pairs) needed[a] = needed[b] = 1;
  for (int li : collision_links_) {
    if (!needed[li]) continue;
    const auto& shapes = links_[li].shapes;
    boxes[li].resize(shapes.size());
    shape_poses[li].resize(shapes.size());
    for (std::size_t s = 0; s < shapes.size(); ++s) {
      shape_poses[li][s] = poses[li] * shapes[s].origin;
      boxes[li][s] = world_aabb(*shapes[s].geometry, shape_poses[li][s]);
    }
  }
  for (const auto& [a, b] : pairs) {
    const auto& sa = links_[a].shapes;
    const auto& sb = links_[b].shapes;
    for (std::size_t i = 0; i < sa.size(); ++i)
      for (std::size_t k = 0; k < sb.size(); ++k) {
        if (!boxes[a][i].overlap(boxes[b][k])) continue;
        if (geometry_collide(sa[i].geometry.get(), shape_poses[a][i], sb[k].geometry.get(), shape_poses[b][k]))
          return true;
      }
  }
  return false;
}

bool Robot::in_self_collision(const Eigen::VectorXd& q) const {
  thread_local std::vector<Pose> poses;
  link_poses(q, poses);
  return in_self_collision_poses(poses);
}

bool Robot::links_in_collision(const std::vector<Pose>& poses, const Obstacles& obstacles, const Pose& base_pose,
                               const std::vector<int>* only_links) const {
  const std::vector<int>& links = only_links ? *only_links : collision_links_;
  for (int li : links) {
    for (const auto& s : links_[li].shapes)
      if (obstacles.collides(*s.geometry, base_pose * poses[li] * s.origin)) return true;
  }
  return false;
}

bool Robot::in_collision(const Eigen::VectorXd& q, const Obstacles& obstacles, const Pose& base_pose,
                         bool check_self) const {
  thread_local std::vector<Pose> poses;
  link_poses(q, poses);
  if (links_in_collision(poses, obstacles, base_pose)) return true;
  return check_self && in_self_collision_poses(poses);
}

std::size_t Robot::compute_allowed_collisions(int samples, std::uint64_t seed, const ProgressCallback& progress) {
  if (samples < 1) throw std::invalid_argument("samples must be at least 1, got " + std::to_string(samples));
  const auto pairs = checked_;
  std::vector<int> hits(pairs.size(), 0);
  Eigen::VectorXd lo = lower(), hi = upper();
  std::mt19937_64 rng(seed);
  std::vector<Pose> poses;
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd q(dof());
    for (int i = 0; i < dof(); ++i) {
      double a = std::isfinite(lo[i]) ? lo[i] : -M_PI, b = std::isfinite(hi[i]) ? hi[i] : M_PI;
      q[i] = std::uniform_real_distribution<double>(a, b)(rng);
    }
    link_poses(q, poses);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      auto [a, b] = pairs[p];
      bool hit = false;
      for (const auto& sa : links_[a].shapes) {
        for (const auto& sb : links_[b].shapes)
          if (geometry_collide(sa.geometry.get(), poses[a] * sa.origin, sb.geometry.get(), poses[b] * sb.origin)) {
            hit = true;
            break;
          }
        if (hit) break;
      }
      hits[p] += hit;
    }
    if (progress && !progress(s + 1, samples)) throw Cancelled("allowed-collision sampling cancelled");
  }
  std::set<std::pair<int, int>> allowed(allowed_.begin(), allowed_.end());
  std::size_t before = allowed.size();
  for (std::size_t p = 0; p < pairs.size(); ++p)
    if (hits[p] == 0 || hits[p] == samples) allowed.insert(pairs[p]);
  allowed_.assign(allowed.begin(), allowed.end());
  rebuild_checked_();
  return allowed.size() - before;
}

}  // namespace octoreach
