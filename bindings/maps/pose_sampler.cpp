// CostMap and PoseSampler: the grounding attachment of a planner.
#include "common.hpp"
#include "octoreach/pose_sampler.hpp"

namespace octoreach::py_bindings {

namespace {

// PoseSampler(in_collision=...): an Obstacles (the map's body against them), a tuple (robot, obstacles[, reference])
// or a callable replaces the room check; None keeps it.
void collision_arg(PoseSampler& s, const py::object& in_collision) {
  if (py::isinstance<Obstacles>(in_collision)) {
    s.set_room(in_collision.cast<std::shared_ptr<Obstacles>>());
    return;
  }
  if (py::isinstance<py::tuple>(in_collision)) {
    py::tuple t = in_collision;
    if (t.size() < 2 || t.size() > 3)
      throw std::invalid_argument("in_collision must be a callable or a tuple (robot, obstacles[, reference])");
    Eigen::VectorXd ref = t.size() == 3 && !t[2].is_none()
                              ? cast_arg<Eigen::VectorXd>(t[2], "in_collision[2] (reference)", "a float array")
                              : Eigen::VectorXd();
    s.set_collision(cast_arg<std::shared_ptr<Robot>>(t[0], "in_collision[0]", "an octoreach.Robot"),
                    cast_arg<std::shared_ptr<Obstacles>>(t[1], "in_collision[1]", "an octoreach.Obstacles"),
                    ref);
  } else if (!in_collision.is_none()) {
    if (!PyCallable_Check(in_collision.ptr()))
      throw py::type_error("in_collision must be an Obstacles, a tuple (robot, obstacles[, reference]) or a callable, got " +
                           type_name(in_collision));
    py::function f = in_collision;
    s.set_in_collision([f](const Eigen::Vector4d& c) {
      py::gil_scoped_acquire gil;
      return bool_result(f(c), "in_collision");
    });
  }
}

}  // namespace

void wrap_pose_sampler(py::module_& m) {
  py::class_<CostMap>(m, "CostMap",
      "2D navigation cost map: grid[row, col] covers x in [ox + col r, ...), y in [oy + row r, ...);\n"
      "free where the cost is below threshold; outside the grid is not free.")
      .def(py::init([](const Eigen::MatrixXf& grid, const Eigen::Vector2d& origin, double resolution, double threshold) {
             if (grid.size() == 0) throw std::invalid_argument("the cost map grid is empty");
             if (!grid.allFinite()) throw std::invalid_argument("the cost map grid must be finite (no NaN or inf)");
             if (!origin.allFinite()) throw std::invalid_argument("the cost map origin must be finite");
             if (!(resolution > 0) || !std::isfinite(resolution))
               throw std::invalid_argument("cost map resolution must be a positive finite number of metres");
             if (!std::isfinite(threshold)) throw std::invalid_argument("cost map threshold must be finite");
             CostMap c;
             c.cost = grid;
             c.origin = origin;
             c.resolution = resolution;
             c.threshold = threshold;
             return c;
           }), py::arg("grid"), py::arg("origin"), py::arg("resolution"), py::arg("threshold") = 0.5)
      .def("is_free", [](const CostMap& c, double x, double y) {
             if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("x and y must be finite");
             return c.is_free(x, y);
           }, py::arg("x"), py::arg("y"));

  py::class_<PoseSampler>(m, "PoseSampler",
      "Samples good, well spread base poses (x, y, z, theta) from a surface map: the grounding attachment.")
      .def(py::init([](std::shared_ptr<SurfaceMap> map, int candidates, const Eigen::Vector4d& sigma, std::uint64_t seed,
                       const py::object& is_free, const py::object& in_collision, std::size_t max_draws, bool room_check) {
             PoseSamplerOptions o;
             o.room_check = room_check;
             o.candidates = candidates;
             o.discount_sigma = sigma;
             o.seed = seed;
             o.max_draws = max_draws;
             PoseSampler s(map, o);
             if (py::isinstance<CostMap>(is_free)) s.set_cost_map(is_free.cast<CostMap>());
             else if (!is_free.is_none()) {
               if (!PyCallable_Check(is_free.ptr()))
                 throw py::type_error("is_free must be a CostMap or a callable (pose (4,)) -> bool, got " + type_name(is_free));
               py::function f = is_free;
               s.set_is_free([f](const Eigen::Vector4d& c) {
                 py::gil_scoped_acquire gil;
                 return bool_result(f(c), "is_free");
               });
             }
             collision_arg(s, in_collision);
             return s;
           }), py::arg("surface_map"), py::arg("candidates") = 40,
           py::arg("discount_sigma") = Eigen::Vector4d(0.5, 0.5, 0.5, M_PI / 4), py::arg("seed") = 0,
           py::arg("is_free") = py::none(), py::arg("in_collision") = py::none(), py::arg("max_draws") = 0,
           py::arg("room_check") = PoseSamplerOptions().room_check, py::keep_alive<1, 2>(),
           "candidates: valid candidates per sample (best R_S x w wins). discount_sigma: S of eq. (3).\n"
           "is_free: a CostMap or a callable (pose (4,) as x, y, z, theta) -> bool. By default the body is checked against\n"
           "the room the map was built with (SurfaceMap.room); in_collision replaces that check: an Obstacles (the map's\n"
           "body against them), a tuple (robot, obstacles[, reference configuration]) checked with FCL in C++, or a\n"
           "callable (pose (4,)) -> bool (True = in collision). room_check=False turns the room check off.")
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
             if (!PyIndex_Check(k.ptr()) || PyBool_Check(k.ptr()))
               throw py::type_error("k must be an int or None, got " + std::string(py::str(py::type::of(k).attr("__name__"))));
             const long long kk = PyLong_AsLongLong(py::reinterpret_steal<py::object>(PyNumber_Index(k.ptr())).ptr());
             if (kk == -1 && PyErr_Occurred()) throw py::error_already_set();
             if (kk < 0 || std::uint64_t(kk) > limits::kSamplerCandidates)
               throw std::invalid_argument("k must be in [0, " + std::to_string(limits::kSamplerCandidates) + "] (at most " +
                                           std::to_string(limits::kSamplerCandidates) + " poses per call), got " +
                                           std::to_string(kk));
             const int n = int(kk);
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
      .def("discount", [](const PoseSampler& s, const Eigen::Vector4d& c) {
             if (!c.allFinite()) throw std::invalid_argument("pose must be finite (x, y, z, theta), got NaN or inf");
             return s.discount(c);
           }, py::arg("pose"),
           "w of eq. (3) for a pose against the history.")
      .def_property_readonly("checks_room", &PoseSampler::checks_room,
                             "True when the map's body is checked against a room (its own, or in_collision's Obstacles).")
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
