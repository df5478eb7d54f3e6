// Python binding of Shape: the one description of a solid (box, cylinder, sphere, mesh, OctoMap) with its pose.
#include "common.hpp"
#include "octoreach/shape.hpp"

#include <octomap/OcTree.h>

namespace octoreach::py_bindings {

namespace {

Pose pose_or_identity(const py::object& pose) { return pose.is_none() ? Pose::Identity() : pose_from(pose); }

py::tuple mesh_arrays(const Shape& s) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  s.mesh_triangles(vertices, triangles);
  py::array_t<std::int64_t> f({py::ssize_t(triangles.size()), py::ssize_t(3)});
  auto w = f.mutable_unchecked<2>();
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) w(py::ssize_t(i), k) = triangles[i][k];
  return py::make_tuple(to_points(vertices), f);
}

// (centres (N, 3), edges (N,)) of an OctoMap shape's occupied leaves, in its own frame (before `pose`).
py::tuple octree_cells(const Shape& s) {
  if (s.type != Shape::Type::Octree || !s.octree)
    throw std::invalid_argument(std::string("a ") + s.type_name() + " has no OctoMap cells");
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> edges;
  for (auto it = s.octree->begin_leafs(), end = s.octree->end_leafs(); it != end; ++it) {
    if (!s.octree->isNodeOccupied(*it)) continue;
    centres.emplace_back(it.getX(), it.getY(), it.getZ());
    edges.push_back(it.getSize());
  }
  return py::make_tuple(to_points(centres), py::array_t<double>(py::ssize_t(edges.size()), edges.data()));
}

}  // namespace

void wrap_shape(py::module_& m) {
  py::class_<Shape>(m, "Shape",
      "A solid with its pose: a box, cylinder (along its local z), sphere, triangle mesh or OctoMap. The one shape\n"
      "description of the library: a robot link's collision and visual shapes (pose in the link frame), Obstacles,\n"
      "Scene and rooms (pose in the world frame). Build one with the static methods; metres, 4x4 poses.")
      .def_static("box", [](const Eigen::Vector3d& size, const py::object& pose) {
                    return Shape::box(size, pose_or_identity(pose));
                  }, py::arg("size"), py::arg("pose") = py::none(), "A box of extents `size` (x, y, z) centred at `pose`.")
      .def_static("cylinder", [](double radius, double length, const py::object& pose) {
                    return Shape::cylinder(radius, length, pose_or_identity(pose));
                  }, py::arg("radius"), py::arg("length"), py::arg("pose") = py::none(),
                  "A cylinder along the local z axis of `pose`, centred there.")
      .def_static("sphere", [](double radius, const py::object& pose) {
                    return Shape::sphere(radius, pose_or_identity(pose));
                  }, py::arg("radius"), py::arg("pose") = py::none())
      .def_static("mesh_file", [](const std::string& path, const py::object& pose, const Eigen::Vector3d& scale) {
                    return Shape::mesh_file(path, pose_or_identity(pose), scale);
                  }, py::arg("path"), py::arg("pose") = py::none(), py::arg("scale") = Eigen::Vector3d::Ones(),
                  "A mesh file (STL, DAE, OBJ ... read by assimp), scaled per axis (OSError if it cannot be read).")
      .def_static("triangle_mesh", [](const py::object& vertices, const py::object& triangles, const py::object& pose) {
                    MeshVertices v = matrix_from(vertices, 3, "vertices");
                    MeshTriangles tri = index_triples_from(triangles, std::size_t(v.rows()), "triangles");
                    return Shape::triangle_mesh(v, tri, pose_or_identity(pose));
                  }, py::arg("vertices"), py::arg("triangles"), py::arg("pose") = py::none(),
                  "A triangle mesh: vertices (N, 3) and triangles (M, 3) of vertex indices, in the frame of `pose`.")
      .def_static("octree_file", [](const std::string& path, const py::object& pose) {
                    return Shape::octree_file(path, pose_or_identity(pose));
                  }, py::arg("path"), py::arg("pose") = py::none(),
                  "The occupied cells of an OctoMap file (.bt, or .ot holding an OcTree).")
      .def_property_readonly("kind", &Shape::type_name, "'box', 'cylinder', 'sphere', 'mesh' or 'octree'.")
      .def_property_readonly("size", [](const Shape& s) { return s.size; }, "Box extents (x, y, z).")
      .def_property_readonly("radius", [](const Shape& s) { return s.radius; }, "Cylinder or sphere radius.")
      .def_property_readonly("length", [](const Shape& s) { return s.length; }, "Cylinder length.")
      .def_property_readonly("mesh_path", [](const Shape& s) { return s.mesh_path; },
                             "Mesh file ('' for triangles given in memory, or a robot's visual mesh not found).")
      .def_property_readonly("scale", [](const Shape& s) { return s.scale; }, "Mesh scale, per axis.")
      .def_property_readonly("pose", [](const Shape& s) { return pose_to_array(s.origin); },
                             "4x4 pose in the parent frame (a link's frame, or the world).")
      .def("mesh_triangles", &mesh_arrays,
           "(vertices (N, 3), triangles (M, 3)) of a mesh shape in its own frame (before `pose`); ValueError for\n"
           "other kinds.")
      .def("octree_cells", &octree_cells,
           "(centres (N, 3), edges (N,)) of an OctoMap shape's occupied cells in its own frame (before `pose`);\n"
           "ValueError for other kinds.")
      .def("__repr__", [](const Shape& s) { return std::string("<octoreach.Shape ") + s.type_name() + ">"; });
}

}  // namespace octoreach::py_bindings
