#pragma once
// The next-best-view bindings' parts: the options classes (nbv_options.cpp), the result classes
// (nbv_results.cpp) and the functions (next_best_view.cpp, whose wrap_next_best_view binds all three).
#include "common.hpp"

namespace octoreach::py_bindings {

/// NbvOptions (with its exploration_loop preset) and ExploreOptions, defaults from the C++ structs.
void wrap_nbv_options(py::module_& m);
/// ViewGains, ViewGainsResult, ViewCandidate, ScoredView, ScoredViews and NbvResult: read-only, to_dict().
void wrap_nbv_results(py::module_& m);

}  // namespace octoreach::py_bindings
