#pragma once
/// \file map_room.hpp
/// \brief The room a surface map was built with: the obstacles its build checked and the robot body it checked
/// against them, recorded in the map (its file too), so that whoever uses the map (the pose sampler, the
/// planner, the viewer) sees the room of the build without being given it again.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/arm.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/shape.hpp"
#include "octoreach/surface.hpp"

namespace octoreach {

/// \brief What a surface map was built with: the obstacles (world frame: the surface's slab and boxes, and the
/// rest of the room) and the robot's body as the build checked it (its collision shapes on the links the arm
/// does not move, at the build's reference posture, in the map's reference frame). Built once, then only read:
/// the const checks may run from many threads at once.
class MapRoom {
 public:
  MapRoom() = default;
  /// \brief A room from its parts: the first `surface_count` obstacles are the map's own surface (its slab and
  /// boxes); a body shape without geometry gets it built.
  /// \throws std::invalid_argument when `body_links` is not one name per body shape, or `surface_count` exceeds
  /// the obstacles
  MapRoom(Obstacles obstacles, std::size_t surface_count, std::vector<Shape> body, std::vector<std::string> body_links);
  /// \brief The room of a surface map build: the surface's slab and boxes, then `others` (null: none); the body
  /// (the placement's body links at its reference posture) only when `check_body`, as the build checks it.
  static MapRoom of_build(const Robot& robot, const ArmPlacement& place, const Surface& surface,
                          const Obstacles* others, bool check_body);
  /// \brief The room of maps combined (SurfaceMap::combine): their obstacles and the body shapes every one of
  /// them records (two arms' maps each record the other arm: their combination, neither); an empty room when
  /// one of them records none. \throws std::invalid_argument when two of them record different obstacles
  static MapRoom combined(const std::vector<const MapRoom*>& rooms);

  /// \brief The obstacles (world frame), named as in the room they came from.
  const Obstacles& obstacles() const { return obstacles_; }
  /// \brief How many of the obstacles, from the first, are the map's own surface (its slab and boxes).
  std::size_t surface_count() const { return surface_count_; }
  /// \brief The body's collision shapes in the map's reference frame.
  const std::vector<Shape>& body() const { return body_; }
  /// \brief The link of each body shape.
  const std::vector<std::string>& body_links() const { return body_links_; }
  /// \brief True when nothing was recorded (maps written before maps recorded their room).
  bool empty() const { return obstacles_.empty() && body_.empty(); }

  /// \brief Index in `obstacles` of the first obstacle the body touches with the map's reference frame at base
  /// pose (x, y, z, theta); -1 when none. \throws std::invalid_argument for a non-finite pose
  int touched(const Eigen::Vector4d& pose, const Obstacles& obstacles) const;
  /// \brief True when the body, with the map's reference frame at base pose (x, y, z, theta), touches one of
  /// `obstacles` (AABBs and oriented boxes first, then FCL). \throws std::invalid_argument for a non-finite pose
  bool body_collides(const Eigen::Vector4d& pose, const Obstacles& obstacles) const;
  /// \brief body_collides against the recorded obstacles.
  bool body_collides(const Eigen::Vector4d& pose) const { return body_collides(pose, obstacles_); }

  /// \brief How `other` differs from the recorded obstacles: one line per obstacle found in only one of
  /// them, "<kind> '<name>' at (x, y, z) <where>"; empty when both hold the same shapes (kind, sizes, pose
  /// within `tolerance` metres; order and names do not matter).
  std::vector<std::string> differences(const Obstacles& other, double tolerance = 1e-4) const;

 private:
  Obstacles obstacles_;
  std::size_t surface_count_ = 0;
  std::vector<Shape> body_;
  std::vector<std::string> body_links_;
};

/// \brief True when two shapes describe the same solid (kind, sizes, mesh vertex count and bounds, OctoMap
/// cells and resolution) at the same pose, within `tolerance` metres (and radians, about).
bool same_shape(const Shape& a, const Shape& b, double tolerance = 1e-4);

}  // namespace octoreach
