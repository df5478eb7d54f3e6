#pragma once
// numpy <-> C++ conversions shared by the exploration, next-best-view and simulation bindings (and
// the stock-insert reference of octoreach._bench).
#include <string>
#include <vector>

#include "common.hpp"
#include "octoreach/exploration.hpp"

namespace octoreach::py_bindings {

/// Rows of an (N, 3) array; ValueError naming `what` and the shape it got otherwise.
inline std::vector<Eigen::Vector3d> points_from(const py::handle& obj, const char* what) {
  Array a = array_arg(obj, what, "an (N, 3) array");
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    shape += a.ndim() == 1 ? ",)" : ")";
    throw std::invalid_argument(std::string(what) + " must have shape (N, 3), got " + shape);
  }
  auto r = a.unchecked<2>();
  std::vector<Eigen::Vector3d> out(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out[i] = {r(i, 0), r(i, 1), r(i, 2)};
  return out;
}

inline Eigen::Vector3d vec3_from(const py::handle& obj, const char* what) {
  Array a = array_arg(obj, what, "3 numbers");
  if (a.size() != 3) throw std::invalid_argument(std::string(what) + " must have 3 entries");
  const double* d = a.data();
  return {d[0], d[1], d[2]};
}

inline py::array_t<double> to_points(const std::vector<Eigen::Vector3d>& pts) {
  py::array_t<double> out({static_cast<py::ssize_t>(pts.size()), py::ssize_t(3)});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int j = 0; j < 3; ++j) w(i, j) = pts[i][j];
  return out;
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

inline py::dict digest_dict(const OccupancyDigest& g) {
  py::dict d;
  d["free"] = g.free;
  d["occupied"] = g.occupied;
  d["hash"] = g.hash;
  return d;
}

}  // namespace octoreach::py_bindings
