// MapRoom: the room a surface map was built with, the body checked against it, and how another room differs.
#include "octoreach/map_room.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <octomap/OcTree.h>

namespace octoreach {
namespace {

void check_pose(const Eigen::Vector4d& pose) {
  if (!pose.allFinite()) throw std::invalid_argument("base pose (x, y, z, theta) must be finite");
}

// A mesh's vertex count and bounds in its own frame.
void mesh_summary(const Shape& s, std::size_t& count, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> t;
  s.mesh_triangles(v, t);
  count = v.size();
  lo = hi = v.empty() ? Eigen::Vector3d::Zero() : v[0];
  for (const auto& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

bool same_octree(const Shape& a, const Shape& b) {
  if (!a.octree || !b.octree) return a.octree == b.octree;
  return a.octree->getResolution() == b.octree->getResolution() &&
         a.octree->getNumLeafNodes() == b.octree->getNumLeafNodes() && a.octree->size() == b.octree->size();
}

std::string describe(const Shape& s, const std::string& name) {
  std::ostringstream out;
  out.precision(3);
  const Eigen::Vector3d p = s.origin.translation();
  out << s.type_name() << " '" << name << "' at (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

// For each shape of `a`, whether some still unmatched shape of `b` is the same (a greedy matching).
std::vector<bool> matched(const std::vector<Shape>& a, const std::vector<Shape>& b, double tolerance) {
  std::vector<bool> found(a.size(), false), used(b.size(), false);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size() && !found[i]; ++j)
      if (!used[j] && same_shape(a[i], b[j], tolerance)) found[i] = used[j] = true;
  return found;
}

}  // namespace

bool same_shape(const Shape& a, const Shape& b, double tolerance) {
  if (a.type != b.type) return false;
  if (!((a.origin.matrix() - b.origin.matrix()).cwiseAbs().maxCoeff() <= tolerance)) return false;
  switch (a.type) {
    case Shape::Type::Box: return (a.size - b.size).cwiseAbs().maxCoeff() <= tolerance;
    case Shape::Type::Cylinder:
      return std::abs(a.radius - b.radius) <= tolerance && std::abs(a.length - b.length) <= tolerance;
    case Shape::Type::Sphere: return std::abs(a.radius - b.radius) <= tolerance;
    case Shape::Type::Mesh: {
      std::size_t na = 0, nb = 0;
      Eigen::Vector3d la, ha, lb, hb;
      mesh_summary(a, na, la, ha);
      mesh_summary(b, nb, lb, hb);
      return na == nb && (la - lb).cwiseAbs().maxCoeff() <= tolerance && (ha - hb).cwiseAbs().maxCoeff() <= tolerance;
    }
    case Shape::Type::Octree: return same_octree(a, b);
  }
  return false;
}

MapRoom::MapRoom(Obstacles obstacles, std::size_t surface_count, std::vector<Shape> body,
                 std::vector<std::string> body_links)
    : obstacles_(std::move(obstacles)), surface_count_(surface_count), body_links_(std::move(body_links)) {
  if (surface_count_ > obstacles_.size())
    throw std::invalid_argument("a map room's surface count (" + std::to_string(surface_count_) +
                                ") exceeds its obstacles (" + std::to_string(obstacles_.size()) + ")");
  if (body_links_.size() != body.size())
    throw std::invalid_argument("a map room needs one link name per body shape (" + std::to_string(body.size()) +
                                " shapes, " + std::to_string(body_links_.size()) + " names)");
  body_.reserve(body.size());
  for (const Shape& s : body) body_.push_back(s.with_geometry());
}

MapRoom MapRoom::of_build(const Robot& robot, const ArmPlacement& place, const Surface& surface,
                          const Obstacles* others, bool check_body) {
  Obstacles room;
  room.add(*surface.obstacles());
  const std::size_t surface_count = room.size();
  if (others) room.add(*others);
  std::vector<Shape> body;
  std::vector<std::string> links;
  if (check_body) {
    for (int li : place.roles.body) {
      const Link& link = robot.links()[li];
      for (const Shape& s : link.shapes) {
        Shape placed = s;
        placed.origin = place.root_in_reference * place.link_poses[li] * s.origin;
        body.push_back(std::move(placed));
        links.push_back(link.name);
      }
    }
  }
  return MapRoom(std::move(room), surface_count, std::move(body), std::move(links));
}

MapRoom MapRoom::combined(const std::vector<const MapRoom*>& rooms) {
  if (rooms.empty()) return MapRoom();
  for (const MapRoom* room : rooms)
    if (room->empty()) return MapRoom();
  const MapRoom& first = *rooms[0];
  for (std::size_t r = 1; r < rooms.size(); ++r) {
    const std::vector<std::string> d = first.differences(rooms[r]->obstacles_);
    if (!d.empty())
      throw std::invalid_argument("cannot combine maps built in different rooms: " + d[0] +
                                  (d.size() > 1 ? " (and " + std::to_string(d.size() - 1) + " more differences)" : ""));
  }
  std::vector<Shape> body;
  std::vector<std::string> links;
  for (std::size_t i = 0; i < first.body_.size(); ++i) {
    bool everywhere = true;
    for (std::size_t r = 1; r < rooms.size() && everywhere; ++r) {
      bool here = false;
      for (std::size_t j = 0; j < rooms[r]->body_.size() && !here; ++j)
        here = rooms[r]->body_links_[j] == first.body_links_[i] && same_shape(rooms[r]->body_[j], first.body_[i]);
      everywhere = here;
    }
    if (everywhere) {
      body.push_back(first.body_[i]);
      links.push_back(first.body_links_[i]);
    }
  }
  return MapRoom(first.obstacles_, first.surface_count_, std::move(body), std::move(links));
}

int MapRoom::touched(const Eigen::Vector4d& pose, const Obstacles& obstacles) const {
  check_pose(pose);
  const Pose B = base_pose(pose[0], pose[1], pose[2], pose[3]);
  for (const Shape& s : body_) {
    const Pose at = B * s.origin;
    if (!obstacles.collides(*s.geometry, at)) continue;
    for (std::size_t i = 0; i < obstacles.size(); ++i) {  // which one: rare, so one obstacle at a time
      Obstacles one;
      one.add(obstacles.shapes()[i]);
      if (one.collides(*s.geometry, at)) return static_cast<int>(i);
    }
  }
  return -1;
}

bool MapRoom::body_collides(const Eigen::Vector4d& pose, const Obstacles& obstacles) const {
  check_pose(pose);
  if (obstacles.empty()) return false;
  const Pose B = base_pose(pose[0], pose[1], pose[2], pose[3]);
  for (const Shape& s : body_)
    if (obstacles.collides(*s.geometry, B * s.origin)) return true;
  return false;
}

std::vector<std::string> MapRoom::differences(const Obstacles& other, double tolerance) const {
  std::vector<std::string> out;
  const std::vector<bool> kept = matched(obstacles_.shapes(), other.shapes(), tolerance);
  const std::vector<bool> known = matched(other.shapes(), obstacles_.shapes(), tolerance);
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (!kept[i]) out.push_back(describe(obstacles_.shapes()[i], obstacles_.names()[i]) + " is in the map's room only");
  for (std::size_t i = 0; i < known.size(); ++i)
    if (!known[i]) out.push_back(describe(other.shapes()[i], other.names()[i]) + " is not in the map's room");
  return out;
}

}  // namespace octoreach
