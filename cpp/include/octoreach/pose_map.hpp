#pragma once
/// \file pose_map.hpp
/// \brief A map from planar robot poses (x, y, z, theta) to a value in [0, 1], stored in an OctoMap
/// octree: each voxel (x, y, z) carries one value per theta bin. Inverse point maps and surface maps
/// are pose maps.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "octoreach/types.hpp"
#include "octoreach/voxel_octree.hpp"

namespace octoreach {

/// \brief Pose map: voxels of edge `resolution` holding `theta_bins` values each.
///
/// Theta bin k is centred on theta = 2 pi k / theta_bins; a lookup rounds theta to the nearest bin.
/// A lookup costs one octree descent (O(depth)) and one array access. Immutable once built.
class PoseMap {
 public:
  PoseMap() = default;
  PoseMap(double resolution, int theta_bins);

  double resolution() const { return resolution_; }
  int theta_bins() const { return theta_bins_; }
  std::size_t voxel_count() const { return values_.size() / std::max(1, theta_bins_); }
  /// \brief Value of pose (x, y, z, theta); 0 where the map has no voxel.
  double value(double x, double y, double z, double theta) const;
  /// \brief Values of n poses given as rows x, y, z, theta (`rows` holds 4 n doubles) into `out`
  /// (n doubles); large batches run on every core. Thread-safe. Throws std::invalid_argument naming the
  /// first row with a NaN or an infinity.
  void values(const double* rows, std::size_t n, double* out) const;
  /// \brief The theta bin of an angle (any real angle).
  int theta_bin(double theta) const;
  /// \brief The theta_bins values of the voxel holding (x, y, z), or nullptr.
  const float* voxel_values(double x, double y, double z) const;
  /// \brief Centres (M, 3) and values (M x theta_bins, row-major) of all voxels.
  void voxels(std::vector<Eigen::Vector3d>& centres, std::vector<float>& values) const;
  /// \brief (min, max) corners of the voxels with a non-zero value.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> bounds() const;
  /// \brief Number of (voxel, theta bin) poses with a value above 0.
  std::size_t pose_count() const;
  /// \brief Largest value in the map.
  double max_value() const;

  /// \brief Adds a voxel at key with its values (theta_bins floats); replaces existing values.
  void set_voxel(const octomap::OcTreeKey& key, const float* values);
  /// \brief Removes voxels whose values are all zero and refreshes inner-node maxima.
  void finalize();
  const VoxelOcTree& tree() const { return *tree_; }

  /// \brief Atomic save with the given kind and header; payload is the octree and the values. `format_version`
  /// (the kind's) and `sections` (which need version 2 or later) as map_files.hpp describes.
  void save(const std::string& path, const std::string& kind, const std::map<std::string, std::string>& header,
            std::uint32_t format_version = 1, const MapSections& sections = {}) const;
  /// \brief Loads a pose map of the given kind; returns the header and, when `sections` is given, the file's
  /// sections (none in a version 1 file). Throws FileError on damage.
  static PoseMap load(const std::string& path, const std::string& kind, std::map<std::string, std::string>& header,
                      MapSections* sections = nullptr);
  /// \brief Colour octree (.ot) for octovis: one cell per voxel, coloured by the best theta value.
  void export_octovis(const std::string& path) const;

 private:
  double resolution_ = 0;  // set by the constructor or load()
  int theta_bins_ = 16;
  std::shared_ptr<VoxelOcTree> tree_;
  std::vector<float> values_;  // voxel record r: values_[r * theta_bins_ + k]
  DenseIndex index_;
};

}  // namespace octoreach
