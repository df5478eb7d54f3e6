// Frontier-void exploration: ExplorationMap, Scene, DepthCamera, next best view.
#include <chrono>
#include <cstring>

#include <octomap/OcTree.h>

#include "common.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/simulation.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::py_bindings {

namespace {

std::vector<Eigen::Vector3d> points_from(const py::handle& obj, const char* what) {
  Array a = Array::ensure(obj);
  if (!a || a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "?";
    if (a) {
      shape = "(";
      for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
      shape += a.ndim() == 1 ? ",)" : ")";
    }
    throw std::invalid_argument(std::string(what) + " must have shape (N, 3), got " + shape);
  }
  auto r = a.unchecked<2>();
  std::vector<Eigen::Vector3d> out(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out[i] = {r(i, 0), r(i, 1), r(i, 2)};
  return out;
}

Eigen::Vector3d vec3_from(const py::handle& obj, const char* what) {
  Array a = Array::ensure(obj);
  if (!a || a.size() != 3) throw std::invalid_argument(std::string(what) + " must have 3 entries");
  const double* d = a.data();
  return {d[0], d[1], d[2]};
}

py::array_t<double> to_points(const std::vector<Eigen::Vector3d>& pts) {
  py::array_t<double> out({static_cast<py::ssize_t>(pts.size()), py::ssize_t(3)});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int j = 0; j < 3; ++j) w(i, j) = pts[i][j];
  return out;
}

py::array_t<double> centers(const ExplorationMap& m, const std::vector<CellKey>& keys) {
  std::vector<Eigen::Vector3d> pts(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) pts[i] = m.center(keys[i]);
  return to_points(pts);
}

py::array_t<std::uint64_t> key_array(const std::vector<CellKey>& keys) {
  py::array_t<std::uint64_t> out(static_cast<py::ssize_t>(keys.size()));
  std::copy(keys.begin(), keys.end(), out.mutable_data());
  return out;
}

py::dict stats_dict(const InsertStats& s) {
  py::dict d;
  d["points"] = s.points;
  d["dropped"] = s.dropped;
  d["out_of_bounds"] = s.out_of_bounds;
  d["free_cells"] = s.free_cells;
  d["occupied_cells"] = s.occupied_cells;
  d["changed_cells"] = s.changed_cells;
  d["frontier_added"] = s.frontier_added;
  d["frontier_removed"] = s.frontier_removed;
  d["void_added"] = s.void_added;
  d["void_removed"] = s.void_removed;
  d["seconds_rays"] = s.seconds_rays;
  d["seconds_tree"] = s.seconds_tree;
  d["seconds_frontiers"] = s.seconds_frontiers;
  d["seconds_hull"] = s.seconds_hull;
  d["seconds_voids"] = s.seconds_voids;
  d["seconds"] = s.seconds_total;
  return d;
}

py::dict snapshot_dict(const ExplorationSnapshot& s) {
  py::dict d;
  d["frontier_cells"] = key_array(s.frontier_cells);
  py::list cl;
  for (const auto& c : s.frontier_clusters) cl.append(key_array(c));
  d["frontier_clusters"] = cl;
  d["void_cells"] = key_array(s.void_cells);
  return d;
}

// Order-independent digest of an occupancy tree at the finest resolution: counts of free and
// occupied cells and a sum of mixed (key, class, log-odds) hashes.
py::dict occupancy_digest(const octomap::OcTree& t) {
  std::size_t n_free = 0, n_occ = 0;
  std::uint64_t h = 0;
  auto mix = [](std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
  };
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    bool occ = t.isNodeOccupied(*it);
    float lo = it->getLogOdds();
    std::uint32_t lo_bits;
    std::memcpy(&lo_bits, &lo, 4);
    octomap::OcTreeKey k = it.getKey();
    int size = 1 << (16 - it.getDepth());
    int mask = ~(size - 1);
    for (int z = 0; z < size; ++z)
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          CellKey c = pack_key((k[0] & mask) + x, (k[1] & mask) + y, (k[2] & mask) + z);
          h += mix(c ^ (std::uint64_t(lo_bits) << 48) ^ (std::uint64_t(occ) << 47));
          (occ ? n_occ : n_free)++;
        }
  }
  py::dict d;
  d["free"] = n_free;
  d["occupied"] = n_occ;
  d["hash"] = h;
  return d;
}

CameraIntrinsics intrinsics_from(const py::object& camera) {
  if (py::isinstance<DepthCamera>(camera)) return camera.cast<const DepthCamera&>().intrinsics();
  if (py::isinstance<CameraIntrinsics>(camera)) return camera.cast<CameraIntrinsics>();
  throw std::invalid_argument("camera must be a DepthCamera or CameraIntrinsics");
}

py::dict view_dict(const ViewCandidate& v, double res) {
  py::dict d;
  d["pose"] = pose_to_array(v.pose);
  d["void_cells"] = v.void_cells;
  d["unknown_cells"] = v.unknown_cells;
  d["utility_dm3"] = double(v.void_cells) * res * res * res * 1000.0;
  d["cell_utility"] = v.cell_utility;
  d["q"] = v.q.size() ? py::object(py::cast(v.q)) : py::object(py::none());
  return d;
}

}  // namespace

void wrap_exploration(py::module_& m) {
  m.def("look_at", [](const Eigen::Vector3d& eye, const Eigen::Vector3d& target, double roll) {
        return pose_to_array(look_at(eye, target, roll));
      }, py::arg("eye"), py::arg("target"), py::arg("roll") = 0.0,
      "Camera pose (4x4 camera -> world) at `eye` looking at `target` (world frame), rolled by `roll` radians\n"
      "about the optical axis (+z); at roll 0 the image +y points down.");
  py::class_<VoidCluster>(m, "VoidCluster",
                          "Ellipsoidal cluster of void cells (map frame, metres): centroid, axes (columns e1..e3),\n"
                          "eigenvalues (m^2, decreasing), semi_axes sqrt(5 lambda), fit score of eq. (2), cells.")
      .def_readonly("centroid", &VoidCluster::centroid)
      .def_readonly("axes", &VoidCluster::axes)
      .def_readonly("eigenvalues", &VoidCluster::eigenvalues)
      .def_readonly("semi_axes", &VoidCluster::semi_axes)
      .def_readonly("score", &VoidCluster::score)
      .def_property_readonly("size", [](const VoidCluster& v) { return v.cells.size(); })
      .def_property_readonly("keys", [](const VoidCluster& v) { return key_array(v.cells); })
      .def("__repr__", [](const VoidCluster& v) {
        return "<octoreach.VoidCluster " + std::to_string(v.cells.size()) + " cells, score " +
               std::to_string(v.score) + ">";
      });

  py::class_<ExplorationMap>(m, "ExplorationMap",
                             "OctoMap occupancy map with incremental frontiers (free cells with an unknown 6-neighbour,\n"
                             "clustered by 26-connectivity) and voids (unknown cells inside the convex hull of the\n"
                             "occupied cells), clustered into ellipsoids. Map frame, metres.")
      .def(py::init([](double resolution, double threshold, std::uint64_t seed, int threads, bool track_voids,
                       const py::object& search_space) {
             ExplorationOptions o;
             if (!search_space.is_none()) {
               RowMatrixXd b = matrix_from(search_space, 3, "search_space");
               if (b.rows() != 2 || !b.allFinite() || (b.row(0).array() > b.row(1).array()).any())
                 throw std::invalid_argument("search_space must be finite (2, 3) rows lo, hi with lo <= hi");
               o.search_lo = b.row(0).transpose();
               o.search_hi = b.row(1).transpose();
             }
             o.resolution = resolution;
             o.void_fit_threshold = threshold;
             o.seed = seed;
             o.threads = threads;
             o.track_voids = track_voids;
             return std::make_unique<ExplorationMap>(o);
           }),
           py::arg("resolution") = 0.025, py::arg("void_fit_threshold") = 0.6, py::arg("seed") = 0,
           py::arg("threads") = 0, py::arg("track_voids") = true, py::arg("search_space") = py::none(),
           "search_space: (2, 3) box (lo, hi) of the paper's search space S; voids are only looked for inside it.")
      .def_static("from_file", [](const std::string& path, double threshold, std::uint64_t seed) {
             ExplorationOptions o;
             o.void_fit_threshold = threshold;
             o.seed = seed;
             return ExplorationMap::from_file(path, o);
           }, py::arg("path"), py::arg("void_fit_threshold") = 0.6, py::arg("seed") = 0,
           "Map from an OctoMap .bt file (OSError if it cannot be read).")
      .def_property_readonly("resolution", &ExplorationMap::resolution)
      .def("insert", [](ExplorationMap& self, const py::object& points, const py::object& origin, double max_range) {
             auto pts = points_from(points, "points");
             Eigen::Vector3d o = vec3_from(origin, "sensor_origin");
             InsertStats s;
             {
               py::gil_scoped_release release;
               s = self.insert(pts, o, max_range);
             }
             return stats_dict(s);
           }, py::arg("points"), py::arg("sensor_origin"), py::arg("max_range") = -1.0,
           "Integrates points (N, 3) seen from sensor_origin (map frame); returns statistics and timings.\n"
           "Same occupancy as OctoMap insertPointCloud. Rows with NaN/inf are dropped; an empty cloud is a\n"
           "no-op; max_range <= 0 means unlimited. ValueError for a wrong shape, a non-finite origin or an\n"
           "origin outside the map bounds.")
      .def("insert_stock", [](ExplorationMap& self, const py::object& points, const py::object& origin,
                              double max_range) {
             auto pts = points_from(points, "points");
             Eigen::Vector3d o = vec3_from(origin, "sensor_origin");
             py::gil_scoped_release release;
             return self.insert_stock(pts, o, max_range);
           }, py::arg("points"), py::arg("sensor_origin"), py::arg("max_range") = -1.0,
           "Stock OctoMap insertPointCloud into this map's tree (reference; frontiers and voids go stale).")
      .def("state", [](const ExplorationMap& self, const py::object& points) {
             auto pts = points_from(points, "points");
             py::array_t<std::uint8_t> out(static_cast<py::ssize_t>(pts.size()));
             for (std::size_t i = 0; i < pts.size(); ++i) out.mutable_data()[i] = std::uint8_t(self.state(pts[i]));
             return out;
           }, py::arg("points"), "Class of the cell of each point (N, 3): 0 unknown, 1 free, 2 occupied.")
      .def("key_of", [](const ExplorationMap& self, const py::object& p) { return self.key_of(vec3_from(p, "point")); })
      .def("center", &ExplorationMap::center, py::arg("key"), "Centre (metres) of a cell key.")
      .def("centers", [](const ExplorationMap& self, const py::array_t<std::uint64_t>& keys) {
             std::vector<CellKey> k(keys.data(), keys.data() + keys.size());
             return centers(self, k);
           }, py::arg("keys"))
      .def("cells", [](const ExplorationMap& self, const std::string& which) {
             std::vector<CellKey> keys;
             if (which == "frontier") keys = self.frontier_cells();
             else if (which == "void") keys = self.void_cells();
             else if (which == "occupied" || which == "free") {
               const auto& t = self.octree();
               bool want = which == "occupied";
               for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
                 if (t.isNodeOccupied(*it) != want) continue;
                 octomap::OcTreeKey k = it.getKey();
                 int size = 1 << (16 - it.getDepth());
                 int mask = ~(size - 1);
                 for (int z = 0; z < size; ++z)
                   for (int y = 0; y < size; ++y)
                     for (int x = 0; x < size; ++x)
                       keys.push_back(pack_key((k[0] & mask) + x, (k[1] & mask) + y, (k[2] & mask) + z));
               }
               std::sort(keys.begin(), keys.end());
             } else {
               throw std::invalid_argument("cells: which must be 'frontier', 'void', 'occupied' or 'free', got '" +
                                           which + "'");
             }
             return centers(self, keys);
           }, py::arg("which"), "Centres (N, 3) of the frontier, void, occupied or free cells.")
      .def("frontier_keys", [](const ExplorationMap& self) { return key_array(self.frontier_cells()); })
      .def("void_keys", [](const ExplorationMap& self) { return key_array(self.void_cells()); })
      .def("frontier_clusters", [](const ExplorationMap& self) {
             py::list out;
             for (const auto& c : self.frontier_clusters()) out.append(centers(self, c));
             return out;
           }, "Frontier clusters as a list of (N, 3) cell centres.")
      .def_property_readonly("void_cell_count", &ExplorationMap::void_cell_count)
      .def_property_readonly("frontier_cell_count", [](const ExplorationMap& self) { return self.frontier_cells().size(); })
      .def("void_clusters", [](const ExplorationMap& self) {
             std::vector<VoidCluster> v;
             {
               py::gil_scoped_release release;
               v = self.void_clusters();
             }
             return v;
           }, "Void clusters (ellipsoid region growing, deterministic for the map's seed).")
      .def("void_cluster_cells", [](const ExplorationMap& self, const VoidCluster& v) { return centers(self, v.cells); },
           py::arg("cluster"), "Centres (N, 3) of a void cluster's cells.")
      .def("frontier_voids", [](const ExplorationMap& self) {
             std::vector<FrontierVoid> fvs;
             {
               py::gil_scoped_release release;
               fvs = self.frontier_voids();
             }
             py::list out;
             for (const auto& fv : fvs) {
               py::dict d;
               d["void_index"] = fv.void_index;
               d["frontier_clusters"] = fv.frontier_clusters;
               d["frontier_cells"] = centers(self, fv.frontier_cells);
               d["utility"] = fv.utility;
               out.append(d);
             }
             return out;
           }, "Void clusters with the frontier clusters touching them: dicts with void_index, frontier_clusters,\n"
              "frontier_cells (touching frontier cells, (K, 3)) and utility (void volume, m^3).")
      .def("hull_vertices", [](const ExplorationMap& self) { return to_points(self.hull_vertices()); })
      .def("inside_hull", [](const ExplorationMap& self, const py::object& p) { return self.inside_hull(vec3_from(p, "point")); })
      .def("changed_keys", [](const ExplorationMap& self) {
             std::vector<CellKey> k;
             for (const auto& c : self.changed_cells()) k.push_back(c.key);
             return key_array(k);
           }, "Keys of the cells whose class the last insert changed.")
      .def("snapshot", [](const ExplorationMap& self) { return snapshot_dict(self.snapshot()); },
           "Incrementally maintained frontier cells, clusters and void cells (keys).")
      .def("recompute_from_scratch", [](const ExplorationMap& self) {
             ExplorationSnapshot s;
             {
               py::gil_scoped_release release;
               s = self.recompute_from_scratch();
             }
             return snapshot_dict(s);
           }, "The same, recomputed from the occupancy and hull alone.")
      .def("count_known", [](const ExplorationMap& self, const py::object& lo, const py::object& hi) {
             return self.count_known(vec3_from(lo, "lo"), vec3_from(hi, "hi"));
           }, py::arg("lo"), py::arg("hi"), "(known, unknown) cell counts in an axis-aligned box.")
      .def("occupancy_digest", [](const ExplorationMap& self) { return occupancy_digest(self.octree()); },
           "Counts and an order-independent hash of the finest-resolution occupancy (to compare trees).")
      .def("write_bt", &ExplorationMap::write_bt, py::arg("path"), "Writes an OctoMap .bt file (octovis can open it).");

  py::class_<Scene>(m, "Scene",
                    "Simulated world: axis-aligned boxes, crates, closed boxes with an opening, boards, triangle\n"
                    "meshes, or an OctoMap .bt file. Metres, world frame.")
      .def(py::init<>())
      .def("add_box", [](Scene& s, const py::object& lo, const py::object& hi) { s.add_box(vec3_from(lo, "lo"), vec3_from(hi, "hi")); },
           py::arg("lo"), py::arg("hi"), "Solid box (a board is a thin box).")
      .def("add_board", [](Scene& s, const py::object& lo, const py::object& hi) { s.add_box(vec3_from(lo, "lo"), vec3_from(hi, "hi")); },
           py::arg("lo"), py::arg("hi"))
      .def("add_crate", [](Scene& s, const py::object& lo, const py::object& hi, double th) {
             s.add_crate(vec3_from(lo, "lo"), vec3_from(hi, "hi"), th);
           }, py::arg("lo"), py::arg("hi"), py::arg("thickness") = 0.02, "Open-topped crate; its inside is an interior.")
      .def("add_closed_box", [](Scene& s, const py::object& lo, const py::object& hi, double th, const std::string& face,
                                double w, double h) {
             s.add_closed_box(vec3_from(lo, "lo"), vec3_from(hi, "hi"), th, face, w, h);
           }, py::arg("lo"), py::arg("hi"), py::arg("thickness") = 0.02, py::arg("face") = "-x",
           py::arg("opening_width") = 0.1, py::arg("opening_height") = 0.1,
           "Closed box with one opening centred in face '+x', '-x', '+y', '-y' or '+z'; its inside is an interior.")
      .def("add_mesh", [](Scene& s, const py::object& vertices, const py::array_t<std::int64_t>& triangles) {
             auto v = points_from(vertices, "vertices");
             if (triangles.ndim() != 2 || triangles.shape(1) != 3)
               throw std::invalid_argument("triangles must have shape (M, 3)");
             auto r = triangles.unchecked<2>();
             std::vector<Eigen::Vector3i> t(triangles.shape(0));
             for (py::ssize_t i = 0; i < triangles.shape(0); ++i) t[i] = {int(r(i, 0)), int(r(i, 1)), int(r(i, 2))};
             s.add_mesh(v, t);
           }, py::arg("vertices"), py::arg("triangles"))
      .def("load_octomap", &Scene::load_octomap, py::arg("path"),
           "Adds the occupied cells of an OctoMap .bt file to the world (OSError if it cannot be read).")
      .def("add_interior", [](Scene& s, const py::object& lo, const py::object& hi) { s.add_interior(vec3_from(lo, "lo"), vec3_from(hi, "hi")); },
           py::arg("lo"), py::arg("hi"), "Records a region of interest for coverage figures.")
      .def_property_readonly("boxes", [](const Scene& s) {
        py::list out;
        for (const auto& b : s.boxes()) out.append(py::make_tuple(b.lo, b.hi));
        return out;
      }, "Solid boxes as (lo, hi) pairs.")
      .def_property_readonly("interiors", [](const Scene& s) {
        py::list out;
        for (const auto& b : s.interiors()) out.append(py::make_tuple(b.lo, b.hi));
        return out;
      }, "Regions of interest (insides of crates and closed boxes) as (lo, hi) pairs.")
      .def_property_readonly("triangle_count", &Scene::triangle_count)
      .def("bounds", [](const Scene& s) {
        Aabb b = s.bounds();
        return py::make_tuple(b.lo, b.hi);
      })
      .def("solid", [](const Scene& s, const py::object& points) {
             auto pts = points_from(points, "points");
             py::array_t<bool> out(static_cast<py::ssize_t>(pts.size()));
             for (std::size_t i = 0; i < pts.size(); ++i) out.mutable_data()[i] = s.solid(pts[i]);
             return out;
           }, py::arg("points"), "True for points inside a solid box.")
      .def("raycast", [](const Scene& s, const py::object& o, const py::object& d, double max_range) -> py::object {
             Eigen::Vector3d dir = vec3_from(d, "direction");
             if (!(dir.norm() > 0)) throw std::invalid_argument("direction must be non-zero");
             double t;
             if (!s.raycast(vec3_from(o, "origin"), dir.normalized(), max_range, t)) return py::none();
             return py::float_(t);
           }, py::arg("origin"), py::arg("direction"), py::arg("max_range") = 4.0,
           "Distance to the first surface along the ray, or None.");

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
                          "deviation at 1 m, growing with depth^2.")
      .def(py::init<int, int, double, double, double, std::uint64_t>(), py::arg("width") = 640,
           py::arg("height") = 480, py::arg("fov") = 1.0123, py::arg("max_range") = 4.0, py::arg("noise") = 0.0,
           py::arg("seed") = 0)
      .def_property_readonly("intrinsics", &DepthCamera::intrinsics)
      .def_property_readonly("width", [](const DepthCamera& c) { return c.intrinsics().width; })
      .def_property_readonly("height", [](const DepthCamera& c) { return c.intrinsics().height; })
      .def_property_readonly("fov", [](const DepthCamera& c) { return c.intrinsics().fov; })
      .def_property_readonly("max_range", [](const DepthCamera& c) { return c.intrinsics().max_range; })
      .def_property_readonly("noise", &DepthCamera::noise)
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

  m.def("view_utility", [](const ExplorationMap& map, const py::object& camera, const py::object& pose, int sw, int sh) {
          CameraIntrinsics c = intrinsics_from(camera);
          Pose T = pose_from(pose, "camera_pose");
          py::gil_scoped_release release;
          return view_utility(map, c, T, sw, sh);
        }, py::arg("map"), py::arg("camera"), py::arg("camera_pose"), py::arg("score_width") = 48,
        py::arg("score_height") = 36,
        "(void cells, unknown cells) a camera at camera_pose (4x4) sees before the first occupied cell,\n"
        "casting a score_width x score_height grid of rays.");

  m.def("accumulate_utility", [](const ExplorationMap& map, double range) {
          std::vector<std::pair<CellKey, double>> u;
          {
            py::gil_scoped_release release;
            u = accumulate_utility(map, range);
          }
          std::vector<CellKey> keys;
          py::array_t<double> val(static_cast<py::ssize_t>(u.size()));
          for (std::size_t i = 0; i < u.size(); ++i) {
            keys.push_back(u[i].first);
            val.mutable_data()[i] = u[i].second;
          }
          return py::make_tuple(centers(map, keys), val);
        }, py::arg("map"), py::arg("sensor_range"),
        "Algorithm 1: (cell centres (N, 3), accumulated utility (N,), m^3) before workspace pruning.");

  m.def("next_best_view", [](const ExplorationMap& map, const py::object& camera, int max_valid_poses,
                             int orientations_per_cell, double spread, int max_cells, int sw, int sh,
                             double min_distance, std::uint64_t seed, int threads, const py::object& box,
                             const py::object& sphere, const py::object& workspace, const Chain* chain,
                             const py::object& chain_base, int ik_attempts, double ik_position_tolerance,
                             double ik_orientation_tolerance, const CapabilityMap* capability_map,
                             const py::object& capability_base, double min_reachability, bool arm_collisions,
                             bool capability_orientations) {
          CameraIntrinsics c = intrinsics_from(camera);
          NbvOptions o;
          o.max_valid_poses = max_valid_poses;
          o.orientations_per_cell = orientations_per_cell;
          o.orientation_spread = spread;
          o.max_candidate_cells = max_cells;
          o.score_width = sw;
          o.score_height = sh;
          o.min_distance = min_distance;
          o.seed = seed;
          o.threads = threads;
          if (!box.is_none()) {
            RowMatrixXd b = matrix_from(box, 3, "workspace_box");
            if (b.rows() != 2) throw std::invalid_argument("workspace_box must have shape (2, 3): lo and hi rows");
            o.workspace.box = Aabb{b.row(0).transpose(), b.row(1).transpose()};
          }
          if (!sphere.is_none()) {
            auto t = sphere.cast<py::tuple>();
            if (t.size() != 2) throw std::invalid_argument("workspace_sphere must be (center, radius)");
            o.workspace.sphere_center = vec3_from(t[0], "workspace_sphere center");
            o.workspace.sphere_radius = t[1].cast<double>();
          }
          if (!workspace.is_none()) {
            py::object fn = workspace;
            o.workspace.filter = [fn](const std::vector<Eigen::Vector3d>& pts) {
              py::gil_scoped_acquire gil;
              py::object r = fn(to_points(pts));
              py::array_t<bool> a = py::array_t<bool>::ensure(r);
              if (!a || a.size() != py::ssize_t(pts.size()))
                throw std::invalid_argument("workspace callable must return one bool per row of its (N, 3) input");
              return std::vector<bool>(a.data(), a.data() + a.size());
            };
          }
          o.chain = chain;
          if (!chain_base.is_none()) o.chain_base = pose_from(chain_base, "chain_base");
          o.ik.attempts = ik_attempts;
          o.ik.position_tolerance = ik_position_tolerance;
          o.ik.orientation_tolerance = ik_orientation_tolerance;
          o.ik.seed = seed;
          o.capability_map = capability_map;
          if (!capability_base.is_none()) o.capability_base = pose_from(capability_base, "capability_base");
          o.min_reachability = min_reachability;
          o.arm_collisions = arm_collisions;
          o.capability_orientations = capability_orientations;
          NbvResult r;
          {
            py::gil_scoped_release release;
            r = next_best_view(map, c, o);
          }
          const double res = map.resolution();
          py::dict d;
          py::list ranked;
          for (const auto& v : r.ranked) ranked.append(view_dict(v, res));
          d["ranked"] = ranked;
          d["best"] = r.ranked.empty() ? py::object(py::none()) : py::object(view_dict(r.ranked.front(), res));
          d["best_pose"] = r.ranked.empty() ? py::object(py::none()) : py::object(pose_to_array(r.ranked.front().pose));
          d["void_cells"] = r.best_void_cells();
          d["utility_dm3"] = double(r.best_void_cells()) * res * res * res * 1000.0;
          d["utility_vectors"] = r.utility_vectors;
          d["utility_cells"] = r.utility_cells;
          d["candidate_cells"] = r.candidate_cells;
          d["poses_scored"] = r.poses_scored;
          d["ik_failures"] = r.ik_failures;
          d["capability_pruned"] = r.capability_pruned;
          d["arm_collisions"] = r.arm_collisions;
          d["capability_rejected"] = r.capability_rejected;
          d["seconds"] = r.seconds;
          d["seconds_vectors"] = r.seconds_vectors;
          d["seconds_prune"] = r.seconds_prune;
          d["seconds_score"] = r.seconds_score;
          return d;
        }, py::arg("map"), py::arg("camera"), py::arg("max_valid_poses") = 50, py::arg("orientations_per_cell") = 8,
        py::arg("orientation_spread") = 0.35, py::arg("max_candidate_cells") = 400, py::arg("score_width") = 48,
        py::arg("score_height") = 36, py::arg("min_distance") = 0.0, py::arg("seed") = 0, py::arg("threads") = 0,
        py::arg("workspace_box") = py::none(), py::arg("workspace_sphere") = py::none(),
        py::arg("workspace") = py::none(), py::arg("chain") = nullptr, py::arg("chain_base") = py::none(),
        py::arg("ik_attempts") = 8, py::arg("ik_position_tolerance") = 1e-3, py::arg("ik_orientation_tolerance") = 1e-2,
        py::arg("capability_map") = nullptr, py::arg("capability_base") = py::none(), py::arg("min_reachability") = 0.0,
        py::arg("arm_collisions") = true, py::arg("capability_orientations") = true,
        "Next best view (Algorithm 1 + frustum scoring). Returns a dict: best_pose (4x4 camera -> map, or None),\n"
        "void_cells and utility_dm3 expected from it, ranked (valid poses, best first, each with pose,\n"
        "void_cells, unknown_cells, utility_dm3, cell_utility, q), and search statistics. The workspace is\n"
        "workspace_box ((2, 3): lo, hi), workspace_sphere ((center, radius)) and/or workspace, a callable\n"
        "taking cell centres (N, 3) and returning (N,) bools. With chain (its tip is the camera frame,\n"
        "+z forward) and chain_base (4x4 chain base -> map), a pose counts only if IK reaches it.\n"
        "capability_map (a CapabilityMap of that arm) with capability_base (4x4 map base link -> map) prunes\n"
        "candidate cells whose voxel has reachability index <= min_reachability before any IK, and with\n"
        "capability_orientations skips IK for sampled poses whose (voxel, optical axis) cell it marks unreachable.\n"
        "arm_collisions (with chain): IK solutions whose links touch an occupied cell are rejected.");

  m.def("_stock_insert_point_cloud", [](const py::object& points, const py::object& origin, double max_range,
                                        double resolution) {
          auto pts = points_from(points, "points");
          Eigen::Vector3d o = vec3_from(origin, "sensor_origin");
          octomap::Pointcloud pc;
          for (const auto& p : pts)
            if (p.allFinite()) pc.push_back(float(p.x()), float(p.y()), float(p.z()));
          octomap::OcTree tree(resolution);
          double seconds;
          {
            py::gil_scoped_release release;
            auto t0 = std::chrono::steady_clock::now();
            tree.insertPointCloud(pc, octomap::point3d(float(o.x()), float(o.y()), float(o.z())),
                                  max_range > 0 ? max_range : -1.0);
            seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          }
          py::dict d = occupancy_digest(tree);
          d["seconds"] = seconds;
          return d;
        }, py::arg("points"), py::arg("sensor_origin"), py::arg("max_range"), py::arg("resolution"),
        "Reference: stock OctoMap OcTree::insertPointCloud into a fresh tree; returns seconds and the\n"
        "occupancy digest (compare with ExplorationMap.occupancy_digest()).");
}

}  // namespace octoreach::py_bindings
