// Next-best-view bindings: NbvOptions (defaults from the C++ struct), view_utility,
// accumulate_utility and next_best_view.
#include <algorithm>
#include <cmath>

#include "exploration/convert.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::py_bindings {

namespace {

CameraIntrinsics intrinsics_from(const py::object& camera) {
  if (py::isinstance<DepthCamera>(camera)) return camera.cast<const DepthCamera&>().intrinsics();
  if (py::isinstance<CameraIntrinsics>(camera)) return camera.cast<CameraIntrinsics>();
  throw py::type_error("camera must be a DepthCamera or CameraIntrinsics, got " + type_name(camera));
}

py::object optional_pose(const Pose& T) { return T.matrix().isIdentity(0) ? py::object(py::none()) : py::object(pose_to_array(T)); }

// The Python keywords that are not plain fields: workspace_box, workspace_sphere, workspace (a
// callable), 4x4 arrays for the base poses, ik_* for the IK options. None keeps the default.
void def_workspace(py::class_<NbvOptions>& cls) {
  cls.def_property("workspace_box", [](const NbvOptions& o) -> py::object {
        if (!o.workspace.box) return py::none();
        return py::make_tuple(o.workspace.box->lo, o.workspace.box->hi);
      }, [](NbvOptions& o, const py::object& box) {
        if (box.is_none()) return o.workspace.box.reset();
        RowMatrixXd b = matrix_from(box, 3, "workspace_box");
        if (b.rows() != 2) throw std::invalid_argument("workspace_box must have shape (2, 3): lo and hi rows");
        o.workspace.box = Aabb{b.row(0).transpose(), b.row(1).transpose()};
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
      }, "Callable taking candidate cell centres (N, 3) and returning (N,) bools, or None.");
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

void wrap_nbv_options(py::module_& m) {
  py::class_<NbvOptions> cls(m, "NbvOptions",
                             "Options of next_best_view (defaults of the C++ struct); every attribute is also a\n"
                             "keyword argument of next_best_view.");
  cls.def(py::init<>())
      .def_readwrite("max_valid_poses", &NbvOptions::max_valid_poses, "N of the paper: stop after this many valid poses")
      .def_readwrite("orientations_per_cell", &NbvOptions::orientations_per_cell)
      .def_readwrite("orientation_spread", &NbvOptions::orientation_spread, "radians around the mean utility direction")
      .def_readwrite("max_candidate_cells", &NbvOptions::max_candidate_cells)
      .def_readwrite("score_width", &NbvOptions::score_width)
      .def_readwrite("score_height", &NbvOptions::score_height)
      .def_readwrite("min_distance", &NbvOptions::min_distance, "metres from the camera to any occupied cell")
      .def_readwrite("seed", &NbvOptions::seed, "seeds the orientation samples and the IK restarts")
      .def_readwrite("threads", &NbvOptions::threads)
      .def_readwrite("arm_collisions", &NbvOptions::arm_collisions)
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
      .def_readwrite("unknown_is_obstacle", &NbvOptions::unknown_is_obstacle,
                     "safe views: unknown cells of the map's search space are obstacles for the arm and the camera")
      .def_readwrite("unknown_margin", &NbvOptions::unknown_margin,
                     "metres around the camera with no unknown cell of the search space (unknown_is_obstacle)")
      .def_readwrite("ground_is_obstacle", &NbvOptions::ground_is_obstacle,
                     "with a chain: the ground below the map's search space is an obstacle for the links the chain\n"
                     "moves (its unknown cells are not obstacles otherwise)")
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

void gains_into(py::dict& d, const ViewGains& v) {
  d["void_cells"] = v.void_cells;
  d["unknown_cells"] = v.unknown_cells;
  d["frontier_cells"] = v.frontier_cells;
  d["expected_void"] = v.expected_void;
  d["expected_unknown"] = v.expected_unknown;
  d["expected_frontier"] = v.expected_frontier;
  d["expected_enclosed_void"] = v.expected_enclosed_void;
}

py::dict view_dict(const ViewCandidate& v) {
  py::dict d;
  d["pose"] = pose_to_array(v.pose);
  gains_into(d, v);
  d["gain"] = v.gain;
  d["utility_dm3"] = v.utility_dm3;
  d["cell_utility"] = v.cell_utility;
  d["q"] = v.q.size() ? py::object(py::cast(v.q)) : py::object(py::none());
  return d;
}

py::dict result_dict(const NbvResult& r) {
  py::dict d;
  py::list ranked;
  for (const auto& v : r.ranked) ranked.append(view_dict(v));
  d["ranked"] = ranked;
  d["best"] = r.ranked.empty() ? py::object(py::none()) : py::object(view_dict(r.ranked.front()));
  d["best_pose"] = r.ranked.empty() ? py::object(py::none()) : py::object(pose_to_array(r.ranked.front().pose));
  gains_into(d, r.ranked.empty() ? ViewGains() : static_cast<const ViewGains&>(r.ranked.front()));
  d["expected_gain"] = r.best_gain();
  d["utility_dm3"] = r.best_utility_dm3();
  d["pass_probability"] = r.pass_probability;
  d["void_pass_probability"] = r.void_pass_probability;
  d["camera_not_clear"] = r.camera_not_clear;
  d["utility_vectors"] = r.utility_vectors;
  d["utility_cells"] = r.utility_cells;
  d["candidate_cells"] = r.candidate_cells;
  d["poses_scored"] = r.poses_scored;
  d["ik_failures"] = r.ik_failures;
  d["capability_pruned"] = r.capability_pruned;
  d["arm_collisions"] = r.arm_collisions;
  d["capability_rejected"] = r.capability_rejected;
  d["seconds"] = r.seconds;
  d["seconds_vectors"] = r.seconds_vectors;
  d["seconds_prune"] = r.seconds_prune;
  d["seconds_score"] = r.seconds_score;
  return d;
}

// score_views' result: one entry per pose, as arrays.
py::dict scored_dict(const std::vector<ScoredView>& sv, const NbvOptions& o, std::pair<double, double> p) {
  const py::ssize_t n = py::ssize_t(sv.size());
  const py::ssize_t dof = o.chain ? py::ssize_t(o.chain->dof()) : 0;
  py::array_t<bool> valid(n);
  py::list status;
  std::vector<Pose> poses;
  py::array_t<double> q({n, dof});
  py::array_t<std::int64_t> voids(n), unknown(n), frontier(n);
  py::array_t<double> e_void(n), e_unknown(n), e_frontier(n), gain(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const ScoredView& s = sv[std::size_t(i)];
    valid.mutable_data()[i] = s.valid();
    status.append(status_name(s.status));
    poses.push_back(s.view.pose);
    for (py::ssize_t j = 0; j < dof; ++j)
      q.mutable_data()[i * dof + j] = s.view.q.size() == dof ? s.view.q[j] : std::nan("");
    voids.mutable_data()[i] = std::int64_t(s.view.void_cells);
    unknown.mutable_data()[i] = std::int64_t(s.view.unknown_cells);
    frontier.mutable_data()[i] = std::int64_t(s.view.frontier_cells);
    e_void.mutable_data()[i] = s.view.expected_void;
    e_unknown.mutable_data()[i] = s.view.expected_unknown;
    e_frontier.mutable_data()[i] = s.view.expected_frontier;
    gain.mutable_data()[i] = s.view.gain;
  }
  py::dict d;
  d["valid"] = valid;
  d["status"] = status;
  d["pose"] = poses_to_array(poses);
  d["q"] = o.chain ? py::object(q) : py::object(py::none());
  d["void_cells"] = voids;
  d["unknown_cells"] = unknown;
  d["frontier_cells"] = frontier;
  d["expected_void"] = e_void;
  d["expected_unknown"] = e_unknown;
  d["expected_frontier"] = e_frontier;
  d["expected_gain"] = gain;
  d["gain"] = std::string(gain_name(o.gain));
  d["pass_probability"] = p.first;
  d["void_pass_probability"] = p.second;
  return d;
}

}  // namespace

void wrap_next_best_view(py::module_& m) {
  wrap_nbv_options(m);
  m.def("view_utility", [](const ExplorationMap& map, const py::object& camera, const py::object& pose, int sw, int sh) {
          CameraIntrinsics c = intrinsics_from(camera);
          Pose T = pose_from(pose, "camera_pose");
          py::gil_scoped_release release;
          return view_utility(map, c, T, sw, sh);
        }, py::arg("map"), py::arg("camera"), py::arg("camera_pose"), py::arg("score_width") = 48,
        py::arg("score_height") = 36,
        "(void cells, unknown cells) a camera at camera_pose (4x4) sees before the first occupied cell,\n"
        "casting a score_width x score_height grid of rays.");

  m.def("view_gains", [](const ExplorationMap& map, const py::object& camera, const py::object& pose, int sw, int sh,
                         const py::object& pass_probability) {
          CameraIntrinsics c = intrinsics_from(camera);
          Pose T = pose_from(pose, "camera_pose");
          double p = map.pass_probability(), pv = map.void_pass_probability();
          const bool learned = pass_probability.is_none();
          if (!learned) p = pv = cast_arg<double>(pass_probability, "pass_probability", "a float in [0, 1] or None");
          ViewGains v;
          {
            py::gil_scoped_release release;
            v = view_gains(map, c, T, sw, sh, p, pv, learned);
          }
          py::dict d;
          gains_into(d, v);
          d["pass_probability"] = p;
          d["void_pass_probability"] = pv;
          return d;
        }, py::arg("map"), py::arg("camera"), py::arg("camera_pose"), py::arg("score_width") = 48,
        py::arg("score_height") = 36, py::arg("pass_probability") = py::none(),
        "What a camera at camera_pose (4x4) is expected to see under the visibility model (a ray's weight\n"
        "starts at 1 and is multiplied by pass_probability after each unknown cell; None: the map's learned\n"
        "values, void_pass_probability for void cells and pass_probability for the others, and its visibility\n"
        "curve learned from the views announced with expect_view): raw distinct void_cells, unknown_cells, frontier_cells and their visibility-weighted\n"
        "expected_void, expected_unknown, expected_frontier.");

  m.def("score_views", [](const ExplorationMap& map, const py::object& camera, const py::object& poses,
                          const py::object& options, bool score_invalid, const py::kwargs& kwargs) {
          CameraIntrinsics c = intrinsics_from(camera);
          std::vector<Pose> T = poses_from(poses, "poses");
          NbvOptions o = options_from<NbvOptions>(options, kwargs, "score_views");
          o.ik.seed = o.seed;
          std::vector<ScoredView> r;
          std::pair<double, double> p{o.unknown_pass_probability, o.unknown_pass_probability};
          {
            py::gil_scoped_release release;
            r = score_views(map, c, T, o, score_invalid);
            if (o.unknown_pass_probability < 0) p = {map.pass_probability(), map.void_pass_probability()};
          }
          return scored_dict(r, o, p);
        }, py::arg("map"), py::arg("camera"), py::arg("poses"), py::arg("options") = py::none(), py::kw_only(),
        py::arg("score_invalid").noconvert() = true,
        "Gains and validity of given camera poses (N, 4, 4) (camera -> map) with the checks and ray casting\n"
        "of next_best_view (same options: workspace_*, capability_map, chain, chain_base, arm_collisions,\n"
        "min_distance, unknown_is_obstacle, unknown_margin, gain, unknown_pass_probability, score_*).\n"
        "Returns a dict of per-pose arrays: valid (N,) bool, status (list of 'valid', 'outside_workspace',\n"
        "'not_reachable', 'camera_not_clear', 'no_ik', 'arm_collision'), pose (N, 4, 4: the pose the arm\n"
        "reaches when IK succeeds, else the given one), q ((N, dof), NaN rows without a solution; None\n"
        "without a chain), void_cells, unknown_cells, frontier_cells (N,) int, expected_void,\n"
        "expected_unknown, expected_frontier, expected_gain (N,) float; gain (its name), pass_probability and\n"
        "void_pass_probability. score_invalid=False: poses that fail a check are not ray cast (cell counts 0,\n"
        "expected gains NaN), far less work when most fail.");

  m.def("expect_view", [](ExplorationMap& map, const py::object& camera, const py::object& pose,
                          const py::object& options, const py::kwargs& kwargs) {
          CameraIntrinsics c = intrinsics_from(camera);
          Pose T = pose_from(pose, "camera_pose");
          NbvOptions o = options_from<NbvOptions>(options, kwargs, "expect_view");
          py::gil_scoped_release release;
          expect_view(map, c, T, o);
        }, py::arg("map"), py::arg("camera"), py::arg("camera_pose"), py::arg("options") = py::none(),
        "Announces the view (4x4 camera -> map) the map's next insert comes from: the unknown cells it is\n"
        "expected to see (score_width x score_height rays, unknown_pass_probability as in next_best_view)\n"
        "are recorded with their ray weights w, and the next insert multiplies the seeability of each one it\n"
        "leaves unknown by (1 - w). Later view scores count unknown cells with w * seeability.");
  m.def("exposed_cells", [](const ExplorationMap& map, const py::array_t<std::uint64_t>& keys) {
          const std::vector<CellKey> k(keys.data(), keys.data() + keys.size());
          std::vector<bool> e;
          {
            py::gil_scoped_release release;
            e = exposed_cells(map, k);
          }
          py::array_t<bool> out(static_cast<py::ssize_t>(e.size()));
          std::copy(e.begin(), e.end(), out.mutable_data());
          return out;
        }, py::arg("map"), py::arg("keys"),
        "(N,) bools: each cell (keys (N,) uint64) has an observed free cell among its 26 neighbours (the\n"
        "exposure NbvOptions.unexposed_weight weighs).");
  m.def("void_enclosure", [](const ExplorationMap& map, double range) {
          std::vector<std::pair<CellKey, double>> e;
          {
            py::gil_scoped_release release;
            e = void_enclosure(map, range);
          }
          std::vector<CellKey> keys(e.size());
          py::array_t<double> enc(static_cast<py::ssize_t>(e.size()));
          for (std::size_t i = 0; i < e.size(); ++i) {
            keys[i] = e[i].first;
            enc.mutable_data()[i] = e[i].second;
          }
          return py::make_tuple(key_array(keys), enc);
        }, py::arg("map"), py::arg("range") = 0.5,
        "How enclosed each void cell is, as next_best_view's enclosure_power weighs it: (keys (N,) uint64\n"
        "sorted as map.void_keys(), enclosure (N,) in [0, 1]): the share of the six axis directions that, walking\n"
        "from the cell through unknown cells up to `range` metres, meet an occupied cell (1) rather than a\n"
        "free one (0; unknown all the way: 1/2).");
  m.def("missed_cells", [](const ExplorationMap& map) { return missed_cells(map); }, py::arg("map"),
        "Unknown cells whose seeability a missed view (expect_view) has lowered.");

  m.def("visibility_curve", [](const ExplorationMap& map) {
          const VisibilityCurveTable t = visibility_curve(map);
          py::dict d;
          const char* names[2] = {"unknown", "void"};
          for (int c = 0; c < 2; ++c) {
            d[(std::string(names[c]) + "_expected").c_str()] = py::array_t<double>(t.expected[c].size(), t.expected[c].data());
            d[(std::string(names[c]) + "_seen").c_str()] = py::array_t<double>(t.seen[c].size(), t.seen[c].data());
            d[(std::string(names[c]) + "_share").c_str()] = py::array_t<double>(t.share[c].size(), t.share[c].data());
          }
          return d;
        }, py::arg("map"),
        "The visibility curve the map learned from the views announced with expect_view: per unknown depth d\n"
        "(index; the last holds deeper cells), for unknown cells outside the voids ('unknown_*') and void cells\n"
        "('void_*'), the cells views expected (weighted by seeability), the cells their inserts turned known and\n"
        "the learned non-increasing share.");

  m.def("accumulate_utility", [](const ExplorationMap& map, double range) {
          std::vector<std::pair<CellKey, double>> u;
          {
            py::gil_scoped_release release;
            u = accumulate_utility(map, range);
          }
          std::vector<CellKey> keys;
          py::array_t<double> val(static_cast<py::ssize_t>(u.size()));
          for (std::size_t i = 0; i < u.size(); ++i) {
            keys.push_back(u[i].first);
            val.mutable_data()[i] = u[i].second;
          }
          return py::make_tuple(centers(map, keys), val);
        }, py::arg("map"), py::arg("sensor_range"),
        "Algorithm 1: (cell centres (N, 3), accumulated utility (N,), m^3) before workspace pruning.");

  m.def("next_best_view", [](const ExplorationMap& map, const py::object& camera, const py::object& options,
                             const py::kwargs& kwargs) {
          CameraIntrinsics c = intrinsics_from(camera);
          NbvOptions o = options_from<NbvOptions>(options, kwargs, "next_best_view");
          o.ik.seed = o.seed;  // the Python API has one seed for the samples and the IK restarts
          NbvResult r;
          {
            py::gil_scoped_release release;
            r = next_best_view(map, c, o);
          }
          return result_dict(r);
        }, py::arg("map"), py::arg("camera"), py::arg("options") = py::none(),
        "Next best view (Algorithm 1 + frustum scoring). Options: an NbvOptions and/or its attributes as\n"
        "keyword arguments. Returns a dict: best_pose (4x4 camera -> map, or None); of the best view:\n"
        "void_cells, unknown_cells, frontier_cells (raw distinct cells met), expected_void,\n"
        "expected_unknown, expected_frontier (visibility-weighted), expected_gain (of `gain`), utility_dm3\n"
        "(expected_void as dm^3); pass_probability, void_pass_probability (the p used); ranked (valid poses, best first, each with\n"
        "pose, the same gains, gain, utility_dm3, cell_utility, q), and search statistics. The workspace is\n"
        "workspace_box ((2, 3): lo, hi), workspace_sphere ((center, radius)) and/or workspace, a callable\n"
        "taking cell centres (N, 3) and returning (N,) bools. With chain (its tip is the camera frame,\n"
        "+z forward) and chain_base (4x4 chain base -> map), a pose counts only if IK reaches it.\n"
        "capability_map (a CapabilityMap of that arm) with capability_base (4x4 map base link -> map) prunes\n"
        "candidate cells whose voxel has reachability index <= min_reachability before any IK, and with\n"
        "capability_orientations skips IK for sampled poses whose (voxel, optical axis) cell it marks unreachable.\n"
        "arm_collisions (with chain): IK solutions whose links touch an occupied cell are rejected.");
}

}  // namespace octoreach::py_bindings
