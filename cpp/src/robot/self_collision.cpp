// The robot's collision model: which link pairs are checked (adjacent and SRDF pairs allowed,
// sampled pairs added through a new robot) and the checks themselves, against itself and against
// Obstacles.
#include <algorithm>
#include <limits>
#include <map>

#include <fcl/fcl.h>

#include "collision/detail.hpp"
#include "collision/mesh_pair_check.hpp"
#include "octoreach/robot.hpp"
#include "robot/robot_builder.hpp"

namespace octoreach {

using detail::geometry_collide;
using detail::is_mesh;
using detail::meshes_collide;
using detail::MeshPairWitnesses;
using detail::world_aabb;

namespace detail {

void RobotBuilder::finish_collision_model(PairSet allowed) {
  for (std::size_t i = 0; i < r.links_.size(); ++i)
    if (!r.links_[i].shapes.empty()) r.collision_links_.push_back(static_cast<int>(i));
  // Adjacent links: a link and its nearest ancestor that has geometry (fixed joints and
  // geometry-less links in between do not separate them).
  PairSet adjacent;
  for (int li : r.collision_links_) {
    int cur = li;
    while (r.links_[cur].parent_joint >= 0) {
      int parent = r.joints_[r.links_[cur].parent_joint].parent_link;
      add_pair(adjacent, li, parent);
      if (!r.links_[parent].shapes.empty()) break;
      cur = parent;
    }
  }
  std::map<std::pair<int, int>, AllowedSource> sources;
  for (const auto& p : adjacent) sources.emplace(p, AllowedSource::kAdjacent);
  for (const auto& p : allowed) sources.emplace(p, AllowedSource::kSrdf);
  r.set_allowed_pairs_(sources);
}

}  // namespace detail

const char* allowed_source_name(AllowedSource source) {
  switch (source) {
    case AllowedSource::kAdjacent: return "adjacent";
    case AllowedSource::kSrdf: return "SRDF";
    case AllowedSource::kNever: return "never in collision";
    case AllowedSource::kAlways: return "always in collision";
    case AllowedSource::kDefaultPosture: return "in collision at home";
    case AllowedSource::kGiven: return "given";
  }
  return "given";
}

void Robot::set_allowed_pairs_(const std::map<std::pair<int, int>, AllowedSource>& allowed) {
  allowed_.clear();
  allowed_sources_.clear();
  for (const auto& [pair, source] : allowed) {
    allowed_.push_back(pair);
    allowed_sources_.push_back(source);
  }
  checked_.clear();
  for (std::size_t a = 0; a < collision_links_.size(); ++a)
    for (std::size_t b = a + 1; b < collision_links_.size(); ++b) {
      std::pair<int, int> p{std::min(collision_links_[a], collision_links_[b]),
                            std::max(collision_links_[a], collision_links_[b])};
      if (!std::binary_search(allowed_.begin(), allowed_.end(), p)) checked_.push_back(p);
    }
}

std::shared_ptr<Robot> Robot::with_allowed_collisions(const std::vector<std::pair<int, int>>& pairs,
                                                      AllowedSource source) const {
  std::map<std::pair<int, int>, AllowedSource> allowed;
  for (std::size_t i = 0; i < allowed_.size(); ++i) allowed.emplace(allowed_[i], allowed_sources_[i]);
  const int n = static_cast<int>(links_.size());
  for (const auto& [a, b] : pairs) {
    if (a < 0 || a >= n || b < 0 || b >= n)
      throw std::invalid_argument("allowed-collision pair (" + std::to_string(a) + ", " + std::to_string(b) +
                                  ") names a link index outside [0, " + std::to_string(n) + ")");
    if (a != b) allowed.emplace(std::make_pair(std::min(a, b), std::max(a, b)), source);
  }
  std::shared_ptr<Robot> robot(new Robot(*this));
  robot->set_allowed_pairs_(allowed);
  return robot;
}

std::shared_ptr<Robot> Robot::with_allowed_collisions(
    const std::vector<std::pair<std::string, std::string>>& pairs) const {
  std::vector<std::pair<int, int>> indices;
  indices.reserve(pairs.size());
  for (const auto& [a, b] : pairs) indices.emplace_back(link_index(a), link_index(b));
  return with_allowed_collisions(indices);
}

namespace {

// Lowest world z of one shape at a world pose.
double shape_lowest(const fcl::CollisionGeometryd& g, const Pose& T) {
  if (const auto* mesh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(&g); mesh && mesh->vertices) {
    double z = std::numeric_limits<double>::infinity();
    for (int i = 0; i < mesh->num_vertices; ++i) z = std::min(z, (T * mesh->vertices[i]).z());
    return z;
  }
  if (const auto* box = dynamic_cast<const fcl::Boxd*>(&g)) {
    // The lowest corner: each half side along the direction that lowers z.
    Eigen::Vector3d h = 0.5 * box->side;
    return T.translation().z() - (T.linear().row(2).transpose().cwiseAbs().array() * h.array()).sum();
  }
  return world_aabb(g, T).min_.z();
}

}  // namespace

double Robot::lowest_point(const std::vector<Pose>& poses, const Pose& base_pose, int* link,
                           const std::vector<int>* only_links) const {
  double lowest = std::numeric_limits<double>::infinity();
  if (link) *link = -1;
  for (int li : only_links ? *only_links : collision_links_)
    for (const auto& shape : links_[li].shapes) {
      double z = shape_lowest(*shape.geometry, base_pose * poses[li] * shape.origin);
      if (z < lowest) {
        lowest = z;
        if (link) *link = li;
      }
    }
  return lowest;
}

bool Robot::in_self_collision_poses(const std::vector<Pose>& poses) const {
  return in_self_collision_poses(poses, checked_);
}

bool Robot::in_self_collision_poses(const std::vector<Pose>& poses, const std::vector<std::pair<int, int>>& pairs) const {
  return detail::first_colliding_pair(*this, poses, pairs) >= 0;
}

void detail::ShapeBoxes::update(const Robot& robot, const std::vector<Pose>& link_poses, int link) {
  if (boxes.size() < robot.links().size()) {
    boxes.resize(robot.links().size());
    poses.resize(robot.links().size());
  }
  const auto& shapes = robot.links()[link].shapes;
  boxes[link].resize(shapes.size());
  poses[link].resize(shapes.size());
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    poses[link][s] = link_poses[link] * shapes[s].origin;
    boxes[link][s] = world_aabb(*shapes[s].geometry, poses[link][s]);
  }
}

int detail::first_colliding_pair(const Robot& robot, const std::vector<Pose>& poses,
                                 const std::vector<std::pair<int, int>>& pairs) {
  // AABBs of every shape first, so most pairs are rejected without FCL. The scratch is per thread:
  // the robot itself is shared and never written. Only the links named by `pairs` need their boxes.
  thread_local ShapeBoxes boxes;
  thread_local std::vector<char> needed;
  needed.assign(robot.links().size(), 0);
  for (const auto& [a, b] : pairs) needed[a] = needed[b] = 1;
  for (int li : robot.collision_links())
    if (needed[li]) boxes.update(robot, poses, li);
  return first_colliding_pair(robot, boxes, pairs);
}

int detail::first_colliding_pair(const Robot& robot, const ShapeBoxes& shape_boxes, const std::vector<std::pair<int, int>>& pairs) {
  const auto& links = robot.links();
  const auto& boxes = shape_boxes.boxes;
  const auto& shape_poses = shape_boxes.poses;
  // Mesh pairs go through their witnesses (mesh_pair_check.hpp), per thread like the scratch above,
  // under (link, shape, link, shape): successive checks on a thread are mostly of one robot.
  thread_local MeshPairWitnesses witnesses;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [a, b] = pairs[p];
    const auto& shapes_a = links[a].shapes;
    const auto& shapes_b = links[b].shapes;
    for (std::size_t i = 0; i < shapes_a.size(); ++i)
      for (std::size_t k = 0; k < shapes_b.size(); ++k) {
        if (!boxes[a][i].overlap(boxes[b][k])) continue;
        const fcl::CollisionGeometryd& ga = *shapes_a[i].geometry;
        const fcl::CollisionGeometryd& gb = *shapes_b[k].geometry;
        const bool hit =
            is_mesh(ga) && is_mesh(gb)
                ? meshes_collide(ga, shape_poses[a][i], gb, shape_poses[b][k],
                                 witnesses.of(MeshPairWitnesses::key(a, i, b, k)))
                : geometry_collide(&ga, shape_poses[a][i], &gb, shape_poses[b][k]);
        if (hit) return static_cast<int>(p);
      }
  }
  return -1;
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
                         bool check_self, const std::vector<int>* only_links) const {
  check_rigid(base_pose, "base_pose");
  thread_local std::vector<Pose> poses;
  link_poses(q, poses);
  if (links_in_collision(poses, obstacles, base_pose, only_links)) return true;
  return check_self && in_self_collision_poses(poses);
}

}  // namespace octoreach
