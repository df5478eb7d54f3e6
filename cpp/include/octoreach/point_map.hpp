#pragma once
/// \file point_map.hpp
/// \brief Inverse point map (Vahrenkamp; Hertle & Nebel): which base poses reach a target point.

#include <string>
#include <vector>

#include "octoreach/arm.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/map_provenance.hpp"
#include "octoreach/pose_map.hpp"
#include "octoreach/robot.hpp"

namespace octoreach {

/// \brief Build parameters of an inverse point map.
struct PointMapOptions {
  std::string reference_frame;  ///< link whose pose (x, y, z, theta) is mapped (empty: the robot's root link)
  /// Grasp set: direction indices of the capability map's orientation set (all rolls of each are used).
  /// Empty: the named subset `grasp_subset`.
  std::vector<int> grasps;
  std::string grasp_subset = "upper_hemisphere";
  int theta_bins = 16;
  double resolution = 0;       ///< voxel edge (m); 0: the capability map's resolution
  Eigen::VectorXd reference;   ///< robot configuration for the joints between reference frame and arm (empty: default_reference)
  double z_min = -1e9, z_max = 1e9;  ///< base z range relative to the target (clipped to what can reach)
  bool use_symmetry = true;    ///< derive theta bins by rotating the grid where the grasp set allows it
  /// R_P counts each reachable grasp with its cell's quality relative to the capability map's best cell
  /// (CellQuality::value() / CapabilityMap::max_quality(): a grasp whose solution sits at a joint limit counts 0);
  /// false, the paper's R_P: each counts 1. Needs a capability map with quality (CapabilityMap::has_quality()).
  bool quality_weight = false;
  int threads = 0;
};

/// \brief Inverse point map: for base poses (x, y, z, theta) of the reference frame around a target
/// point at the origin (axes parallel to the world's, z up), R_P = share of the grasp set that the
/// capability map marks reachable from that pose (with PointMapOptions::quality_weight, each grasp weighted by
/// its cell's quality). A grasp direction d means the tool approaches the target along d (world frame).
class InversePointMap {
 public:
  /// \brief The kind tag of its files (map_files.hpp) and their usual extension.
  static constexpr char kKind[] = "point";
  static constexpr char kExtension[] = ".orpm";
  /// \brief The map file format version its files are written in.
  static constexpr std::uint32_t kFormatVersion = 1;

  static InversePointMap build(const Robot& robot, const CapabilityMap& capability, const PointMapOptions& options = {},
                               const ProgressCallback& progress = nullptr);
  static InversePointMap load(const std::string& path);
  void save(const std::string& path) const;

  /// \brief R_P of base pose (x, y, z, theta) relative to the target; 0 outside the map.
  double reachability(double x, double y, double z, double theta) const { return map_.value(x, y, z, theta); }
  /// \brief reachability() of n base poses given as rows x, y, z, theta (4 n doubles) into `out`.
  void reachability(const double* rows, std::size_t n, double* out) const { map_.values(rows, n, out); }
  /// \brief R_P computed directly from the capability map (no grid), for checks.
  static double direct_reachability(const CapabilityMap& capability, const Pose& reference_to_arm,
                                    const std::vector<int>& orientations, double x, double y, double z, double theta);

  const PoseMap& map() const { return map_; }
  /// \brief The robot built for.
  const MapProvenance& provenance() const { return provenance_; }
  const std::string& robot_name() const { return provenance_.robot_name; }
  std::uint64_t urdf_hash() const { return provenance_.urdf_hash; }
  /// \brief Robot::model_hash() of the robot built for; 0 when unknown (older files).
  std::uint64_t model_hash() const { return provenance_.model_hash; }
  const std::string& reference_frame() const { return reference_frame_; }
  const std::string& arm_base_link() const { return arm_base_; }
  const std::string& arm_tip_link() const { return arm_tip_; }
  /// \brief Approach axis of the capability map's tool frame (+z in files written before maps recorded it).
  const Eigen::Vector3d& approach_axis() const { return approach_axis_; }
  /// \brief Pose of the capability map's base link in the reference frame (at the reference posture).
  const Pose& reference_to_arm() const { return reference_to_arm_; }
  /// \brief Orientation indices (of the capability map's set) in the grasp set.
  const std::vector<int>& grasp_orientations() const { return grasp_orientations_; }
  bool used_symmetry() const { return used_symmetry_; }
  /// \brief "quality" when R_P weights grasps by their cells' quality (PointMapOptions::quality_weight), else "".
  const std::string& weight() const { return weight_; }
  double build_seconds() const { return seconds_; }
  /// \brief The parameters recorded in files.
  std::map<std::string, std::string> parameters() const;

 private:
  PoseMap map_;
  MapProvenance provenance_;
  std::string reference_frame_, arm_base_, arm_tip_, grasp_name_;
  Eigen::Vector3d approach_axis_ = Eigen::Vector3d::UnitZ();
  Pose reference_to_arm_ = Pose::Identity();
  std::vector<int> grasp_orientations_;
  bool used_symmetry_ = false;
  std::string weight_;
  double seconds_ = 0;
};

}  // namespace octoreach
