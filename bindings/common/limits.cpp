// octoreach._core.limits: the numeric limits of octoreach/limits.hpp as a read-only mapping.
#include "common.hpp"
#include "octoreach/limits.hpp"

namespace octoreach::py_bindings {

void wrap_limits(py::module_& m) {
  namespace L = octoreach::limits;
  py::dict d;
  d["robot_file_bytes"] = L::kRobotFileBytes;
  d["mesh_file_bytes"] = L::kMeshFileBytes;
  d["octree_file_bytes"] = L::kOctreeFileBytes;
  d["map_file_bytes"] = L::kMapFileBytes;
  d["map_payload_bytes"] = L::kMapPayloadBytes;
  d["map_voxels"] = L::kMapVoxels;
  d["coordinate"] = L::kCoordinate;
  d["min_octree_resolution"] = L::kMinOctreeResolution;
  d["max_octree_resolution"] = L::kMaxOctreeResolution;
  d["min_map_resolution"] = L::kMinMapResolution;
  d["max_map_resolution"] = L::kMaxMapResolution;
  d["polygon_vertices"] = L::kPolygonVertices;
  d["surface_points"] = L::kSurfacePoints;
  d["directions"] = L::kDirections;
  d["rolls"] = L::kRolls;
  d["count_known_cells"] = L::kCountKnownCells;
  d["theta_bins"] = L::kThetaBins;
  d["map_grid_values"] = L::kMapGridValues;
  d["capability_cells"] = L::kCapabilityCells;
  d["image_pixels"] = L::kImagePixels;
  d["fk_samples"] = L::kFkSamples;
  d["view_candidates"] = L::kViewCandidates;
  d["sampler_candidates"] = L::kSamplerCandidates;
  m.attr("limits") = py::module_::import("types").attr("MappingProxyType")(d);
}

}  // namespace octoreach::py_bindings
