#pragma once
/// \file types.hpp
/// \brief Common types of octoreach: poses, progress callbacks, errors.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace octoreach {

/// \brief A rigid transform (metres, right-handed, z up).
using Pose = Eigen::Isometry3d;

/// \brief Progress callback: (done, total). Return false to cancel the work.
using ProgressCallback = std::function<bool(std::size_t done, std::size_t total)>;

/// \brief Raised when a long computation is cancelled through its progress callback.
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// \brief Raised when a file cannot be read or written, or is damaged (Python: OSError).
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// \brief Library version string.
inline const char* version() { return OCTOREACH_VERSION; }

}  // namespace octoreach
