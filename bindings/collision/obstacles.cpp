// Python binding of Obstacles: environment objects (shapes) in the world frame.
#include <memory>

#include "common.hpp"
#include "octoreach/collision.hpp"

namespace octoreach::py_bindings {

void wrap_obstacles(py::module_& m) {
  py::class_<Obstacles, std::shared_ptr<Obstacles>>(m, "Obstacles",
      "Environment objects in the world frame (boxes, spheres, cylinders, meshes, OctoMaps).")
      .def(py::init<>())
      .def("add_shape", [](Obstacles& o, const Shape& shape, const std::string& name) { o.add(shape, name); },
           py::arg("shape"), py::arg("name") = "", "Adds a Shape (world frame).")
      .def("add_box", [](Obstacles& o, const Eigen::Vector3d& size, const py::object& pose, const std::string& name) {
             o.add_box(size, pose.is_none() ? Pose::Identity() : pose_from(pose), name);
           }, py::arg("size"), py::arg("pose") = py::none(), py::arg("name") = "",
           "Adds a box of extents `size` (x, y, z) centred at `pose` (4x4, world frame).")
      .def("add_sphere", [](Obstacles& o, double r, const py::object& pose, const std::string& name) {
             o.add_sphere(r, pose.is_none() ? Pose::Identity() : pose_from(pose), name);
           }, py::arg("radius"), py::arg("pose") = py::none(), py::arg("name") = "")
      .def("add_cylinder", [](Obstacles& o, double r, double l, const py::object& pose, const std::string& name) {
             o.add_cylinder(r, l, pose.is_none() ? Pose::Identity() : pose_from(pose), name);
           }, py::arg("radius"), py::arg("length"), py::arg("pose") = py::none(), py::arg("name") = "",
           "Adds a cylinder along the local z axis of `pose`.")
      .def("add_mesh", [](Obstacles& o, const std::string& path, const py::object& pose, const Eigen::Vector3d& scale,
                          const std::string& name) {
             o.add_mesh_file(path, pose.is_none() ? Pose::Identity() : pose_from(pose), scale, name);
           }, py::arg("path"), py::arg("pose") = py::none(), py::arg("scale") = Eigen::Vector3d::Ones(),
           py::arg("name") = "", "Adds a mesh file (STL, DAE, OBJ ... read by assimp).")
      .def("add_triangles", [](Obstacles& o, const py::object& vertices, const py::object& triangles,
                               const py::object& pose, const std::string& name) {
             Points v = matrix_from(vertices, 3, "vertices");
             IndexTriples tri = index_triples_from(triangles, std::size_t(v.rows()), "triangles");
             o.add_geometry(make_mesh(v, tri), pose.is_none() ? Pose::Identity() : pose_from(pose), name);
           }, py::arg("vertices"), py::arg("triangles"), py::arg("pose") = py::none(), py::arg("name") = "",
           "Adds a triangle mesh from arrays: vertices (N, 3) and triangles (M, 3) of vertex indices.")
      .def("add_octree_file", [](Obstacles& o, const std::string& path, const py::object& pose, const std::string& name) {
             o.add_octree_file(path, pose.is_none() ? Pose::Identity() : pose_from(pose), name);
           }, py::arg("path"), py::arg("pose") = py::none(), py::arg("name") = "",
           "Adds the occupied cells of an OctoMap file (.bt or .ot).")
      .def("add_points", [](Obstacles& o, const py::object& points, double resolution, const std::string& name) {
             o.add_points(matrix_from(points, 3, "points"), resolution, name);
           }, py::arg("points"), py::arg("resolution"), py::arg("name") = "",
           "Adds occupied cells at the given points (N, 3) as an OctoMap of the given resolution.")
      .def("add", [](Obstacles& o, const std::shared_ptr<Obstacles>& other) {
             if (!other) throw py::type_error("add needs an octoreach.Obstacles, got None");
             o.add(*other);
           }, py::arg("other"), "Adds every obstacle of `other` (the objects are shared; the two sets stay independent).")
      .def("__len__", &Obstacles::size)
      .def_property_readonly("names", &Obstacles::names)
      .def_property_readonly("shapes", &Obstacles::shapes, "The obstacles' Shapes (world frame), in the order added.")
      .def("collides_box", [](const Obstacles& o, const Eigen::Vector3d& size, const py::object& pose) {
             return o.collides_box(size, pose_from(pose));
           }, py::arg("size"), py::arg("pose"), "True when a box of extents `size` at `pose` touches an obstacle.");
}

}  // namespace octoreach::py_bindings
