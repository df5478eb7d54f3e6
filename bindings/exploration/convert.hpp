#pragma once
// numpy <-> C++ conversions of the exploration and next-best-view bindings (cells, keys, digests).
#include <string>
#include <vector>

#include "common.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::py_bindings {

/// The intrinsics of a DepthCamera or CameraIntrinsics argument; TypeError naming its type otherwise.
inline CameraIntrinsics intrinsics_from(const py::object& camera) {
  if (py::isinstance<DepthCamera>(camera)) return camera.cast<const DepthCamera&>().intrinsics();
  if (py::isinstance<CameraIntrinsics>(camera)) return camera.cast<CameraIntrinsics>();
  throw py::type_error("camera must be a DepthCamera or CameraIntrinsics, got " + type_name(camera));
}

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

/// An insert's statistics and timings as a dict.
inline py::dict stats_dict(const InsertStats& s) {
  py::dict d;
  d["points"] = s.points;
  d["dropped"] = s.dropped;
  d["out_of_bounds"] = s.out_of_bounds;
  d["free_cells"] = s.free_cells;
  d["occupied_cells"] = s.occupied_cells;
  d["changed_cells"] = s.changed_cells;
  d["frontier_added"] = s.frontier_added;
  d["frontier_removed"] = s.frontier_removed;
  d["void_added"] = s.void_added;
  d["void_removed"] = s.void_removed;
  d["space_known"] = s.space_known;
  d["seconds_rays"] = s.seconds_rays;
  d["seconds_tree"] = s.seconds_tree;
  d["seconds_frontiers"] = s.seconds_frontiers;
  d["seconds_hull"] = s.seconds_hull;
  d["seconds_voids"] = s.seconds_voids;
  d["seconds"] = s.seconds_total;
  return d;
}

inline py::dict digest_dict(const OccupancyDigest& g) {
  py::dict d;
  d["free"] = g.free;
  d["occupied"] = g.occupied;
  d["hash"] = g.hash;
  return d;
}

}  // namespace octoreach::py_bindings
