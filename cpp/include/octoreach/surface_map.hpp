#pragma once
/// \file surface_map.hpp
/// \brief Surface inverse reachability maps (Hertle & Nebel): base poses from which a robot's arm
/// reaches a large share of a working surface.

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "octoreach/arm.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/map_provenance.hpp"
#include "octoreach/map_room.hpp"
#include "octoreach/pose_map.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/surface.hpp"

namespace octoreach {

/// \brief Build parameters of a surface map.
struct SurfaceMapOptions {
  std::string reference_frame;      ///< link whose pose (x, y, z, theta) is mapped (empty: root link)
  std::vector<int> grasps;          ///< grasp direction indices (empty: `grasp_subset`)
  std::string grasp_subset = "upper_hemisphere";
  int theta_bins = 16;
  double resolution = 0;            ///< 0: the capability map's resolution
  /// Base z range (world frame). The default (0, 0): the robot stands on the floor; a floating base
  /// (a humanoid's pelvis, a lift) only when asked, e.g. (-1e9, 1e9).
  double z_min = 0, z_max = 0;
  Eigen::VectorXd reference;        ///< robot configuration off the arm (torso, other arm); empty: default_reference
  /// The rest of the room (other surfaces, walls, meshes, OctoMaps), world frame: checked against the
  /// body and, with check_arm, against the arm at its stored solutions, like the surface's own boxes.
  std::shared_ptr<const Obstacles> obstacles;
  bool check_body = true;           ///< reject base poses where the robot body touches the surface, boxes or obstacles
  /// Reject grasps whose arm passes below the surface inside its outline or whose arm (gripper
  /// included) touches a box of the surface or an obstacle.
  bool check_arm = true;
  /// Grasp points lie this far above the surface along its normal (the tool frame holds an object,
  /// it does not touch the board): 0.05 m suits cans and cups.
  double grasp_height = 0.05;
  /// R_P counts each valid grasp with its cell's quality relative to the capability map's best cell
  /// (CellQuality::value() / CapabilityMap::max_quality()), so R_S and the sampler prefer base poses the arm reaches
  /// away from its joint limits and singularities; false, the paper's R_S: each counts 1. Needs a capability
  /// map with quality (CapabilityMap::has_quality()).
  bool quality_weight = false;
  int threads = 0;
};

/// \brief Figures of a surface map build.
struct SurfaceMapStats {
  double seconds = 0;
  std::size_t surface_points = 0;
  std::size_t base_poses = 0;          ///< (x, y, z, theta) cells examined
  std::size_t candidate_poses = 0;     ///< (base pose, surface point) pairs with a capability voxel
  std::size_t valid_poses = 0;         ///< of those, pairs with at least one valid grasp
  std::size_t body_collisions = 0;     ///< base poses rejected because the body touches the surface
  std::size_t arm_rejections = 0;      ///< grasps rejected because the arm passes under the surface
};

/// \brief Surface map: R_S(x, y, z, theta) = (1/n) sum over the n surface points of the validated R_P.
class SurfaceMap {
 public:
  /// \brief The kind tag of its files (map_files.hpp) and their usual extension.
  static constexpr char kKind[] = "surface";
  static constexpr char kExtension[] = ".orsm";
  /// \brief The map file format version its files are written in (2: the room it was built with).
  static constexpr std::uint32_t kFormatVersion = 2;

  static SurfaceMap build(const Robot& robot, const CapabilityMap& capability, const Surface& surface,
                          const SurfaceMapOptions& options = {}, const ProgressCallback& progress = nullptr);
  /// \brief Per-pose maximum ("any arm") or minimum ("both arms") of maps of the same robot, frame,
  /// resolution and theta bins; throws std::invalid_argument otherwise.
  static SurfaceMap combine(const std::vector<const SurfaceMap*>& maps, const std::string& mode);
  static SurfaceMap load(const std::string& path);
  void save(const std::string& path) const;

  /// \brief R_S of base pose (x, y, z, theta) of the reference frame (world frame); 0 outside. Heights
  /// are clipped into z_range() first, as in the build (a floor robot's z of -1e-12 is z = 0).
  double reachability(double x, double y, double z, double theta) const {
    return map_.value(x, y, std::min(std::max(z, z_min_), z_max_), theta);
  }
  /// \brief reachability() of n base poses given as rows x, y, z, theta (4 n doubles) into `out`
  /// (n doubles); large batches run on every core. Throws std::invalid_argument for a NaN or infinite value.
  void reachability(const double* rows, std::size_t n, double* out) const;
  const PoseMap& map() const { return map_; }
  const SurfaceMapStats& stats() const { return stats_; }
  /// \brief The robot built for.
  const MapProvenance& provenance() const { return provenance_; }
  const std::string& robot_name() const { return provenance_.robot_name; }
  std::uint64_t urdf_hash() const { return provenance_.urdf_hash; }
  /// \brief Robot::model_hash() of the robot built for; 0 when unknown (older files).
  std::uint64_t model_hash() const { return provenance_.model_hash; }
  const std::string& reference_frame() const { return reference_frame_; }
  const std::string& arms() const { return arms_; }
  /// \brief The approach axis (tip frame) of each arm's capability map, in the order of arms(), e.g.
  /// "1 0 0" or "1 0 0 max 1 0 0"; empty for files written before it was recorded.
  const std::string& approach_axes() const { return approach_axes_; }
  /// \brief Surface outline (world frame) the map was built for.
  const std::vector<Eigen::Vector3d>& polygon() const { return polygon_; }
  /// \brief The base z range the map was built for (world frame): poses are evaluated at heights
  /// clipped into it, so a single height (a robot on the floor) is exact.
  std::pair<double, double> z_range() const { return {z_min_, z_max_}; }
  /// \brief The room the map was built with: its obstacles and the body checked against them (map_room.hpp);
  /// empty for files written before maps recorded it.
  const MapRoom& room() const { return *room_; }
  /// \brief The room, shared (a sampler keeps it as long as it needs it).
  std::shared_ptr<const MapRoom> shared_room() const { return room_; }
  /// \brief "quality" when R_P weights grasps by their cells' quality (SurfaceMapOptions::quality_weight), else "".
  const std::string& weight() const { return weight_; }
  /// \brief Why the map is empty ("" when it is not).
  const std::string& empty_reason() const { return empty_reason_; }
  /// \brief One line when the build looks suspicious (the surface at the edge of the arm's reach,
  /// map_warnings.hpp), with what to try; "" otherwise and for a loaded map.
  const std::string& warning() const { return warning_; }
  std::map<std::string, std::string> parameters() const;

 private:
  PoseMap map_;
  SurfaceMapStats stats_;
  MapProvenance provenance_;
  std::string reference_frame_, arms_, approach_axes_, empty_reason_, grasp_name_, warning_;
  std::vector<Eigen::Vector3d> polygon_;
  double z_min_ = -1e9, z_max_ = 1e9;
  double grasp_height_ = 0.05;
  std::string checks_ = "body+arm";
  std::shared_ptr<const MapRoom> room_ = std::make_shared<const MapRoom>();
  std::string weight_;
};

}  // namespace octoreach
