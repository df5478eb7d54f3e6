// Stock OctoMap insertion, bound for tests/python and benchmarks/exploration.py: the reference
// ExplorationMap.insert is compared with (same occupancy, leaf by leaf) and timed against.
#include <octomap/OcTree.h>

#include "exploration/convert.hpp"
#include "stock_insert.hpp"

namespace octoreach::py_bindings {

void wrap_stock_insert(py::module_& m) {
  m.def("stock_insert_point_cloud", [](const py::object& points, const py::object& origin, double max_range,
                                       double resolution) {
          auto pts = points_from(points, "points");
          Eigen::Vector3d o = vec3_from(origin, "sensor_origin");
          octomap::OcTree tree(resolution);
          double seconds;
          {
            py::gil_scoped_release release;
            seconds = bench::stock_insert(tree, pts, o, max_range);
          }
          py::dict d = digest_dict(occupancy_digest(tree));
          d["seconds"] = seconds;
          return d;
        }, py::arg("points"), py::arg("sensor_origin"), py::arg("max_range"), py::arg("resolution"),
        "Reference: stock OctoMap OcTree::insertPointCloud into a fresh tree; returns seconds and the\n"
        "occupancy digest (compare with ExplorationMap.occupancy_digest()). For tests and benchmarks only.");
}

}  // namespace octoreach::py_bindings
