#pragma once
// Argument conversion shared by the Robot and Chain bindings.
#include "common.hpp"
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

}  // namespace octoreach::py_bindings
