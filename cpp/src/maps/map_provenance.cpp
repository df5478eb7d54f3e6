#include "octoreach/map_provenance.hpp"

#include "maps/map_io.hpp"
#include "octoreach/robot.hpp"

namespace octoreach {

MapProvenance MapProvenance::of(const Robot& robot) {
  return MapProvenance{robot.name(), robot.urdf_hash(), robot.model_hash()};
}

bool MapProvenance::matches(const Robot& robot) const {
  return robot.name() == robot_name && robot.urdf_hash() == urdf_hash &&
         (model_hash == 0 || robot.model_hash() == model_hash);
}

namespace detail {

std::vector<std::pair<std::string, std::string>> provenance_entries(const MapProvenance& p) {
  return {{"robot", p.robot_name}, {"urdf_hash", std::to_string(p.urdf_hash)}, {"model_hash", std::to_string(p.model_hash)}};
}

MapProvenance header_provenance(const Header& h, const std::string& path) {
  MapProvenance p;
  p.robot_name = header_string(h, "robot", path);
  p.urdf_hash = header_u64(h, "urdf_hash", path);
  p.model_hash = header_model_hash(h, path);
  return p;
}

}  // namespace detail
}  // namespace octoreach
