#pragma once
/// \file orientation_set.hpp
/// \brief Evenly spread end-effector orientations: approach directions on the sphere and rolls about them.

#include <cstdint>
#include <string>
#include <vector>

#include "octoreach/types.hpp"

namespace octoreach {

/// \brief A set of end-effector orientations: `directions` approach directions times `rolls` rolls.
///
/// Orientation index o = direction * rolls + roll. A direction d means the tool's approach
/// axis points along d (from the gripper toward the object). The default set spreads its
/// directions evenly (a Fibonacci spiral inside one azimuth wedge, repeated `symmetry` times
/// about z), so that it maps onto itself under rotations of 2 pi / symmetry about z: the
/// inverse point map uses that to derive yaw bins instead of recomputing them.
class OrientationSet {
 public:
  /// \brief Most directions a set may hold, and most rolls (checked before anything is allocated).
  static constexpr std::int64_t kMaxDirections = limits::kDirections;
  static constexpr int kMaxRolls = limits::kRolls;
  /// \brief Evenly spread set of about `count` directions (rounded to a multiple of `symmetry`); built in
  /// O(count log count). With `poles`, the two directions along +z and -z follow the spiral, which then holds
  /// about count - 2 (a tool held vertical, as a SCARA's, points along one of them exactly; the spiral never
  /// does). \throws std::invalid_argument for count outside [1, kMaxDirections], rolls outside [1, kMaxRolls] or
  /// symmetry outside [1, 64].
  static OrientationSet sphere(std::int64_t count = 200, int rolls = 1, int symmetry = 4, bool poles = false);
  /// \brief Number of directions sphere(count, rolls, symmetry, poles) holds, without building the set.
  /// \throws std::invalid_argument for count outside [1, kMaxDirections] or symmetry outside [1, 64].
  static int sphere_directions(std::int64_t count, int symmetry = 4, bool poles = false);
  /// \brief Set from explicit unit directions (normalised here); symmetry 1.
  static OrientationSet from_directions(const std::vector<Eigen::Vector3d>& directions, int rolls = 1);

  int directions() const { return static_cast<int>(dirs_.size()); }
  int rolls() const { return rolls_; }
  /// \brief Number of orientations (directions x rolls).
  int size() const { return directions() * rolls_; }
  int symmetry() const { return symmetry_; }
  /// \brief True when the set holds the directions along +z and -z after its spiral (sphere(..., poles)).
  bool poles() const { return poles_; }
  const Eigen::Vector3d& direction(int i) const { return dirs_.at(i); }
  const std::vector<Eigen::Vector3d>& all_directions() const { return dirs_; }

  /// \brief Index of the direction nearest to unit vector d (exact nearest, table-accelerated).
  int nearest_direction(const Eigen::Vector3d& d) const;
  /// \brief Orientation index nearest to the rotation R of a tool whose approach axis is `approach_axis`.
  int nearest(const Eigen::Matrix3d& R, const Eigen::Vector3d& approach_axis) const;
  /// \brief Tool rotation of orientation o for a tool with the given approach axis.
  Eigen::Matrix3d rotation(int o, const Eigen::Vector3d& approach_axis) const;
  /// \brief The k directions nearest to direction i (itself excluded).
  const std::vector<int>& neighbours(int i) const { return neighbours_.at(i); }

  /// \brief Direction indices of a named subset: "all", "upper_hemisphere" (approach pointing
  /// down or sideways: the gripper is above the object, d_z <= 0), "top" (d_z <= -cos 30 deg),
  /// "side" (|d_z| <= sin 30 deg), "lower_hemisphere" (d_z >= 0).
  std::vector<int> subset(const std::string& name) const;
  /// \brief Index of the direction that Rz(k * 2 pi / symmetry) maps direction i to.
  int rotated(int i, int k) const;

 private:
  void finalize_();
  std::vector<Eigen::Vector3d> dirs_;
  int rolls_ = 1;
  int symmetry_ = 1;
  bool poles_ = false;
  std::vector<std::vector<int>> neighbours_;
  std::vector<std::vector<int>> rotated_;  // [k][i]
  // Cube-map table: for each face cell the candidate directions that can be nearest, one flat array
  // (cell i's candidates are candidates_[start_[i] .. start_[i + 1])) so that a lookup reads one short run.
  static constexpr int kCells = 24;
  std::vector<std::uint32_t> start_;
  std::vector<std::int32_t> candidates_;
};

}  // namespace octoreach
