// MapRoom: the room a surface map was built with (obstacles and the body checked against them), and
// SurfaceMap.room.
#include "common.hpp"
#include "octoreach/map_room.hpp"
#include "octoreach/surface_map.hpp"

namespace octoreach::py_bindings {
namespace {

// The obstacles a check uses: `obstacles` when given, else the recorded ones.
const Obstacles& obstacles_or_recorded(const MapRoom& room, const std::shared_ptr<Obstacles>& obstacles) {
  return obstacles ? *obstacles : room.obstacles();
}

}  // namespace

void wrap_map_room(py::module_& m) {
  py::class_<MapRoom, std::shared_ptr<MapRoom>>(m, "MapRoom",
      "The room a surface map was built with (SurfaceMap.room): its obstacles (world frame: the surface's slab and\n"
      "boxes, the rest of the room) and the robot's body as the build checked it (collision shapes of the links the\n"
      "arm does not move, at the reference posture, in the map's reference frame). Saved in the map file.")
      .def_property_readonly("obstacles", [](const MapRoom& r) { return std::make_shared<Obstacles>(r.obstacles()); },
                             "The obstacles (a copy), named as in the room they came from.")
      .def_property_readonly("surface_count", &MapRoom::surface_count,
                             "How many of the obstacles, from the first, are the map's own surface (slab and boxes).")
      .def_property_readonly("body", [](const MapRoom& r) { return r.body(); },
                             "The body's collision Shapes, poses in the map's reference frame.")
      .def_property_readonly("body_links", [](const MapRoom& r) { return r.body_links(); }, "The link of each body shape.")
      .def_property_readonly("empty", &MapRoom::empty,
                             "True when nothing was recorded (files written before maps recorded their room).")
      .def("body_collides", [](const MapRoom& r, const py::object& poses, const std::shared_ptr<Obstacles>& obstacles) {
             RowMatrixXd p = finite_matrix_from(poses, 4, "poses");
             const Obstacles& o = obstacles_or_recorded(r, obstacles);
             py::array_t<bool> out(p.rows());
             auto w = out.mutable_unchecked<1>();
             py::gil_scoped_release release;
             for (Eigen::Index i = 0; i < p.rows(); ++i) w(i) = r.body_collides(p.row(i).transpose(), o);
             return out;
           }, py::arg("poses"), py::arg("obstacles") = py::none(),
           "(N,) bools: whether the body, with the map's reference frame at base poses (N, 4) as x, y, z, theta, touches\n"
           "`obstacles` (default: the recorded ones).")
      .def("touched", [](const MapRoom& r, const py::object& poses, const std::shared_ptr<Obstacles>& obstacles) {
             RowMatrixXd p = finite_matrix_from(poses, 4, "poses");
             const Obstacles& o = obstacles_or_recorded(r, obstacles);
             std::vector<std::string> names;
             for (Eigen::Index i = 0; i < p.rows(); ++i) {
               const int k = r.touched(p.row(i).transpose(), o);
               names.push_back(k < 0 ? "" : o.names()[std::size_t(k)]);
             }
             return names;
           }, py::arg("poses"), py::arg("obstacles") = py::none(),
           "Per base pose (N, 4), the name of the first obstacle the body touches there ('' when none).")
      .def("differences", &MapRoom::differences, py::arg("obstacles"), py::arg("tolerance") = 1e-4,
           "How `obstacles` differ from the recorded ones: a line per obstacle in only one of them; [] when they\n"
           "hold the same shapes (kind, sizes, pose within `tolerance` m; order and names do not matter).")
      .def("__repr__", [](const MapRoom& r) {
        return "<octoreach.MapRoom " + std::to_string(r.obstacles().size()) + " obstacles, body of " +
               std::to_string(r.body().size()) + " shapes>";
      });
  auto cls = py::reinterpret_borrow<py::class_<SurfaceMap, std::shared_ptr<SurfaceMap>>>(m.attr("SurfaceMap"));
  cls.def_property_readonly("room", [](const SurfaceMap& sm) { return std::const_pointer_cast<MapRoom>(sm.shared_room()); },
                            "The room the map was built with (MapRoom: obstacles and body); empty (room.empty) for files\n"
                            "written before maps recorded their room.");
}

}  // namespace octoreach::py_bindings
