#pragma once
// numpy <-> C++ conversions of the exploration and next-best-view bindings (cells, keys, digests).
#include <string>
#include <vector>

#include "common.hpp"
#include "octoreach/exploration.hpp"

namespace octoreach::py_bindings {

inline py::array_t<double> centers(const ExplorationMap& m, const std::vector<CellKey>& keys) {
  std::vector<Eigen::Vector3d> pts(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) pts[i] = m.center(keys[i]);
  return to_points(pts);
}

inline py::array_t<std::uint64_t> key_array(const std::vector<CellKey>& keys) {
  py::array_t<std::uint64_t> out(static_cast<py::ssize_t>(keys.size()));
  std::copy(keys.begin(), keys.end(), out.mutable_data());
  return out;
}

inline py::dict digest_dict(const OccupancyDigest& g) {
  py::dict d;
  d["free"] = g.free;
  d["occupied"] = g.occupied;
  d["hash"] = g.hash;
  return d;
}

}  // namespace octoreach::py_bindings
