// Next-best-view results bound as read-only classes, with the same field names everywhere: the gains of a
// view (ViewGains), a scored pose (ViewCandidate, ScoredView), the answers of view_gains (ViewGainsResult),
// score_views (ScoredViews: per-pose arrays, and the poses one by one) and next_best_view (NbvResult).
// to_dict() gives every field as a dict.
#include <cmath>
#include <cstdint>
#include <string>

#include "exploration/next_best_view.hpp"
#include "octoreach/next_best_view.hpp"

namespace octoreach::py_bindings {

namespace {

py::object plain(const py::handle& v);

// Every property of `self`'s class and of its bases (bases first, each in the order it was bound) as a dict;
// results inside (a view, a list of views) become dicts too.
py::dict fields_dict(const py::object& self) {
  py::dict d;
  const py::tuple mro = py::type::of(self).attr("__mro__");
  const py::handle property = reinterpret_cast<PyObject*>(&PyProperty_Type);
  for (std::size_t i = mro.size(); i-- > 0;)
    for (auto item : mro[i].attr("__dict__").attr("items")()) {
      const auto kv = item.cast<py::tuple>();
      const std::string name = py::str(kv[0]);
      if (name.empty() || name[0] == '_' || !py::isinstance(kv[1], property)) continue;
      d[name.c_str()] = plain(self.attr(name.c_str()));
    }
  return d;
}

py::object plain(const py::handle& v) {
  if (py::isinstance<py::list>(v)) {
    py::list out;
    for (auto x : v) out.append(plain(x));
    return std::move(out);
  }
  if (!v.is_none() && py::hasattr(v, "to_dict")) return v.attr("to_dict")();
  return py::reinterpret_borrow<py::object>(v);
}

const char* kToDict = "Every field as a dict (views inside as dicts too).";

py::object joints(const Eigen::VectorXd& q) { return q.size() ? py::object(py::cast(q)) : py::object(py::none()); }

// best_by of a result (ScoredViews, NbvResult): its best view by the key named `by`, or None.
template <class Result>
py::object best_by(const Result& r, const std::string& by) {
  const auto* v = r.best(rank_key_from_name(by));
  return v ? py::cast(*v) : py::object(py::none());
}

void wrap_view(py::module_& m) {
  py::class_<ViewGains>(m, "ViewGains", "What a camera pose is expected to see (the visibility model of next_best_view).")
      .def_readonly("void_cells", &ViewGains::void_cells, "distinct void cells met before the first occupied cell (raw)")
      .def_readonly("unknown_cells", &ViewGains::unknown_cells,
                    "distinct unknown cells of the search space met (void cells included; raw)")
      .def_readonly("frontier_cells", &ViewGains::frontier_cells, "distinct frontier cells met (raw)")
      .def_readonly("expected_void", &ViewGains::expected_void, "void cells weighted by their expected visibility")
      .def_readonly("expected_unknown", &ViewGains::expected_unknown,
                    "unknown cells of the search space weighted likewise, each outside the voids also by the chance "
                    "that its ray returns at or behind it (1 when it ends on an occupied cell)")
      .def_readonly("expected_frontier", &ViewGains::expected_frontier, "frontier cells weighted likewise")
      .def_readonly("expected_enclosed_void", &ViewGains::expected_enclosed_void,
                    "expected_void with each void cell weighted by enclosure_power and unexposed_weight")
      .def("to_dict", &fields_dict, kToDict);
  py::class_<ViewGainsResult, ViewGains>(m, "ViewGainsResult", "view_gains' answer: the gains and the p it used.")
      .def_readonly("pass_probability", &ViewGainsResult::pass_probability, "p for unknown cells outside the voids")
      .def_readonly("void_pass_probability", &ViewGainsResult::void_pass_probability, "p for void cells");
  py::class_<ViewCandidate, ViewGains>(m, "ViewCandidate", "A scored camera pose (a view of next_best_view).")
      .def_property_readonly("pose", [](const ViewCandidate& v) { return pose_to_array(v.pose); }, "4x4 camera -> map")
      .def_readonly("expected_gain", &ViewCandidate::expected_gain, "the expected gain of `gain` (the ranking key)")
      .def_readonly("utility_dm3", &ViewCandidate::utility_dm3, "expected_void as a volume, dm^3")
      .def_readonly("cell_utility", &ViewCandidate::cell_utility,
                    "accumulated utility at the pose's candidate cell (m^3; 0 for given poses)")
      .def_property_readonly("q", [](const ViewCandidate& v) { return joints(v.q); },
                             "arm joints (with a chain and an IK solution), else None");
  py::class_<ScoredView, ViewCandidate>(m, "ScoredView", "One pose scored by score_views, with its status.")
      .def_property_readonly("status", [](const ScoredView& v) { return status_name(v.status); },
                             "'valid', 'outside_workspace', 'not_reachable', 'camera_not_clear', 'no_ik' or 'arm_collision'")
      .def_property_readonly("valid", &ScoredView::valid, "status == 'valid'");
}

// One value per view of `s` as an (N,) array.
template <class T, class F>
py::array_t<T> per_view(const ScoredViews& s, F f) {
  py::array_t<T> a(static_cast<py::ssize_t>(s.views.size()));
  for (std::size_t i = 0; i < s.views.size(); ++i) a.mutable_data()[i] = T(f(s.views[i]));
  return a;
}

py::object joint_rows(const ScoredViews& s) {
  if (!s.dof) return py::none();
  const py::ssize_t n = py::ssize_t(s.views.size()), dof = py::ssize_t(s.dof);
  py::array_t<double> q({n, dof});
  for (py::ssize_t i = 0; i < n; ++i)
    for (py::ssize_t j = 0; j < dof; ++j) {
      const Eigen::VectorXd& v = s.views[std::size_t(i)].q;
      q.mutable_data()[i * dof + j] = v.size() == dof ? v[j] : std::nan("");
    }
  return std::move(q);
}

void wrap_scored_views(py::module_& m) {
  using S = ScoredViews;
  using V = ScoredView;
  py::class_<S>(m, "ScoredViews",
                "score_views' answer: per-pose arrays (the fields of ScoredView), and the poses one by one\n"
                "(len, [i], iteration); `best_by` picks the first valid view in the ranking order.")
      .def("__len__", [](const S& s) { return s.views.size(); })
      .def("__getitem__", [](const S& s, py::ssize_t i) {
             const py::ssize_t n = py::ssize_t(s.views.size());
             if (i < -n || i >= n) throw py::index_error("view index " + std::to_string(i) + " out of range");
             return s.views[std::size_t(i < 0 ? i + n : i)];
           }, py::arg("index"))
      .def("__iter__", [](const S& s) { return py::make_iterator(s.views.begin(), s.views.end()); },
           py::keep_alive<0, 1>())
      .def_property_readonly("valid", [](const S& s) { return per_view<bool>(s, [](const V& v) { return v.valid(); }); })
      .def_property_readonly("status", [](const S& s) {
             py::list l;
             for (const V& v : s.views) l.append(status_name(v.status));
             return l;
           }, "list of 'valid', 'outside_workspace', 'not_reachable', 'camera_not_clear', 'no_ik', 'arm_collision'")
      .def_property_readonly("pose", [](const S& s) {
             std::vector<Pose> T;
             for (const V& v : s.views) T.push_back(v.pose);
             return poses_to_array(T);
           }, "(N, 4, 4): the pose the arm reaches when IK succeeds, else the given one")
      .def_property_readonly("q", &joint_rows, "(N, dof) joints, NaN rows without a solution; None without a chain")
      .def_property_readonly("void_cells", [](const S& s) { return per_view<std::int64_t>(s, [](const V& v) { return v.void_cells; }); })
      .def_property_readonly("unknown_cells", [](const S& s) { return per_view<std::int64_t>(s, [](const V& v) { return v.unknown_cells; }); })
      .def_property_readonly("frontier_cells", [](const S& s) { return per_view<std::int64_t>(s, [](const V& v) { return v.frontier_cells; }); })
      .def_property_readonly("expected_void", [](const S& s) { return per_view<double>(s, [](const V& v) { return v.expected_void; }); })
      .def_property_readonly("expected_unknown", [](const S& s) { return per_view<double>(s, [](const V& v) { return v.expected_unknown; }); })
      .def_property_readonly("expected_frontier", [](const S& s) { return per_view<double>(s, [](const V& v) { return v.expected_frontier; }); })
      .def_property_readonly("expected_enclosed_void", [](const S& s) { return per_view<double>(s, [](const V& v) { return v.expected_enclosed_void; }); })
      .def_property_readonly("expected_gain", [](const S& s) { return per_view<double>(s, [](const V& v) { return v.expected_gain; }); },
                             "(N,) the expected gain of `gain` (NaN for invalid poses with score_invalid=False)")
      .def_property_readonly("utility_dm3", [](const S& s) { return per_view<double>(s, [](const V& v) { return v.utility_dm3; }); })
      .def_property_readonly("gain", [](const S& s) { return gain_name(s.gain); }, "the gain expected_gain is of")
      .def_readonly("pass_probability", &S::pass_probability, "p the model used for unknown cells outside the voids")
      .def_readonly("void_pass_probability", &S::void_pass_probability, "p it used for void cells")
      .def("best_by", &best_by<S>, py::arg("by") = "expected_gain",
           "The first valid view in the ranking order by `by` ('expected_gain' or 'expected_void'), then expected\n"
           "unknown cells; None when no view is valid.")
      .def("to_dict", &fields_dict, kToDict);
}

void wrap_nbv_result(py::module_& m) {
  using R = NbvResult;
  // the best view's figures (0 and None when there is none)
  const auto best = [](const R& r) -> const ViewCandidate& {
    static const ViewCandidate none;
    return r.ranked.empty() ? none : r.ranked.front();
  };
  py::class_<R>(m, "NbvResult",
                "next_best_view's answer: the valid poses ranked (best first), the best one's figures and the\n"
                "search's statistics.")
      .def_readonly("ranked", &R::ranked, "valid views (ViewCandidate), best first (with rescore_best: those scored in full)")
      .def_property_readonly("best", [](const R& r) { return r.ranked.empty() ? py::object(py::none()) : py::cast(r.ranked.front()); },
                             "the best view, or None")
      .def_property_readonly("best_pose", [](const R& r) {
             return r.ranked.empty() ? py::object(py::none()) : py::object(pose_to_array(r.ranked.front().pose));
           }, "4x4 camera -> map of the best view, or None")
      .def_property_readonly("void_cells", [best](const R& r) { return best(r).void_cells; }, "of the best view")
      .def_property_readonly("unknown_cells", [best](const R& r) { return best(r).unknown_cells; }, "of the best view")
      .def_property_readonly("frontier_cells", [best](const R& r) { return best(r).frontier_cells; }, "of the best view")
      .def_property_readonly("expected_void", [best](const R& r) { return best(r).expected_void; }, "of the best view")
      .def_property_readonly("expected_unknown", [best](const R& r) { return best(r).expected_unknown; }, "of the best view")
      .def_property_readonly("expected_frontier", [best](const R& r) { return best(r).expected_frontier; }, "of the best view")
      .def_property_readonly("expected_enclosed_void", [best](const R& r) { return best(r).expected_enclosed_void; },
                             "of the best view")
      .def_property_readonly("expected_gain", &R::best_gain, "of the best view: its expected gain of `gain`")
      .def_property_readonly("utility_dm3", &R::best_utility_dm3, "of the best view: expected_void as dm^3")
      .def_property_readonly("gain", [](const R& r) { return gain_name(r.gain); }, "the gain the views are ranked by")
      .def_readonly("pass_probability", &R::pass_probability, "p the model used for unknown cells outside the voids")
      .def_readonly("void_pass_probability", &R::void_pass_probability, "p it used for void cells")
      .def_readonly("utility_vectors", &R::utility_vectors)
      .def_readonly("utility_cells", &R::utility_cells, "cells with utility > 0 in the workspace's box and sphere")
      .def_readonly("candidate_cells", &R::candidate_cells, "after workspace and capability-map pruning")
      .def_readonly("capability_pruned", &R::capability_pruned, "cells the capability map removed")
      .def_readonly("poses_scored", &R::poses_scored)
      .def_readonly("ik_failures", &R::ik_failures)
      .def_readonly("arm_collisions", &R::arm_collisions, "IK solutions whose arm touches an occupied (or unknown) cell")
      .def_readonly("camera_not_clear", &R::camera_not_clear, "cells whose camera is not in observed-free space")
      .def_readonly("capability_rejected", &R::capability_rejected, "sampled poses the capability map ruled out")
      .def_readonly("seconds", &R::seconds)
      .def_readonly("seconds_vectors", &R::seconds_vectors, "steps 1-2")
      .def_readonly("seconds_prune", &R::seconds_prune, "step 3")
      .def_readonly("seconds_score", &R::seconds_score, "step 4")
      .def("best_by", &best_by<R>, py::arg("by") = "expected_gain",
           "The first ranked view by `by` ('expected_gain': `best`; 'expected_void': the most expected void\n"
           "cells), then expected unknown cells; None when there is none.")
      .def("to_dict", &fields_dict, kToDict);
}

}  // namespace

void wrap_nbv_results(py::module_& m) {
  wrap_view(m);
  wrap_scored_views(m);
  wrap_nbv_result(m);
}

}  // namespace octoreach::py_bindings
