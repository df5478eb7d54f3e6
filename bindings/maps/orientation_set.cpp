// OrientationSet: the approach directions and rolls of capability maps.
#include "common.hpp"
#include "octoreach/orientation_set.hpp"

namespace octoreach::py_bindings {

void wrap_orientation_set(py::module_& m) {
  py::class_<OrientationSet>(m, "OrientationSet",
      "Evenly spread approach directions on the sphere, times rolls about each (index = direction * rolls + roll).")
      .def_static("sphere", &OrientationSet::sphere, py::arg("count") = 200, py::arg("rolls") = 1,
                  py::arg("symmetry") = 4, py::arg("poles") = false)
      .def_static("sphere_directions", &OrientationSet::sphere_directions, py::arg("count"), py::arg("symmetry") = 4,
                  py::arg("poles") = false, "Number of directions sphere(count, ..., symmetry, poles) holds.")
      .def_property_readonly("poles", &OrientationSet::poles, "True when the set holds the directions along +z and -z.")
      .def_property_readonly("directions", [](const OrientationSet& s) {
        Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> d(s.directions(), 3);
        for (int i = 0; i < s.directions(); ++i) d.row(i) = s.direction(i).transpose();
        return d;
      }, "(K, 3) unit approach directions.")
      .def_property_readonly("rolls", &OrientationSet::rolls)
      .def_property_readonly("symmetry", &OrientationSet::symmetry)
      .def("__len__", &OrientationSet::size)
      .def("subset", &OrientationSet::subset, py::arg("name"),
           "Direction indices of 'all', 'upper_hemisphere' (d_z <= 0: gripper above the object), 'top', 'side', "
           "'lower_hemisphere'.")
      .def("nearest_direction", &OrientationSet::nearest_direction, py::arg("d"))
      .def("rotation", &OrientationSet::rotation, py::arg("index"), py::arg("approach_axis") = Eigen::Vector3d::UnitZ(),
           "Tool rotation (3x3) of orientation `index` for a tool whose approach axis is `approach_axis`.");
}

}  // namespace octoreach::py_bindings
