// Plain-KDL reference solvers, bound for benchmarks/ik.py (filled in by the IK benchmark work).
#include "common.hpp"

namespace octoreach::py_bindings {
void wrap_kdl_reference(py::module_&) {}
}  // namespace octoreach::py_bindings
