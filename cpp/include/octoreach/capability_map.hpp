#pragma once
/// \file capability_map.hpp
/// \brief Capability map of an arm: which end-effector orientations are reachable in each voxel.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "octoreach/arm.hpp"
#include "octoreach/map_provenance.hpp"
#include "octoreach/orientation_set.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/types.hpp"
#include "octoreach/voxel_octree.hpp"

namespace octoreach {

/// \brief Build parameters of a capability map.
struct CapabilityMapOptions {
  double resolution = 0.05;                                  ///< voxel edge (m)
  int directions = 200;                                      ///< approach directions on the sphere
  int rolls = 1;                                             ///< rolls per direction (1: any roll)
  int symmetry = 4;                                          ///< z symmetry of the direction set
  Eigen::Vector3d approach_axis = Eigen::Vector3d::UnitZ();  ///< tool axis that approaches the object
  bool self_collision = true;                                ///< solutions must be free of self-collision
  Eigen::VectorXd reference;  ///< robot configuration off the chain (empty: default_reference(robot, chain))
  std::uint64_t seed = 0;
  std::size_t fk_samples = 0;         ///< forward-kinematics samples (0: 40 per voxel of the bounding box)
  bool exhaustive = false;            ///< also run random-restart IK on every cell the sampling did not reach
  int exhaustive_attempts = 10;       ///< random restarts per cell in exhaustive mode
  double position_tolerance = 1e-3;   ///< IK tolerance at the voxel centre (m)
  double orientation_tolerance = 1e-2;  ///< IK tolerance (rad)
  bool keep_solutions = true;         ///< keep one joint solution per reachable cell
  /// Block build (capability_blocks.hpp): 0 floods the whole workspace box at once; n > 0 cuts it into
  /// cubes of n voxels, each flooded on its own from the one FK sampling, so blocks can be built on
  /// different machines and merged into the same bytes. Part of the map's definition (recorded in files).
  int block_size = 0;
  int threads = 0;                    ///< 0: every core
};

/// \brief How reachable() answers a pose from the map's cells.
///
/// nearest_cell: the cell of the voxel holding the position (and the orientation nearest the pose's).
/// vote: the 8 voxel centres around the position, each asked with the pose's (nearest) orientation,
/// weighted trilinearly; reachable when the reachable ones weigh at least one half. This is the
/// one-half level set of the trilinear interpolation of the cells' 0/1 field: at a voxel centre it is
/// that cell's answer, and between centres the boundary follows the cells' boundary instead of the
/// voxel faces' staircase (on the PR2 arm at 0.05 m it agrees with IK at the exact pose more often
/// than even IK at the nearest cell, the ceiling of any nearest-cell rule: benchmarks/capability_map.py).
enum class CapabilityLookup { nearest_cell, vote };

/// The lookup of CapabilityMap::reachable() when none is given (defined here only).
inline constexpr CapabilityLookup kDefaultCapabilityLookup = CapabilityLookup::vote;

/// \brief Figures of a build.
struct BuildStats {
  double seconds = 0;
  std::size_t fk_samples = 0;
  std::size_t ik_calls = 0;
  std::size_t cells = 0;            ///< voxels x orientations in the bounding box
  std::size_t reachable_cells = 0;
  std::size_t voxels = 0;           ///< voxels with at least one reachable orientation
};

/// \brief Capability map (Zacharias et al.): for each voxel around the arm's base link, the set of
/// reachable orientations and the reachability index D = reachable / total.
///
/// A cell (voxel, orientation) is reachable when IK finds a solution inside the joint limits (and
/// free of self-collision) for the voxel centre and that orientation. Positions are in the chain's
/// base link frame. Immutable after build or load; queries are thread-safe.
class CapabilityBlocks;

class CapabilityMap {
 public:
  /// \brief The kind tag of its files (map_files.hpp) and their usual extension.
  static constexpr char kKind[] = "capability";
  static constexpr char kExtension[] = ".orcm";
  /// \brief The map file format version its files are written in.
  static constexpr std::uint32_t kFormatVersion = 1;

  /// \brief Builds the map: forward-kinematics sampling finds candidate cells and IK seeds, IK at
  /// the voxel centres settles them, and a flood fill over neighbouring cells finds the rest.
  static CapabilityMap build(const Chain& chain, const CapabilityMapOptions& options = {},
                             const ProgressCallback& progress = nullptr);
  /// \brief Builds the map of a robot's arm: the chain between the arm's links, with the arm's
  /// approach axis in place of options.approach_axis.
  static CapabilityMap build(const Robot& robot, const Arm& arm, const CapabilityMapOptions& options = {},
                             const ProgressCallback& progress = nullptr);
  /// \brief Reads a map saved by save(); throws FileError on a damaged, truncated or foreign file.
  static CapabilityMap load(const std::string& path);
  /// \brief Writes the map atomically (temporary file, then rename).
  void save(const std::string& path, bool with_solutions = false) const;
  /// \brief Writes a colour octree (.ot) that octovis opens, coloured red (low D) to blue (high D).
  void export_octovis(const std::string& path) const;

  /// \brief Reachability index D of the voxel holding p (0 outside the map).
  double reachability(const Eigen::Vector3d& p) const;
  /// \brief reachability() of n points (3 n doubles) into `out` (n doubles); large batches run on every core.
  /// Throws std::invalid_argument naming the first point with a NaN or an infinity.
  void reachability(const double* points, std::size_t n, double* out) const;
  /// \brief reachable() of n tool poses, each a row-major 4x4 matrix (16 n doubles), into `out`;
  /// throws std::invalid_argument naming the first pose with a NaN or an infinity.
  void reachable(const double* poses, std::size_t n, bool* out,
                 CapabilityLookup lookup = kDefaultCapabilityLookup) const;
  /// \brief True when the tool pose T (base link frame) is reachable by the map: orientation nearest
  /// T's, position looked up by `lookup` (CapabilityLookup).
  bool reachable(const Pose& T, CapabilityLookup lookup = kDefaultCapabilityLookup) const;
  /// \brief The stored cell: true when orientation o is reachable in the voxel holding p (the
  /// nearest_cell rule; the cell-level consumers, e.g. the point map, read cells).
  bool reachable(const Eigen::Vector3d& p, int orientation) const {
    return reachable(p, orientation, CapabilityLookup::nearest_cell);
  }
  /// \brief True when orientation o is reachable at p by `lookup`.
  bool reachable(const Eigen::Vector3d& p, int orientation, CapabilityLookup lookup) const;
  /// \brief The stored joint solution of cell (p, orientation), if the map kept solutions.
  std::optional<Eigen::VectorXd> solution(const Eigen::Vector3d& p, int orientation) const;
  bool has_solutions() const { return !solutions_.empty(); }

  /// \brief Record (voxel) index of the voxel holding p, or -1; its centre goes to `centre`.
  std::int64_t record_at(const Eigen::Vector3d& p, Eigen::Vector3d* centre = nullptr) const;
  /// \brief True when orientation o is reachable in voxel record `rec`.
  bool record_has(std::uint32_t rec, int o) const { return bit(rec, o); }
  /// \brief The stored solution (dof floats) of (record, orientation), or nullptr.
  const float* record_solution(std::uint32_t rec, int o) const;

  /// \brief Centres (base link frame) and D of every voxel with D > 0.
  void voxels(std::vector<Eigen::Vector3d>& centres, std::vector<double>& values) const;
  /// \brief Axis-aligned bounds of the voxels with D > 0: (min, max) corners.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> bounds() const;

  double resolution() const { return resolution_; }
  const OrientationSet& orientations() const { return orientations_; }
  const Eigen::Vector3d& approach_axis() const { return approach_axis_; }
  /// \brief The robot built for.
  const MapProvenance& provenance() const { return provenance_; }
  const std::string& robot_name() const { return provenance_.robot_name; }
  std::uint64_t urdf_hash() const { return provenance_.urdf_hash; }
  /// \brief Robot::model_hash() of the robot built for (URDF and allowed-collision matrix); 0 when
  /// unknown (a file written before maps recorded it).
  std::uint64_t model_hash() const { return provenance_.model_hash; }
  const std::string& base_link() const { return base_link_; }
  const std::string& tip_link() const { return tip_link_; }
  int dof() const { return dof_; }
  const BuildStats& stats() const { return stats_; }
  const VoxelOcTree& tree() const { return *tree_; }
  std::size_t voxel_count() const { return sol_offset_.size(); }
  /// \brief The build parameters as recorded in files (key -> text).
  std::vector<std::pair<std::string, std::string>> parameters() const;

 private:
  friend class CapabilityBlocks;  // assembles a map from blocks with the steps below
  CapabilityMap() = default;
  /// The empty map of a build of `chain` (parameters, orientations, robot, tree) after checking the options
  /// and that the reference posture (returned in `reference`) is free of self-collision.
  static CapabilityMap shell_(const Chain& chain, const CapabilityMapOptions& o, Eigen::VectorXd& reference);
  /// Appends the voxel at `key`: its orientation bits (words_ words, not all zero) and, when solutions are
  /// kept, one row of dof_ floats per set bit, in bit order.
  void add_voxel_(const octomap::OcTreeKey& key, const std::uint64_t* bits, const float* solutions);
  /// Completes a build: inner node values, query tables and the figures.
  void finish_build_(std::size_t samples, std::size_t ik_calls, std::size_t cells, double seconds);
  /// Record of the voxel holding p, or DenseIndex::kNone.
  std::uint32_t record(const Eigen::Vector3d& p) const {
    if (index_.active()) return index_.find(*tree_, p.x(), p.y(), p.z());
    const VoxelNode* n = tree_->find(p.x(), p.y(), p.z());
    return n ? n->payload : DenseIndex::kNone;
  }
  /// CapabilityLookup::vote of orientation o at p (o in range).
  bool vote_(const Eigen::Vector3d& p, int o) const;
  void finish_();  // builds the query tables once the tree and records are complete
  bool bit(std::uint32_t record, int o) const {
    return (bits_[static_cast<std::size_t>(record) * words_ + (o >> 6)] >> (o & 63)) & 1ULL;
  }
  void set_parameters_(const CapabilityMapOptions& o);

  std::shared_ptr<VoxelOcTree> tree_;
  double resolution_ = 0;  // set by build() or load()
  OrientationSet orientations_ = OrientationSet::sphere(200);
  Eigen::Vector3d approach_axis_ = Eigen::Vector3d::UnitZ();
  int words_ = 4;                        // uint64 words per voxel record
  std::vector<std::uint64_t> bits_;      // records x words_
  std::vector<std::uint64_t> sol_offset_;  // per record: first solution row
  std::vector<float> solutions_;         // rows of dof_ floats, in record/bit order
  std::vector<float> d_;                 // per record: reachability index D
  DenseIndex index_;
  MapProvenance provenance_;
  std::string base_link_, tip_link_;
  int dof_ = 0;
  bool self_collision_ = true;
  std::uint64_t seed_ = 0;
  std::size_t fk_samples_ = 0;
  bool exhaustive_ = false;
  int block_size_ = 0;
  double position_tolerance_ = 1e-3, orientation_tolerance_ = 1e-2;
  BuildStats stats_;
};

}  // namespace octoreach
