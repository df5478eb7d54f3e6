// Surfaces, surface maps and the base-pose sampler.
#include "common.hpp"
#include "octoreach/pose_sampler.hpp"
#include "octoreach/surface.hpp"
#include "octoreach/surface_map.hpp"

namespace octoreach::py_bindings {
namespace {

std::vector<Eigen::Vector3d> vertices_from(const py::object& obj) {
  RowMatrixXd v = matrix_from(obj, 3, "vertices");
  std::vector<Eigen::Vector3d> out;
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.emplace_back(v.row(i).transpose());
  return out;
}

py::array_t<double> lookup(const SurfaceMap& sm, const py::object& poses) {
  return pose_rows_lookup(poses, [&](double x, double y, double z, double t) { return sm.reachability(x, y, z, t); });
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
      .def("add_legs", &Surface::add_legs, py::arg("width") = 0.05, "Adds a leg under each vertex down to the floor.")
      .def_property_readonly("vertices", [](const Surface& s) {
        RowMatrixXd v(s.vertices().size(), 3);
        for (std::size_t i = 0; i < s.vertices().size(); ++i) v.row(i) = s.vertices()[i].transpose();
        return v;
      })
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
             RowMatrixXd p = matrix_from(points, 3, "points");
             py::array_t<bool> out(p.rows());
             auto w = out.mutable_unchecked<1>();
             for (Eigen::Index i = 0; i < p.rows(); ++i) w(i) = s.contains(s.project(p.row(i).transpose()));
             return out;
           }, py::arg("points"), "True where a point's projection on the plane lies inside the polygon.")
      .def("obstacles", [](const Surface& s) { return s.obstacles(); },
           "The surface slab and its boxes as Obstacles (for collision checks).");

  py::class_<SurfaceMap, std::shared_ptr<SurfaceMap>>(m, "SurfaceMap",
      "Surface inverse reachability map: R_S of base poses (x, y, z, theta) of the reference frame, world frame.")
      .def_static("_build", [](const Robot& robot, const CapabilityMap& cap, const Surface& surface,
                               const std::string& reference_frame, const py::object& grasps, int theta_bins,
                               double resolution, const py::object& z_range, const py::object& reference,
                               bool check_body, bool check_arm, double grasp_height, int threads,
                               const py::object& progress) {
             SurfaceMapOptions o;
             o.reference_frame = reference_frame;
             grasps_arg(grasps, o.grasps, o.grasp_subset);
             o.theta_bins = theta_bins;
             o.resolution = resolution;
             z_range_arg(z_range, o.z_min, o.z_max);
             if (!reference.is_none()) o.reference = reference.cast<Eigen::VectorXd>();
             o.check_body = check_body;
             o.check_arm = check_arm;
             o.grasp_height = grasp_height;
             o.threads = threads;
             ProgressCallback cb = progress_arg(progress, "surface map");
             py::gil_scoped_release release;
             return std::make_shared<SurfaceMap>(SurfaceMap::build(robot, cap, surface, o, cb));
           }, py::arg("robot"), py::arg("capability_map"), py::arg("surface"), py::arg("reference_frame") = "",
           py::arg("grasps") = "upper_hemisphere", py::arg("theta_bins") = 16, py::arg("resolution") = 0.0,
           py::arg("z_range") = py::none(), py::arg("reference") = py::none(), py::arg("check_body") = true,
           py::arg("check_arm") = true, py::arg("grasp_height") = 0.05, py::arg("threads") = 0,
           py::arg("progress") = true)
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
      .def("reachability", &lookup, py::arg("poses"),
           "R_S (N,) of base poses (N, 4) as x, y, z, theta (world frame); 0 outside the map. The condition attachment.")
      .def("voxels", [](const SurfaceMap& sm) {
             std::vector<Eigen::Vector3d> c;
             std::vector<float> v;
             sm.map().voxels(c, v);
             RowMatrixXd C(c.size(), 3);
             for (std::size_t i = 0; i < c.size(); ++i) C.row(i) = c[i].transpose();
             Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> V =
                 Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(v.data(), c.size(),
                                                                                                  sm.map().theta_bins());
             return py::make_tuple(C, V);
           }, "(centres (M, 3), R_S (M, theta_bins)) of the voxels with R_S > 0.")
      .def_property_readonly("bounds", [](const SurfaceMap& sm) {
        auto b = sm.map().bounds();
        return py::make_tuple(b.first, b.second);
      }, "(min corner, max corner) of the voxels with R_S > 0.")
      .def_property_readonly("resolution", [](const SurfaceMap& sm) { return sm.map().resolution(); })
      .def_property_readonly("theta_bins", [](const SurfaceMap& sm) { return sm.map().theta_bins(); })
      .def_property_readonly("voxel_count", [](const SurfaceMap& sm) { return sm.map().voxel_count(); })
      .def_property_readonly("max_reachability", [](const SurfaceMap& sm) { return sm.map().max_value(); })
      .def_property_readonly("robot_name", &SurfaceMap::robot_name)
      .def_property_readonly("urdf_hash", &SurfaceMap::urdf_hash)
      .def_property_readonly("reference_frame", &SurfaceMap::reference_frame)
      .def_property_readonly("arms", &SurfaceMap::arms)
      .def_property_readonly("z_range", &SurfaceMap::z_range)
      .def_property_readonly("empty_reason", &SurfaceMap::empty_reason)
      .def_property_readonly("polygon", [](const SurfaceMap& sm) {
        RowMatrixXd v(sm.polygon().size(), 3);
        for (std::size_t i = 0; i < sm.polygon().size(); ++i) v.row(i) = sm.polygon()[i].transpose();
        return v;
      })
      .def_property_readonly("stats", [](const SurfaceMap& sm) {
        const auto& s = sm.stats();
        py::dict d;
        d["seconds"] = s.seconds;
        d["surface_points"] = s.surface_points;
        d["base_poses"] = s.base_poses;
        d["candidate_poses"] = s.candidate_poses;
        d["valid_poses"] = s.valid_poses;
        d["body_collisions"] = s.body_collisions;
        d["arm_rejections"] = s.arm_rejections;
        return d;
      })
      .def_property_readonly("parameters", [](const SurfaceMap& sm) {
        py::dict d;
        for (auto& [k, v] : sm.parameters()) d[py::str(k)] = v;
        return d;
      })
      .def("__repr__", [](const SurfaceMap& sm) {
        return "<octoreach.SurfaceMap " + sm.robot_name() + " (" + sm.arms() + "), frame '" + sm.reference_frame() +
               "', " + std::to_string(sm.map().voxel_count()) + " voxels x " + std::to_string(sm.map().theta_bins()) +
               " theta>";
      });

  py::class_<CostMap>(m, "CostMap",
      "2D navigation cost map: grid[row, col] covers x in [ox + col r, ...), y in [oy + row r, ...);\n"
      "free where the cost is below threshold; outside the grid is not free.")
      .def(py::init([](const Eigen::MatrixXf& grid, const Eigen::Vector2d& origin, double resolution, double threshold) {
             if (grid.size() == 0) throw std::invalid_argument("the cost map grid is empty");
             if (!(resolution > 0)) throw std::invalid_argument("cost map resolution must be positive");
             CostMap c;
             c.cost = grid;
             c.origin = origin;
             c.resolution = resolution;
             c.threshold = threshold;
             return c;
           }), py::arg("grid"), py::arg("origin"), py::arg("resolution"), py::arg("threshold") = 0.5)
      .def("is_free", &CostMap::is_free, py::arg("x"), py::arg("y"));

  py::class_<PoseSampler>(m, "PoseSampler",
      "Samples good, well spread base poses (x, y, z, theta) from a surface map: the grounding attachment.")
      .def(py::init([](std::shared_ptr<SurfaceMap> map, int candidates, const Eigen::Vector4d& sigma, std::uint64_t seed,
                       const py::object& is_free, const py::object& in_collision, std::size_t max_draws) {
             PoseSamplerOptions o;
             o.candidates = candidates;
             o.discount_sigma = sigma;
             o.seed = seed;
             o.max_draws = max_draws;
             PoseSampler s(map, o);
             if (py::isinstance<CostMap>(is_free)) s.set_cost_map(is_free.cast<CostMap>());
             else if (!is_free.is_none()) {
               if (!PyCallable_Check(is_free.ptr()))
                 throw std::invalid_argument("is_free must be a CostMap or a callable (pose (4,)) -> bool");
               py::function f = is_free;
               s.set_is_free([f](const Eigen::Vector4d& c) {
                 py::gil_scoped_acquire gil;
                 return f(c).cast<bool>();
               });
             }
             if (py::isinstance<py::tuple>(in_collision)) {
               py::tuple t = in_collision;
               if (t.size() < 2 || t.size() > 3)
                 throw std::invalid_argument("in_collision must be a callable or a tuple (robot, obstacles[, reference])");
               Eigen::VectorXd ref = t.size() == 3 && !t[2].is_none() ? t[2].cast<Eigen::VectorXd>() : Eigen::VectorXd();
               s.set_collision(t[0].cast<std::shared_ptr<Robot>>(), t[1].cast<std::shared_ptr<Obstacles>>(), ref);
             } else if (!in_collision.is_none()) {
               if (!PyCallable_Check(in_collision.ptr()))
                 throw std::invalid_argument("in_collision must be a callable or a tuple (robot, obstacles[, reference])");
               py::function f = in_collision;
               s.set_in_collision([f](const Eigen::Vector4d& c) {
                 py::gil_scoped_acquire gil;
                 return f(c).cast<bool>();
               });
             }
             return s;
           }), py::arg("surface_map"), py::arg("candidates") = 40,
           py::arg("discount_sigma") = Eigen::Vector4d(0.5, 0.5, 0.5, M_PI / 4), py::arg("seed") = 0,
           py::arg("is_free") = py::none(), py::arg("in_collision") = py::none(), py::arg("max_draws") = 0,
           py::keep_alive<1, 2>(),
           "candidates: valid candidates per sample (best R_S x w wins). discount_sigma: S of eq. (3).\n"
           "is_free: a CostMap or a callable (pose (4,) as x, y, z, theta) -> bool. in_collision: a tuple (robot, obstacles[,\n"
           "reference configuration]) checked with FCL in C++, or a callable (pose (4,)) -> bool (True = in collision).")
      .def("sample", [](PoseSampler& s, const py::object& k) -> py::object {
             auto one = [&]() {
               auto p = s.sample();
               if (!p) throw std::runtime_error("no valid base pose found within max_draws draws (all rejected: " +
                                                std::to_string(s.last_counts()[1]) + " R_S = 0, " +
                                                std::to_string(s.last_counts()[2]) + " not free, " +
                                                std::to_string(s.last_counts()[3]) + " in collision)");
               return *p;
             };
             if (k.is_none()) return py::cast(one());
             int n = k.cast<int>();
             if (n < 0) throw std::invalid_argument("k must be non-negative");
             RowMatrixXd out(n, 4);
             for (int i = 0; i < n; ++i) out.row(i) = one().transpose();
             return py::cast(out);
           }, py::arg("k") = py::none(),
           "One base pose (4,) as x, y, z, theta, or k poses (k, 4); each is discounted against all earlier ones.")
      .def("reset", &PoseSampler::reset, "Forgets the history and restarts the random stream.")
      .def_property_readonly("history", [](const PoseSampler& s) {
        RowMatrixXd out(s.history().size(), 4);
        for (std::size_t i = 0; i < s.history().size(); ++i) out.row(i) = s.history()[i].transpose();
        return out;
      }, "Poses returned so far (K, 4).")
      .def("discount", [](const PoseSampler& s, const Eigen::Vector4d& c) { return s.discount(c); }, py::arg("pose"),
           "w of eq. (3) for a pose against the history.")
      .def_property_readonly("last_counts", [](const PoseSampler& s) {
        auto c = s.last_counts();
        py::dict d;
        d["draws"] = c[0];
        d["zero_reachability"] = c[1];
        d["not_free"] = c[2];
        d["in_collision"] = c[3];
        return d;
      });
}

}  // namespace octoreach::py_bindings
