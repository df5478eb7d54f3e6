#include "common.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_core, m) {
  m.doc() = "octoreach compiled core: robot model, IK, collision, reachability maps, exploration";
  m.attr("__version__") = octoreach::version();
  py::register_exception<octoreach::Cancelled>(m, "Cancelled", PyExc_KeyboardInterrupt);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const octoreach::FileError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  octoreach::py_bindings::wrap_progress(m);
  octoreach::py_bindings::wrap_obstacles(m);
  octoreach::py_bindings::wrap_chain(m);
  octoreach::py_bindings::wrap_robot(m);
  octoreach::py_bindings::wrap_orientation_set(m);
  octoreach::py_bindings::wrap_arm(m);
  octoreach::py_bindings::wrap_capability_map(m);
  octoreach::py_bindings::wrap_point_map(m);
  octoreach::py_bindings::wrap_surface(m);
  octoreach::py_bindings::wrap_surface_map(m);
  octoreach::py_bindings::wrap_pose_sampler(m);
  octoreach::py_bindings::wrap_simulation(m);
  octoreach::py_bindings::wrap_exploration_map(m);
  octoreach::py_bindings::wrap_next_best_view(m);
}
