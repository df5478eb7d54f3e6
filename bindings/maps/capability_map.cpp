// CapabilityMap and its build options.
#include "maps/convert.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/map_warnings.hpp"

namespace octoreach::py_bindings {
namespace {

py::dict stats_dict(const BuildStats& s) {
  py::dict d;
  d["seconds"] = s.seconds;
  d["fk_samples"] = s.fk_samples;
  d["ik_calls"] = s.ik_calls;
  d["cells"] = s.cells;
  d["reachable_cells"] = s.reachable_cells;
  d["voxels"] = s.voxels;
  d["mixed_cells"] = s.mixed_cells;
  return d;
}

void wrap_options(py::module_& m) {
  using O = CapabilityMapOptions;
  py::class_<O> cls(m, "CapabilityMapOptions", "Build parameters of a capability map (defaults defined once, in C++).");
  cls.def(py::init<>())
      .def_readwrite("resolution", &O::resolution, "Voxel edge (m).")
      .def_readwrite("directions", &O::directions,
                     "Approach directions on the sphere, rounded to the nearest multiple of the symmetry\n"
                     "(4: 50 gives 52; with poles the spiral takes two fewer and the poles come on top: 200 gives 202).")
      .def_readwrite("rolls", &O::rolls, "Rolls per direction (1: any roll).")
      .def_readwrite("symmetry", &O::symmetry, "z symmetry of the direction set.")
      .def_readwrite("poles", &O::poles,
                     "Also the directions straight up and down (+z, -z of the base link): for a tool held vertical\n"
                     "(a SCARA's), which no direction of the spiral points along exactly. Recorded in files.")
      .def_readwrite("approach_axis", &O::approach_axis, "Tool axis that approaches the object (tool frame).")
      .def_readwrite("self_collision", &O::self_collision, "Solutions must be free of self-collision.")
      .def_readwrite("seed", &O::seed)
      .def_readwrite("fk_samples", &O::fk_samples, "Forward-kinematics samples (0: 40 per voxel of the bounding box).")
      .def_readwrite("exhaustive", &O::exhaustive, "Also run random-restart IK on every cell sampling did not reach.")
      .def_readwrite("exhaustive_attempts", &O::exhaustive_attempts)
      .def_readwrite("position_tolerance", &O::position_tolerance, "IK tolerance at the voxel centre (m).")
      .def_readwrite("orientation_tolerance", &O::orientation_tolerance, "IK tolerance (rad).")
      .def_readwrite("keep_solutions", &O::keep_solutions, "Keep one joint solution per reachable cell.")
      .def_readwrite("block_size", &O::block_size,
                     "0: one flood over the whole box; n: blocks of n voxels per edge, each flooded on its own\n"
                     "(CapabilityBlocks: built anywhere, merged into the same bytes).")
      .def_readwrite("threads", &O::threads, "0: every core.");
  def_reference<O>(cls, "Robot configuration off the chain; None: default_reference(robot, chain).");
}

// The lookup argument of the reachable() queries: a CapabilityLookup, its name, or None (the C++ default).
CapabilityLookup lookup_arg(const py::object& lookup) {
  if (lookup.is_none()) return kDefaultCapabilityLookup;
  if (py::isinstance<CapabilityLookup>(lookup)) return lookup.cast<CapabilityLookup>();
  if (py::isinstance<py::str>(lookup)) {
    const std::string name = lookup.cast<std::string>();
    if (name == "vote") return CapabilityLookup::vote;
    if (name == "nearest_cell") return CapabilityLookup::nearest_cell;
    if (name == "any") return CapabilityLookup::any;
    throw std::invalid_argument("lookup must be 'vote', 'nearest_cell' or 'any', got '" + name + "'");
  }
  throw py::type_error("lookup must be a CapabilityLookup, 'vote', 'nearest_cell', 'any' or None, got " +
                       std::string(py::str(py::type::of(lookup).attr("__name__"))));
}

void wrap_lookup(py::module_& m) {
  py::enum_<CapabilityLookup>(m, "CapabilityLookup",
      "How CapabilityMap.reachable answers a pose from the cells. nearest_cell: the voxel holding the position.\n"
      "vote: the 8 voxel centres around the position weighted trilinearly; reachable when the reachable ones\n"
      "weigh at least one half (equal to nearest_cell at voxel centres). any: reachable when any of those 8\n"
      "is; no only where every cell around the pose says no (for pruning ahead of IK).")
      .value("nearest_cell", CapabilityLookup::nearest_cell)
      .value("vote", CapabilityLookup::vote)
      .value("any", CapabilityLookup::any);
}

void wrap_queries(py::class_<CapabilityMap>& cls) {
  cls.def("reachability", [](const CapabilityMap& cm, const py::object& points) {
        Array a = rows_arg(points, 3, "points must have shape (N, 3)");
        py::array_t<double> out(a.shape(0));
        const double* p = a.data();
        double* o = out.mutable_data();
        py::gil_scoped_release release;
        cm.reachability(p, a.shape(0), o);
        return out;
      }, py::arg("points"), "Reachability index D (N,) of points (N, 3) in the base link frame; 0 outside.")
      .def("reachable", [](const CapabilityMap& cm, const py::object& poses, const py::object& lookup) {
        const CapabilityLookup how = lookup_arg(lookup);
        Array a = array_arg(poses, "poses", "an (N, 4, 4) array");
        if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4)
          throw std::invalid_argument("poses must have shape (N, 4, 4)");
        py::array_t<bool> out(a.shape(0));
        const double* p = a.data();
        bool* o = out.mutable_data();
        py::gil_scoped_release release;
        cm.reachable(p, a.shape(0), o, how);
        return out;
      }, py::arg("poses"), py::arg("lookup") = py::none(),
      "True (N,) where tool pose (N, 4, 4) (base link frame) is reachable: the orientation nearest the pose's,\n"
      "the position by `lookup` (CapabilityLookup or its name; None: CapabilityMap.DEFAULT_LOOKUP, the vote).")
      .def("reachable_cell", [](const CapabilityMap& cm, const py::object& point, int orientation) {
             return cm.reachable(vec3_from(point, "point"), orientation);
           }, py::arg("point"), py::arg("orientation"),
           "The stored cell: orientation index `orientation` reachable in the voxel holding `point` (the\n"
           "nearest_cell rule; reachable(poses) gives the map's answer for poses).")
      .def("solution", [](const CapabilityMap& cm, const py::object& point, int orientation) {
             return cm.solution(vec3_from(point, "point"), orientation);
           }, py::arg("point"), py::arg("orientation"),
           "Stored joint solution of a reachable cell, or None when the cell is not reachable; ValueError on a\n"
           "map without solutions (has_solutions False).")
      .def("quality", [](const CapabilityMap& cm, const py::object& point, int o) -> py::object {
             auto q = cm.quality(vec3_from(point, "point"), o);
             if (!q) return py::none();
             return py::make_tuple(q->manipulability, q->penalty);
           }, py::arg("point"), py::arg("orientation"),
           "(manipulability, joint-limit penalty) of the stored solution of reachable cell (point, orientation), or\n"
           "None when the cell is not reachable; their product is the cell's quality. ValueError (saying how to\n"
           "rebuild) for a map without quality.")
      .def("voxel_quality", [](const CapabilityMap& cm, const std::string& how, bool relative) {
             if (how != "mean" && how != "max") throw std::invalid_argument("how must be 'mean' or 'max', got '" + how + "'");
             const std::vector<double> q = cm.voxel_quality(how == "max");
             Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
             if (relative && cm.max_quality() > 0) v /= cm.max_quality();
             return v;
           }, py::arg("how") = "mean", py::arg("relative") = false,
           "Per voxel of voxels() (D > 0): the mean or the largest quality (manipulability x penalty) of its reachable\n"
           "cells; relative=True divides by the map's best cell (values in [0, 1]). ValueError (saying how to rebuild)\n"
           "for a map without quality.")
      .def("mixed_cell", [](const CapabilityMap& cm, const py::object& point, int o) {
             const std::int64_t r = cm.record_at(vec3_from(point, "point"));
             if (o < 0 || o >= cm.orientations().size()) throw std::invalid_argument("orientation index out of range");
             return r >= 0 && cm.record_mixed(static_cast<std::uint32_t>(r), o);
           }, py::arg("point"), py::arg("orientation"),
           "True when cell (point, orientation) is mixed: IK at its centre fails but a configuration reaches a pose\n"
           "inside it.")
      .def("voxels", [](const CapabilityMap& cm) {
        std::vector<Eigen::Vector3d> c;
        std::vector<double> v;
        cm.voxels(c, v);
        Points C(c.size(), 3);
        for (std::size_t i = 0; i < c.size(); ++i) C.row(i) = c[i].transpose();
        return py::make_tuple(C, Eigen::Map<Eigen::VectorXd>(v.data(), v.size()).eval());
      }, "(centres (M, 3), D (M,)) of the voxels with D > 0, base link frame.")
      .def_property_readonly("bounds", [](const CapabilityMap& cm) { return bounds_tuple(cm.bounds()); },
                             "(min corner, max corner) of the reachable voxels.");
}

}  // namespace

void wrap_capability_map(py::module_& m) {
  wrap_options(m);
  wrap_lookup(m);
  py::class_<CapabilityMap> cls(m, "CapabilityMap",
      "Capability map of an arm: for each voxel around the chain's base link, the reachable orientations.");
  cls.def_static("build", [](const Chain& chain, const py::object& options, const py::object& progress, const py::kwargs& kw) {
        CapabilityMapOptions o = options_from<CapabilityMapOptions>(options, kw, "CapabilityMap.build");
        ProgressCallback cb = progress_arg(progress, "capability map");
        CapabilityMap map = [&] {
          py::gil_scoped_release release;
          return CapabilityMap::build(chain, o, cb);
        }();
        warn_map(capability_map_warning(map));
        return map;
      }, py::arg("chain"), py::arg("options") = py::none(), py::arg("progress") = true,
      "Builds the map of `chain` (positions in its base link frame); keyword arguments set CapabilityMapOptions\n"
      "fields. A cell (voxel, orientation) is reachable when IK finds a solution inside the limits, free of\n"
      "self-collision (joints off the chain at `reference`, default default_reference(robot, chain)), for the voxel\n"
      "centre. Forward-kinematics sampling proposes cells and IK seeds; a flood fill over neighbouring cells\n"
      "settles the rest; exhaustive=True also tries every other cell.\n"
      "progress: True draws a bar, False is silent, or a callable (done, total).")
      .def_static("build_for_arm", [](const Robot& robot, const py::object& arm, const py::object& options,
                                      const py::object& progress, const py::kwargs& kw) {
        py::object axis = kw.contains("approach_axis") ? kw.attr("pop")("approach_axis") : py::none();
        CapabilityMapOptions o = options_from<CapabilityMapOptions>(options, kw, "CapabilityMap.build_for_arm");
        Arm a = arm_from(robot, arm, axis);
        ProgressCallback cb = progress_arg(progress, "capability map");
        CapabilityMap map = [&] {
          py::gil_scoped_release release;
          return CapabilityMap::build(robot, a, o, cb);
        }();
        warn_map(capability_map_warning(map));
        return map;
      }, py::arg("robot"), py::arg("arm"), py::arg("options") = py::none(), py::arg("progress") = true,
      "Builds the map of an arm (a name, an Arm or a (base_link, tip_link[, approach_axis]) tuple) with the arm's\n"
      "approach axis (inferred from the gripper unless given; approach_axis=(x, y, z) overrides it); other\n"
      "keyword arguments set CapabilityMapOptions fields.")
      .def_static("load", &CapabilityMap::load, py::arg("path"))
      .def("save", &CapabilityMap::save, py::arg("path"), py::arg("with_solutions") = false,
           "Writes the map atomically; with_solutions also stores one joint solution per reachable cell.")
      .def("export_octovis", &CapabilityMap::export_octovis, py::arg("path"),
           "Writes a ColorOcTree (.ot) for octovis, red (low D) to blue (high D).");
  wrap_queries(cls);
  def_map_identity<CapabilityMap>(cls);
  cls.attr("DEFAULT_LOOKUP") = kDefaultCapabilityLookup;
  cls.attr("FEW_DIRECTIONS") = kFewDirections;  // the warnings' thresholds (map_warnings.hpp)
  cls.attr("MIXED_PER_REACHABLE") = kMixedPerReachable;
  cls.def_property_readonly("resolution", &CapabilityMap::resolution)
      .def_property_readonly("orientations", &CapabilityMap::orientations)
      .def_property_readonly("approach_axis", &CapabilityMap::approach_axis)
      .def_property_readonly("base_link", &CapabilityMap::base_link)
      .def_property_readonly("tip_link", &CapabilityMap::tip_link)
      .def_property_readonly("has_solutions", &CapabilityMap::has_solutions,
                             "True when the map keeps joint solutions (built with keep_solutions, saved with them),\n"
                             "also where no cell is reachable.")
      .def_property_readonly("has_cell_data", &CapabilityMap::has_cell_data,
                             "True when the map marks its mixed cells (format 2; CertifiedLookup needs it).")
      .def_property_readonly("has_quality", &CapabilityMap::has_quality,
                             "True when the map keeps a quality per reachable cell (built with solutions).")
      .def_property_readonly("max_quality", &CapabilityMap::max_quality, "Largest cell quality of the map (0: none).")
      .def_property_readonly("jacobian_rank", &CapabilityMap::jacobian_rank,
                             "Jacobian rank the manipulability was computed with (0: unknown).")
      .def_property_readonly("reference", [](const CapabilityMap& cm) -> py::object {
             return cm.reference().size() ? py::cast(cm.reference()) : py::none();
           }, "Robot configuration the map was built at (None for older files).")
      .def_property_readonly("voxel_count", &CapabilityMap::voxel_count)
      .def_property_readonly("stats", [](const CapabilityMap& cm) { return stats_dict(cm.stats()); })
      .def_property_readonly("warning", &capability_map_warning,
                             "One line when the map looks suspicious, with what to try; '' otherwise: no\n"
                             "reachable voxel (a reach thinner than a cell), a best voxel reaching few approach\n"
                             "directions (something blocks the wrist), or more than MIXED_PER_REACHABLE mixed cells\n"
                             "per reachable one (the plain lookups miss much of the reach). Builds emit it as a\n"
                             "MapWarning.")
      .def_property_readonly("parameters", [](const CapabilityMap& cm) { return to_dict(cm.parameters()); })
      .def("__repr__", [](const CapabilityMap& cm) {
        return "<octoreach.CapabilityMap " + cm.robot_name() + " '" + cm.base_link() + "' -> '" + cm.tip_link() +
               "', " + std::to_string(cm.voxel_count()) + " voxels at " + std::to_string(cm.resolution()) + " m>";
      });
}

}  // namespace octoreach::py_bindings
