// Next-best-view functions: next_best_view, score_views, view_gains and the parts of the search and the
// visibility model (accumulate_utility, view_utility, expect_view, void_enclosure, exposed_cells,
// visibility_curve); their options and results are bound classes (nbv_options.cpp, nbv_results.cpp).
#include <algorithm>
#include <optional>

#include "exploration/convert.hpp"
#include "exploration/next_best_view.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::py_bindings {

namespace {

// (cell, value) pairs as their keys and an (N,) array of the values.
std::pair<std::vector<CellKey>, py::array_t<double>> split_keyed(const std::vector<std::pair<CellKey, double>>& kv) {
  std::vector<CellKey> keys(kv.size());
  py::array_t<double> values(static_cast<py::ssize_t>(kv.size()));
  for (std::size_t i = 0; i < kv.size(); ++i) {
    keys[i] = kv[i].first;
    values.mutable_data()[i] = kv[i].second;
  }
  return {std::move(keys), std::move(values)};
}

// The search and the scores of views: view_utility, view_gains, score_views, accumulate_utility and
// next_best_view.
void wrap_search(py::module_& m) {
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
          std::optional<double> p;
          if (!pass_probability.is_none())
            p = cast_arg<double>(pass_probability, "pass_probability", "a float in [0, 1] or None");
          py::gil_scoped_release release;
          return view_gains(map, c, T, sw, sh, p);
        }, py::arg("map"), py::arg("camera"), py::arg("camera_pose"), py::arg("score_width") = 48,
        py::arg("score_height") = 36, py::arg("pass_probability") = py::none(),
        "What a camera at camera_pose (4x4) is expected to see under the visibility model (a ray's weight\n"
        "starts at 1 and is multiplied by pass_probability after each unknown cell, and a cell counts with\n"
        "the chance that its ray returns at or behind it: 1 in front of an occupied cell, else 1 minus the\n"
        "product of the pass probabilities of the unknown cells from there on; None: the map's learned\n"
        "values, void_pass_probability for void cells and pass_probability for the others, and its visibility\n"
        "curve learned from the views announced with expect_view): a ViewGainsResult (the raw distinct\n"
        "void_cells, unknown_cells, frontier_cells, their visibility-weighted expected_void, expected_unknown,\n"
        "expected_frontier, expected_enclosed_void, and the pass probabilities used).");

  m.def("score_views", [](const ExplorationMap& map, const py::object& camera, const py::object& poses,
                          const py::object& options, bool score_invalid, const py::kwargs& kwargs) {
          CameraIntrinsics c = intrinsics_from(camera);
          std::vector<Pose> T = poses_from(poses, "poses");
          NbvOptions o = options_from<NbvOptions>(options, kwargs, "score_views");
          o.ik.seed = o.seed;
          py::gil_scoped_release release;
          return score_views(map, c, T, o, score_invalid);
        }, py::arg("map"), py::arg("camera"), py::arg("poses"), py::arg("options") = py::none(), py::kw_only(),
        py::arg("score_invalid").noconvert() = true,
        "Gains and validity of given camera poses (N, 4, 4) (camera -> map) with the checks and ray casting\n"
        "of next_best_view (same options: workspace_*, capability_map, chain, chain_base, arm_collisions,\n"
        "min_distance, unknown_is_obstacle, unknown_margin, gain, unknown_pass_probability, score_*).\n"
        "A chain that can only aim its camera (aiming 'look_at', or 'auto' and fewer than 5 joints: a pan/tilt\n"
        "head) aims it at the point half the camera's range along each pose's optical axis, and the checks and\n"
        "gains are of the pose it reaches, which pose and q hold whenever the aim succeeds (status no_ik when\n"
        "it cannot aim there).\n"
        "Returns ScoredViews: per-pose arrays valid, status, pose (the pose the arm reaches when IK succeeds,\n"
        "else the given one), q, the gains and expected_gain (of `gain`), and the poses one by one as\n"
        "ScoredView. score_invalid=False: poses that fail a check are not ray cast (cell counts 0, expected\n"
        "gains NaN), far less work when most fail.");

  m.def("ranks_before", [](const ViewCandidate& a, const ViewCandidate& b, const std::string& by) {
          return ranks_before(a, b, rank_key_from_name(by));
        }, py::arg("a"), py::arg("b"), py::arg("by") = "expected_gain",
        "True when view a ranks before view b in the one order of views: more of `by` ('expected_gain' or\n"
        "'expected_void'), then more expected unknown cells (next_best_view's ranking, best_by's choice).");

  m.def("accumulate_utility", [](const ExplorationMap& map, double range) {
          std::vector<std::pair<CellKey, double>> u;
          {
            py::gil_scoped_release release;
            u = accumulate_utility(map, range);
          }
          auto [keys, values] = split_keyed(u);
          return py::make_tuple(centers(map, keys), values);
        }, py::arg("map"), py::arg("sensor_range"),
        "Algorithm 1: (cell centres (N, 3), accumulated utility (N,), m^3) before workspace pruning.");

  m.def("next_best_view", [](const ExplorationMap& map, const py::object& camera, const py::object& options,
                             const py::kwargs& kwargs) {
          CameraIntrinsics c = intrinsics_from(camera);
          NbvOptions o = options_from<NbvOptions>(options, kwargs, "next_best_view");
          o.ik.seed = o.seed;  // the Python API has one seed for the samples and the IK restarts
          py::gil_scoped_release release;
          return next_best_view(map, c, o);
        }, py::arg("map"), py::arg("camera"), py::arg("options") = py::none(),
        "Next best view (Algorithm 1 + frustum scoring). Options: an NbvOptions and/or its attributes as\n"
        "keyword arguments. Returns an NbvResult: ranked (the valid views, best first, as ViewCandidate;\n"
        "with rescore_best, those scored in full), best and best_pose (4x4 camera -> map, or None), the best\n"
        "view's gains, expected_gain (of `gain`) and utility_dm3, the pass probabilities used and the\n"
        "search's statistics. The workspace is\n"
        "workspace_box ((2, 3): lo, hi), workspace_sphere ((center, radius)) and/or workspace, a callable\n"
        "taking cell centres (N, 3) and returning (N,) bools. With chain (its tip is the camera frame,\n"
        "+z forward) and chain_base (4x4 chain base -> map), a pose counts only if IK reaches it.\n"
        "capability_map (a CapabilityMap of that arm) with capability_base (4x4 map base link -> map) prunes\n"
        "candidate cells where each of the 8 voxels around them has reachability index <= min_reachability before\n"
        "any IK, and with capability_orientations skips IK for sampled poses whose optical axis none of the 8 cells\n"
        "around them reaches (CapabilityLookup.any: the map says no only where it is sure).\n"
        "arm_collisions (with chain): IK solutions whose links touch an occupied cell are rejected.");
}

// The visibility model's memory (expect_view, missed_cells, visibility_curve) and the void weights
// (void_enclosure, exposed_cells).
void wrap_visibility_model(py::module_& m) {
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
        "leaves unknown by (1 - w). Later view scores count unknown cells with w * seeability; a void cell\n"
        "its rays still meet after the insert with no surface behind it within range (they ended on nothing)\n"
        "counts 0 in views from an eye within the angle one cell spans from this one and no nearer.");
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
          auto [keys, values] = split_keyed(e);
          return py::make_tuple(key_array(keys), values);
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
}

}  // namespace

void wrap_next_best_view(py::module_& m) {
  wrap_nbv_options(m);
  wrap_nbv_results(m);
  wrap_search(m);
  wrap_visibility_model(m);
}

}  // namespace octoreach::py_bindings
