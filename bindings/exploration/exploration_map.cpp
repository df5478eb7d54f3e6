// ExplorationMap bindings: the map, its cells, frontiers, voids and clusters.
#include "exploration/convert.hpp"

namespace octoreach::py_bindings {

namespace {

using MapClass = py::class_<ExplorationMap>;


py::dict snapshot_dict(const ExplorationSnapshot& s) {
  py::dict d;
  d["frontier_cells"] = key_array(s.frontier_cells);
  py::list cl;
  for (const auto& c : s.frontier_clusters) cl.append(key_array(c));
  d["frontier_clusters"] = cl;
  d["void_cells"] = key_array(s.void_cells);
  return d;
}

void wrap_void_cluster(py::module_& m) {
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

}

// The search space box of the constructor and of from_file into the options.
void set_search_space(ExplorationOptions& o, const py::object& search_space) {
  if (search_space.is_none()) return;
  const Aabb b = box_from(search_space, "search_space");
  if ((b.lo.array() > b.hi.array()).any()) throw std::invalid_argument("search_space must have lo <= hi on every axis");
  o.search_lo = b.lo;
  o.search_hi = b.hi;
}

// Construction, insertion and per-cell queries.
void def_map_core(MapClass& cls) {
  cls
      .def(py::init([](double resolution, double threshold, std::uint64_t seed, int threads, bool track_voids,
                       const py::object& search_space, bool voids_fill_search_space) {
             ExplorationOptions o;
             set_search_space(o, search_space);
             o.voids_fill_search_space = voids_fill_search_space;
             o.resolution = resolution;
             o.void_fit_threshold = threshold;
             o.seed = seed;
             o.threads = threads;
             o.track_voids = track_voids;
             return std::make_unique<ExplorationMap>(o);
           }),
           py::arg("resolution") = ExplorationOptions().resolution,
           py::arg("void_fit_threshold") = ExplorationOptions().void_fit_threshold, py::arg("seed") = 0,
           py::arg("threads") = 0, py::arg("track_voids") = true, py::arg("search_space") = py::none(),
           py::arg("voids_fill_search_space") = ExplorationOptions().voids_fill_search_space,
           "search_space: (2, 3) box (lo, hi) of the paper's search space S; voids are only looked for inside it.\n"
           "voids_fill_search_space: every unknown cell of S is a void cell (not only those inside the hull).")
      .def_static("from_file", [](const std::string& path, double threshold, std::uint64_t seed, std::uint64_t max_cells,
                                  const py::object& search_space) {
             ExplorationOptions o;
             o.void_fit_threshold = threshold;
             o.seed = seed;
             o.max_file_cells = max_cells;
             set_search_space(o, search_space);
             py::gil_scoped_release release;
             return ExplorationMap::from_file(path, o);
           }, py::arg("path"), py::arg("void_fit_threshold") = ExplorationOptions().void_fit_threshold, py::arg("seed") = 0,
           py::arg("max_cells") = ExplorationOptions().max_file_cells, py::arg("search_space") = py::none(),
           "Map from an OctoMap .bt file: FileNotFoundError if it does not exist, OSError if it cannot be read,\n"
           "states a resolution outside [1e-4, 1e4] m, covers more than max_cells finest-resolution cells, or\n"
           "its occupied cells span a box (clipped to search_space) too large to look for voids in.")
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
      .def("state", [](const ExplorationMap& self, const py::object& points) {
             RowMatrixXd pts = matrix_from(points, 3, "points");
             py::array_t<std::uint8_t> out(static_cast<py::ssize_t>(pts.rows()));
             self.state(pts.data(), std::size_t(pts.rows()), out.mutable_data());
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
             else if (which == "occupied") keys = self.known_cells(CellState::Occupied);
             else if (which == "free") keys = self.known_cells(CellState::Free);
             else
               throw std::invalid_argument("cells: which must be 'frontier', 'void', 'occupied' or 'free', got '" +
                                           which + "'");
             return centers(self, keys);
           }, py::arg("which"), "Centres (N, 3) of the frontier, void, occupied or free cells.");
}

// Frontiers, voids, clusters, hull, snapshots and files.
void def_map_sets(MapClass& cls) {
  cls
      .def("frontier_keys", [](const ExplorationMap& self) { return key_array(self.frontier_cells()); })
      .def("void_keys", [](const ExplorationMap& self) { return key_array(self.void_cells()); })
      .def("frontier_clusters", [](const ExplorationMap& self) {
             py::list out;
             for (const auto& c : self.frontier_clusters()) out.append(centers(self, c));
             return out;
           }, "Frontier clusters as a list of (N, 3) cell centres.")
      .def_property_readonly("void_cell_count", &ExplorationMap::void_cell_count)
      .def_property_readonly("sealed_void_cell_count", &ExplorationMap::sealed_void_cell_count,
                             "void cells no view can reveal (their void component touches only occupied cells)")
      .def_property_readonly("frontier_cell_count", [](const ExplorationMap& self) { return self.frontier_cells().size(); })
      .def("void_clusters", &ExplorationMap::void_clusters, py::call_guard<py::gil_scoped_release>(), "Void clusters (ellipsoid region growing, deterministic for the map's seed).")
      .def("void_clusters_from_scratch", &ExplorationMap::void_clusters_from_scratch,
           py::call_guard<py::gil_scoped_release>(), "Void clusters computed from scratch from the current void cells (void_clusters() equals them).")
      .def("ray_statistics", [](const ExplorationMap& self) {
             RayStatistics r = self.ray_statistics();
             py::dict d;
             d["unknown_to_free"] = r.unknown_to_free;
             d["unknown_to_occupied"] = r.unknown_to_occupied;
             d["void_to_free"] = r.void_to_free;
             d["void_to_occupied"] = r.void_to_occupied;
             d["pass_probability"] = r.pass_probability();
             d["void_pass_probability"] = r.void_pass_probability();
             return d;
           }, "What the rays of all inserts did to cells that were unknown (distinct cells that became free or\n"
              "occupied; all unknown cells and void cells alone) and the pass probabilities learned from it.")
      .def_property_readonly("pass_probability", &ExplorationMap::pass_probability,
                             "p of the next-best-view visibility model for unknown cells outside the voids, learned\n"
                             "from the inserts so far.")
      .def_property_readonly("void_pass_probability", &ExplorationMap::void_pass_probability,
                             "p of the visibility model for void cells (prior: pass_probability).")
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
      .def("occupancy_digest", [](const ExplorationMap& self) { return digest_dict(self.occupancy_digest()); },
           "Counts and an order-independent hash of the finest-resolution occupancy (to compare trees).")
      .def("write_bt", &ExplorationMap::write_bt, py::arg("path"), "Writes an OctoMap .bt file (octovis can open it).");
}

}  // namespace

void wrap_exploration_map(py::module_& m) {
  wrap_void_cluster(m);
  MapClass cls(m, "ExplorationMap",
               "OctoMap occupancy map with incremental frontiers (free cells with an unknown 6-neighbour,\n"
               "clustered by 26-connectivity) and voids (unknown cells inside the convex hull of the\n"
               "occupied cells), clustered into ellipsoids. Map frame, metres.");
  def_map_core(cls);
  def_map_sets(cls);
}

}  // namespace octoreach::py_bindings
