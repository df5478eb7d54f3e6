#include "common.hpp"

namespace py = pybind11;

namespace {

// The Python side of octoreach::set_cancel_check: long C++ loops poll it about every 100 ms. Signals are
// handled by Python's main thread only, so other threads answer "go on" at once; on the main thread it
// takes the GIL and runs the pending signal handlers: a KeyboardInterrupt (Ctrl-C) cancels the work,
// which then surfaces as octoreach.Cancelled (a KeyboardInterrupt).
unsigned long g_main_thread = 0;

bool python_interrupted() {
  if (PyThread_get_thread_ident() != g_main_thread) return false;
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() == 0) return false;
  PyErr_Clear();
  return true;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "octoreach compiled core: robot model, IK, collision, reachability maps, exploration";
  m.attr("__version__") = octoreach::version();
  m.def("map_format_version", &octoreach::map_format_version,
        "The newest map file format version this library writes and reads (part of a map cache key); older\n"
        "versions are read too, and each map kind writes its own (SurfaceMap.format_version).");
  py::register_exception<octoreach::Cancelled>(m, "Cancelled", PyExc_KeyboardInterrupt);
  g_main_thread = py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  octoreach::set_cancel_check(&python_interrupted);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const octoreach::FileNotFound& e) {
      octoreach::py_bindings::set_error(PyExc_FileNotFoundError, e.what());
    } catch (const octoreach::FileError& e) {
      octoreach::py_bindings::set_error(PyExc_OSError, e.what());
    }
  });
  octoreach::py_bindings::wrap_progress(m);
  octoreach::py_bindings::wrap_shape(m);
  octoreach::py_bindings::wrap_limits(m);
  octoreach::py_bindings::wrap_obstacles(m);
  octoreach::py_bindings::wrap_chain(m);
  octoreach::py_bindings::wrap_robot(m);
  octoreach::py_bindings::wrap_self_collision_report(m);
  octoreach::py_bindings::wrap_orientation_set(m);
  octoreach::py_bindings::wrap_arm(m);
  octoreach::py_bindings::wrap_camera_link(m);
  octoreach::py_bindings::wrap_arm_placement(m);
  octoreach::py_bindings::wrap_arm_report(m);
  octoreach::py_bindings::wrap_map_warnings(m);
  octoreach::py_bindings::wrap_map_files(m);
  octoreach::py_bindings::wrap_capability_map(m);
  octoreach::py_bindings::wrap_certified_lookup(m);
  octoreach::py_bindings::wrap_capability_blocks(m);
  octoreach::py_bindings::wrap_point_map(m);
  octoreach::py_bindings::wrap_surface(m);
  octoreach::py_bindings::wrap_surface_map(m);
  octoreach::py_bindings::wrap_map_room(m);
  octoreach::py_bindings::wrap_pose_sampler(m);
  octoreach::py_bindings::wrap_simulation(m);
  octoreach::py_bindings::wrap_exploration_map(m);
  octoreach::py_bindings::wrap_next_best_view(m);
  octoreach::py_bindings::wrap_view_choice(m);
  octoreach::py_bindings::wrap_explorer(m);
}
