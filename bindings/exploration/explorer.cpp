// The exploration session: ExplorerSetup is built from keywords, NextView is read-only (explorer.hpp).
#include "exploration/convert.hpp"
#include "exploration/next_best_view.hpp"
#include "octoreach/explorer.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::py_bindings {

namespace {

py::object joint_values(const Eigen::VectorXd& q) { return q.size() ? py::object(py::cast(q)) : py::object(py::none()); }

ExplorerSetup setup_from(const py::object& camera, const py::object& search_space, const py::object& bases,
                         double reach, const py::object& resolution, const py::object& void_fit_threshold,
                         const py::object& options, const std::string& strategy) {
  ExplorerSetup s;
  s.camera = intrinsics_from(camera);
  if (!bases.is_none()) s.bases = poses_from(bases, "bases");
  s.reach = reach;  // the values are checked by Explorer
  if (!resolution.is_none()) s.resolution = cast_arg<double>(resolution, "resolution", "a number of metres");
  if (!void_fit_threshold.is_none())
    s.void_fit_threshold = cast_arg<double>(void_fit_threshold, "void_fit_threshold", "a number");
  if (!options.is_none()) {
    if (!py::isinstance<ExploreOptions>(options))
      throw py::type_error("options must be an ExploreOptions or None, got " + type_name(options));
    s.options = options.cast<ExploreOptions>();
  }
  s.strategy = strategy_from_name(strategy);
  // The search space last: every other argument's wrong type is named before a shape is checked.
  s.search_space = box_from(search_space, "search_space");
  return s;
}

}  // namespace

void wrap_explorer(py::module_& m) {
  py::class_<NextView>(m, "NextView", "Explorer.next_view()'s answer: the view to take next, or why to stop.")
      .def_readonly("stop", &NextView::stop)
      .def_readonly("stop_reason", &NextView::stop_reason)
      .def_property_readonly("camera_pose", [](const NextView& v) { return pose_to_array(v.camera_pose); },
                             "4x4 camera -> map")
      .def_property_readonly("q", [](const NextView& v) { return joint_values(v.q); }, "chain joints, or None")
      .def_readonly("base", &NextView::base, "index of the base pose to drive to")
      .def_property_readonly("base_pose", [](const NextView& v) { return pose_to_array(v.base_pose); })
      .def_readonly("expected_gain", &NextView::expected_gain, "what the stop rule looks at (expected void cells)")
      .def_readonly("choice", &NextView::choice, "choose_view's whole answer (ViewChoice)");
  py::class_<Explorer>(m, "ExplorerCore",
                       "An exploration session (octoreach.exploration.Explorer wraps it): the map, the loop's memory,\n"
                       "integrate clouds or depth images, ask for the next view.")
      .def(py::init([](const py::object& camera, const py::object& search_space, const py::object& bases, double reach,
                       const py::object& resolution, const py::object& void_fit_threshold, const py::object& options,
                       const std::string& strategy) {
             return std::make_unique<Explorer>(setup_from(camera, search_space, bases, reach, resolution,
                                                          void_fit_threshold, options, strategy));
           }), py::arg("camera"), py::arg("search_space"), py::arg("bases") = py::none(), py::arg("reach") = 0.0,
           py::arg("resolution") = py::none(), py::arg("void_fit_threshold") = py::none(),
           py::arg("options") = py::none(), py::arg("strategy") = "frontier_void", py::keep_alive<1, 8>())
      .def("integrate", [](Explorer& e, const py::object& points, const py::object& pose) {
             auto pts = points_from(points, "points");
             Pose T = pose_from(pose, "camera_pose");
             InsertStats st;
             {
               py::gil_scoped_release release;
               st = e.integrate(pts, T);
             }
             return stats_dict(st);
           }, py::arg("points"), py::arg("camera_pose"))
      .def("integrate_depth", [](Explorer& e, const py::array_t<float, py::array::c_style | py::array::forcecast>& d,
                                 const py::object& pose) {
             if (d.ndim() != 2)
               throw std::invalid_argument("depth image must be a 2-D (height, width) array, got " +
                                           std::to_string(d.ndim()) + " dimensions");
             std::vector<float> v(d.data(), d.data() + d.size());
             Pose T = pose_from(pose, "camera_pose");
             InsertStats st;
             {
               py::gil_scoped_release release;
               st = e.integrate_depth(v, int(d.shape(1)), int(d.shape(0)), T);
             }
             return stats_dict(st);
           }, py::arg("depth"), py::arg("camera_pose"))
      .def("view_failed", &Explorer::view_failed)
      .def("next_view", &Explorer::next_view, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("map", &Explorer::map, py::return_value_policy::reference_internal)
      .def_property_readonly("memory", [](const Explorer& e) { return e.memory(); })
      .def_property_readonly("views", &Explorer::views)
      .def_property_readonly("current_base", &Explorer::current_base);
}

}  // namespace octoreach::py_bindings
