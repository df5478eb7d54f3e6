// The exploration loop's choice of a view: ChoiceMemory, ViewChoice and choose_view (view_choice.hpp).
#include "exploration/convert.hpp"
#include "exploration/next_best_view.hpp"
#include "octoreach/simulation.hpp"
#include "octoreach/view_choice.hpp"

namespace octoreach::py_bindings {

void wrap_view_choice(py::module_& m) {
  py::class_<ChoiceMemory>(m, "ChoiceMemory",
                           "What the exploration loop remembers between choices of a view (plain data, copyable).")
      .def(py::init<>())
      .def_readwrite("choices", &ChoiceMemory::choices, "views chosen so far")
      .def_readwrite("low_views", &ChoiceMemory::low_views,
                     "choices in a row with utility <= min_utility (frontier-void's utility, also where a view "
                     "beyond the voids was taken instead)")
      .def_readwrite("last_void_seen", &ChoiceMemory::last_void_seen,
                     "void cells the last view taken took off the void set (InsertStats void_removed; Explorer "
                     "sets it) or None: for frontier_void and random, a low view that saw more than the stop "
                     "threshold breaks the row of low views (cleared by the next choice)")
      .def_readwrite("last_space_seen", &ChoiceMemory::last_space_seen,
                     "unknown cells of the search space the last view taken made known (InsertStats space_known; "
                     "Explorer sets it) or None: see beyond_misses (cleared by the next choice)")
      .def_readwrite("beyond_misses", &ChoiceMemory::beyond_misses,
                     "frontier_void: views beyond the voids in a row that saw no more than the stop threshold of the "
                     "search space's unknown cells; at patience none is chosen until a view sees more")
      .def_readwrite("last_beyond", &ChoiceMemory::last_beyond, "the last choice was a view beyond the voids")
      .def_property("failed_views", [](const ChoiceMemory& c) { return to_points(c.failed_views); },
                    [](ChoiceMemory& c, const py::object& p) { c.failed_views = points_from(p, "failed_views"); },
                    "(N, 3) cameras of views chosen and not taken: no view is chosen near them again")
      .def("__copy__", [](const ChoiceMemory& c) { return ChoiceMemory(c); });
  py::class_<ViewChoice>(m, "ViewChoice", "choose_view's answer: the view, its utility and the stop decision.")
      .def_readonly("found", &ViewChoice::found, "a valid view was found")
      .def_property_readonly("view", [](const ViewChoice& c) -> py::object {
        return c.found ? py::cast(c.view) : py::object(py::none());
      }, "the view (ViewCandidate: pose, q, gains) or None")
      .def_readonly("base", &ViewChoice::base, "index of the base the view is taken from")
      .def_readonly("utility", &ViewChoice::utility, "the gain the stop rule looks at")
      .def_readonly("candidates", &ViewChoice::candidates, "poses scored")
      .def_readonly("valid", &ViewChoice::valid, "of them valid (with rescore_best, of those an aimed look checked)")
      .def_readonly("aimed", &ViewChoice::aimed, "found by a look aimed at void cells")
      .def_readonly("harder", &ViewChoice::harder, "found by the looks before a low view")
      .def_readonly("beyond", &ViewChoice::beyond,
                    "frontier_void (beyond_voids): a view beyond the voids, expecting the most unknown cells of the "
                    "search space (its expected_unknown is the utility): more than frontier-void's view expects "
                    "void cells, or where frontier-void's own choice would end the loop")
      .def_readonly("stop", &ViewChoice::stop, "the loop ends here")
      .def_readonly("stop_reason", &ViewChoice::stop_reason, "why it ends ('' when it goes on)")
      .def_readonly("search", &ViewChoice::search, "frontier_void: next_best_view's answer from the chosen base");
  m.def("choose_view", [](const ExplorationMap& map, const py::object& camera, const py::object& bases, int current,
                          const ExploreOptions& options, ChoiceMemory& memory, const std::string& strategy,
                          double reach) {
          const CameraIntrinsics c = intrinsics_from(camera);
          ViewSites sites;  // checked by choose_view
          sites.bases = poses_from(bases, "bases");
          sites.reach = reach;
          const ViewStrategy s = strategy_from_name(strategy);
          ExploreOptions o = options;
          o.search.ik.seed = o.search.seed;
          py::gil_scoped_release release;
          return choose_view(map, c, sites, current, o, memory, s);
        }, py::arg("map"), py::arg("camera"), py::arg("bases"), py::arg("current"), py::arg("options"),
        py::arg("memory"), py::arg("strategy") = "frontier_void", py::arg("reach") = 0.0,
        "The exploration loop's whole choice of the next view from any of `bases` ((N, 4, 4) chain base -> map;\n"
        "the current one first): the search, the second looks, the last chance and the stop decision, with\n"
        "options (ExploreOptions; its search's chain carries the camera). `reach` (m, with a chain and no\n"
        "workspace): the camera stays that near each base. Updates `memory` (ChoiceMemory). Returns ViewChoice.");
}

}  // namespace octoreach::py_bindings
