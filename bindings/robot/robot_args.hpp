#pragma once
// Argument conversion shared by the Robot, Arm, Chain and map bindings: robot configurations and arms.
#include "common.hpp"
#include "octoreach/arm_discovery.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::py_bindings {

/// A robot configuration (dof,) from a 1-D array; ValueError naming the expected size or a non-finite entry.
inline Eigen::VectorXd robot_q(const Robot& r, const py::handle& q, const std::string& what = "q") {
  Array a = array_arg(q, what, "a vector of " + std::to_string(r.dof()) + " joint values");
  if (a.ndim() != 1 || a.shape(0) != r.dof())
    throw std::invalid_argument(what + " must be a vector of " + std::to_string(r.dof()) + " joint values (robot.joint_names)");
  Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(a.data(), r.dof());
  if (!v.allFinite()) throw std::invalid_argument(what + " must be finite");
  return v;
}

/// An arm argument: an arm name or a (base_link, tip_link[, approach_axis]) tuple or list; the
/// approach axis is inferred unless the tuple gives it.
inline Arm arm_from(const Robot& robot, const py::handle& arm) {
  if (py::isinstance<py::str>(arm)) return Arm::named(robot, arm.cast<std::string>());
  if (py::isinstance<Arm>(arm)) return arm.cast<Arm>();
  if ((py::isinstance<py::tuple>(arm) || py::isinstance<py::list>(arm)) && (py::len(arm) == 2 || py::len(arm) == 3)) {
    py::sequence s = py::reinterpret_borrow<py::sequence>(arm);
    auto base = cast_arg<std::string>(s[0], "arm[0] (base_link)", "a link name (str)");
    auto tip = cast_arg<std::string>(s[1], "arm[1] (tip_link)", "a link name (str)");
    if (py::len(s) == 3 && !s[2].is_none())
      return Arm::from_links(robot, base, tip, cast_arg<Eigen::Vector3d>(s[2], "arm[2] (approach_axis)", "3 numbers (x, y, z)"));
    return Arm::from_links(robot, base, tip);
  }
  throw py::type_error("arm must be a name, an Arm, a (base_link, tip_link[, approach_axis]) tuple or a CapabilityMap, got " +
                       std::string(py::repr(arm)));
}

/// arm_from with an optional approach-axis override (None keeps the arm's).
inline Arm arm_from(const Robot& robot, const py::handle& arm, const py::object& approach_axis) {
  if (approach_axis.is_none()) return arm_from(robot, arm);
  Eigen::Vector3d axis;
  try {
    axis = approach_axis.cast<Eigen::Vector3d>();
  } catch (const py::cast_error&) {
    throw py::type_error("approach_axis must be 3 numbers (x, y, z), got " +
                         std::string(py::str(py::type::handle_of(approach_axis).attr("__name__"))));
  }
  // An arm given by its links takes the axis as given: its own may not be inferable (a tip with no gripper).
  if ((py::isinstance<py::tuple>(arm) || py::isinstance<py::list>(arm)) && py::len(arm) == 2) {
    py::sequence s = py::reinterpret_borrow<py::sequence>(arm);
    return arm_from(robot, py::make_tuple(s[0], s[1], axis));
  }
  return arm_from(robot, arm).with_approach_axis(axis);
}

}  // namespace octoreach::py_bindings
