// Progress of long calls: the Python package registers how `progress=True` is drawn.
#include "common.hpp"

namespace octoreach::py_bindings {
namespace {

// Leaked on purpose: a py::object destroyed after the interpreter is gone would crash at exit.
py::object& factory() {
  static py::object* f = new py::object();
  return *f;
}

}  // namespace

ProgressCallback progress_arg(const py::object& progress, const char* label) {
  if (factory() && !factory().is_none()) return progress_from(factory()(progress, label));
  if (progress.is_none() || py::isinstance<py::bool_>(progress)) return nullptr;
  if (PyCallable_Check(progress.ptr())) return progress_from(progress);
  throw py::type_error("progress must be True, False or a callable (done, total), got " + type_name(progress));
}

void wrap_progress(py::module_& m) {
  m.def("set_progress_factory", [](const py::object& f) { factory() = f; }, py::arg("factory"),
        "Registers factory(progress, label) -> callable (done, total) or None, used for progress=True and\n"
        "callables; octoreach/__init__.py registers octoreach.progress.make_progress. None unregisters.");
}

}  // namespace octoreach::py_bindings
