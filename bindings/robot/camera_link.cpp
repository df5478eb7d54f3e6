// CameraLink: a robot's head camera, given or found from its link names and SRDF.
#include "common.hpp"
#include "octoreach/camera_link.hpp"

namespace octoreach::py_bindings {

void wrap_camera_link(py::module_& m) {
  py::class_<CameraLink>(m, "CameraLink", "A robot's camera link and why it was chosen.")
      .def_readonly("link", &CameraLink::link)
      .def_readonly("reason", &CameraLink::reason, "'given', or how find_camera_link found it.")
      .def("__repr__", [](const CameraLink& c) { return "<octoreach.CameraLink '" + c.link + "' (" + c.reason + ")>"; });
  m.def("find_camera_link", &find_camera_link, py::arg("robot"),
        "The robot's head camera link: the links named like a camera on one rigid body (on the head when they are\n"
        "on several), else the end of the head; ValueError naming the candidates and asking for the link otherwise.\n"
        "The planner's inspect actions use its position. Its axes are the URDF's: a camera link often looks along +x,\n"
        "so an exploration chain ends at the camera's optical frame (+z forward), named as in the URDF.");
  m.def("camera_link", [](const Robot& robot, const py::object& given) {
          return camera_link(robot, given.is_none() ? std::string() : cast_arg<std::string>(given, "given", "a link name (str) or None"));
        }, py::arg("robot"), py::arg("given") = py::none(),
        "`given` checked against the robot's links (reason 'given'), or find_camera_link(robot) when it is None.");
}

}  // namespace octoreach::py_bindings
