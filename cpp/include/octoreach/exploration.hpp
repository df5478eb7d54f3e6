#pragma once
/// \file exploration.hpp
/// \brief Frontier-void exploration map (Dornhege & Kleiner, SSRR 2011, section IV A-B).
///
/// An OctoMap occupancy tree plus what the exploration needs on top of it:
/// the cells each insertion changed, the frontier cells and their clusters
/// (maintained incrementally), the convex hull of the accumulated point cloud
/// and the void cells inside it, and ellipsoidal void clusters.
///
/// Definitions used throughout (all at the finest resolution of the tree):
/// - a cell is *unknown* when the tree has no node covering it, else *occupied*
///   or *free* by OcTree::isNodeOccupied;
/// - a *frontier* cell is a free cell with at least one unknown cell among its
///   6 face neighbours; frontier clusters are connected components of frontier
///   cells under 26-connectivity (face, edge or corner neighbours);
/// - a *void* cell is an unknown cell whose centre lies inside (or on) the convex
///   hull of the occupied cells' centres inserted so far;
/// - a void cluster is grown from a random seed cell over 26-neighbours while the
///   fit score of eq. (2) stays at or above a threshold (see VoidCluster).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/types.hpp"

namespace octomap {
class OcTree;
}

namespace octoreach {

namespace detail {
struct ExplorationState;
struct ExplorationAccess;
}  // namespace detail

/// \brief Occupancy class of one cell.
enum class CellState : std::uint8_t { Unknown = 0, Free = 1, Occupied = 2 };

/// \brief A cell index: OctoMap's key (three 16-bit integers) packed as k0 | k1 << 16 | k2 << 32.
using CellKey = std::uint64_t;

/// \brief Packs three OctoMap key components.
inline CellKey pack_key(std::uint32_t k0, std::uint32_t k1, std::uint32_t k2) {
  return CellKey(k0) | (CellKey(k1) << 16) | (CellKey(k2) << 32);
}
/// \brief Key components of a packed key.
inline std::uint32_t key_x(CellKey k) { return std::uint32_t(k & 0xffff); }
inline std::uint32_t key_y(CellKey k) { return std::uint32_t((k >> 16) & 0xffff); }
inline std::uint32_t key_z(CellKey k) { return std::uint32_t((k >> 32) & 0xffff); }

/// \brief One cell whose class an insertion changed.
struct CellChange {
  CellKey key = 0;
  CellState before = CellState::Unknown;
  CellState after = CellState::Unknown;
};

/// \brief What one ExplorationMap::insert did and how long its parts took (seconds).
struct InsertStats {
  std::size_t points = 0;           ///< finite points used
  std::size_t dropped = 0;          ///< non-finite rows dropped
  std::size_t out_of_bounds = 0;    ///< finite points outside the map bounds (ignored, as OctoMap does)
  std::size_t free_cells = 0;       ///< distinct cells updated as free
  std::size_t occupied_cells = 0;   ///< distinct cells updated as occupied
  std::size_t changed_cells = 0;    ///< cells whose class changed
  std::size_t frontier_added = 0, frontier_removed = 0;
  std::size_t void_added = 0, void_removed = 0;
  std::size_t space_known = 0;      ///< unknown cells of the search space this insert made known (free or occupied)
  double seconds_rays = 0, seconds_tree = 0, seconds_frontiers = 0, seconds_hull = 0, seconds_voids = 0,
         seconds_total = 0;
};

/// \brief An ellipsoidal cluster of void cells.
///
/// The eigenvalues are those of the covariance (1) of the cluster's cell
/// centres, each cell counted as a solid cube (so a covariance of a flat layer is
/// not singular: R^2/12 is added on the diagonal). eq. (2) multiplies eigenvalues
/// as if they were lengths; we use the semi-axes a_j = sqrt(5 lambda_j) of the
/// solid ellipsoid with that covariance, so the score
///   S = N R^3 / (4/3 pi a_1 a_2 a_3)
/// is the share of the ellipsoid filled by the cluster (about 0.9 for convex blobs).
struct VoidCluster {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();     ///< metres, map frame
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();     ///< columns e1, e2, e3 (unit, decreasing eigenvalue)
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();  ///< lambda_1 >= lambda_2 >= lambda_3 (m^2)
  Eigen::Vector3d semi_axes = Eigen::Vector3d::Zero();    ///< sqrt(5 lambda_j), metres
  double score = 0;                                       ///< eq. (2) as above
  std::vector<CellKey> cells;                             ///< sorted
  double volume(double resolution) const { return double(cells.size()) * resolution * resolution * resolution; }
};

/// \brief A void cluster with the frontier clusters next to it (26-neighbourhood).
struct FrontierVoid {
  int void_index = -1;                  ///< index into ExplorationMap::void_clusters()
  std::vector<int> frontier_clusters;   ///< indices into ExplorationMap::frontier_clusters()
  std::vector<CellKey> frontier_cells;  ///< the frontier cells of those clusters touching the void (sorted)
  double utility = 0;                   ///< void volume, m^3
};

/// \brief What the rays of all inserts so far did to cells that were unknown: distinct cells that
/// became free (a ray passed) or occupied (a ray stopped), all unknown cells and void cells alone.
/// The next-best-view's visibility model learns from it how often an unknown cell lets a ray through.
///
/// Counted per ray, not per cell: a bundle of rays of equal solid angle crosses a cell at distance t
/// from the sensor about 1 / t^2 times, so each cell also adds 1 / max(t, 0.1 m)^2 to the weighted sums
/// (m^-2); the probabilities are taken from those (plain cell counts would under-weight the free
/// cells near the sensor that many rays cross).
struct RayStatistics {
  std::uint64_t unknown_to_free = 0, unknown_to_occupied = 0;  ///< cells
  std::uint64_t void_to_free = 0, void_to_occupied = 0;        ///< cells
  double unknown_to_free_w = 0, unknown_to_occupied_w = 0;     ///< 1/t^2-weighted sums
  double void_to_free_w = 0, void_to_occupied_w = 0;
  /// \brief P(an unknown cell a ray reaches lets it through): free / (free + occupied) of the
  /// weighted sums over all unknown cells, with a prior of 0.5 worth kPrior m^-2 (0.5 before any insert).
  double pass_probability() const {
    return (unknown_to_free_w + 0.5 * kPrior) / (unknown_to_free_w + unknown_to_occupied_w + kPrior);
  }
  /// \brief The same over void cells alone (cells inside the hull, mostly behind surfaces), with a
  /// prior of 0.5 worth kPrior: until rays have met void cells nothing is known of the voids' insides
  /// (open space's pass_probability(), learned from rays through air, made the first views over-expect).
  double void_pass_probability() const {
    return (void_to_free_w + 0.5 * kPrior) / (void_to_free_w + void_to_occupied_w + kPrior);
  }
  static constexpr double kPrior = 100.0;  ///< m^-2: about 25 cells at 0.5 m
};

/// \brief Tuning of the exploration map.
struct ExplorationOptions {
  double resolution = 0.025;        ///< cell edge, metres (the paper's 2.5 cm)
  double void_fit_threshold = 0.6;  ///< region growing accepts a cell while eq. (2) stays >= this
  std::uint64_t seed = 0;           ///< seeds the void clustering's random start cells
  int threads = 0;                  ///< 0: all cores
  bool track_voids = true;          ///< maintain the hull and void cells at every insert
  /// The search space S of the paper (its boundary is known): void cells are only looked for
  /// inside this box. Default: unbounded.
  Eigen::Vector3d search_lo = Eigen::Vector3d::Constant(-1e9), search_hi = Eigen::Vector3d::Constant(1e9);
  /// With a finite search space: once the map has an occupied cell, every unknown cell of the search space is a
  /// void cell, not only those inside the hull. The paper's S is known and is to be explored whole (section III);
  /// the hull (section IV-B) finds the voids of an unbounded space, and leaves out the unknown parts of S beyond
  /// the outermost surfaces seen (outside the first views, above low objects). false: the paper's voids.
  bool voids_fill_search_space = false;
  /// from_file rejects a .bt file whose leaves cover more finest-resolution cells than this (counted
  /// before anything is expanded: a damaged file cannot make the load run out of memory or time).
  std::uint64_t max_file_cells = std::uint64_t(1) << 24;
  /// Voids are looked for in the bounding box of the occupied cells clipped to the search space. An insert
  /// or a file that would make that box hold more cells than this is refused before anything changes (occupied
  /// cells kilometres apart would make the void upkeep run for hours and fill the memory): pass a search space
  /// around the region to explore, or track_voids = false.
  std::uint64_t max_void_box_cells = std::uint64_t(1) << 28;
};

/// \brief Order-independent digest of an occupancy tree at the finest resolution: counts of free and
/// occupied cells and a sum of mixed (key, class, log-odds) hashes. Equal digests: equal trees, leaf by leaf
/// (up to hash collisions), however they are pruned.
struct OccupancyDigest {
  std::size_t free = 0, occupied = 0;
  std::uint64_t hash = 0;
  bool operator==(const OccupancyDigest& o) const { return free == o.free && occupied == o.occupied && hash == o.hash; }
};

/// \brief The digest of any OctoMap occupancy tree (compares ExplorationMap::octree() with a stock tree).
OccupancyDigest occupancy_digest(const octomap::OcTree& tree);

/// \brief Frontier clusters and void cells computed from the occupancy alone (tests compare these).
struct ExplorationSnapshot {
  std::vector<CellKey> frontier_cells;                ///< sorted
  std::vector<std::vector<CellKey>> frontier_clusters;  ///< each sorted; sorted by first cell
  std::vector<CellKey> void_cells;                    ///< sorted
};

/// \brief OctoMap occupancy tree with incremental frontiers, voids and their clusters.
///
/// Threads: every method may be called from any number of threads at once. The map holds a
/// reader-writer lock: insert() takes it exclusively, every const method (and next_best_view,
/// accumulate_utility and view_utility for their whole run) shares it, so a query waits for a running
/// insert and sees the map before or after it, never in between. resolution(), options(), key_of()
/// and center() read only what is fixed at construction and take no lock. The one exception is
/// octree(): the reference it returns is not guarded, do not use it while another thread inserts.
class ExplorationMap {
 public:
  explicit ExplorationMap(const ExplorationOptions& options = ExplorationOptions());
  ~ExplorationMap();
  ExplorationMap(const ExplorationMap&) = delete;
  ExplorationMap& operator=(const ExplorationMap&) = delete;

  /// \brief Map whose occupancy comes from an OctoMap .bt file (frontiers and voids rebuilt;
  /// the hull from the occupied cells). \throws FileNotFound if it does not exist, FileError if it cannot be
  /// read, states a resolution outside [1e-4, 1e4] m or covers more than options.max_file_cells cells.
  static std::unique_ptr<ExplorationMap> from_file(const std::string& path,
                                                   const ExplorationOptions& options = ExplorationOptions());

  /// \brief Integrates a point cloud (map frame) seen from `sensor_origin`.
  ///
  /// Same occupancy result as octomap::OcTree::insertPointCloud(cloud, origin, max_range)
  /// (rays to points beyond max_range clear free space up to max_range). Non-finite
  /// rows are dropped; an empty cloud changes nothing. max_range <= 0 means unlimited.
  /// \throws std::invalid_argument for a non-finite origin or max_range, or an origin
  /// outside the map bounds.
  InsertStats insert(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& sensor_origin,
                     double max_range);

  /// \brief Cell edge, metres.
  double resolution() const { return resolution_; }
  /// \brief The options the map was made with (resolution: that of the tree).
  const ExplorationOptions& options() const { return options_; }
  /// \brief The occupancy tree (not guarded by the map's lock: see the class comment).
  const octomap::OcTree& octree() const;

  /// \brief Class of the cell holding point p (map frame); Unknown outside the map bounds.
  CellState state(const Eigen::Vector3d& p) const;
  CellState state(CellKey key) const;
  /// \brief Batched state(p): rows (n, 3), out[i] = CellState as a byte; one lock for the batch.
  /// \throws std::invalid_argument naming the first row holding NaN or inf.
  void state(const double* rows, std::size_t n, std::uint8_t* out) const;
  /// \brief Key of the cell holding p; throws std::invalid_argument outside the map bounds.
  CellKey key_of(const Eigen::Vector3d& p) const;
  /// \brief Centre of a cell, metres.
  Eigen::Vector3d center(CellKey key) const;
  /// \brief Is the cell a frontier / void cell (as maintained incrementally)?
  bool is_frontier(CellKey key) const;
  bool is_void(CellKey key) const;

  /// \brief Cells whose class the last insert changed (in Morton order).
  std::vector<CellChange> changed_cells() const;

  /// \brief Frontier cells, sorted.
  std::vector<CellKey> frontier_cells() const;
  /// \brief Frontier clusters (each sorted, ordered by their first cell).
  std::vector<std::vector<CellKey>> frontier_clusters() const;
  /// \brief Void cells, sorted.
  std::vector<CellKey> void_cells() const;
  std::size_t void_cell_count() const;
  /// \brief Void cells no view can reveal: their void component (6-connected) touches only occupied cells
  /// (and the ground under the search space), so every ray into it meets a surface first (the inside of a
  /// solid whose faces have been seen). They count with seeability 0 in every view score and utility.
  std::size_t sealed_void_cell_count() const;
  /// \brief Void clusters (ellipsoidal region growing, deterministic for options().seed).
  std::vector<VoidCluster> void_clusters() const;
  /// \brief Frontier-voids: each void cluster with the frontier clusters touching it.
  std::vector<FrontierVoid> frontier_voids() const;
  /// \brief Vertices of the current convex hull of the occupied cells (metres).
  std::vector<Eigen::Vector3d> hull_vertices() const;
  /// \brief Facet planes (n, d) with n.x + d <= 0 inside, unit n.
  std::vector<Eigen::Vector4d> hull_planes() const;
  /// \brief True when p lies inside (or on) the current hull. \throws std::invalid_argument for a non-finite p.
  bool inside_hull(const Eigen::Vector3d& p) const;

  /// \brief Frontiers, their clusters and voids recomputed from the occupancy and hull alone.
  ExplorationSnapshot recompute_from_scratch() const;
  /// \brief The same three things as maintained incrementally.
  ExplorationSnapshot snapshot() const;

  /// \brief Keys of the free or occupied cells (finest resolution, sorted); `which` must not be Unknown.
  std::vector<CellKey> known_cells(CellState which) const;
  /// \brief occupancy_digest(octree()).
  OccupancyDigest occupancy_digest() const;

  /// \brief Most cells count_known visits.
  static constexpr std::uint64_t kMaxCountCells = limits::kCountKnownCells;
  /// \brief Counts of known / unknown cells (at the finest resolution) in an axis-aligned box.
  /// \throws std::invalid_argument for a corner outside the map bounds or a box of more than kMaxCountCells cells.
  std::pair<std::size_t, std::size_t> count_known(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;

  /// \brief What rays did to unknown cells over all inserts (see RayStatistics).
  RayStatistics ray_statistics() const;
  /// \brief The pass probabilities the next-best-view search learns from the map (the visibility
  /// model's p): ray_statistics().pass_probability() for unknown cells outside the voids and
  /// ray_statistics().void_pass_probability() for void cells.
  double pass_probability() const;
  double void_pass_probability() const;

  /// \brief Void clusters computed from scratch from the current void cells (the incrementally kept
  /// void_clusters() must equal them; tests compare the two).
  std::vector<VoidCluster> void_clusters_from_scratch() const;

  /// \brief Writes the tree as an OctoMap binary .bt (for octovis); temporary file + rename.
  /// \throws FileError on failure.
  void write_bt(const std::string& path) const;

 private:
  friend struct detail::ExplorationAccess;  // octoreach's own algorithms read the state (cpp/src only)
  ExplorationOptions options_;
  double resolution_;
  std::unique_ptr<detail::ExplorationState> state_;
  std::vector<CellChange> changed_;
};

}  // namespace octoreach
