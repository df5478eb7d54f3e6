// Python binding of Robot: the model's queries, collision checks and allowed-collision pairs.
// A Robot never changes: with_allowed_collisions returns a new one.
#include "common.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "robot_args.hpp"

namespace octoreach::py_bindings {

namespace {

using NamePairs = std::vector<std::pair<std::string, std::string>>;

NamePairs pair_names(const Robot& r, const std::vector<std::pair<int, int>>& pairs) {
  NamePairs out;
  for (auto [a, b] : pairs) out.emplace_back(r.links()[a].name, r.links()[b].name);
  return out;
}

std::vector<std::string> link_names(const Robot& r, const std::vector<int>& links) {
  std::vector<std::string> out;
  for (int l : links) out.push_back(r.links()[l].name);
  return out;
}

// Model queries: names, limits, configurations, chains, link poses.
void wrap_robot_model(py::class_<Robot, std::shared_ptr<Robot>>& c) {
  c.def_static("from_urdf", [](const std::string& urdf, const std::vector<std::string>& package_dirs,
                               const py::object& srdf) {
          return Robot::from_urdf(urdf, package_dirs,
                                  srdf.is_none() ? "" : cast_arg<std::string>(srdf, "srdf", "a path or XML string (str)"));
        }, py::arg("urdf"), py::arg("package_dirs") = std::vector<std::string>{}, py::arg("srdf") = py::none(),
        "Robot from a URDF file path or XML string. package:// and file:// mesh URIs are resolved through\n"
        "package_dirs. srdf (path or XML) adds chain groups and disabled collision pairs.")
      .def_property_readonly("name", &Robot::name)
      .def_property_readonly("urdf_hash", &Robot::urdf_hash,
                             "64-bit FNV-1a hash of the URDF text (the same for robots that differ only in their\n"
                             "allowed collisions; see model_hash).")
      .def_property_readonly("model_hash", &Robot::model_hash,
                             "64-bit hash of the URDF text and the allowed-collision pairs: what maps depend on.")
      .def_property_readonly("dof", &Robot::dof)
      .def_property_readonly("joint_names", &Robot::joint_names, "Joints of the configuration vector, in order.")
      .def_property_readonly("lower", &Robot::lower)
      .def_property_readonly("upper", &Robot::upper)
      .def_property_readonly("mimic_joints", &Robot::mimic_joints)
      .def_property_readonly("root_link", [](const Robot& r) { return r.links()[r.root_link()].name; })
      .def_property_readonly("link_names", [](const Robot& r) {
        std::vector<std::string> out;
        for (const auto& l : r.links()) out.push_back(l.name);
        return out;
      })
      .def_property_readonly("collision_links", [](const Robot& r) { return link_names(r, r.collision_links()); })
      .def_property_readonly("groups", [](const Robot& r) {
        py::dict d;
        for (const auto& g : r.groups()) d[py::str(g.name)] = py::make_tuple(g.base_link, g.tip_link);
        return d;
      }, "SRDF chain groups: name -> (base_link, tip_link).")
      .def_property_readonly("named_states", &Robot::named_states,
                             "SRDF group states: name -> {joint: value} (for example 'tuck_left_arm').")
      .def("has_link", &Robot::has_link)
      .def("home", &Robot::home, "Zero configuration moved into the joint limits.")
      .def("configuration", &Robot::configuration, py::arg("values"),
           "Configuration vector from a {joint name: value} dict, the rest from home().")
      .def("chain", &Robot::chain, py::arg("base_link"), py::arg("tip_link"))
      .def("link_poses", [](const Robot& r, const py::object& q) {
             std::vector<Pose> poses = r.link_poses(robot_q(r, q));
             py::dict d;
             for (std::size_t i = 0; i < poses.size(); ++i) d[py::str(r.links()[i].name)] = pose_to_array(poses[i]);
             return d;
           }, py::arg("q"), "{link name: 4x4 pose in the root link frame}.")
      .def("__repr__", [](const Robot& r) {
        return "<octoreach.Robot '" + r.name() + "', " + std::to_string(r.links().size()) + " links, " +
               std::to_string(r.dof()) + " dof>";
      });
}

// Collision checks and the allowed-collision matrix.
void wrap_robot_collision(py::class_<Robot, std::shared_ptr<Robot>>& c) {
  c.def("in_self_collision", [](const Robot& r, const py::object& q) {
         Eigen::VectorXd v = robot_q(r, q);
         py::gil_scoped_release release;
         return r.in_self_collision(v);
       }, py::arg("q"), "True when two links that are not allowed to touch collide at q.")
      .def("in_collision", [](const Robot& r, const py::object& q, const Obstacles& obstacles,
                              const py::object& base_pose, bool self, const py::object& links) {
             Eigen::VectorXd v = robot_q(r, q);
             Pose base = base_pose.is_none() ? Pose::Identity() : pose_from(base_pose, "base_pose");
             std::vector<int> only;
             if (!links.is_none())
               for (const auto& name : links.cast<std::vector<std::string>>()) only.push_back(r.link_index(name));
             py::gil_scoped_release release;
             return r.in_collision(v, obstacles, base, self, links.is_none() ? nullptr : &only);
           }, py::arg("q"), py::arg("obstacles"), py::arg("base_pose") = py::none(), py::arg("self_collision") = false,
           py::arg("links") = py::none(),
           "True when a link (all, or the named `links`) touches an obstacle (world frame) with the root link at\n"
           "base_pose (4x4); self_collision also checks the robot against itself.")
      .def_property_readonly("allowed_collisions", [](const Robot& r) { return pair_names(r, r.allowed_pairs()); },
                             "Link pairs whose contacts are ignored (adjacent, SRDF, sampled).")
      .def_property_readonly("checked_pairs", [](const Robot& r) { return r.checked_pairs().size(); },
                             "Number of link pairs checked for self-collision.")
      .def("with_allowed_collisions", py::overload_cast<const NamePairs&>(&Robot::with_allowed_collisions, py::const_),
           py::arg("pairs"),
           "A new Robot, this one with the (link_a, link_b) pairs added to its allowed collisions (its own\n"
           "model_hash); this robot is left as it is.")
      .def("compute_allowed_collisions", [](const Robot& r, int samples, std::uint64_t seed, const py::object& progress) {
             auto cb = progress_from(progress);
             std::vector<std::pair<int, int>> pairs;
             {
               py::gil_scoped_release release;
               pairs = r.compute_allowed_collisions(samples, seed, cb);
             }
             return pair_names(r, pairs);
           }, py::arg("samples") = 2000, py::arg("seed") = 0, py::arg("progress") = py::none(),
           "Link pairs (link_a, link_b) never or always in collision over `samples` random configurations\n"
           "(deterministic for seed), among the pairs checked now: pass them to with_allowed_collisions.\n"
           "Empty when there is nothing to add.");
}

}  // namespace

void wrap_robot(py::module_& m) {
  py::class_<Robot, std::shared_ptr<Robot>> c(m, "Robot",
      "Robot model from a URDF: links, joints, collision shapes. Never changes once built.");
  wrap_robot_model(c);
  wrap_robot_collision(c);
}

}  // namespace octoreach::py_bindings
