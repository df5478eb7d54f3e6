#pragma once
/// \file map_provenance.hpp
/// \brief The robot a map was built for, as every map kind records it in its file header.

#include <cstdint>
#include <string>

namespace octoreach {

class Robot;

/// \brief The robot a map was built for: a map answers for that robot only, so builders and samplers
/// compare it with the robot they are given. Every map kind keeps one and writes it into its file header
/// (entries robot, urdf_hash, model_hash).
struct MapProvenance {
  std::string robot_name;        ///< Robot::name()
  std::uint64_t urdf_hash = 0;   ///< Robot::urdf_hash()
  std::uint64_t model_hash = 0;  ///< Robot::model_hash(); 0 when unknown (files written before maps recorded it)

  /// \brief The provenance of a map built for `robot`.
  static MapProvenance of(const Robot& robot);
  /// \brief True when `robot` is the one recorded: same name and URDF, and same model hash where it is known.
  bool matches(const Robot& robot) const;
  bool operator==(const MapProvenance& other) const {
    return robot_name == other.robot_name && urdf_hash == other.urdf_hash && model_hash == other.model_hash;
  }
  bool operator!=(const MapProvenance& other) const { return !(*this == other); }
};

}  // namespace octoreach
