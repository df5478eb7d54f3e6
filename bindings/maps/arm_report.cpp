// ArmReport: an arm's moving joints, the joints carrying it that map builds hold still, its self-collision share.
#include "common.hpp"
#include "octoreach/arm_report.hpp"
#include "robot/robot_args.hpp"

namespace octoreach::py_bindings {

void wrap_arm_report(py::module_& m) {
  py::class_<HeldJoint>(m, "HeldJoint", "A moving joint a map build holds still, at its reference value (rad or m).")
      .def_readonly("name", &HeldJoint::name)
      .def_readonly("value", &HeldJoint::value)
      .def("__repr__", [](const HeldJoint& h) { return "<octoreach.HeldJoint " + h.name + " = " + std::to_string(h.value) + ">"; });
  py::class_<ArmReport>(m, "ArmReport", "An arm's joints as map builds see them.")
      .def_readonly("moving", &ArmReport::moving, "The chain's moving joints, base to tip.")
      .def_readonly("held", &ArmReport::held,
                    "Moving joints between the root and the arm's base link, held at default_reference().")
      .def_readonly("base_to_include_held", &ArmReport::base_to_include_held,
                    "The link to give as the chain's base (--base LINK) to include every held joint; '' when none.")
      .def_readonly("self_collision", &ArmReport::self_collision,
                    "The arm's joints drawn at random, the rest of the robot at default_reference(); only pairs of two\n"
                    "links the arm moves count (its collision model fighting its joints).")
      .def_readonly("with_body", &ArmReport::with_body, "The same draws with every checked pair (the body too).");
  m.def("arm_report", [](const Robot& robot, const py::object& arm, const py::object& options, const py::object& progress,
                          const py::kwargs& kw) {
          Arm a = arm_from(robot, arm);
          SelfCollisionOptions o = options_from<SelfCollisionOptions>(options, kw, "arm_report");
          ProgressCallback cb = progress_arg(progress, "self-collision");
          py::gil_scoped_release release;
          return arm_report(robot, a, o, cb);
        }, py::arg("robot"), py::arg("arm"), py::arg("options") = py::none(), py::arg("progress") = false,
        "The ArmReport of an arm (a name, an Arm or a (base_link, tip_link) tuple); keywords set SelfCollisionOptions\n"
        "fields of the arm's self-collision sampling (samples, seed, threads).");
}

}  // namespace octoreach::py_bindings
