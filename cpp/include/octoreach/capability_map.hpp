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

namespace detail {
class ByteReader;
struct VoxelCellData;
}

/// \brief Build parameters of a capability map.
struct CapabilityMapOptions {
  double resolution = 0.05;                                  ///< voxel edge (m)
  int directions = 200;                                      ///< approach directions (nearest multiple of `symmetry`)
  int rolls = 1;                                             ///< rolls per direction (1: any roll)
  int symmetry = 4;                                          ///< z symmetry of the direction set
  /// Also the directions straight up and down (+z, -z of the base link): for a tool held vertical (a SCARA's,
  /// a palletiser's), which no direction of the spiral points along exactly. Recorded in files.
  bool poles = false;
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
/// any: reachable when any of those 8 cells is. The map's "maybe": it says no only where every cell
/// around the pose does, so a pruning step ahead of an exact check (IK) keeps the poses where the cells
/// disagree, which a coarse map's vote would drop (the exploration's view search prunes with it).
enum class CapabilityLookup { nearest_cell, vote, any };

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
  std::size_t mixed_cells = 0;      ///< cells marked mixed (CapabilityMap::record_mixed)
};

/// \brief Quality of a reachable cell's stored joint solution (manipulability.hpp).
struct CellQuality {
  float manipulability = 0;  ///< Yoshikawa's sqrt(det(J J^T)) (product of the jacobian_rank largest singular values)
  float penalty = 0;         ///< joint-limit penalty in [0, 1] (Tsai; Vahrenkamp et al.)
  /// The product: manipulability scaled down near the joint limits.
  float value() const { return manipulability * penalty; }
};

/// \brief Capability map (Zacharias et al.): for each voxel around the arm's base link, the set of
/// reachable orientations and the reachability index D = reachable / total.
///
/// A cell (voxel, orientation) is reachable when IK finds a solution inside the joint limits (and
/// free of self-collision) for the voxel centre and that orientation. A cell whose centre is not reachable
/// but that holds the tool pose of a configuration inside the limits is mixed: it holds reachable and
/// unreachable poses (a five-joint arm reaches a thin set of directions that rarely passes through a
/// direction bin's centre). With solutions kept, a map stores per reachable cell one joint solution and its
/// quality (CellQuality), and per mixed cell the configuration found in it; CertifiedLookup answers from them
/// where the cells around a pose disagree. Positions are in the chain's base link frame. Immutable after
/// build or load; queries are thread-safe.
class CapabilityBlocks;

class CapabilityMap {
 public:
  /// \brief The kind tag of its files (map_files.hpp) and their usual extension.
  static constexpr char kKind[] = "capability";
  static constexpr char kExtension[] = ".orcm";
  /// \brief The newest map file format version its files are written in: 3 for a map whose direction set holds
  /// the poles (CapabilityMapOptions::poles), which an older octoreach would read without them; the others in
  /// kFormatVersionWithoutPoles. Version 1 files load without the mixed cells and the quality per cell.
  static constexpr std::uint32_t kFormatVersion = 3;
  /// \brief The version of the files of maps without the poles: 2, as the payload may hold the mixed cells and
  /// the quality per cell (header "cell_data").
  static constexpr std::uint32_t kFormatVersionWithoutPoles = 2;

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
  /// throws std::invalid_argument naming the first pose that is not a finite rigid transform (is_rigid).
  void reachable(const double* poses, std::size_t n, bool* out,
                 CapabilityLookup lookup = kDefaultCapabilityLookup) const;
  /// \brief True when the tool pose T (base link frame) is reachable by the map: orientation nearest
  /// T's, position looked up by `lookup` (CapabilityLookup). \throws std::invalid_argument unless T is a finite
  /// rigid transform (check_rigid).
  bool reachable(const Pose& T, CapabilityLookup lookup = kDefaultCapabilityLookup) const;
  /// \brief The stored cell: true when orientation o is reachable in the voxel holding p (the
  /// nearest_cell rule; the cell-level consumers, e.g. the point map, read cells).
  bool reachable(const Eigen::Vector3d& p, int orientation) const {
    return reachable(p, orientation, CapabilityLookup::nearest_cell);
  }
  /// \brief True when orientation o is reachable at p by `lookup`.
  bool reachable(const Eigen::Vector3d& p, int orientation, CapabilityLookup lookup) const;
  /// \brief The stored joint solution of cell (p, orientation), none when the cell is not reachable; throws
  /// std::invalid_argument on a map without solutions (has_solutions() false).
  std::optional<Eigen::VectorXd> solution(const Eigen::Vector3d& p, int orientation) const;
  /// \brief True when the map keeps the joint solutions of its cells (built with keep_solutions, saved with them),
  /// also where no cell is reachable (its mixed cells' configurations are then all it holds).
  bool has_solutions() const { return keeps_solutions_; }
  /// \brief True when the map marks its mixed cells (maps of files older than format 2 do not).
  bool has_cell_data() const { return cell_data_; }
  /// \brief True when the map keeps a CellQuality per reachable cell (built with solutions, format 2).
  bool has_quality() const { return !quality_.empty() || (cell_data_ && has_solutions()); }
  /// \brief Quality of the reachable cell (p, orientation); nothing when the cell is not reachable.
  /// \throws std::invalid_argument when the map holds no quality (see has_quality(); the message says how to rebuild).
  std::optional<CellQuality> quality(const Eigen::Vector3d& p, int orientation) const;
  /// \brief Throws std::invalid_argument saying how to rebuild unless has_quality(); `what` names the feature asked for.
  void require_quality(const std::string& what) const;
  /// \brief Largest CellQuality::value() of the map's cells (0 without cell data): the scale of quality weights.
  double max_quality() const { return max_quality_; }
  /// \brief Per voxel with D > 0 (in voxels() order): the mean (`max` false) or the largest CellQuality::value()
  /// of its reachable cells. \throws std::invalid_argument without quality (see quality()).
  std::vector<double> voxel_quality(bool max = false) const;
  /// \brief Generic rank of the chain's Jacobian the manipulability was computed with (0: unknown).
  int jacobian_rank() const { return jacobian_rank_; }
  /// \brief The robot configuration the map was built at (the joints off the chain); empty for older files.
  const Eigen::VectorXd& reference() const { return reference_; }

  /// \brief Record (voxel) index of the voxel holding p, or -1; its centre goes to `centre`.
  std::int64_t record_at(const Eigen::Vector3d& p, Eigen::Vector3d* centre = nullptr) const;
  /// \brief True when orientation o is reachable in voxel record `rec`.
  bool record_has(std::uint32_t rec, int o) const { return bit(rec, o); }
  /// \brief Reachability index D of voxel record `rec` (0 for DenseIndex::kNone).
  double record_reachability(std::uint32_t rec) const { return rec == DenseIndex::kNone ? 0.0 : d_[rec]; }
  /// \brief The stored solution (dof floats) of (record, orientation), or nullptr.
  const float* record_solution(std::uint32_t rec, int o) const;
  /// \brief True when cell (record, orientation) is mixed (its centre is not reachable, a pose in it is).
  bool record_mixed(std::uint32_t rec, int o) const { return cell_data_ && mixed_bit(rec, o); }
  /// \brief The configuration (dof floats) stored for a mixed cell, or nullptr.
  const float* record_mixed_solution(std::uint32_t rec, int o) const;
  /// \brief The quality of reachable cell (record, orientation), or nullptr.
  const CellQuality* record_quality(std::uint32_t rec, int o) const;
  /// \brief CellQuality::value() of reachable cell (record, orientation) over max_quality(), in [0, 1]; 0 for a cell
  /// that is not reachable or a map without quality (or whose best cell scores 0).
  double relative_quality(std::uint32_t rec, int o) const {
    const CellQuality* q = record_quality(rec, o);
    return q && max_quality_ > 0 ? q->value() / max_quality_ : 0.0;
  }
  /// \brief Record of the voxel with octree key `key`, or DenseIndex::kNone.
  std::uint32_t record_of_key(const octomap::OcTreeKey& key) const {
    if (index_.active()) return index_.find(key);
    const VoxelNode* n = tree_->search(key);
    return n && !tree_->nodeHasChildren(n) ? n->payload : DenseIndex::kNone;
  }
  /// \brief The 8 voxels whose centres surround p: their records (DenseIndex::kNone where there is none) and
  /// trilinear weights (summing to 1), corner k at +1 voxel along axis a where bit a of k is set.
  void corners(const Eigen::Vector3d& p, std::uint32_t records[8], double weights[8]) const;

  /// \brief Centres (base link frame) and D of every voxel with D > 0 (voxels holding only mixed cells left out).
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
  /// \brief The IK tolerances the cells were settled with (m, rad) and whether solutions avoid self-collision.
  double position_tolerance() const { return position_tolerance_; }
  double orientation_tolerance() const { return orientation_tolerance_; }
  bool self_collision() const { return self_collision_; }
  /// \brief The seed of its forward-kinematics samples and IK restarts (CapabilityMapOptions::seed).
  std::uint64_t seed() const { return seed_; }
  const std::string& base_link() const { return base_link_; }
  const std::string& tip_link() const { return tip_link_; }
  int dof() const { return dof_; }
  const BuildStats& stats() const { return stats_; }
  const VoxelOcTree& tree() const { return *tree_; }
  /// \brief Number of voxel records: voxels with a reachable or a mixed cell.
  std::size_t voxel_count() const { return sol_offset_.size(); }
  /// \brief The build parameters as recorded in files (key -> text).
  std::vector<std::pair<std::string, std::string>> parameters() const;

 private:
  friend class CapabilityBlocks;  // assembles a map from blocks with the steps below
  friend struct CapabilityMapTestAccess;  // the C++ tests: the plain lookups without their grid (maps above its limit)
  CapabilityMap() = default;
  /// The empty map of a build of `chain` (parameters, orientations, robot, tree) after checking the options
  /// and that the reference posture (returned in `reference`) is free of self-collision.
  static CapabilityMap shell_(const Chain& chain, const CapabilityMapOptions& o, Eigen::VectorXd& reference);
  /// Appends the voxel at `key` with its cells (reachable and mixed bits not all zero; solutions, quality and
  /// mixed-cell configurations when the map keeps solutions).
  void add_voxel_(const octomap::OcTreeKey& key, const detail::VoxelCellData& cells);
  /// The record of `leaf` (a leaf of tree_, the next record) from `cells`.
  void append_record_(VoxelNode& leaf, const detail::VoxelCellData& cells);
  /// The cells of record `rec` as add_voxel_ takes them (what files hold).
  void cells_of_(std::uint32_t rec, detail::VoxelCellData& cells) const;
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
  /// The vote from the lower corner's key and the fractions towards the upper corners (corner_grid's answer).
  bool vote_corners_(const octomap::OcTreeKey& low, const double frac[3], int o) const;
  /// CapabilityLookup::nearest_cell of orientation o at p (o in range).
  bool nearest_cell_(const Eigen::Vector3d& p, int o) const;
  /// CapabilityLookup::any from the lower corner's key and the fractions (corner_grid's answer).
  bool any_corner_(const octomap::OcTreeKey& low, const double frac[3], int o) const;
  /// The lookup of orientation o at p (o in range).
  bool lookup_(const Eigen::Vector3d& p, int o, CapabilityLookup lookup) const;
  void finish_();  // builds the query tables once the tree and records are complete
  void build_grid_();
  /// The plain lookups' grid: the bit index of orientation o at grid position (x, y, z), each inside grid_dim_.
  std::size_t grid_index_(int o, int x, int y, int z) const {
    return ((static_cast<std::size_t>(o) * grid_dim_[0] + x) * grid_dim_[1] + y) * grid_dim_[2] + z;
  }
  bool grid_bit_(int o, int x, int y, int z) const {
    const std::size_t i = grid_index_(o, x, y, z);
    return (grid_[i >> 6] >> (i & 63)) & 1ULL;
  }
  bool bit(std::uint32_t record, int o) const {
    return (bits_[static_cast<std::size_t>(record) * words_ + (o >> 6)] >> (o & 63)) & 1ULL;
  }
  bool mixed_bit(std::uint32_t record, int o) const {
    return (mixed_[static_cast<std::size_t>(record) * words_ + (o >> 6)] >> (o & 63)) & 1ULL;
  }
  /// Rank of bit o among the set bits of `words` (words_ words).
  std::size_t rank_(const std::uint64_t* words, int o) const;
  void read_payload_(detail::ByteReader& r, std::uint64_t count, bool sols);
  void set_parameters_(const CapabilityMapOptions& o);

  std::shared_ptr<VoxelOcTree> tree_;
  double resolution_ = 0;  // set by build() or load()
  OrientationSet orientations_ = OrientationSet::sphere(200);
  Eigen::Vector3d approach_axis_ = Eigen::Vector3d::UnitZ();
  int words_ = 4;                        // uint64 words per voxel record
  std::vector<std::uint64_t> bits_;      // records x words_
  std::vector<std::uint64_t> sol_offset_;  // per record: first solution row
  bool keeps_solutions_ = false;         // built with keep_solutions / loaded from a file with solutions
  std::vector<float> solutions_;         // rows of dof_ floats, in record/bit order
  std::vector<float> d_;                 // per record: reachability index D
  bool cell_data_ = false;               // mixed cells marked, their configurations and the quality kept
  std::vector<std::uint64_t> mixed_;     // records x words_ (cell_data_)
  std::vector<std::uint64_t> mixed_offset_;  // per record: first mixed-cell row (cell_data_ with solutions)
  std::vector<float> mixed_solutions_;   // rows of dof_ floats, in record/bit order
  std::vector<CellQuality> quality_;     // per reachable cell, in solution order
  double max_quality_ = 0;
  int jacobian_rank_ = 0;
  Eigen::VectorXd reference_;
  DenseIndex index_;
  // The reachable bits again, orientation-major over the voxels' key box with one empty voxel around it, for the
  // plain lookups: a vote's 8 corners share one or two cache lines and no record index is read. Empty (the
  // records answer) when it would take more than kGridBytes.
  std::vector<std::uint64_t> grid_;
  int grid_lo_[3] = {0, 0, 0}, grid_dim_[3] = {0, 0, 0};
  // One bit per voxel of grid_'s box (grid_index_ of orientation 0): the voxel holds a reachable orientation. A
  // batch skips the orientation of a pose whose voxels (its own, or the 8 around it) hold none.
  std::vector<std::uint64_t> grid_any_;
  bool grid_any_bit_(int x, int y, int z) const {
    const std::size_t i = grid_index_(0, x, y, z);
    return (grid_any_[i >> 6] >> (i & 63)) & 1ULL;
  }
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
