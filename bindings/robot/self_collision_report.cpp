// SelfCollisionReport: how often random configurations put a robot in self-collision, and which pairs.
#include "common.hpp"
#include "octoreach/self_collision_report.hpp"
#include "robot/robot_args.hpp"

namespace octoreach::py_bindings {

void wrap_self_collision_report(py::module_& m) {
  {
    using O = SelfCollisionOptions;
    py::class_<O>(m, "SelfCollisionOptions", "What self_collision_report samples (defaults defined once, in C++).")
        .def(py::init<>())
        .def_readwrite("samples", &O::samples, "Random configurations.")
        .def_readwrite("seed", &O::seed)
        .def_readwrite("threads", &O::threads, "0: every core.")
        .def_readwrite("joints", &O::joints, "Joints drawn at random (names; empty: every joint).")
        .def_readwrite("reference", &O::reference, "Values of the joints not drawn (empty: home()).")
        .def_readwrite("links", &O::links, "Only the checked pairs of two of these links count (empty: every pair).");
  }
  py::class_<PairHits>(m, "PairHits", "A checked link pair and the sampled configurations that put it in collision.")
      .def_readonly("link_a", &PairHits::link_a)
      .def_readonly("link_b", &PairHits::link_b)
      .def_readonly("hits", &PairHits::hits)
      .def("__repr__", [](const PairHits& p) {
        return "<octoreach.PairHits " + p.link_a + " / " + p.link_b + ": " + std::to_string(p.hits) + ">";
      });
  py::class_<SelfCollisionReport> cls(m, "SelfCollisionReport",
                                      "Random configurations free of self-collision and the pairs that collide, most often first.");
  cls.attr("FREE_SHARE_HINT") = kFreeShareHint;  // the hint's threshold (self_collision_report.hpp)
  cls.def_readonly("samples", &SelfCollisionReport::samples)
      .def_readonly("free", &SelfCollisionReport::free)
      .def_readonly("pairs", &SelfCollisionReport::pairs)
      .def_property_readonly("free_share", &SelfCollisionReport::free_share)
      .def_property_readonly("suspicious", &SelfCollisionReport::suspicious,
                             "free_share below FREE_SHARE_HINT: the collision model likely blocks the joints.")
      .def("__repr__", [](const SelfCollisionReport& r) {
        return "<octoreach.SelfCollisionReport " + std::to_string(r.free) + " of " + std::to_string(r.samples) +
               " free, " + std::to_string(r.pairs.size()) + " colliding pairs>";
      });
  m.def("self_collision_report", [](const Robot& robot, const py::object& options, const py::object& progress,
                                     const py::kwargs& kw) {
          SelfCollisionOptions o = options_from<SelfCollisionOptions>(options, kw, "self_collision_report");
          ProgressCallback cb = progress_arg(progress, "self-collision");
          py::gil_scoped_release release;
          return self_collision_report(robot, o, cb);
        }, py::arg("robot"), py::arg("options") = py::none(), py::arg("progress") = false,
        "How often configurations drawn uniformly inside the joint limits are free of self-collision, and how often\n"
        "each checked pair collides; keywords set SelfCollisionOptions fields (samples, seed, joints, reference).");
}

}  // namespace octoreach::py_bindings
