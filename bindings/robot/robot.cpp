// Python binding of Robot: the model's queries, collision checks and allowed-collision pairs.
// A Robot never changes: with_allowed_collisions returns a new one.
#include "common.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "robot/robot_args.hpp"

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

// A path (str or os.PathLike such as pathlib.Path) or XML text; TypeError naming `what` otherwise.
std::string path_or_text(const py::object& o, const char* what) {
  if (py::isinstance<py::str>(o)) return o.cast<std::string>();
  if (py::hasattr(o, "__fspath__")) {
    const py::object p = o.attr("__fspath__")();
    if (py::isinstance<py::str>(p)) return p.cast<std::string>();
  }
  throw py::type_error(std::string(what) + " must be a path (str or os.PathLike) or an XML string, got " + type_name(o));
}

// Model queries: names, limits, configurations, chains, link poses.
void wrap_robot_model(py::class_<Robot, std::shared_ptr<Robot>>& c) {
  c.def_static("from_urdf", [](const py::object& urdf_arg, const py::object& package_dir_args,
                               const py::object& srdf, const py::object& srdf_mismatch) {
          const std::string urdf = path_or_text(urdf_arg, "urdf");
          std::vector<std::string> package_dirs;
          if (!package_dir_args.is_none()) {
            if (!py::isinstance<py::list>(package_dir_args) && !py::isinstance<py::tuple>(package_dir_args))
              throw py::type_error("package_dirs must be a list of paths or None, got " + type_name(package_dir_args));
            for (const py::handle d : package_dir_args)
              package_dirs.push_back(path_or_text(py::reinterpret_borrow<py::object>(d), "package_dirs entry"));
          }
          const std::string text = srdf.is_none() ? "" : path_or_text(srdf, "srdf");
          if (srdf_mismatch.is_none()) return Robot::from_urdf(urdf, package_dirs, text);  // the C++ default
          const auto m = cast_arg<std::string>(srdf_mismatch, "srdf_mismatch", "'error' or 'leave_out'");
          if (m != "error" && m != "leave_out")
            throw py::value_error("srdf_mismatch must be 'error' or 'leave_out', got '" + m + "'");
          return Robot::from_urdf(urdf, package_dirs, text, m == "error" ? SrdfMismatch::kError : SrdfMismatch::kLeaveOut);
        }, py::arg("urdf"), py::arg("package_dirs") = py::none(), py::arg("srdf") = py::none(),
        py::arg("srdf_mismatch") = py::none(),
        "Robot from a URDF file path (str or os.PathLike) or XML string. package:// and file:// mesh URIs are resolved through\n"
        "package_dirs. srdf (path or XML) adds chain groups and disabled collision pairs. srdf_mismatch: SRDF\n"
        "groups and end effectors that name links, joints or groups the URDF lacks are an error ('error', the\n"
        "default) or left out ('leave_out', as MoveIt does; srdf_left_out says which).")
      .def_property_readonly("srdf_left_out", &Robot::srdf_left_out,
                             "SRDF groups and end effectors left out (srdf_mismatch='leave_out'), each with what it names\n"
                             "that the URDF lacks.")
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
      .def_property_readonly("srdf_groups", [](const Robot& r) {
        py::dict d;
        for (const auto& g : r.srdf_groups()) {
          py::dict e;
          e["chains"] = g.chains;
          e["joints"] = g.joints;
          e["links"] = g.links;
          e["subgroups"] = g.subgroups;
          d[py::str(g.name)] = e;
        }
        return d;
      }, "Every SRDF group: name -> {'chains': [(base, tip)], 'joints': [...], 'links': [...], 'subgroups': [...]}.")
      .def_property_readonly("end_effectors", [](const Robot& r) {
        py::list out;
        for (const auto& e : r.end_effectors()) {
          py::dict d;
          d["name"] = e.name;
          d["parent_link"] = e.parent_link;
          d["group"] = e.group;
          d["parent_group"] = e.parent_group;
          out.append(d);
        }
        return out;
      }, "SRDF end effectors: [{'name', 'parent_link', 'group', 'parent_group'}].")
      .def("group_joints", [](const Robot& r, const std::string& group) {
             std::vector<std::string> out;
             for (int j : r.group_joints(group)) out.push_back(r.joints()[j].name);
             return out;
           }, py::arg("group"), "Moving joints of an SRDF group (chains, joints, links' parent joints, subgroups).")
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
  c.def("lowest_point", [](const Robot& r, const py::object& q) {
         int link = -1;
         double z = r.lowest_point(r.link_poses(robot_q(r, q)), Pose::Identity(), &link);
         return py::make_tuple(z, link < 0 ? py::object(py::none()) : py::object(py::str(r.links()[link].name)));
       }, py::arg("q"),
       "(z, link): the lowest point of the collision geometry at q in the root link frame and the link holding it\n"
       "((inf, None) without geometry). A surface map refuses a robot that would stand in the floor.")
      .def("in_self_collision", [](const Robot& r, const py::object& q) {
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
               for (const auto& name : cast_arg<std::vector<std::string>>(links, "links", "a list of link names")) only.push_back(r.link_index(name));
             py::gil_scoped_release release;
             return r.in_collision(v, obstacles, base, self, links.is_none() ? nullptr : &only);
           }, py::arg("q"), py::arg("obstacles"), py::arg("base_pose") = py::none(), py::arg("self_collision") = false,
           py::arg("links") = py::none(),
           "True when a link (all, or the named `links`) touches an obstacle (world frame) with the root link at\n"
           "base_pose (4x4); self_collision also checks the robot against itself.")
      .def_property_readonly("allowed_collisions", [](const Robot& r) { return pair_names(r, r.allowed_pairs()); },
                             "Link pairs whose contacts are ignored (adjacent, SRDF, sampled).")
      .def_property_readonly("allowed_collision_sources", [](const Robot& r) {
             py::list out;
             for (std::size_t i = 0; i < r.allowed_pairs().size(); ++i)
               out.append(py::make_tuple(r.links()[r.allowed_pairs()[i].first].name,
                                         r.links()[r.allowed_pairs()[i].second].name,
                                         allowed_source_name(r.allowed_sources()[i])));
             return out;
           },
           "(link_a, link_b, reason) of every allowed pair, in the order of allowed_collisions; reason: 'adjacent',\n"
           "'SRDF', 'never in collision', 'always in collision', 'in collision at home' (sampled) or 'given'.")
      .def_property_readonly("checked_pairs", [](const Robot& r) { return r.checked_pairs().size(); },
                             "Number of link pairs checked for self-collision.")
      .def("with_allowed_collisions", py::overload_cast<const NamePairs&>(&Robot::with_allowed_collisions, py::const_),
           py::arg("pairs"),
           "A new Robot, this one with the (link_a, link_b) pairs added to its allowed collisions (its own\n"
           "model_hash); this robot is left as it is.")
      .def("compute_allowed_collisions", [](const Robot& r, int samples, std::uint64_t seed, const py::object& progress) {
             auto cb = progress_arg(progress, "allowed collisions");
             std::vector<std::pair<int, int>> pairs;
             {
               py::gil_scoped_release release;
               pairs = r.compute_allowed_collisions(samples, seed, cb);
             }
             return pair_names(r, pairs);
           }, py::arg("samples") = 2000, py::arg("seed") = 0, py::arg("progress") = py::none(),
           "Link pairs (link_a, link_b) never or always in collision over `samples` random configurations\n"
           "(deterministic for seed), among the pairs checked now: pass them to with_allowed_collisions.\n"
           "Empty when there is nothing to add. with_sampled_collisions() does it all (and caches).")
      .def("sample_allowed_collisions", [](const Robot& r, const py::object& options, const py::object& progress,
                                            const py::kwargs& kw) {
             AllowedCollisionOptions o = options_from<AllowedCollisionOptions>(options, kw, "Robot.sample_allowed_collisions");
             auto cb = progress_arg(progress, "allowed collisions");
             SampledCollisions s;
             {
               py::gil_scoped_release release;
               s = r.sample_allowed_collisions(o, cb);
             }
             py::dict d;
             d["never"] = pair_names(r, s.never);
             d["always"] = pair_names(r, s.always);
             d["default"] = pair_names(r, s.default_posture);
             d["from_cache"] = s.from_cache;
             d["cache_file"] = s.cache_file;
             return d;
           }, py::arg("options") = py::none(), py::arg("progress") = false,
           "MoveIt setup-assistant pairs among the checked ones: {'never', 'always', 'default': [(a, b)], 'from_cache',\n"
           "'cache_file'}; keywords set AllowedCollisionOptions fields (samples, seed, threads, default_posture, cache_dir).")
      .def("with_sampled_collisions", [](const Robot& r, const py::object& options, const py::object& progress,
                                          const py::kwargs& kw) {
             AllowedCollisionOptions o = options_from<AllowedCollisionOptions>(options, kw, "Robot.with_sampled_collisions");
             auto cb = progress_arg(progress, "allowed collisions");
             py::gil_scoped_release release;
             return r.with_sampled_collisions(o, cb);
           }, py::arg("options") = py::none(), py::arg("progress") = false,
           "A new Robot with the sampled allowed-collision pairs added (cached on disk by model hash); keywords set\n"
           "AllowedCollisionOptions fields.")
      .def("self_collisions", [](const Robot& r, const py::object& q) {
             std::vector<Pose> poses = r.link_poses(robot_q(r, q));
             return pair_names(r, r.colliding_pairs(poses, r.checked_pairs(), r.checked_pairs().size()));
           }, py::arg("q"), "Checked link pairs (link_a, link_b) in collision at q.")
      .def("srdf_text", &Robot::srdf_text, "SRDF of the model: groups, end effectors, group states, every allowed pair.")
      .def("write_srdf", &Robot::write_srdf, py::arg("path"), "Writes srdf_text() atomically to path.");
}

// What a viewer draws: visuals and collision shapes per link, and the files the robot came from.
void wrap_robot_geometry(py::module_& m, py::class_<Robot, std::shared_ptr<Robot>>& c) {
  py::class_<Visual>(m, "Visual", "One URDF <visual> of a link: its Shape (link frame) and colour.")
      .def_property_readonly("shape", [](const Visual& v) { return v.shape; },
                             "The Shape (a mesh's mesh_path is '' when its file was not found).")
      .def_property_readonly("mesh_uri", [](const Visual& v) { return v.mesh_uri; }, "The URDF's mesh filename.")
      .def_property_readonly("material", [](const Visual& v) { return v.material; })
      .def("__repr__", [](const Visual& v) {
        return std::string("<octoreach.Visual ") + v.shape.type_name() + (v.mesh_uri.empty() ? "" : " '" + v.mesh_uri + "'") + ">";
      })
      .def_property_readonly("rgba", [](const Visual& v) -> py::object {
             if (!v.rgba) return py::none();
             return py::make_tuple((*v.rgba)[0], (*v.rgba)[1], (*v.rgba)[2], (*v.rgba)[3]);
           },
                             "(red, green, blue, alpha) in [0, 1], or None when the URDF gives no colour.");
  py::class_<RobotSource>(m, "RobotSource", "The files a Robot was read from (absolute paths).")
      .def_readonly("urdf", &RobotSource::urdf, "URDF file ('' when the URDF was given as XML text).")
      .def_readonly("package_dirs", &RobotSource::package_dirs)
      .def_readonly("srdf", &RobotSource::srdf, "SRDF file ('' when none or given as XML text).");
  c.def_property_readonly("visuals", [](const Robot& r) {
         py::dict d;
         for (const auto& l : r.links())
           if (!l.visuals.empty()) d[py::str(l.name)] = l.visuals;
         return d;
       }, "{link name: [Visual]} of the links with <visual> elements.")
      .def_property_readonly("collision_shapes", [](const Robot& r) {
         py::dict d;
         for (const auto& l : r.links())
           if (!l.shapes.empty()) d[py::str(l.name)] = l.shapes;
         return d;
       }, "{link name: [Shape]} of the links with collision shapes (link frame).")
      .def_property_readonly("source", &Robot::source, "The URDF, SRDF and package folders the robot was read from.");
}

}  // namespace

void wrap_robot(py::module_& m) {
  {
    using O = AllowedCollisionOptions;
    py::class_<O>(m, "AllowedCollisionOptions",
                  "How the allowed-collision matrix is sampled (MoveIt setup assistant's method; defaults defined once, in C++).")
        .def(py::init<>())
        .def_readwrite("samples", &O::samples, "Random configurations (MoveIt's default: 10,000).")
        .def_readwrite("seed", &O::seed)
        .def_readwrite("threads", &O::threads, "0: every core.")
        .def_readwrite("default_posture", &O::default_posture, "Also allow pairs in collision at home().")
        .def_readwrite("cache_dir", &O::cache_dir,
                       "'' = $OCTOREACH_CACHE_DIR, else $XDG_CACHE_HOME/octoreach, else ~/.cache/octoreach; 'none' = no cache.");
  }
  py::class_<Robot, std::shared_ptr<Robot>> c(m, "Robot",
      "Robot model from a URDF: links, joints, collision shapes. Never changes once built.");
  wrap_robot_model(c);
  wrap_robot_collision(c);
  wrap_robot_geometry(m, c);
}

}  // namespace octoreach::py_bindings
