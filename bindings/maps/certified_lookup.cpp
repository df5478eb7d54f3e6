// CertifiedLookup and its options.
#include "maps/convert.hpp"
#include "octoreach/certified_lookup.hpp"

namespace octoreach::py_bindings {
namespace {

// Poses (N, 4, 4) as a C-contiguous float64 array; ValueError naming the shape otherwise.
Array poses_arg(const py::object& poses) {
  Array a = array_arg(poses, "poses", "an (N, 4, 4) array");
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4) throw std::invalid_argument("poses must have shape (N, 4, 4)");
  return a;
}

}  // namespace

void wrap_certified_lookup(py::module_& m) {
  using O = CertifiedLookupOptions;
  py::class_<O>(m, "CertifiedLookupOptions", "Options of CertifiedLookup (defaults defined once, in C++).")
      .def(py::init<>())
      .def_readwrite("seeds", &O::seeds, "Stored configurations IK starts from at most, nearest cells first.")
      .def_readwrite("max_iterations", &O::max_iterations, "Iterations per descent.")
      .def_readwrite("branch_seeds", &O::branch_seeds,
                     "Configurations of other IK branches tried at most when the seeds fail (0: none), from the cells\n"
                     "around the corners, each more than 1 rad from every configuration tried in some joint.")
      .def_readwrite("collided_branch_seeds", &O::collided_branch_seeds,
                     "Configurations of other branches tried at most (instead of branch_seeds) once a descent reached\n"
                     "the pose in self-collision: another branch often reaches it free.");
  py::class_<CertifiedLookup>(m, "CertifiedLookup",
      "Reachability of tool poses from a capability map where the cells around a pose agree, and from IK at the\n"
      "exact pose where they do not (the pose lies where the reachable set ends between the cells, or in a mixed\n"
      "cell; where the descents from the cells' configurations fail, configurations of other IK branches stored\n"
      "around them are tried too: branch_seeds; collided_branch_seeds once a descent reached the pose in\n"
      "self-collision). Needs a map built with solutions by this version; keeps the map\n"
      "alive.")
      .def(py::init([](const CapabilityMap& map, const Robot& robot, const py::object& reference,
                       const py::object& options, const py::kwargs& kw) {
             O o = options_from<O>(options, kw, "CertifiedLookup");
             Eigen::VectorXd ref;
             if (!reference.is_none()) ref = cast_arg<Eigen::VectorXd>(reference, "reference", "a vector of joint values or None");
             return CertifiedLookup(map, robot, ref, o);
           }),
           py::arg("map"), py::arg("robot"), py::arg("reference") = py::none(), py::arg("options") = py::none(),
           py::keep_alive<1, 2>(),
           "The lookup of `map` for `robot` (the model it was built for) at `reference` (robot configuration for the\n"
           "joints off the chain; None: the map's own); keywords set CertifiedLookupOptions fields.")
      .def("reachable", [](const CertifiedLookup& c, const py::object& poses, int threads) {
             Array a = poses_arg(poses);
             py::array_t<bool> out(a.shape(0));
             const double* p = a.data();
             bool* o = out.mutable_data();
             py::gil_scoped_release release;
             c.reachable(p, a.shape(0), o, threads);
             return out;
           }, py::arg("poses"), py::arg("threads") = 0,
           "True (N,) where tool pose (N, 4, 4) (base link frame) is reachable; threads: 0 every core (the answers\n"
           "do not depend on it).")
      .def("solution", [](const CertifiedLookup& c, const py::object& pose) -> py::object {
             Array a = array_arg(pose, "pose", "a 4x4 array");
             if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) throw std::invalid_argument("pose must have shape (4, 4)");
             Pose T;
             T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(a.data());
             Eigen::VectorXd q;
             bool yes;
             {
               py::gil_scoped_release release;
               yes = c.reachable(T, &q);
             }
             if (!yes) return py::none();
             return q.size() ? py::cast(q) : py::cast(true);
           }, py::arg("pose"),
           "For one tool pose (4, 4): None when unreachable; the joint solution when IK answered; True when the\n"
           "map's cells answered yes (no solution is computed there).")
      .def("certain", [](const CertifiedLookup& c, const py::object& poses) {
             Array a = poses_arg(poses);
             py::array_t<bool> out(a.shape(0));
             const double* p = a.data();
             bool* o = out.mutable_data();
             py::gil_scoped_release release;
             c.certain(p, a.shape(0), o);
             return out;
           }, py::arg("poses"), "True (N,) where the map's cells decide the pose without IK.")
      .def_property_readonly("chain", &CertifiedLookup::chain)
      .def_property_readonly("reference", &CertifiedLookup::reference)
      .def_property_readonly("options", [](const CertifiedLookup& c) { return c.options(); },
                             "A copy of the options (fixed when the lookup is made).");
}

}  // namespace octoreach::py_bindings
