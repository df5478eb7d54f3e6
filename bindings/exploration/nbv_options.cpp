// Next-best-view options bound as classes: NbvOptions (its defaults and its exploration_loop preset from
// the C++ struct; the Python keywords that are not plain fields) and ExploreOptions, the exploration loop's.
#include "exploration/convert.hpp"
#include "exploration/next_best_view.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/next_best_view.hpp"

namespace octoreach::py_bindings {

namespace {

py::object optional_pose(const Pose& T) { return T.matrix().isIdentity(0) ? py::object(py::none()) : py::object(pose_to_array(T)); }

// The Python keywords that are not plain fields: workspace_box, workspace_sphere, workspace (a
// callable), 4x4 arrays for the base poses, ik_* for the IK options. None keeps the default.
void def_workspace(py::class_<NbvOptions>& cls) {
  cls.def_property("workspace_box", [](const NbvOptions& o) -> py::object {
        if (!o.workspace.box) return py::none();
        return py::make_tuple(o.workspace.box->lo, o.workspace.box->hi);
      }, [](NbvOptions& o, const py::object& box) {
        if (box.is_none()) return o.workspace.box.reset();
        o.workspace.box = box_from(box, "workspace_box");
      }, "Sensor positions inside this box ((2, 3): lo, hi rows; map frame), or None.")
      .def_property("workspace_sphere", [](const NbvOptions& o) -> py::object {
        if (!o.workspace.sphere_center) return py::none();
        return py::make_tuple(*o.workspace.sphere_center, o.workspace.sphere_radius);
      }, [](NbvOptions& o, const py::object& sphere) {
        if (sphere.is_none()) return o.workspace.sphere_center.reset();
        if (!py::isinstance<py::sequence>(sphere) || py::isinstance<py::str>(sphere) || py::len(sphere) != 2)
          throw py::type_error("workspace_sphere must be (center, radius) or None, got " + type_name(sphere));
        auto t = py::reinterpret_borrow<py::sequence>(sphere);
        o.workspace.sphere_center = vec3_from(t[0], "workspace_sphere center");
        o.workspace.sphere_radius = cast_arg<double>(t[1], "workspace_sphere radius", "a float");
      }, "Sensor positions within (center, radius) of a point (map frame), or None.")
      .def_property("workspace", [](const NbvOptions& o) -> py::object {
        return o.workspace.filter ? py::cast(o.workspace.filter) : py::object(py::none());
      }, [](NbvOptions& o, const py::object& fn) {
        if (fn.is_none()) return void(o.workspace.filter = nullptr);
        if (!PyCallable_Check(fn.ptr()))
          throw py::type_error("workspace must be a callable (N, 3) -> (N,) bools or None, got " + type_name(fn));
        o.workspace.filter = [fn](const std::vector<Eigen::Vector3d>& pts) {
          py::gil_scoped_acquire gil;
          py::object r = fn(to_points(pts));
          py::array_t<bool> a = py::array_t<bool>::ensure(r);
          if (!a || a.size() != py::ssize_t(pts.size()))
            throw std::invalid_argument("workspace callable must return one bool per row of its (N, 3) input");
          return std::vector<bool>(a.data(), a.data() + a.size());
        };
      }, "Callable taking positions (N, 3) (candidate cell centres, aimed eyes) and returning (N,) bools, each\n"
         "judged on its own (a search may call it several times), or None.");
}

void def_arm(py::class_<NbvOptions>& cls) {
  // The options keep the chain and the capability map alive (they hold plain pointers).
  const auto ref = py::return_value_policy::reference;
  cls.def_property("chain", py::cpp_function([](const NbvOptions& o) { return o.chain; }, ref),
                   py::cpp_function([](NbvOptions& o, const Chain* c) { o.chain = c; }, py::keep_alive<1, 2>()),
                   "Chain carrying the camera (its tip is the camera frame, +z forward), or None.")
      .def_property("chain_base", [](const NbvOptions& o) { return optional_pose(o.chain_base); },
                    [](NbvOptions& o, const py::object& T) {
                      o.chain_base = T.is_none() ? Pose::Identity() : pose_from(T, "chain_base");
                    }, "4x4 chain base -> map (None: identity).")
      .def_property("capability_map", py::cpp_function([](const NbvOptions& o) { return o.capability_map; }, ref),
                    py::cpp_function([](NbvOptions& o, const CapabilityMap* c) { o.capability_map = c; },
                                     py::keep_alive<1, 2>()),
                    "CapabilityMap of the arm carrying the camera, or None.")
      .def_property("capability_base", [](const NbvOptions& o) { return optional_pose(o.capability_base); },
                    [](NbvOptions& o, const py::object& T) {
                      o.capability_base = T.is_none() ? Pose::Identity() : pose_from(T, "capability_base");
                    }, "4x4 capability map base link -> map (None: identity).")
      .def_property("ik_attempts", [](const NbvOptions& o) { return o.ik.attempts; },
                    [](NbvOptions& o, int v) { o.ik.attempts = v; })
      .def_property("ik_position_tolerance", [](const NbvOptions& o) { return o.ik.position_tolerance; },
                    [](NbvOptions& o, double v) { o.ik.position_tolerance = v; })
      .def_property("ik_orientation_tolerance", [](const NbvOptions& o) { return o.ik.orientation_tolerance; },
                    [](NbvOptions& o, double v) { o.ik.orientation_tolerance = v; });
}

void wrap_search_options(py::module_& m) {
  py::class_<NbvOptions> cls(m, "NbvOptions",
                             "Options of next_best_view (defaults of the C++ struct); every attribute is also a\n"
                             "keyword argument of next_best_view.");
  cls.def(py::init<>())
      .def_static("exploration_loop", &NbvOptions::exploration_loop,
                  "The exploration loop's search: 100 valid poses from the best 800 candidate cells, the best\n"
                  "16 by a coarse score scored in full (rescore_best), the camera 5 cm clear of surfaces,\n"
                  "enclosed voids and the exposed faces of voids first, the ground an obstacle for the arm\n"
                  "(docs/design/next_best_view.md says why).")
      .def_readwrite("max_valid_poses", &NbvOptions::max_valid_poses, "N of the paper: stop after this many valid poses")
      .def_readwrite("orientations_per_cell", &NbvOptions::orientations_per_cell)
      .def_readwrite("orientation_spread", &NbvOptions::orientation_spread, "radians around the mean utility direction")
      .def_readwrite("max_candidate_cells", &NbvOptions::max_candidate_cells)
      .def_readwrite("score_width", &NbvOptions::score_width)
      .def_readwrite("score_height", &NbvOptions::score_height)
      .def_readwrite("rescore_best", &NbvOptions::rescore_best,
                     "n > 0: next_best_view (and the loop's aimed looks) score valid poses with a grid half as fine\n"
                     "across and down first, and only the n best by each ranking key with the full grid (ranked\n"
                     "holds those); the aimed looks rank more than 16 n poses with every fourth ray first and go\n"
                     "on in chunks of 16 n; 0: every one in full. A camera that only aims, score_views and the\n"
                     "baselines always score in full; views beyond the voids rank as the aimed looks, at most 2 in full.")
      .def_readwrite("min_distance", &NbvOptions::min_distance, "metres from the camera to the nearest point of any occupied cell")
      .def_readwrite("seed", &NbvOptions::seed, "seeds the orientation samples and the IK restarts")
      .def_readwrite("threads", &NbvOptions::threads)
      .def_readwrite("arm_collisions", &NbvOptions::arm_collisions)
      .def_property("reference",
                    [](const NbvOptions& o) -> py::object {
                      return o.ik.reference.size() ? py::cast(o.ik.reference) : py::none();
                    },
                    [](NbvOptions& o, const py::object& q) {
                      o.ik.reference = q.is_none() ? Eigen::VectorXd()
                                                   : cast_arg<Eigen::VectorXd>(q, "reference", "a vector of joint values or None");
                    },
                    "The robot's configuration for the joints off the chain (robot.dof values, e.g.\n"
                    "robot.configuration({...})) in the arm's collision checks; None: home.")
      .def_readwrite("min_reachability", &NbvOptions::min_reachability)
      .def_readwrite("capability_orientations", &NbvOptions::capability_orientations)
      .def_property("gain", [](const NbvOptions& o) { return std::string(gain_name(o.gain)); },
                    [](NbvOptions& o, const std::string& g) { o.gain = gain_from_name(g); },
                    "what views are ranked by: 'frontier_void' (expected void cells), 'frontiers' (expected\n"
                    "frontier cells) or 'unknown' (expected unknown cells, as nbvplanner)")
      .def_property("unknown_pass_probability", [](const NbvOptions& o) -> py::object {
            return o.unknown_pass_probability < 0 ? py::object(py::none()) : py::object(py::float_(o.unknown_pass_probability));
          }, [](NbvOptions& o, const py::object& p) {
            if (p.is_none()) return void(o.unknown_pass_probability = -1.0);
            double v = cast_arg<double>(p, "unknown_pass_probability", "a float in [0, 1] or None");
            if (!(v >= 0 && v <= 1))
              throw std::invalid_argument("unknown_pass_probability must be in [0, 1] or None, got " + std::to_string(v));
            o.unknown_pass_probability = v;
          }, "p of the visibility model (chance that an unknown cell lets a ray through); None: learned by the map")
      .def_property("aiming", [](const NbvOptions& o) { return std::string(aiming_name(o.aiming)); },
                    [](NbvOptions& o, const std::string& a) { o.aiming = aiming_from_name(a); },
                    "how a chain's camera is placed: 'auto' (the default: 'look_at' for a chain of fewer than 5\n"
                    "joints, such as a pan/tilt head, else 'pose'), 'pose' (IK of each candidate's position and\n"
                    "optical axis) or 'look_at' (the chain aims the optical axis at void or frontier cells; the\n"
                    "position follows)")
      .def_readwrite("look_at_tolerance", &NbvOptions::look_at_tolerance,
                     "aiming 'look_at': radians an aimed optical axis may miss its target by")
      .def_readwrite("unknown_is_obstacle", &NbvOptions::unknown_is_obstacle,
                     "safe views: unknown cells of the map's search space are obstacles for the arm and the camera")
      .def_readwrite("unknown_margin", &NbvOptions::unknown_margin,
                     "metres around the camera with no unknown cell of the search space (unknown_is_obstacle)")
      .def_readwrite("ground_is_obstacle", &NbvOptions::ground_is_obstacle,
                     "with a chain: the ground is an obstacle for the links the chain moves, at the lower of the\n"
                     "robot's root link and the map's search space floor (on in exploration_loop())")
      .def_readwrite("enclosure_power", &NbvOptions::enclosure_power,
                     "gain 'frontier_void': each void cell also counts with e^power in the ranking and the voids'\n"
                     "utility, e its enclosure (share of the six axis directions that meet a surface before free\n"
                     "space within enclosure_range); 0: the paper's plain count")
      .def_readwrite("enclosure_range", &NbvOptions::enclosure_range,
                     "metres walked from a void cell per direction for its enclosure")
      .def_readwrite("unexposed_weight", &NbvOptions::unexposed_weight,
                     "gain 'frontier_void': a void cell with no observed free cell among its 26 neighbours counts\n"
                     "with this factor in [0, 1] in the ranking and the voids' utility (1: none)");
  def_workspace(cls);
  def_arm(cls);
}

void wrap_explore_options(py::module_& m) {
  using E = ExploreOptions;
  py::class_<E>(m, "ExploreOptions",
                "Settings of the exploration loop (explore(); defaults of the C++ struct, docs/design/next_best_view.md\n"
                "says why each value): its search, budget and stopping rule, and how it chooses a view beyond the search.")
      .def(py::init<>())
      .def_static("benchmark", &E::benchmark,
                  "The exploration benchmark's settings: the defaults (the stop rule of every entry point).")
      .def_static("paper_stop", &E::paper_stop, "The paper's stop rule: the first chosen view with utility 0 (min_utility 0,\n"
                  "patience 1).")
      .def("stop_threshold", [](const E& o, const py::object& camera, double resolution) {
             return o.stop_threshold(intrinsics_from(camera), resolution);
           }, py::arg("camera"), py::arg("resolution"),
           "min_utility, or when it is None the void cells a view must be expected to see to be worth taking:\n"
           "score_width x score_height x resolution / camera.max_range (the cells its score rays would meet if one\n"
           "cell in every max_range / resolution cells along them were void).")
      .def_readwrite("search", &E::search,
                     "NbvOptions of every view's search (default NbvOptions.exploration_loop()); its seed is the\n"
                     "run's: the map's, and view k searches with seed + k")
      .def_readwrite("max_views", &E::max_views, "view budget")
      .def_readwrite("min_utility", &E::min_utility,
                     "stop when the chosen view's utility has been <= this for `patience` views in a row (None, the\n"
                     "default: stop_threshold(camera, resolution), from the sensor and the cell size; 0: the\n"
                     "paper's rule, utility 0)")
      .def_readwrite("patience", &E::patience, "chosen views in a row at or below min_utility before the loop stops")
      .def_readwrite("second_look", &E::second_look,
                     "frontier_void: poses aimed at void cells are scored on every view too, the better view taken")
      .def_readwrite("learn_misses", &E::learn_misses, "announce each view before its insert (expect_view)")
      .def_readwrite("physical_check", &E::physical_check,
                     "with a robot: a view whose arm touches the scene's true geometry is not taken")
      .def_readwrite("failed_view_radius", &E::failed_view_radius,
                     "metres: no view is chosen this near the camera of a view not taken")
      .def_readwrite("sampled_poses", &E::sampled_poses, "baselines: camera poses sampled per view and base")
      .def_readwrite("min_camera_height", &E::min_camera_height, "metres: sampled and aimed cameras stay above this")
      .def_readwrite("aimed_poses", &E::aimed_poses, "second look: poses aimed at void cells, per base")
      .def_readwrite("aimed_distance", &E::aimed_distance, "(min, max) metres from an aimed eye to its void cell")
      .def_readwrite("unexposed_share", &E::unexposed_share,
                     "share of the void cells with no observed free neighbour among the aimed poses' targets")
      .def_readwrite("low_aimed_poses", &E::low_aimed_poses,
                     "before a low view is taken: this many more poses, aimed at any void cell")
      .def_readwrite("last_directions", &E::last_directions,
                     "last chance (the choice would end the loop): rays out of each void cell, half of them "
                     "through the voids' gates (observed-free cells with a void cell across a face)")
      .def_readwrite("last_poses", &E::last_poses, "last chance: poses kept from those rays")
      .def_readwrite("last_distance", &E::last_distance, "(min, max) metres from a last-chance eye to its void cell")
      .def_readwrite("max_ray_cells", &E::max_ray_cells,
                     "last chance: void cells the rays leave from, and gates they pass, each at most")
      .def_readwrite("beyond_voids", &E::beyond_voids,
                     "frontier_void: a view beyond the voids (toward the search space's unknown cells outside the "
                     "hull of the occupied cells) where it expects more unknown cells of the search space (voids "
                     "included) than frontier-void's view expects void cells, and where frontier-void's choice "
                     "would end the loop")
      .def("validate", &E::validate, "ValueError naming the first bad setting (the search's: by the search).")
      .def("__copy__", [](const E& o) { return E(o); })
      .def("__deepcopy__", [](const E& o, const py::dict&) { return E(o); }, py::arg("memo"));
}

}  // namespace

void wrap_nbv_options(py::module_& m) {
  wrap_search_options(m);
  wrap_explore_options(m);
}

}  // namespace octoreach::py_bindings
