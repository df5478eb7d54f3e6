// Capability maps, inverse point maps and surface maps (filled in by the map work).
#include "common.hpp"

namespace octoreach::py_bindings {
void wrap_maps(py::module_&) {}
}  // namespace octoreach::py_bindings
