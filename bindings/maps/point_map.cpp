// InversePointMap and its build options.
#include "maps/convert.hpp"
#include "octoreach/point_map.hpp"

namespace octoreach::py_bindings {
namespace {

void wrap_options(py::module_& m) {
  using O = PointMapOptions;
  py::class_<O> cls(m, "PointMapOptions", "Build parameters of an inverse point map (defaults defined once, in C++).");
  cls.def(py::init<>())
      .def_readwrite("reference_frame", &O::reference_frame, "Link whose pose is mapped ('': the root link).")
      .def_readwrite("theta_bins", &O::theta_bins)
      .def_readwrite("use_symmetry", &O::use_symmetry,
                     "Derive the theta bins the grasp set's z symmetry determines by rotating the grid.")
      .def_readwrite("quality_weight", &O::quality_weight,
                     "R_P weights each reachable grasp by its cell's quality relative to the capability map's best\n"
                     "cell (needs a map with quality); False: the paper's R_P, each grasp counts 1.")
      .def_readwrite("threads", &O::threads, "0: every core.");
  def_grasps<O>(cls);
  def_map_resolution<O>(cls);
  def_z_range<O>(cls);
  def_reference<O>(cls, "Robot configuration fixing the joints between reference frame and arm; None: the default.");
}

}  // namespace

void wrap_point_map(py::module_& m) {
  wrap_options(m);
  py::class_<InversePointMap> cls(m, "InversePointMap",
      "Inverse point map: R_P of base poses (x, y, z, theta) of a reference frame around a target at the origin.");
  def_map_identity<InversePointMap>(cls);
  cls.def_static("build", [](const Robot& robot, const CapabilityMap& cap, const py::object& options,
                              const py::object& progress, const py::kwargs& kw) {
             PointMapOptions o = options_from<PointMapOptions>(options, kw, "InversePointMap.build");
             ProgressCallback cb = progress_arg(progress, "point map");
             py::gil_scoped_release release;
             return InversePointMap::build(robot, cap, o, cb);
           }, py::arg("robot"), py::arg("capability_map"), py::arg("options") = py::none(), py::arg("progress") = true,
           "Inverts a capability map; keyword arguments set PointMapOptions fields. reference_frame: the link whose\n"
           "pose is mapped (default the root link, e.g. base_footprint). grasps: a subset name ('upper_hemisphere',\n"
           "'top', 'side', 'all') or a list of direction indices; a direction d means the tool approaches the target\n"
           "along d (world frame). reference: robot configuration fixing the joints between reference frame and arm\n"
           "(e.g. the torso). z_range: (min, max) base z relative to the target. theta bins that the grasp set's z\n"
           "symmetry determines are derived by rotating the grid instead of being recomputed.")
      .def_static("load", &InversePointMap::load, py::arg("path"))
      .def("save", &InversePointMap::save, py::arg("path"))
      .def("export_octovis", [](const InversePointMap& pm, const std::string& path) { pm.map().export_octovis(path); },
           py::arg("path"))
      .def("reachability", [](const InversePointMap& pm, const py::object& poses) {
             return pose_rows_lookup(poses, [&](const double* r, std::size_t n, double* o) { pm.reachability(r, n, o); });
           }, py::arg("poses"), "R_P (N,) of base poses (N, 4) as x, y, z, theta relative to the target; 0 outside.")
      .def_static("direct_reachability", [](const CapabilityMap& cap, const py::object& reference_to_arm,
                                            const std::vector<int>& orientations, const py::object& poses) {
             Pose T = pose_from(reference_to_arm, "reference_to_arm");
             RowMatrixXd P = finite_matrix_from(poses, 4, "poses");
             Eigen::VectorXd out(P.rows());
             for (Eigen::Index i = 0; i < P.rows(); ++i)
               out[i] = InversePointMap::direct_reachability(cap, T, orientations, P(i, 0), P(i, 1), P(i, 2), P(i, 3));
             return out;
           }, py::arg("capability_map"), py::arg("reference_to_arm"), py::arg("orientations"), py::arg("poses"),
           "R_P computed straight from the capability map at continuous poses (N, 4), for checks.")
      .def("voxels", [](const InversePointMap& pm) { return pose_map_voxels(pm.map()); },
           "(centres (M, 3), values (M, theta_bins)) of the voxels with a non-zero value.")
      .def_property_readonly("bounds", [](const InversePointMap& pm) { return bounds_tuple(pm.map().bounds()); })
      .def_property_readonly("resolution", [](const InversePointMap& pm) { return pm.map().resolution(); })
      .def_property_readonly("theta_bins", [](const InversePointMap& pm) { return pm.map().theta_bins(); })
      .def_property_readonly("voxel_count", [](const InversePointMap& pm) { return pm.map().voxel_count(); })
      .def_property_readonly("pose_count", [](const InversePointMap& pm) { return pm.map().pose_count(); },
                             "Number of (voxel, theta) poses with R_P > 0.")
      .def_property_readonly("reference_frame", &InversePointMap::reference_frame)
      .def_property_readonly("arm_base_link", &InversePointMap::arm_base_link)
      .def_property_readonly("arm_tip_link", &InversePointMap::arm_tip_link)
      .def_property_readonly("approach_axis", &InversePointMap::approach_axis, "Approach axis of the arm's tool frame.")
      .def_property_readonly("reference_to_arm", [](const InversePointMap& pm) { return pose_to_array(pm.reference_to_arm()); })
      .def_property_readonly("grasp_orientations", &InversePointMap::grasp_orientations)
      .def_property_readonly("used_symmetry", &InversePointMap::used_symmetry)
      .def_property_readonly("weight", &InversePointMap::weight,
                             "'quality' when R_P weights grasps by their cells' quality, else ''.")
      .def_property_readonly("build_seconds", &InversePointMap::build_seconds)
      .def_property_readonly("parameters", [](const InversePointMap& pm) { return to_dict(pm.parameters()); })
      .def("__repr__", [](const InversePointMap& pm) {
        return "<octoreach.InversePointMap " + pm.robot_name() + " frame '" + pm.reference_frame() + "', " +
               std::to_string(pm.map().voxel_count()) + " voxels x " + std::to_string(pm.map().theta_bins()) + " theta>";
      });
}

}  // namespace octoreach::py_bindings
