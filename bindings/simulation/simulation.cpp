// Simulation bindings: Scene, CameraIntrinsics, DepthCamera, look_at.
#include <algorithm>

#include "common.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::py_bindings {

namespace {

// A box added with the GIL released while the scene's exclusive lock is taken (see the mutators below).
void unlocked_add_box(Scene& s, const py::object& lo, const py::object& hi) {
  const Eigen::Vector3d l = vec3_from(lo, "lo"), h = vec3_from(hi, "hi");
  py::gil_scoped_release release;
  s.add_box(l, h);
}

void wrap_scene(py::module_& m) {
  py::class_<Scene>(m, "Scene",
                    "Simulated world: Shapes (boxes with any pose, cylinders, spheres, meshes, OctoMaps), crates, closed\n"
                    "boxes with an opening, boards. Whatever it holds is seen by the DepthCamera and is an obstacle\n"
                    "(obstacles()). Metres, world frame.")
      .def(py::init<>())
      // Mutators release the GIL before they wait for the scene's exclusive lock: a capture on another thread
      // holds the shared lock and may need the GIL to poll for Ctrl-C.
      .def("add_shape", py::overload_cast<const Shape&>(&Scene::add), py::arg("shape"),
           py::call_guard<py::gil_scoped_release>(), "Adds a Shape (world frame).")
      .def("add_obstacles", py::overload_cast<const Obstacles&>(&Scene::add), py::arg("obstacles"),
           py::call_guard<py::gil_scoped_release>(),
           "Adds every shape of an Obstacles set (a Room's, a Surface's).")
      .def_property_readonly("shapes", &Scene::shapes, "Every Shape of the scene (world frame), in the order added.")
      .def("obstacles", &Scene::obstacles, "The scene's shapes as Obstacles (for collision checks).")
      .def("add_box", [](Scene& s, const py::object& lo, const py::object& hi) { unlocked_add_box(s, lo, hi); },
           py::arg("lo"), py::arg("hi"), "Solid box (a board is a thin box).")
      .def("add_board", [](Scene& s, const py::object& lo, const py::object& hi) { unlocked_add_box(s, lo, hi); },
           py::arg("lo"), py::arg("hi"))
      .def("add_crate", [](Scene& s, const py::object& lo, const py::object& hi, double th) {
             const Eigen::Vector3d l = vec3_from(lo, "lo"), h = vec3_from(hi, "hi");
             py::gil_scoped_release release;
             s.add_crate(l, h, th);
           }, py::arg("lo"), py::arg("hi"), py::arg("thickness") = 0.02, "Open-topped crate; its inside is an interior.")
      .def("add_closed_box", [](Scene& s, const py::object& lo, const py::object& hi, double th, const std::string& face,
                                double w, double h) {
             const Eigen::Vector3d l = vec3_from(lo, "lo"), u = vec3_from(hi, "hi");
             py::gil_scoped_release release;
             s.add_closed_box(l, u, th, face, w, h);
           }, py::arg("lo"), py::arg("hi"), py::arg("thickness") = 0.02, py::arg("face") = "-x",
           py::arg("opening_width") = 0.1, py::arg("opening_height") = 0.1,
           "Closed box with one opening centred in face '+x', '-x', '+y', '-y' or '+z'; its inside is an interior.")
      .def("add_mesh", [](Scene& s, const py::object& vertices, const py::object& triangles) {
             auto v = points_from(vertices, "vertices");
             IndexTriples tri = index_triples_from(triangles, v.size(), "triangles");
             std::vector<Eigen::Vector3i> t(std::size_t(tri.rows()));
             for (Eigen::Index i = 0; i < tri.rows(); ++i) t[std::size_t(i)] = tri.row(i).transpose();
             py::gil_scoped_release release;
             s.add_mesh(v, t);
           }, py::arg("vertices"), py::arg("triangles"))
      .def("load_octomap", &Scene::load_octomap, py::arg("path"), py::call_guard<py::gil_scoped_release>(),
           "Adds the occupied cells of an OctoMap .bt file to the world (OSError if it cannot be read).")
      .def("add_interior", [](Scene& s, const py::object& lo, const py::object& hi) {
             const Eigen::Vector3d l = vec3_from(lo, "lo"), h = vec3_from(hi, "hi");
             py::gil_scoped_release release;
             s.add_interior(l, h);
           },
           py::arg("lo"), py::arg("hi"), "Records a region of interest for coverage figures.")
      .def_property_readonly("boxes", [](const Scene& s) {
        py::list out;
        for (const auto& b : s.boxes()) out.append(py::make_tuple(b.lo, b.hi));
        return out;
      }, "Axis-aligned solid boxes as (lo, hi) pairs (rotated boxes are in shapes).")
      .def_property_readonly("interiors", [](const Scene& s) {
        py::list out;
        for (const auto& b : s.interiors()) out.append(py::make_tuple(b.lo, b.hi));
        return out;
      }, "Regions of interest (insides of crates and closed boxes) as (lo, hi) pairs.")
      .def_property_readonly("triangle_count", &Scene::triangle_count, "Triangles of every mesh.")
      .def("bounds", [](const Scene& s) {
        Aabb b = s.bounds();
        return py::make_tuple(b.lo, b.hi);
      })
      .def("solid", [](const Scene& s, const py::object& points) {
             const std::vector<char> inside = s.solid(points_from(points, "points"));
             py::array_t<bool> out(static_cast<py::ssize_t>(inside.size()));
             std::copy(inside.begin(), inside.end(), out.mutable_data());
             return out;
           }, py::arg("points"), "True for points inside a solid box, sphere or cylinder.")
      .def("raycast", [](const Scene& s, const py::object& o, const py::object& d, double max_range,
                         bool normal) -> py::object {
             Eigen::Vector3d dir = vec3_from(d, "direction");
             if (dir.allFinite()) dir.stableNormalize();  // any length in Python (zero stays zero: C++ says so)
             double t;
             Eigen::Vector3d n;
             if (!s.raycast(vec3_from(o, "origin"), dir, max_range, t, normal ? &n : nullptr))
               return py::none();
             if (normal) return py::make_tuple(t, n);
             return py::float_(t);
           }, py::arg("origin"), py::arg("direction"), py::arg("max_range") = 4.0, py::arg("normal") = false,
           "Distance to the first surface along the ray (direction: any non-zero length), or None; with\n"
           "normal=True (distance, unit surface normal facing the ray).");

}

void wrap_camera(py::module_& m) {
  m.def("look_at", [](const Eigen::Vector3d& eye, const Eigen::Vector3d& target, double roll) {
        return pose_to_array(look_at(eye, target, roll));
      }, py::arg("eye"), py::arg("target"), py::arg("roll") = 0.0,
      "Camera pose (4x4 camera -> world) at `eye` looking at `target` (world frame), rolled by `roll` radians\n"
      "about the optical axis (+z); at roll 0 the image +y points down.");
  py::class_<CameraIntrinsics>(m, "CameraIntrinsics", "Pinhole depth sensor: image size, horizontal fov (rad), range (m).")
      .def(py::init([](int w, int h, double fov, double r) {
             CameraIntrinsics c;
             c.width = w;
             c.height = h;
             c.fov = fov;
             c.max_range = r;
             c.validate();
             return c;
           }), py::arg("width") = 640, py::arg("height") = 480, py::arg("fov") = 1.0123, py::arg("max_range") = 4.0)
      .def_readonly("width", &CameraIntrinsics::width)
      .def_readonly("height", &CameraIntrinsics::height)
      .def_readonly("fov", &CameraIntrinsics::fov)
      .def_readonly("max_range", &CameraIntrinsics::max_range);

  py::class_<DepthCamera>(m, "DepthCamera",
                          "Simulated depth camera. It looks along its +z axis (+x right, +y down in the image, as\n"
                          "ROS optical frames); poses are 4x4 camera -> world transforms. noise: depth standard\n"
                          "deviation at 1 m, growing with depth^2. max_incidence (radians, (0, pi/2]): pixels whose\n"
                          "ray meets the surface at a larger angle to its normal give no return (pi/2: never);\n"
                          "noisy depths beyond max_range give none either.")
      .def(py::init<int, int, double, double, double, std::uint64_t, double>(), py::arg("width") = 640,
           py::arg("height") = 480, py::arg("fov") = 1.0123, py::arg("max_range") = 4.0, py::arg("noise") = 0.0,
           py::arg("seed") = 0, py::arg("max_incidence") = kPi / 2)
      .def_property_readonly("intrinsics", &DepthCamera::intrinsics)
      .def_property_readonly("width", [](const DepthCamera& c) { return c.intrinsics().width; })
      .def_property_readonly("height", [](const DepthCamera& c) { return c.intrinsics().height; })
      .def_property_readonly("fov", [](const DepthCamera& c) { return c.intrinsics().fov; })
      .def_property_readonly("max_range", [](const DepthCamera& c) { return c.intrinsics().max_range; })
      .def_property_readonly("noise", &DepthCamera::noise)
      .def_property_readonly("max_incidence", &DepthCamera::max_incidence)
      .def("capture", [](DepthCamera& c, const Scene& s, const py::object& pose, int threads) {
             Pose T = pose_from(pose, "camera_pose");
             std::vector<Eigen::Vector3d> pts;
             {
               py::gil_scoped_release release;
               pts = c.capture(s, T, threads);
             }
             return to_points(pts);
           }, py::arg("scene"), py::arg("camera_pose"), py::arg("threads") = 0,
           "Points (N, 3), world frame, seen from camera_pose (4x4 camera -> world).");

}

}  // namespace

void wrap_simulation(py::module_& m) {
  wrap_scene(m);
  wrap_camera(m);
}

}  // namespace octoreach::py_bindings
