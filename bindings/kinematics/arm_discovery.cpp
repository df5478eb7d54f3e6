// Arms of a robot: named arms, where they were found and their approach axes, so Python does not re-derive them.
#include "robot/robot_args.hpp"

namespace octoreach::py_bindings {

void wrap_arm(py::module_& m) {
  py::class_<Arm>(m, "Arm",
                  "An arm: base link, tip (tool) link, the tool's approach axis and why (reason), its name and where it\n"
                  "was found (source). Arm.named / Arm.from_links / find_arms find them; the reference posture of the\n"
                  "joints it does not move is default_reference(robot, robot.chain(arm.base_link, arm.tip_link)).")
      .def(py::init([](const std::string& base, const std::string& tip, const Eigen::Vector3d& axis) {
             return Arm{base, tip, Eigen::Vector3d::Zero(), "", "", "links"}.with_approach_axis(axis);
           }), py::arg("base_link"), py::arg("tip_link"), py::arg("approach_axis"))
      .def_static("resolve", [](const Robot& robot, const py::object& arm, const py::object& approach_axis) {
                    return arm_from(robot, arm, approach_axis);
                  }, py::arg("robot"), py::arg("arm"), py::arg("approach_axis") = py::none(),
                  "The arm of a name or of a (base_link, tip_link[, approach_axis]) tuple; approach_axis overrides the\n"
                  "inferred axis. ValueError listing the arms that exist, or naming a missing link and the nearest names.")
      .def_static("named", &Arm::named, py::arg("robot"), py::arg("name"),
                  "The arm called `name` (find_arms, else a serial SRDF group); ValueError listing the arms otherwise.")
      .def_static("from_links", [](const Robot& robot, const std::string& base, const std::string& tip, const py::object& axis) {
                    return axis.is_none() ? Arm::from_links(robot, base, tip)
                                          : Arm::from_links(robot, base, tip, cast_arg<Eigen::Vector3d>(axis, "approach_axis", "3 numbers (x, y, z)"));
                  }, py::arg("robot"), py::arg("base_link"), py::arg("tip_link"), py::arg("approach_axis") = py::none(),
                  "The arm base_link -> tip_link; the approach axis inferred from the gripper unless given.")
      .def("with_approach_axis", &Arm::with_approach_axis, py::arg("approach_axis"))
      .def_property_readonly_static("NOT_FOUND", [](const py::object&) { return std::string(kNoArmFound); },
                                    "Why find_arms finds no arm on a robot, as the errors that say so put it.")
      .def_readonly("base_link", &Arm::base_link)
      .def_readonly("tip_link", &Arm::tip_link)
      .def_readonly("approach_axis", &Arm::approach_axis)
      .def_readonly("reason", &Arm::reason, "Why this approach axis (inferred from the gripper, or 'given').")
      .def_readonly("name", &Arm::name)
      .def_readonly("source", &Arm::source, "Where the arm was found (SRDF group, end effector, kinematic tree, links).")
      .def("__repr__", [](const Arm& a) {
        return "<octoreach.Arm '" + a.name + "' '" + a.base_link + "' -> '" + a.tip_link + "', approach " + a.reason + ">";
      });
  m.def("find_arms", &find_arms, py::arg("robot"),
        "The robot's arms: serial SRDF groups (tips moved to their tool frames), else branches of the kinematic\n"
        "tree that end in a gripper-like tip.");
  m.def("arm_names", &arm_names, py::arg("robot"), "Names of find_arms(robot), sorted.");
  m.def("infer_approach_axis", [](const Robot& robot, const std::string& base, const std::string& tip) {
          ApproachAxis a = infer_approach_axis(robot, base, tip);
          return py::make_tuple(a.axis, a.reason);
        }, py::arg("robot"), py::arg("base_link"), py::arg("tip_link"),
        "(axis, reason): the approach axis of the tool frame tip_link inferred from the gripper; ValueError saying\n"
        "how to give it when it cannot be inferred.");
}

}  // namespace octoreach::py_bindings
