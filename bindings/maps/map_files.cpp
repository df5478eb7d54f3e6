// The registry of map kinds: load_any, map_kind, map_kinds, and the provenance every map records.
#include <pybind11/operators.h>

#include "maps/convert.hpp"
#include "octoreach/map_files.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::py_bindings {

void wrap_map_files(py::module_& m) {
  py::class_<MapProvenance>(m, "MapProvenance", "The robot a map was built for, as its file records it.")
      .def_readonly("robot_name", &MapProvenance::robot_name)
      .def_readonly("urdf_hash", &MapProvenance::urdf_hash)
      .def_readonly("model_hash", &MapProvenance::model_hash,
                    "Robot.model_hash of the robot built for (URDF and allowed collisions); 0: unknown.")
      .def("matches", &MapProvenance::matches, py::arg("robot"),
           "True when `robot` is the one recorded (name and URDF; the model hash where it is known).")
      .def(py::self == py::self)
      .def(py::self != py::self)
      .def("__repr__", [](const MapProvenance& p) {
        return "<octoreach.MapProvenance robot '" + p.robot_name + "', urdf_hash " + std::to_string(p.urdf_hash) +
               ", model_hash " + std::to_string(p.model_hash) + ">";
      });
  m.def("map_kinds", [] {
    py::dict kinds;
    for (const MapKind& k : map_kinds()) kinds[py::str(k.tag)] = k.extension;
    return kinds;
  }, "The map kinds a file can hold: {kind tag: usual file extension}.");
  m.def("map_kind", &map_kind, py::arg("path"),
        "The kind tag a map file's header names ('capability', 'point', 'surface'), without loading the map.\n"
        "OSError naming the file when it is not an octoreach map file.");
  m.def("load_any", [](const std::string& path, const std::string& kind) {
        AnyMap map = [&] {
          py::gil_scoped_release release;
          return load_any(path, kind);
        }();
        return std::visit([](auto&& loaded) { return py::cast(std::move(loaded)); }, std::move(map));
      }, py::arg("path"), py::arg("kind") = "",
      "The map stored at `path` (CapabilityMap, InversePointMap or SurfaceMap), of the kind its header names;\n"
      "with `kind` the file must hold that kind. OSError naming the file and the problem (not a map file, an\n"
      "unknown or unexpected kind, damage); ValueError for a `kind` that is not a map kind.");
}

}  // namespace octoreach::py_bindings
