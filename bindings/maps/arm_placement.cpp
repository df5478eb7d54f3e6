// An arm's placement on its robot: the default reference posture, link roles, grasp orientations and base
// poses, so Python does not re-derive them.
#include "common.hpp"
#include "octoreach/arm.hpp"
#include "octoreach/orientation_set.hpp"

namespace octoreach::py_bindings {

void wrap_arm_placement(py::module_& m) {
  m.def("default_reference", &default_reference, py::arg("robot"), py::arg("chain"),
        "Reference posture (robot configuration) for the joints off `chain`: home with every SRDF 'tuck*' state\n"
        "applied that does not move the chain (the other arm tucked). Builds use it when given no reference.");
  m.def("base_pose", [](const Eigen::Vector4d& pose) {
          if (!pose.allFinite()) throw std::invalid_argument("pose must be finite (x, y, z, theta), got NaN or inf");
          return pose_to_array(base_pose(pose[0], pose[1], pose[2], pose[3]));
        },
        py::arg("pose"), "4x4 pose (world frame) of a frame at base pose (x, y, z, theta): yaw about z, then translation.");
  m.def("link_roles", [](const Robot& robot, const Chain& chain) {
          LinkRoles r = link_roles(robot, chain);
          auto names = [&](const std::vector<int>& links) {
            std::vector<std::string> out;
            for (int l : links) out.push_back(robot.links()[l].name);
            return out;
          };
          py::dict d;
          d["body"] = names(r.body);
          d["arm"] = names(r.arm);
          d["tool"] = names(r.tool);
          return d;
        }, py::arg("robot"), py::arg("chain"),
        "Collision links by role: 'body' (not moved by the chain), 'arm' (moved by it), 'tool' (rigid with the tip).");
  m.def("grasp_orientations", &grasp_orientations, py::arg("orientations"), py::arg("directions"),
        "Orientation indices (d * rolls + r, sorted) of an OrientationSet for direction indices, all rolls of each.");
}

}  // namespace octoreach::py_bindings
