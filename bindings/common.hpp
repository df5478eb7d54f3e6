#pragma once
// Shared helpers of the binding files: numpy <-> Eigen poses, shape checks, progress.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "octoreach/types.hpp"

namespace octoreach::py_bindings {
namespace py = pybind11;

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Sets a Python error whose message is `what` decoded as UTF-8 with bad bytes replaced (a message
/// quoting a damaged file must not turn into a UnicodeDecodeError).
inline void set_error(PyObject* type, const char* what) {
  PyObject* msg = PyUnicode_DecodeUTF8(what, Py_ssize_t(std::char_traits<char>::length(what)), "replace");
  if (!msg) return;
  PyErr_SetObject(type, msg);
  Py_DECREF(msg);
}

/// Raises ValueError unless `m` is a finite rigid transform (octoreach::check_rigid, the C++ rule).
inline Pose checked_pose(const Eigen::Matrix4d& m, const char* what = "pose") {
  check_rigid(m, what);
  Pose T;
  T.matrix() = m;
  return T;
}

/// The name of `obj`'s type, for messages.
inline std::string type_name(const py::handle& obj) {
  return py::str(py::type::handle_of(obj).attr("__name__"));
}

/// `obj` as a float64 array (numpy's conversion), or TypeError "<what> must be <expected>, got <type>"
/// when it is None or not numbers at all; the caller checks the shape (ValueError).
inline Array array_arg(const py::handle& obj, const std::string& what, const std::string& expected) {
  Array a = obj.is_none() ? Array() : Array::ensure(obj);
  if (!a) throw py::type_error(what + " must be " + expected + ", got " + type_name(obj));
  return a;
}

/// An array's shape as numpy prints it: "(6,)", "(2, 3)", "()".
inline std::string shape_text(const Array& a) {
  std::string out = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) out += (i ? ", " : "") + std::to_string(a.shape(i));
  return out + (a.ndim() == 1 ? ",)" : ")");
}

inline Pose pose_from(const py::handle& obj, const char* what = "pose") {
  Array a = array_arg(obj, what, "a 4x4 array");
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw std::invalid_argument(std::string(what) + " must be a 4x4 array");
  Eigen::Matrix4d m;
  auto r = a.unchecked<2>();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m(i, j) = r(i, j);
  return checked_pose(m, what);
}

inline std::vector<Pose> poses_from(const py::handle& obj, const char* what = "poses") {
  Array a = array_arg(obj, what, "an (N, 4, 4) array");
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4)
    throw std::invalid_argument(std::string(what) + " must have shape (N, 4, 4)");
  auto r = a.unchecked<3>();
  std::vector<Pose> out(a.shape(0));
  for (py::ssize_t n = 0; n < a.shape(0); ++n) {
    Eigen::Matrix4d m;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) m(i, j) = r(n, i, j);
    out[n] = checked_pose(m, what);
  }
  return out;
}

inline py::array_t<double> pose_to_array(const Pose& T) {
  py::array_t<double> out({4, 4});
  auto w = out.mutable_unchecked<2>();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) w(i, j) = T.matrix()(i, j);
  return out;
}

inline py::array_t<double> poses_to_array(const std::vector<Pose>& Ts) {
  py::array_t<double> out({static_cast<py::ssize_t>(Ts.size()), py::ssize_t(4), py::ssize_t(4)});
  auto w = out.mutable_unchecked<3>();
  for (std::size_t n = 0; n < Ts.size(); ++n)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) w(n, i, j) = Ts[n].matrix()(i, j);
  return out;
}

/// (N, cols) float64 array as a row-major Eigen matrix; ValueError naming the shape otherwise.
inline RowMatrixXd matrix_from(const py::handle& obj, py::ssize_t cols, const char* what) {
  Array a = array_arg(obj, what, "an (N, " + (cols >= 0 ? std::to_string(cols) : std::string("M")) + ") array");
  if (a.ndim() != 2 || (cols >= 0 && a.shape(1) != cols))
    throw std::invalid_argument(std::string(what) + " must have shape (N, " + (cols >= 0 ? std::to_string(cols) : "M") + ")");
  return Eigen::Map<const RowMatrixXd>(a.data(), a.shape(0), a.shape(1));
}

/// matrix_from, and ValueError when an entry is NaN or infinite.
inline RowMatrixXd finite_matrix_from(const py::handle& obj, py::ssize_t cols, const char* what) {
  RowMatrixXd m = matrix_from(obj, cols, what);
  if (!m.allFinite()) throw std::invalid_argument(std::string(what) + " must be finite (got NaN or inf)");
  return m;
}

/// A box given as (2, 3) rows lo and hi, every entry finite: ValueError naming the shape or the fault otherwise (the
/// order of lo and hi is the caller's to check: some boxes may be flat).
inline Aabb box_from(const py::handle& obj, const char* what) {
  Array a = array_arg(obj, what, "a (2, 3) array of rows lo, hi");
  if (a.ndim() != 2 || a.shape(0) != 2 || a.shape(1) != 3)
    throw std::invalid_argument(std::string(what) + " must have shape (2, 3): rows lo and hi, got shape " +
                                shape_text(a));
  RowMatrixXd b = Eigen::Map<const RowMatrixXd>(a.data(), 2, 3);
  if (!b.allFinite()) throw std::invalid_argument(std::string(what) + " must be finite (got NaN or inf)");
  return Aabb{b.row(0).transpose(), b.row(1).transpose()};
}

using IndexTriples = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// (M, 3) integer array of vertex indices, each checked against [0, vertices) at full 64-bit width
/// before it is narrowed to int; ValueError naming the first bad entry.
inline IndexTriples index_triples_from(const py::handle& obj, std::size_t vertices, const char* what) {
  auto a = obj.is_none() ? decltype(py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(obj))()
                         : py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a) throw py::type_error(std::string(what) + " must be an (M, 3) array of vertex indices, got " + type_name(obj));
  if (a.ndim() != 2 || a.shape(1) != 3) throw std::invalid_argument(std::string(what) + " must have shape (M, 3)");
  IndexTriples t(a.shape(0), 3);
  const std::int64_t* d = a.data();
  for (py::ssize_t i = 0; i < a.shape(0) * 3; ++i) {
    if (d[i] < 0 || std::uint64_t(d[i]) >= vertices)
      throw std::invalid_argument(std::string(what) + " row " + std::to_string(i / 3) + " refers to vertex " +
                                  std::to_string(d[i]) + ", outside [0, " + std::to_string(vertices) + ")");
    t(i / 3, i % 3) = int(d[i]);
  }
  return t;
}

/// `obj` converted to T, or TypeError "<what> must be <expected>, got <type>" (never pybind11's cast message).
/// Rows of an (N, 3) array; ValueError naming `what` and the shape it got otherwise.
inline std::vector<Eigen::Vector3d> points_from(const py::handle& obj, const char* what) {
  Array a = array_arg(obj, what, "an (N, 3) array");
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw std::invalid_argument(std::string(what) + " must have shape (N, 3), got " + shape_text(a));
  auto r = a.unchecked<2>();
  std::vector<Eigen::Vector3d> out(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out[i] = {r(i, 0), r(i, 1), r(i, 2)};
  return out;
}

inline Eigen::Vector3d vec3_from(const py::handle& obj, const char* what) {
  Array a = array_arg(obj, what, "3 numbers");
  if (a.size() != 3) throw std::invalid_argument(std::string(what) + " must have 3 entries");
  const double* d = a.data();
  if (!std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2]))
    throw std::invalid_argument(std::string(what) + " must be finite, got (" + std::to_string(d[0]) + ", " +
                                std::to_string(d[1]) + ", " + std::to_string(d[2]) + ")");
  return {d[0], d[1], d[2]};
}

inline py::array_t<double> to_points(const std::vector<Eigen::Vector3d>& pts) {
  py::array_t<double> out({static_cast<py::ssize_t>(pts.size()), py::ssize_t(3)});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int j = 0; j < 3; ++j) w(i, j) = pts[i][j];
  return out;
}

template <class T>
T cast_arg(const py::handle& obj, const char* what, const char* expected) {
  try {
    return obj.cast<T>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(what) + " must be " + expected + ", got " + type_name(obj));
  }
}

/// The result of a Python predicate: a bool (or numpy bool), else TypeError naming the callable.
inline bool bool_result(const py::handle& r, const char* what) {
  if (PyBool_Check(r.ptr())) return r.ptr() == Py_True;
  if (py::hasattr(r, "dtype") && py::str(r.attr("dtype").attr("kind")).cast<std::string>() == "b" &&
      py::hasattr(r, "ndim") && r.attr("ndim").cast<int>() == 0)
    return PyObject_IsTrue(r.ptr()) == 1;
  throw py::type_error(std::string(what) + " must return a bool, got " +
                       std::string(py::str(py::type::of(r).attr("__name__"))));
}

/// Wraps a Python callable (done, total) -> bool|None as a C++ progress callback that takes the GIL.
inline ProgressCallback progress_from(const py::object& cb) {
  if (cb.is_none()) return nullptr;
  return [cb](std::size_t done, std::size_t total) {
    py::gil_scoped_acquire gil;
    py::object r = cb(done, total);
    return r.is_none() ? true : bool_result(r, "the progress callback");
  };
}

/// The `progress` argument of a long call (True, False, None or a callable (done, total)) as a C++
/// callback. True asks the factory that the Python package registered with set_progress_factory
/// (octoreach.progress.make_progress draws a bar); the compiled module never imports the package,
/// so without a factory True is silent. Defined in progress.cpp.
ProgressCallback progress_arg(const py::object& progress, const char* label);

/// TypeError for keyword `key` of `call` given `value` where the option holds `current` (its type is
/// the expected one; a None default says only that the value did not fit).
inline py::type_error wrong_keyword_type(const char* call, const std::string& key, const py::handle& current,
                                         const py::handle& value) {
  std::string expected = current.is_none() ? std::string("another type (see the options class's help)")
                                           : std::string(py::str(py::type::handle_of(current).attr("__name__")));
  std::string got = py::str(py::type::handle_of(value).attr("__name__"));
  return py::type_error(std::string(call) + "(): keyword '" + key + "' must be " + expected + ", got " + got);
}

/// An options struct bound as a class: a copy of `options` (None: the C++ defaults), then each keyword
/// argument set as the attribute of that name, so defaults live once, in the C++ struct. An unknown
/// keyword raises TypeError naming it and the call.
template <class Options>
Options options_from(const py::object& options, const py::kwargs& kwargs, const char* call) {
  if (!options.is_none() && !py::isinstance<Options>(options))
    throw py::type_error(std::string(call) + "(): options must be " +
                         std::string(py::str(py::type::of<Options>().attr("__name__"))) + " or None, got " +
                         type_name(options));
  py::object o = options.is_none() ? py::cast(Options()) : py::cast(Options(options.cast<const Options&>()));
  for (auto item : kwargs) {
    std::string key = py::str(item.first);
    if (key.empty() || key[0] == '_' || !py::hasattr(o, key.c_str()))
      throw py::type_error(std::string(call) + "() got an unexpected keyword argument '" + key + "'");
    try {
      o.attr(key.c_str()) = item.second;
    } catch (const py::cast_error&) {
      throw wrong_keyword_type(call, key, o.attr(key.c_str()), item.second);
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_RuntimeError)) throw;
      throw wrong_keyword_type(call, key, o.attr(key.c_str()), item.second);
    }
  }
  return o.cast<Options>();
}

/// A grasp-set argument: a subset name (into `subset`) or a list of direction indices (into `grasps`).
inline void grasps_arg(const py::object& grasps, std::vector<int>& indices, std::string& subset) {
  if (py::isinstance<py::str>(grasps)) {
    subset = grasps.cast<std::string>();
  } else if (!grasps.is_none()) {
    indices = cast_arg<std::vector<int>>(grasps, "grasps", "a subset name or a list of int");
    if (indices.empty()) throw std::invalid_argument("the grasp set is empty");
  }
}

/// A z_range argument: None keeps the defaults, else (min, max) in metres.
inline void z_range_arg(const py::object& z_range, double& z_min, double& z_max) {
  if (z_range.is_none()) return;
  auto zr = cast_arg<std::pair<double, double>>(z_range, "z_range", "None or (min, max) in metres");
  z_min = zr.first;
  z_max = zr.second;
}

/// Emits `message` as an octoreach.MapWarning (a UserWarning) at the caller's line, unless it is empty: the one
/// line a map build prints when its result looks suspicious (map_warnings.hpp). Needs the GIL.
void warn_map(const std::string& message);

void wrap_progress(py::module_& m);
void wrap_shape(py::module_& m);
void wrap_limits(py::module_& m);
void wrap_obstacles(py::module_& m);
void wrap_chain(py::module_& m);
void wrap_robot(py::module_& m);
void wrap_orientation_set(py::module_& m);
void wrap_arm(py::module_& m);
void wrap_arm_placement(py::module_& m);
void wrap_map_files(py::module_& m);
void wrap_map_warnings(py::module_& m);
void wrap_self_collision_report(py::module_& m);
void wrap_arm_report(py::module_& m);
void wrap_camera_link(py::module_& m);
void wrap_capability_map(py::module_& m);
void wrap_certified_lookup(py::module_& m);
void wrap_capability_blocks(py::module_& m);
void wrap_point_map(py::module_& m);
void wrap_surface(py::module_& m);
void wrap_surface_map(py::module_& m);
void wrap_map_room(py::module_& m);
void wrap_pose_sampler(py::module_& m);
void wrap_simulation(py::module_& m);
void wrap_exploration_map(py::module_& m);
void wrap_next_best_view(py::module_& m);
void wrap_view_choice(py::module_& m);
void wrap_explorer(py::module_& m);

}  // namespace octoreach::py_bindings
