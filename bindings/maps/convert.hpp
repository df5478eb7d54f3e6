#pragma once
// Helpers shared by the map binding files: conversions of pose maps and batches.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "robot/robot_args.hpp"
#include "octoreach/map_provenance.hpp"
#include "octoreach/pose_map.hpp"

namespace octoreach::py_bindings {

/// Rows (N, cols) of a float64 array as a C-contiguous array; ValueError naming the shape otherwise.
/// (The C++ lookups reject rows with a NaN or an infinity themselves, inside their parallel loop.)
inline Array rows_arg(const py::object& obj, py::ssize_t cols, const char* message) {
  const std::string name(message, std::string(message).find(' '));  // the argument: the message's first word
  Array a = array_arg(obj, name, "an (N, " + std::to_string(cols) + ") array");
  if (a.ndim() != 2 || a.shape(1) != cols) throw std::invalid_argument(message);
  return a;
}

/// (N, 4) rows x, y, z, theta -> values (N,) of `lookup(rows, n, out)`, computed without the GIL.
template <class F>
py::array_t<double> pose_rows_lookup(const py::object& poses, F&& lookup) {
  Array a = rows_arg(poses, 4, "poses must have shape (N, 4): x, y, z, theta");
  py::array_t<double> out(a.shape(0));
  const double* rows = a.data();
  double* o = out.mutable_data();
  py::gil_scoped_release release;
  lookup(rows, static_cast<std::size_t>(a.shape(0)), o);
  return out;
}

/// (centres (M, 3), values (M, theta_bins)) of a pose map's voxels.
inline py::tuple pose_map_voxels(const PoseMap& pm) {
  std::vector<Eigen::Vector3d> c;
  std::vector<float> v;
  pm.voxels(c, v);
  RowMatrixXd C(c.size(), 3);
  for (std::size_t i = 0; i < c.size(); ++i) C.row(i) = c[i].transpose();
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> V =
      Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(v.data(), c.size(), pm.theta_bins());
  return py::make_tuple(C, V);
}

inline py::tuple bounds_tuple(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& b) { return py::make_tuple(b.first, b.second); }

template <class Map>
py::dict to_dict(const Map& m) {
  py::dict d;
  for (auto& [k, v] : m) d[py::str(k)] = v;
  return d;
}

/// Binds the grasp set of an options struct as one attribute `grasps`: a subset name ("upper_hemisphere",
/// "top", "side", "all") or a non-empty list of direction indices.
template <class Options, class Class>
void def_grasps(Class& cls) {
  cls.def_property("grasps",
      [](const Options& o) -> py::object { return o.grasps.empty() ? py::cast(o.grasp_subset) : py::cast(o.grasps); },
      [](Options& o, const py::object& g) {
        std::vector<int> indices;
        std::string subset = o.grasp_subset;
        grasps_arg(g, indices, subset);
        if (g.is_none()) return;
        o.grasps = indices;
        o.grasp_subset = subset;
      },
      "Grasp set: a subset name ('upper_hemisphere', 'top', 'side', 'all') or a list of direction indices.");
}

/// Binds z_min and z_max of an options struct and `z_range` ((min, max) or None for the defaults).
template <class Options, class Class>
void def_z_range(Class& cls) {
  cls.def_readwrite("z_min", &Options::z_min)
      .def_readwrite("z_max", &Options::z_max)
      .def_property("z_range", [](const Options& o) { return std::make_pair(o.z_min, o.z_max); },
                    [](Options& o, const py::object& z) {
                      Options defaults;
                      o.z_min = defaults.z_min;
                      o.z_max = defaults.z_max;
                      z_range_arg(z, o.z_min, o.z_max);
                    }, "(min, max) base heights in metres; None: unbounded.");
}

/// Binds `reference` of an options struct: a robot configuration, or None (empty: the arm's default).
template <class Options, class Class>
void def_reference(Class& cls, const char* doc) {
  cls.def_property("reference",
      [](const Options& o) -> py::object { return o.reference.size() ? py::cast(o.reference) : py::none(); },
      [](Options& o, const py::object& q) { o.reference = q.is_none() ? Eigen::VectorXd() : cast_arg<Eigen::VectorXd>(q, "reference", "a vector of joint values or None"); }, doc);
}

/// Binds `resolution` of point/surface map options: metres, 0 or None for the capability map's.
template <class Options, class Class>
void def_map_resolution(Class& cls) {
  cls.def_property("resolution", [](const Options& o) { return o.resolution; },
                   [](Options& o, const py::object& r) { o.resolution = r.is_none() ? 0.0 : cast_arg<double>(r, "resolution", "a float or None"); },
                   "Voxel edge (m); 0 or None: the capability map's resolution.");
}

/// Binds what every map kind has: the class attributes `kind` (the tag of its files) and `extension`, and
/// the robot it was built for (`provenance`, and its fields as `robot_name`, `urdf_hash`, `model_hash`).
template <class Map, class Class>
void def_map_identity(Class& cls) {
  cls.attr("kind") = Map::kKind;
  cls.attr("extension") = Map::kExtension;
  cls.attr("format_version") = Map::kFormatVersion;
  cls.def_property_readonly("provenance", &Map::provenance, "The robot the map was built for.")
      .def_property_readonly("robot_name", &Map::robot_name)
      .def_property_readonly("urdf_hash", &Map::urdf_hash)
      .def_property_readonly("model_hash", &Map::model_hash,
                             "Robot.model_hash of the robot built for (URDF and allowed collisions); 0: unknown.");
}

}  // namespace octoreach::py_bindings
