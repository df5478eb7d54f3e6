// SurfaceMap and its build options.
#include <optional>

#include "maps/convert.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/map_warnings.hpp"
#include "octoreach/surface_map.hpp"

namespace octoreach::py_bindings {
namespace {

void wrap_options(py::module_& m) {
  using O = SurfaceMapOptions;
  py::class_<O> cls(m, "SurfaceMapOptions", "Build parameters of a surface map (defaults defined once, in C++).");
  cls.def(py::init<>())
      .def_readwrite("reference_frame", &O::reference_frame, "Link whose pose is mapped ('': the root link).")
      .def_readwrite("theta_bins", &O::theta_bins)
      .def_property("obstacles",
          [](const O& o) { return std::const_pointer_cast<Obstacles>(o.obstacles); },
          [](O& o, const py::object& obs) {
            if (obs.is_none()) o.obstacles = nullptr;
            else if (py::isinstance<Obstacles>(obs)) o.obstacles = obs.cast<std::shared_ptr<Obstacles>>();
            else throw py::type_error("obstacles must be an octoreach.Obstacles or None, got " + type_name(obs));
          }, "The rest of the room (Obstacles, world frame) or None: checked against the body and the arm.")
      .def_readwrite("check_body", &O::check_body, "Reject base poses where the body touches the surface, boxes or obstacles.")
      .def_readwrite("check_arm", &O::check_arm,
                     "Reject grasps whose arm passes below the surface inside its outline or touches a box or obstacle.")
      .def_readwrite("grasp_height", &O::grasp_height, "Grasp points lie this far above the surface (m).")
      .def_readwrite("quality_weight", &O::quality_weight,
                     "R_P weights each valid grasp by its cell's quality relative to the capability map's best cell, so\n"
                     "R_S and the sampler prefer base poses reached away from joint limits and singularities (needs a\n"
                     "map with quality); False: the paper's R_S, each grasp counts 1.")
      .def_readwrite("threads", &O::threads, "0: every core.");
  def_grasps<O>(cls);
  def_map_resolution<O>(cls);
  def_z_range<O>(cls);
  def_reference<O>(cls, "Robot configuration off the arm (torso, other arm); None: default_reference of the arm.");
}

// SurfaceMap.build: `arm` is a CapabilityMap, or an arm whose capability map is built first with
// `directions`, `poles`, `seed` and `approach_axis` (the only capability-map keywords), at the surface map's
// resolution.
std::shared_ptr<SurfaceMap> build(const Robot& robot, const py::object& arm, const Surface& surface,
                                  const py::object& options, const py::object& progress, const py::kwargs& kw) {
  CapabilityMapOptions co;
  py::kwargs rest;
  py::object approach_axis = py::none();
  std::optional<int> directions;  // given: the capability map built must have them, a given one must match
  std::optional<bool> poles;
  std::optional<std::uint64_t> seed;
  for (auto item : kw) {
    std::string key = py::str(item.first);
    if (key == "approach_axis") approach_axis = py::reinterpret_borrow<py::object>(item.second);
    else if (key == "directions") directions = cast_arg<int>(item.second, "SurfaceMap.build(): keyword 'directions'", "an int");
    else if (key == "poles") poles = cast_arg<bool>(item.second, "SurfaceMap.build(): keyword 'poles'", "a bool");
    else if (key == "seed") seed = cast_arg<std::uint64_t>(item.second, "SurfaceMap.build(): keyword 'seed'", "an int");
    else rest[item.first] = item.second;
  }
  SurfaceMapOptions o = options_from<SurfaceMapOptions>(options, rest, "SurfaceMap.build");
  if (py::isinstance<CapabilityMap>(arm)) {
    if (!approach_axis.is_none())
      throw std::invalid_argument("approach_axis: the capability map fixes the approach axis; give an arm name or "
                                  "tuple to build one with another axis");
    const CapabilityMap& cap = arm.cast<const CapabilityMap&>();
    // The map fixes its directions: keywords that ask for others are errors, not silently dropped.
    const OrientationSet& set = cap.orientations();
    if (poles && *poles != set.poles())
      throw std::invalid_argument(std::string("poles=") + (*poles ? "True" : "False") +
                                  ": the capability map was built " + (set.poles() ? "with" : "without") +
                                  " poles and fixes its directions; give an arm name or tuple to build one with them");
    if (directions && OrientationSet::sphere_directions(*directions, set.symmetry(), set.poles()) != set.directions())
      throw std::invalid_argument("directions=" + std::to_string(*directions) + ": the capability map holds " +
                                  std::to_string(set.directions()) + " directions and fixes them; give an arm name "
                                  "or tuple to build one with another count");
    if (seed && *seed != cap.seed())
      throw std::invalid_argument("seed=" + std::to_string(*seed) + ": the capability map was built with seed " +
                                  std::to_string(cap.seed()) + " and fixes its cells; give an arm name or tuple to "
                                  "build one with another seed");
    ProgressCallback cb = progress_arg(progress, "surface map");
    std::shared_ptr<SurfaceMap> map;
    {
      py::gil_scoped_release release;
      map = std::make_shared<SurfaceMap>(SurfaceMap::build(robot, cap, surface, o, cb));
    }
    warn_map(map->warning());
    return map;
  }
  Arm a = arm_from(robot, arm, approach_axis);
  if (directions) co.directions = *directions;
  if (poles) co.poles = *poles;
  if (seed) co.seed = *seed;
  if (o.resolution != 0) co.resolution = o.resolution;
  co.reference = o.reference;
  ProgressCallback cap_cb = progress_arg(progress, "capability map"), cb = progress_arg(progress, "surface map");
  std::string cap_warning;
  std::shared_ptr<SurfaceMap> map;
  {
    py::gil_scoped_release release;
    CapabilityMap cap = CapabilityMap::build(robot, a, co, cap_cb);
    cap_warning = capability_map_warning(cap);
    map = std::make_shared<SurfaceMap>(SurfaceMap::build(robot, cap, surface, o, cb));
  }
  warn_map(cap_warning.empty() ? map->warning() : cap_warning);  // one line: the capability map's explains the rest
  return map;
}

py::dict stats_dict(const SurfaceMapStats& s) {
  py::dict d;
  d["seconds"] = s.seconds;
  d["surface_points"] = s.surface_points;
  d["base_poses"] = s.base_poses;
  d["candidate_poses"] = s.candidate_poses;
  d["valid_poses"] = s.valid_poses;
  d["body_collisions"] = s.body_collisions;
  d["arm_rejections"] = s.arm_rejections;
  return d;
}

}  // namespace

void wrap_surface_map(py::module_& m) {
  wrap_options(m);
  py::class_<SurfaceMap, std::shared_ptr<SurfaceMap>> cls(m, "SurfaceMap",
      "Surface inverse reachability map: R_S of base poses (x, y, z, theta) of the reference frame, world frame.");
  def_map_identity<SurfaceMap>(cls);
  cls.attr("EDGE_OF_REACH") = kEdgeOfReach;  // the warning's threshold (map_warnings.hpp)
  cls.def_static("build", &build, py::arg("robot"), py::arg("arm"), py::arg("surface"), py::arg("options") = py::none(),
                  py::arg("progress") = true,
                  "Surface map of `arm`: a CapabilityMap with solutions, or an arm name or (base, tip[, approach_axis])\n"
                  "tuple whose capability map is built first (keywords directions, poles and seed; at `resolution`,\n"
                  "default CapabilityMapOptions().resolution; a given map fixes its directions and seed, and\n"
                  "directions=, poles= or seed= asking for others raise). Other keywords set SurfaceMapOptions fields. Base poses (x, y, z,\n"
                  "theta) are of `reference_frame` (default the root link, e.g. base_footprint), world frame.\n"
                  "The robot stands on the floor (z_range (0, 0), the default); give z_range=(lo, hi) for a floating base.\n"
                  "`obstacles` (Obstacles: walls, other surfaces, meshes, OctoMaps) are checked against body and arm. `reference` fixes the joints off the arm\n"
                  "(default: default_reference, the other arm tucked). Grasp points lie `grasp_height` above the surface.")
      .def_static("combine", [](const std::vector<std::shared_ptr<SurfaceMap>>& maps, const std::string& mode) {
             std::vector<const SurfaceMap*> ptrs;
             for (const auto& p : maps) {
               if (!p) throw std::invalid_argument("combine got None instead of a map");
               ptrs.push_back(p.get());
             }
             return std::make_shared<SurfaceMap>(SurfaceMap::combine(ptrs, mode));
           }, py::arg("maps"), py::arg("mode") = "max",
           "Per-pose max ('max': any arm reaches) or min ('min': both arms reach) of maps of one robot, frame,\n"
           "resolution and theta bins; ValueError otherwise.")
      .def_static("load", [](const std::string& path) { return std::make_shared<SurfaceMap>(SurfaceMap::load(path)); },
                  py::arg("path"))
      .def("save", &SurfaceMap::save, py::arg("path"), "Writes the map atomically.")
      .def("export_octovis", [](const SurfaceMap& sm, const std::string& path) { sm.map().export_octovis(path); },
           py::arg("path"), "ColorOcTree (.ot) for octovis: each voxel coloured by its best theta, red low, blue high.")
      .def("reachability", [](const SurfaceMap& sm, const py::object& poses) {
             return pose_rows_lookup(poses, [&](const double* r, std::size_t n, double* o) { sm.reachability(r, n, o); });
           }, py::arg("poses"),
           "R_S (N,) of base poses (N, 4) as x, y, z, theta (world frame); 0 outside the map. The condition attachment.")
      .def("voxels", [](const SurfaceMap& sm) { return pose_map_voxels(sm.map()); },
           "(centres (M, 3), R_S (M, theta_bins)) of the voxels with R_S > 0.")
      .def_property_readonly("bounds", [](const SurfaceMap& sm) { return bounds_tuple(sm.map().bounds()); },
                             "(min corner, max corner) of the voxels with R_S > 0.")
      .def_property_readonly("resolution", [](const SurfaceMap& sm) { return sm.map().resolution(); })
      .def_property_readonly("theta_bins", [](const SurfaceMap& sm) { return sm.map().theta_bins(); })
      .def_property_readonly("voxel_count", [](const SurfaceMap& sm) { return sm.map().voxel_count(); })
      .def_property_readonly("max_reachability", [](const SurfaceMap& sm) { return sm.map().max_value(); })
      .def_property_readonly("reference_frame", &SurfaceMap::reference_frame)
      .def_property_readonly("arms", &SurfaceMap::arms)
      .def_property_readonly("approach_axes", &SurfaceMap::approach_axes,
                             "Approach axis (tip frame) of each arm's capability map, as in arms.")
      .def_property_readonly("z_range", &SurfaceMap::z_range)
      .def_property_readonly("empty_reason", &SurfaceMap::empty_reason)
      .def_property_readonly("warning", &SurfaceMap::warning,
                             "One line when the build looks suspicious (the surface at the edge of the arm's reach), with\n"
                             "what to try; '' otherwise and for a loaded map. Builds emit it as a MapWarning.")
      .def_property_readonly("weight", &SurfaceMap::weight,
                             "'quality' when R_P weights grasps by their cells' quality, else ''.")
      .def_property_readonly("polygon", [](const SurfaceMap& sm) {
        RowMatrixXd v(sm.polygon().size(), 3);
        for (std::size_t i = 0; i < sm.polygon().size(); ++i) v.row(i) = sm.polygon()[i].transpose();
        return v;
      })
      .def_property_readonly("stats", [](const SurfaceMap& sm) { return stats_dict(sm.stats()); })
      .def_property_readonly("parameters", [](const SurfaceMap& sm) { return to_dict(sm.parameters()); })
      .def("__repr__", [](const SurfaceMap& sm) {
        return "<octoreach.SurfaceMap " + sm.robot_name() + " (" + sm.arms() + "), frame '" + sm.reference_frame() +
               "', " + std::to_string(sm.map().voxel_count()) + " voxels x " + std::to_string(sm.map().theta_bins()) +
               " theta>";
      });
}

}  // namespace octoreach::py_bindings
