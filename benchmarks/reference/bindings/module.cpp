// octoreach_bench: reference implementations that benchmarks and tests measure octoreach against
// (plain KDL IK/FK, stock OctoMap insertion). Not part of the library or its wheel: built from source
// beside the C++ tests, linking no octoreach code (it reads a Chain's description through Python).
#include "common.hpp"

namespace octoreach::py_bindings {
void wrap_kdl_reference(py::module_& m);
void wrap_stock_insert(py::module_& m);
}  // namespace octoreach::py_bindings

PYBIND11_MODULE(octoreach_bench, m) {
  m.doc() = "octoreach benchmark references (plain KDL solvers, stock OctoMap insertion); not a public API";
  octoreach::py_bindings::wrap_kdl_reference(m);
  octoreach::py_bindings::wrap_stock_insert(m);
}
