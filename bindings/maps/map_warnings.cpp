// MapWarning: the category of the one line a map build emits when its result looks suspicious.
#include "common.hpp"

namespace octoreach::py_bindings {

namespace {
PyObject* g_map_warning = nullptr;  // octoreach._core.MapWarning, owned by the module
}  // namespace

void warn_map(const std::string& message) {
  if (message.empty() || !g_map_warning) return;
  if (PyErr_WarnEx(g_map_warning, message.c_str(), 1) < 0) throw py::error_already_set();  // a filter made it an error
}

void wrap_map_warnings(py::module_& m) {
  g_map_warning = PyErr_NewExceptionWithDoc(
      "octoreach._core.MapWarning",
      "A map build whose result looks suspicious (a capability map whose best voxel reaches few directions, a\n"
      "surface at the edge of the arm's reach): the message says why and what to try.",
      PyExc_UserWarning, nullptr);
  if (!g_map_warning) throw py::error_already_set();
  m.attr("MapWarning") = py::handle(g_map_warning);
}

}  // namespace octoreach::py_bindings
