#pragma once
/// \file simulation.hpp
/// \brief Simulated scenes (shapes of shape.hpp: boxes with a pose, cylinders, spheres, triangle meshes and
/// OctoMaps; crates, closed boxes with openings and boards made of boxes) and a simulated depth camera that
/// ray-casts them into point clouds. What a scene holds is also its collision obstacles (Scene::obstacles).
///
/// Camera frame convention (as ROS optical frames): the camera looks along its +z axis,
/// +x points right in the image and +y down. Poses are camera -> world transforms.

#include <cstdint>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/collision.hpp"
#include "octoreach/shape.hpp"
#include "octoreach/types.hpp"

namespace octomap {
class OcTree;
}

namespace octoreach {

/// \brief A static world the depth camera can see: shapes in the world frame, each both seen by ray casting
/// and an obstacle (obstacles()).
///
/// Threads: const methods may run from many threads at once. The add_* and load_octomap methods take the
/// scene's lock exclusively and DepthCamera::capture takes it shared for a whole capture, so adding while
/// another thread captures is safe (the capture sees the scene before or after). A direct raycast() or
/// solid() call concurrent with an add_* call is not (Python serialises those through the GIL).
class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&);
  Scene& operator=(const Scene&);

  /// \brief Adds a shape (world frame): a box with any pose, a cylinder, a sphere, a mesh or an OctoMap.
  /// \throws std::invalid_argument for a shape without its geometry or map (see Shape::with_geometry)
  void add(const Shape& shape);
  /// \brief Adds every shape of `obstacles`.
  void add(const Obstacles& obstacles);
  /// \brief A solid axis-aligned box (also a board: a thin box); a flat one (lo = hi on an axis) is seen but,
  /// without volume, is no shape and no obstacle. \throws std::invalid_argument if lo > hi.
  void add_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  /// \brief An open-topped crate: floor and four walls of the given thickness inside [lo, hi];
  /// its inside is recorded as an interior.
  void add_crate(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double thickness);
  /// \brief A closed box with one rectangular opening of size (width, height) centred in face
  /// `face` ("+x", "-x", "+y", "-y", "+z"); its inside is recorded as an interior.
  void add_closed_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double thickness, const std::string& face,
                      double opening_width, double opening_height);
  /// \brief Triangles (vertex rows, index triples) in the world frame.
  void add_mesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles);
  /// \brief Adds the occupied cells of an OctoMap .bt file to the world.
  /// \throws FileError if the file does not exist or is not an OctoMap binary file.
  void load_octomap(const std::string& path);
  /// \brief Records a region of interest (e.g. the inside of a box) for coverage figures.
  void add_interior(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

  /// \brief Every shape of the scene (world frame), in the order added (a crate or closed box as its boxes).
  const std::vector<Shape>& shapes() const { return shapes_; }
  /// \brief The scene's shapes as collision obstacles (their FCL geometry shared).
  Obstacles obstacles() const;
  /// \brief The axis-aligned boxes, as given.
  const std::vector<Aabb>& boxes() const { return boxes_; }
  const std::vector<Aabb>& interiors() const { return interiors_; }
  /// \brief Number of triangles (of every mesh).
  std::size_t triangle_count() const { return tris_.size() / 3; }
  bool has_octomap() const;
  /// \brief Bounding box of everything in the scene.
  Aabb bounds() const;
  /// \brief True when p is inside a solid box, sphere or cylinder (meshes and octomaps are surfaces: false).
  /// Throws std::invalid_argument for a point that is not finite.
  bool solid(const Eigen::Vector3d& p) const;
  /// \brief solid() of every point (1 or 0); throws std::invalid_argument naming the first row that is not finite.
  std::vector<char> solid(const std::vector<Eigen::Vector3d>& points) const;

  /// \brief Distance along the unit direction d from o to the first surface within max_range. Throws
  /// std::invalid_argument when o, d or max_range is not finite or d is not of unit length.
  bool raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, double& t) const;
  /// \brief The same, and the unit normal of the surface at the hit facing the ray (a box's face, a sphere's
  /// or cylinder's surface, a triangle's plane, the entered face of an OctoMap cell; -d when the ray starts
  /// inside a solid).
  bool raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, double& t,
               Eigen::Vector3d* normal) const;

 private:
  friend class DepthCamera;
  struct Bvh;     // triangle_bvh.hpp
  struct Solids;  // oriented boxes, spheres, cylinders, OctoMaps (scene_solids.hpp)
  void rebuild_bvh_();
  void add_(const Shape& shape);
  void add_box_(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  void add_interior_(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  struct Lock;                  // a writer-first reader-writer mutex (scene.cpp); copies share it
  std::shared_ptr<Lock> lock_;  // add_* exclusive, DepthCamera::capture shared
  void lock_shared_() const;
  void unlock_shared_() const;
  std::vector<Aabb> boxes_, interiors_;
  std::vector<Eigen::Vector3d> tris_;  // 3 rows per triangle
  std::vector<Shape> shapes_;
  std::shared_ptr<const Bvh> bvh_;
  std::shared_ptr<const Solids> solids_;  // replaced, never changed, by an add: copies of the scene share it
};

/// \brief Pinhole intrinsics of a depth sensor: image size, horizontal field of view, range.
struct CameraIntrinsics {
  int width = 640, height = 480;
  double fov = 1.0123;    ///< horizontal field of view, radians (58 degrees, a Kinect)
  double max_range = 4.0;  ///< metres
  /// \brief Unit ray through pixel (u, v) (pixel centres at +0.5) in the camera frame (+z forward).
  Eigen::Vector3d ray(double u, double v) const;
  /// \brief Focal length in pixels.
  double focal() const;
  /// \brief Throws std::invalid_argument naming the bad value.
  void validate() const;
};

/// \brief Camera pose (camera -> world) at `position` looking along `forward` (need not be unit), rolled by
/// `roll` radians about the optical axis; at roll 0 the image +y points down (towards -z of the world,
/// or along +x of the world when looking straight up or down). \throws std::invalid_argument for a
/// zero or non-finite direction.
Pose camera_pose(const Eigen::Vector3d& position, const Eigen::Vector3d& forward, double roll = 0.0);

/// \brief Camera pose at `eye` looking at `target` (camera_pose with forward = target - eye).
Pose look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, double roll = 0.0);

/// \brief A simulated depth camera: one ray per pixel, Gaussian depth noise growing with depth^2,
/// missing returns at grazing angles and beyond the range.
///
/// Threads: capture() may run from many threads at once (each call takes the next noise stream).
class DepthCamera {
 public:
  /// \param width, height image size in pixels
  /// \param fov horizontal field of view (radians)
  /// \param max_range metres: no return from farther surfaces
  /// \param seed seed of the depth noise (each capture draws the next stream of it)
  /// \param noise standard deviation of the depth at 1 m (metres); at depth z it is noise * z^2
  /// (as for structured-light sensors). 0 for exact depths.
  /// \param max_incidence radians: a pixel whose ray meets the surface at a larger angle to its normal
  /// gives no return (structured light and time of flight lose grazing surfaces); pi/2: never.
  DepthCamera(int width, int height, double fov, double max_range, double noise = 0.0, std::uint64_t seed = 0,
              double max_incidence = kPi / 2);
  const CameraIntrinsics& intrinsics() const { return intr_; }
  double noise() const { return noise_; }
  double max_incidence() const { return max_incidence_; }
  /// \brief Points (world frame) the camera at `camera_pose` (camera -> world) sees in `scene`;
  /// pixels without a surface within max_range, with a noisy depth beyond max_range (or <= 0) or whose
  /// ray meets the surface at more than max_incidence from its normal give no point. Each call draws
  /// new noise (deterministic for the seed and the call count).
  std::vector<Eigen::Vector3d> capture(const Scene& scene, const Pose& camera_pose, int threads = 0);

 private:
  CameraIntrinsics intr_;
  double noise_;
  std::uint64_t seed_;
  double max_incidence_;
  std::atomic<std::uint64_t> calls_{0};
};

}  // namespace octoreach
