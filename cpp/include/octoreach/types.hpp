#pragma once
/// \file types.hpp
/// \brief Common types of octoreach: poses, boxes, progress callbacks, errors.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "octoreach/limits.hpp"

namespace octoreach {

/// \brief A rigid transform (metres, right-handed, z up).
using Pose = Eigen::Isometry3d;

/// \brief True when `m` (any 4x4 Eigen expression) is a finite rigid transform: rotation orthonormal (R^T R within
/// 1e-6 of I) and not a reflection, last row 0 0 0 1 within 1e-6 (the rule every pose argument is checked by,
/// Python's included; check_rigid throws by it).
template <class Derived>
bool is_rigid(const Eigen::MatrixBase<Derived>& m) {
  // (R^T R)_ij is column i . column j; each comparison is false for a NaN or an infinity, so only the translation
  // needs its own finiteness test. Written out (no temporaries, no branches): the batch lookups test every row.
  const auto near = [](double x, double v) { return std::abs(x - v) <= 1e-6; };
  const Eigen::Vector3d a = m.template block<3, 1>(0, 0), b = m.template block<3, 1>(0, 1),
                        c = m.template block<3, 1>(0, 2);
  return near(a.dot(a), 1) & near(b.dot(b), 1) & near(c.dot(c), 1) & near(a.dot(b), 0) & near(a.dot(c), 0) &
         near(b.dot(c), 0) & (a.dot(b.cross(c)) > 0) & near(m(3, 0), 0) & near(m(3, 1), 0) & near(m(3, 2), 0) &
         near(m(3, 3), 1) & std::isfinite(m(0, 3)) & std::isfinite(m(1, 3)) & std::isfinite(m(2, 3));
}

/// \brief Checks that `m` is a finite rigid transform (is_rigid);
/// \throws std::invalid_argument naming `what` otherwise.
inline void check_rigid(const Eigen::Matrix4d& m, const std::string& what) {
  if (!m.allFinite()) throw std::invalid_argument(what + " is not finite (NaN or inf)");
  if (!is_rigid(m))
    throw std::invalid_argument(what + " is not a rigid transform (rotation not orthonormal with determinant 1, "
                                "or last row not 0 0 0 1)");
}
inline void check_rigid(const Pose& T, const std::string& what) { check_rigid(T.matrix(), what); }

/// \brief pi, without relying on the non-standard M_PI in public headers.
inline constexpr double kPi = 3.14159265358979323846;

/// \brief Axis-aligned box (metres).
struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  bool contains(const Eigen::Vector3d& p) const { return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all(); }
  double volume() const { return (hi - lo).prod(); }
};

/// \brief Progress callback: (done, total). Return false to cancel the work.
using ProgressCallback = std::function<bool(std::size_t done, std::size_t total)>;

/// \brief Raised when a long computation is cancelled through its progress callback.
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// \brief A process-wide check that long computations (map builds, IK batches and many-attempt IK,
/// pose sampling, orientation sets, OctoMap loading) poll about every 100 ms on the thread that called
/// them: returning true stops the computation with Cancelled (the object it was building is dropped;
/// existing objects stay valid). The Python module installs one that reports a pending Ctrl-C.
using CancelCheck = bool (*)();
void set_cancel_check(CancelCheck check);

/// \brief Raised when a file cannot be read or written, or is damaged (Python: OSError).
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// \brief Raised when a file to read does not exist (Python: FileNotFoundError).
class FileNotFound : public FileError {
 public:
  using FileError::FileError;
};

/// \brief Library version string.
inline const char* version() { return OCTOREACH_VERSION; }
/// \brief The newest version of the map file format this library writes and reads (part of a map cache key);
/// every older version is read too, and each map kind writes its own (map_files.hpp: MapKind).
int map_format_version();
/// \brief Named extra blocks of a map file (format version 2 and later), e.g. the room a surface map records.
using MapSections = std::map<std::string, std::vector<char>>;

}  // namespace octoreach
