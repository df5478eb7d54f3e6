// Capability maps, inverse point maps and surface maps.
#include "common.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/point_map.hpp"

namespace octoreach::py_bindings {

namespace {

// Runs f(i) for i in [0, n) without the GIL, on every core for large n.
template <class F>
void batch(std::size_t n, F&& f) {
  py::gil_scoped_release release;
  detail::parallel_for(n, n > 20000 ? 0 : 1, [&](std::size_t i, int) { f(i); }, 4096);
}

Array points_arg(const py::object& obj, const char* what) {
  Array a = Array::ensure(obj);
  if (!a || a.ndim() != 2 || a.shape(1) != 3) throw std::invalid_argument(std::string(what) + " must have shape (N, 3)");
  return a;
}

Array poses_arg(const py::object& obj, const char* what) {
  Array a = Array::ensure(obj);
  if (!a || a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4)
    throw std::invalid_argument(std::string(what) + " must have shape (N, 4, 4)");
  return a;
}

py::dict stats_dict(const BuildStats& s) {
  py::dict d;
  d["seconds"] = s.seconds;
  d["fk_samples"] = s.fk_samples;
  d["ik_calls"] = s.ik_calls;
  d["cells"] = s.cells;
  d["reachable_cells"] = s.reachable_cells;
  d["voxels"] = s.voxels;
  return d;
}

// (N, 4) rows x, y, z, theta -> values (N,) of a pose map.
py::array_t<double> pose_map_lookup(const PoseMap& pm, const py::object& poses) {
  return pose_rows_lookup(poses, [&](double x, double y, double z, double t) { return pm.value(x, y, z, t); });
}

py::tuple pose_map_voxels(const PoseMap& pm) {
  std::vector<Eigen::Vector3d> c;
  std::vector<float> v;
  pm.voxels(c, v);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> C(c.size(), 3);
  for (std::size_t i = 0; i < c.size(); ++i) C.row(i) = c[i].transpose();
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> V =
      Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(v.data(), c.size(), pm.theta_bins());
  return py::make_tuple(C, V);
}

py::tuple pose_map_bounds(const PoseMap& pm) {
  auto b = pm.bounds();
  return py::make_tuple(b.first, b.second);
}

py::dict to_dict(const std::map<std::string, std::string>& m) {
  py::dict d;
  for (auto& [k, v] : m) d[py::str(k)] = v;
  return d;
}

}  // namespace

void wrap_maps(py::module_& m) {
  py::class_<OrientationSet>(m, "OrientationSet",
      "Evenly spread approach directions on the sphere, times rolls about each (index = direction * rolls + roll).")
      .def_static("sphere", &OrientationSet::sphere, py::arg("count") = 200, py::arg("rolls") = 1, py::arg("symmetry") = 4)
      .def_property_readonly("directions", [](const OrientationSet& s) {
        Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> d(s.directions(), 3);
        for (int i = 0; i < s.directions(); ++i) d.row(i) = s.direction(i).transpose();
        return d;
      }, "(K, 3) unit approach directions.")
      .def_property_readonly("rolls", &OrientationSet::rolls)
      .def_property_readonly("symmetry", &OrientationSet::symmetry)
      .def("__len__", &OrientationSet::size)
      .def("subset", &OrientationSet::subset, py::arg("name"),
           "Direction indices of 'all', 'upper_hemisphere' (d_z <= 0: gripper above the object), 'top', 'side', "
           "'lower_hemisphere'.")
      .def("nearest_direction", &OrientationSet::nearest_direction, py::arg("d"))
      .def("rotation", &OrientationSet::rotation, py::arg("index"), py::arg("approach_axis") = Eigen::Vector3d::UnitZ(),
           "Tool rotation (3x3) of orientation `index` for a tool whose approach axis is `approach_axis`.");

  py::class_<CapabilityMap>(m, "CapabilityMap",
      "Capability map of an arm: for each voxel around the chain's base link, the reachable orientations.")
      .def_static("build", [](const Chain& chain, double resolution, int directions, int rolls, int symmetry,
                              const Eigen::Vector3d& approach_axis, bool self_collision, const py::object& reference,
                              std::uint64_t seed, std::size_t fk_samples, bool exhaustive, int exhaustive_attempts,
                              double position_tolerance, double orientation_tolerance, bool keep_solutions,
                              int threads, const py::object& progress) {
             CapabilityMapOptions o;
             o.resolution = resolution;
             o.directions = directions;
             o.rolls = rolls;
             o.symmetry = symmetry;
             o.approach_axis = approach_axis;
             o.self_collision = self_collision;
             if (!reference.is_none()) o.reference = reference.cast<Eigen::VectorXd>();
             o.seed = seed;
             o.fk_samples = fk_samples;
             o.exhaustive = exhaustive;
             o.exhaustive_attempts = exhaustive_attempts;
             o.position_tolerance = position_tolerance;
             o.orientation_tolerance = orientation_tolerance;
             o.keep_solutions = keep_solutions;
             o.threads = threads;
             ProgressCallback cb = progress_arg(progress, "capability map");
             py::gil_scoped_release release;
             return CapabilityMap::build(chain, o, cb);
           }, py::arg("chain"), py::arg("resolution") = 0.05, py::arg("directions") = 200, py::arg("rolls") = 1,
           py::arg("symmetry") = 4, py::arg("approach_axis") = Eigen::Vector3d::UnitZ(),
           py::arg("self_collision") = true, py::arg("reference") = py::none(), py::arg("seed") = 0,
           py::arg("fk_samples") = 0, py::arg("exhaustive") = false, py::arg("exhaustive_attempts") = 10,
           py::arg("position_tolerance") = 1e-3, py::arg("orientation_tolerance") = 1e-2,
           py::arg("keep_solutions") = true, py::arg("threads") = 0, py::arg("progress") = true,
           "Builds the map of `chain` (positions in its base link frame). A cell (voxel, orientation) is reachable\n"
           "when IK finds a solution inside the limits, free of self-collision (joints off the chain at `reference`,\n"
           "default robot.home()), for the voxel centre. Forward-kinematics sampling proposes cells and IK seeds;\n"
           "a flood fill over neighbouring cells settles the rest; exhaustive=True also tries every other cell.\n"
           "progress: True draws a bar, False is silent, or a callable (done, total).")
      .def_static("load", &CapabilityMap::load, py::arg("path"))
      .def("save", &CapabilityMap::save, py::arg("path"), py::arg("with_solutions") = false,
           "Writes the map atomically; with_solutions also stores one joint solution per reachable cell.")
      .def("export_octovis", &CapabilityMap::export_octovis, py::arg("path"),
           "Writes a ColorOcTree (.ot) for octovis, red (low D) to blue (high D).")
      .def("reachability", [](const CapabilityMap& cm, const py::object& points) {
             Array a = points_arg(points, "points");
             std::size_t n = a.shape(0);
             py::array_t<double> out(n);
             const double* p = a.data();
             double* o = out.mutable_data();
             batch(n, [&](std::size_t i) { o[i] = cm.reachability(Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2])); });
             return out;
           }, py::arg("points"), "Reachability index D (N,) of points (N, 3) in the base link frame; 0 outside.")
      .def("reachable", [](const CapabilityMap& cm, const py::object& poses) {
             Array a = poses_arg(poses, "poses");
             std::size_t n = a.shape(0);
             py::array_t<bool> out(n);
             const double* p = a.data();
             bool* o = out.mutable_data();
             batch(n, [&](std::size_t i) {
               const double* m = p + 16 * i;
               Pose T;
               T.matrix() << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11], m[12], m[13],
                   m[14], m[15];
               o[i] = T.matrix().allFinite() && cm.reachable(T);
             });
             return out;
           }, py::arg("poses"), "True (N,) where the cell of tool pose (N, 4, 4) (base link frame) is reachable.")
      .def("reachable_cell", py::overload_cast<const Eigen::Vector3d&, int>(&CapabilityMap::reachable, py::const_),
           py::arg("point"), py::arg("orientation"))
      .def("solution", &CapabilityMap::solution, py::arg("point"), py::arg("orientation"),
           "Stored joint solution of a reachable cell, or None.")
      .def("voxels", [](const CapabilityMap& cm) {
             std::vector<Eigen::Vector3d> c;
             std::vector<double> v;
             cm.voxels(c, v);
             Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> C(c.size(), 3);
             for (std::size_t i = 0; i < c.size(); ++i) C.row(i) = c[i].transpose();
             return py::make_tuple(C, Eigen::Map<Eigen::VectorXd>(v.data(), v.size()).eval());
           }, "(centres (M, 3), D (M,)) of the voxels with D > 0, base link frame.")
      .def_property_readonly("bounds", [](const CapabilityMap& cm) {
        auto b = cm.bounds();
        return py::make_tuple(b.first, b.second);
      }, "(min corner, max corner) of the reachable voxels.")
      .def_property_readonly("resolution", &CapabilityMap::resolution)
      .def_property_readonly("orientations", &CapabilityMap::orientations)
      .def_property_readonly("approach_axis", &CapabilityMap::approach_axis)
      .def_property_readonly("robot_name", &CapabilityMap::robot_name)
      .def_property_readonly("urdf_hash", &CapabilityMap::urdf_hash)
      .def_property_readonly("base_link", &CapabilityMap::base_link)
      .def_property_readonly("tip_link", &CapabilityMap::tip_link)
      .def_property_readonly("has_solutions", &CapabilityMap::has_solutions)
      .def_property_readonly("voxel_count", &CapabilityMap::voxel_count)
      .def_property_readonly("stats", [](const CapabilityMap& cm) { return stats_dict(cm.stats()); })
      .def_property_readonly("parameters", [](const CapabilityMap& cm) {
        py::dict d;
        for (auto& [k, v] : cm.parameters()) d[py::str(k)] = v;
        return d;
      })
      .def("__repr__", [](const CapabilityMap& cm) {
        return "<octoreach.CapabilityMap " + cm.robot_name() + " '" + cm.base_link() + "' -> '" + cm.tip_link() +
               "', " + std::to_string(cm.voxel_count()) + " voxels at " + std::to_string(cm.resolution()) + " m>";
      });

  py::class_<InversePointMap>(m, "InversePointMap",
      "Inverse point map: R_P of base poses (x, y, z, theta) of a reference frame around a target at the origin.")
      .def_static("build", [](const Robot& robot, const CapabilityMap& cap, const std::string& reference_frame,
                              const py::object& grasps, int theta_bins, double resolution, const py::object& reference,
                              const py::object& z_range, bool use_symmetry, int threads, const py::object& progress) {
             PointMapOptions o;
             o.reference_frame = reference_frame;
             grasps_arg(grasps, o.grasps, o.grasp_subset);
             o.theta_bins = theta_bins;
             o.resolution = resolution;
             if (!reference.is_none()) o.reference = reference.cast<Eigen::VectorXd>();
             z_range_arg(z_range, o.z_min, o.z_max);
             o.use_symmetry = use_symmetry;
             o.threads = threads;
             ProgressCallback cb = progress_arg(progress, "point map");
             py::gil_scoped_release release;
             return InversePointMap::build(robot, cap, o, cb);
           }, py::arg("robot"), py::arg("capability_map"), py::arg("reference_frame") = "",
           py::arg("grasps") = "upper_hemisphere", py::arg("theta_bins") = 16, py::arg("resolution") = 0.0,
           py::arg("reference") = py::none(), py::arg("z_range") = py::none(), py::arg("use_symmetry") = true,
           py::arg("threads") = 0, py::arg("progress") = true,
           "Inverts a capability map. reference_frame: the link whose pose is mapped (default the root link, e.g.\n"
           "base_footprint). grasps: a subset name ('upper_hemisphere', 'top', 'side', 'all') or a list of direction\n"
           "indices; a direction d means the tool approaches the target along d (world frame). reference: robot\n"
           "configuration fixing the joints between reference frame and arm (e.g. the torso). z_range: (min, max)\n"
           "base z relative to the target. theta bins that the grasp set's z symmetry determines are derived by\n"
           "rotating the grid instead of being recomputed.")
      .def_static("load", &InversePointMap::load, py::arg("path"))
      .def("save", &InversePointMap::save, py::arg("path"))
      .def("export_octovis", [](const InversePointMap& pm, const std::string& path) { pm.map().export_octovis(path); },
           py::arg("path"))
      .def("reachability", [](const InversePointMap& pm, const py::object& poses) { return pose_map_lookup(pm.map(), poses); },
           py::arg("poses"), "R_P (N,) of base poses (N, 4) as x, y, z, theta relative to the target; 0 outside.")
      .def_static("direct_reachability", [](const CapabilityMap& cap, const py::object& reference_to_arm,
                                            const std::vector<int>& orientations, const py::object& poses) {
             Pose T = pose_from(reference_to_arm, "reference_to_arm");
             RowMatrixXd P = matrix_from(poses, 4, "poses");
             Eigen::VectorXd out(P.rows());
             for (Eigen::Index i = 0; i < P.rows(); ++i)
               out[i] = InversePointMap::direct_reachability(cap, T, orientations, P(i, 0), P(i, 1), P(i, 2), P(i, 3));
             return out;
           }, py::arg("capability_map"), py::arg("reference_to_arm"), py::arg("orientations"), py::arg("poses"),
           "R_P computed straight from the capability map at continuous poses (N, 4), for checks.")
      .def("voxels", [](const InversePointMap& pm) { return pose_map_voxels(pm.map()); },
           "(centres (M, 3), values (M, theta_bins)) of the voxels with a non-zero value.")
      .def_property_readonly("bounds", [](const InversePointMap& pm) { return pose_map_bounds(pm.map()); })
      .def_property_readonly("resolution", [](const InversePointMap& pm) { return pm.map().resolution(); })
      .def_property_readonly("theta_bins", [](const InversePointMap& pm) { return pm.map().theta_bins(); })
      .def_property_readonly("voxel_count", [](const InversePointMap& pm) { return pm.map().voxel_count(); })
      .def_property_readonly("pose_count", [](const InversePointMap& pm) {
        std::vector<Eigen::Vector3d> c;
        std::vector<float> v;
        pm.map().voxels(c, v);
        return std::count_if(v.begin(), v.end(), [](float x) { return x > 0; });
      }, "Number of (voxel, theta) poses with R_P > 0.")
      .def_property_readonly("robot_name", &InversePointMap::robot_name)
      .def_property_readonly("urdf_hash", &InversePointMap::urdf_hash)
      .def_property_readonly("reference_frame", &InversePointMap::reference_frame)
      .def_property_readonly("arm_base_link", &InversePointMap::arm_base_link)
      .def_property_readonly("arm_tip_link", &InversePointMap::arm_tip_link)
      .def_property_readonly("reference_to_arm", [](const InversePointMap& pm) { return pose_to_array(pm.reference_to_arm()); })
      .def_property_readonly("grasp_orientations", &InversePointMap::grasp_orientations)
      .def_property_readonly("used_symmetry", &InversePointMap::used_symmetry)
      .def_property_readonly("build_seconds", &InversePointMap::build_seconds)
      .def_property_readonly("parameters", [](const InversePointMap& pm) { return to_dict(pm.parameters()); })
      .def("__repr__", [](const InversePointMap& pm) {
        return "<octoreach.InversePointMap " + pm.robot_name() + " frame '" + pm.reference_frame() + "', " +
               std::to_string(pm.map().voxel_count()) + " voxels x " + std::to_string(pm.map().theta_bins()) + " theta>";
      });
}

}  // namespace octoreach::py_bindings
