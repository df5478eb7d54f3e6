#pragma once
// Internal: the argument checks many calls share (finite numbers, coordinates and resolutions within
// octoreach/limits.hpp), each throwing std::invalid_argument that names the argument and its value.
// Called once per call on its arguments, never inside a per-element loop.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "common/format.hpp"
#include "octoreach/limits.hpp"

namespace octoreach::detail {

/// \brief Throws unless `v` is finite: "<name> must be finite, got nan".
inline void check_finite(double v, const char* name) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(name) + " must be finite, got " + format_number(v));
}

/// \brief Throws unless every entry of `v` is finite, naming the first bad entry.
template <class Derived>
void check_finite(const Eigen::DenseBase<Derived>& v, const char* name) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(double(v(i))))
      throw std::invalid_argument(std::string(name) + " must be finite, got " + format_number(double(v(i))) +
                                  " in entry " + std::to_string(i));
}

/// \brief Throws unless `v` is a finite number of metres, at most limits::kCoordinate in magnitude.
inline void check_coordinate(double v, const char* name) {
  check_finite(v, name);
  if (std::abs(v) > limits::kCoordinate)
    throw std::invalid_argument(std::string(name) + " " + format_number(v) + " m is out of range (at most " +
                                format_number(limits::kCoordinate) + " m in magnitude)");
}

/// \brief check_coordinate on every entry.
template <class Derived>
void check_coordinates(const Eigen::DenseBase<Derived>& v, const char* name) {
  check_finite(v, name);
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::abs(double(v(i))) > limits::kCoordinate)
      throw std::invalid_argument(std::string(name) + " entry " + std::to_string(i) + " = " + format_number(double(v(i))) +
                                  " m is out of range (at most " + format_number(limits::kCoordinate) +
                                  " m in magnitude)");
}

/// \brief Throws unless `v` is finite and > 0: "<name> must be a positive finite number, got ...".
inline void check_positive(double v, const char* name) {
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument(std::string(name) + " must be a positive finite number, got " + format_number(v));
}

/// \brief Throws unless a map resolution lies in [limits::kMinMapResolution, limits::kMaxMapResolution].
inline void check_map_resolution(double res, const char* name = "resolution") {
  if (!(res >= limits::kMinMapResolution && res <= limits::kMaxMapResolution))
    throw std::invalid_argument(std::string(name) + " must be a number of metres in [" +
                                format_number(limits::kMinMapResolution) + ", " +
                                format_number(limits::kMaxMapResolution) + "], got " + format_number(res));
}

/// \brief Throws unless a build's dense grid of nx x ny x nz positions x bins values stays within
/// limits::kMapGridValues (counts multiplied at 64 bits: each is below 2^17).
inline void check_grid_values(std::uint64_t nx, std::uint64_t ny, std::uint64_t nz, std::uint64_t bins, const char* what) {
  const std::uint64_t values = nx * ny * nz * bins;
  if (values > limits::kMapGridValues)
    throw std::invalid_argument(std::string(what) + " grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " x " +
                                std::to_string(nz) + " positions x " + std::to_string(bins) + " theta bins holds " +
                                std::to_string(values) + " values, more than the limit of " +
                                std::to_string(limits::kMapGridValues) +
                                ": use a coarser resolution, fewer theta_bins or a narrower z range");
}

/// \brief Throws unless 0 < count <= limit: "<name> must be in [1, limit], got count".
inline void check_count(std::int64_t count, std::uint64_t limit, const char* name) {
  if (count < 1 || std::uint64_t(count) > limit)
    throw std::invalid_argument(std::string(name) + " must be in [1, " + std::to_string(limit) + "], got " +
                                std::to_string(count));
}

}  // namespace octoreach::detail
