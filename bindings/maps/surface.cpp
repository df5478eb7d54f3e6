// Surface: a flat working surface and its obstacle boxes.
#include "common.hpp"
#include "octoreach/surface.hpp"

namespace octoreach::py_bindings {
namespace {

std::vector<Eigen::Vector3d> vertices_from(const py::object& obj) {
  RowMatrixXd v = matrix_from(obj, 3, "vertices");
  std::vector<Eigen::Vector3d> out;
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.emplace_back(v.row(i).transpose());
  return out;
}

}  // namespace

void wrap_surface(py::module_& m) {
  py::class_<Surface>(m, "Surface",
      "A flat working surface: a planar polygon (3D vertices, world frame, convex or not, any height and tilt)\n"
      "with a thickness below its top face, plus obstacle boxes (legs, walls).")
      .def(py::init([](const py::object& vertices, double thickness) { return Surface(vertices_from(vertices), thickness); }),
           py::arg("vertices"), py::arg("thickness") = 0.03)
      .def_static("rectangle", &Surface::rectangle, py::arg("size_x"), py::arg("size_y"), py::arg("height"),
                  py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("yaw") = 0.0, py::arg("thickness") = 0.03,
                  "A rectangular table top of size_x by size_y centred at (x, y), top face at `height`.")
      .def("add_box", [](Surface& s, const Eigen::Vector3d& size, const py::object& pose) {
             s.add_box(size, pose_from(pose));
           }, py::arg("size"), py::arg("pose"), "Adds an obstacle box (extents, 4x4 centre pose in the world frame).")
      .def("add_legs", &Surface::add_legs, py::arg("width") = 0.05, "Adds a leg under each vertex down to the floor: a box `width` by `width` across, its sides\n"
           "along the world axes, its centre `width` from the vertex towards the polygon's centre.")
      .def_property_readonly("vertices", [](const Surface& s) {
        RowMatrixXd v(s.vertices().size(), 3);
        for (std::size_t i = 0; i < s.vertices().size(); ++i) v.row(i) = s.vertices()[i].transpose();
        return v;
      })
      .def_property_readonly("boxes", [](const Surface& s) {
        py::list out;
        for (const auto& [size, pose] : s.boxes()) out.append(py::make_tuple(size, pose_to_array(pose)));
        return out;
      }, "The obstacle boxes as (size (3,), pose (4, 4)) pairs.")
      .def_property_readonly("triangles", [](const Surface& s) {
        py::array_t<std::int64_t> out({py::ssize_t(s.triangles().size()), py::ssize_t(3)});
        auto w = out.mutable_unchecked<2>();
        for (std::size_t i = 0; i < s.triangles().size(); ++i)
          for (int k = 0; k < 3; ++k) w(py::ssize_t(i), k) = s.triangles()[i][k];
        return out;
      }, "The polygon's triangles (M, 3) as indices into vertices (ear clipping; any simple polygon), wound\n"
         "counter-clockwise seen from the normal; their areas add up to area.")
      .def_property_readonly("normal", &Surface::normal)
      .def_property_readonly("area", &Surface::area)
      .def_property_readonly("thickness", &Surface::thickness)
      .def("points", [](const Surface& s, double resolution) {
             auto p = s.sample_points(resolution);
             RowMatrixXd out(p.size(), 3);
             for (std::size_t i = 0; i < p.size(); ++i) out.row(i) = p[i].transpose();
             return out;
           }, py::arg("resolution"), "Grid points (M, 3) inside the polygon, as used to build surface maps.")
      .def("contains", [](const Surface& s, const py::object& points) {
             RowMatrixXd p = finite_matrix_from(points, 3, "points");
             py::array_t<bool> out(p.rows());
             auto w = out.mutable_unchecked<1>();
             for (Eigen::Index i = 0; i < p.rows(); ++i) w(i) = s.contains(s.project(p.row(i).transpose()));
             return out;
           }, py::arg("points"), "True where a point's projection on the plane lies inside the polygon.")
      .def("obstacles", [](const Surface& s) { return s.obstacles(); },
           "The surface slab and its boxes as Obstacles (for collision checks).");
}

}  // namespace octoreach::py_bindings
