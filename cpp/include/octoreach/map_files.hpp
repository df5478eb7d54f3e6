#pragma once
/// \file map_files.hpp
/// \brief Map files of any kind: the registry of map kinds, and loading whichever kind a file holds (as
/// OctoMap's AbstractOcTree::read finds the tree type a file names in its registry).

#include <string>
#include <variant>
#include <vector>

#include "octoreach/capability_map.hpp"
#include "octoreach/map_provenance.hpp"
#include "octoreach/point_map.hpp"
#include "octoreach/surface_map.hpp"

namespace octoreach {

/// \brief The registry of map kinds: one alternative per kind a map file can hold. A map class joins it
/// with its kind tag `kKind` (written in its files' header), file extension `kExtension` and the file format
/// version it writes `kFormatVersion` (the newest, where its files differ by content; every version up to
/// map_format_version() is read), a static
/// `load(path)`, `save(path)` and `provenance()`.
using AnyMap = std::variant<CapabilityMap, InversePointMap, SurfaceMap>;

/// \brief A kind of the registry: its tag, as file headers name it, and its usual file extension.
struct MapKind {
  std::string tag;
  std::string extension;
  int format_version = 1;  ///< the newest map file format version its files are written in
};

/// \brief Every kind of the registry, in the order of AnyMap's alternatives.
std::vector<MapKind> map_kinds();

/// \brief The kind tag the map file at `path` names in its header, read without loading the map (a
/// character other than a letter, digit, '_' or '-' shows as '?'). Throws FileNotFound, or FileError
/// naming the file and the problem when it is not an octoreach map file of this format version.
std::string map_kind(const std::string& path);

/// \brief The map stored at `path`, of the kind its header names. With `expected` (a kind tag), the file
/// must hold that kind. Throws FileNotFound, FileError naming the file and the problem (not a map file,
/// a kind this library does not read or not the expected one, damage), std::invalid_argument when
/// `expected` is not a kind of the registry.
AnyMap load_any(const std::string& path, const std::string& expected = "");

/// \brief The kind tag of a map.
const char* kind_of(const AnyMap& map);

/// \brief The robot a map of any kind was built for.
const MapProvenance& provenance_of(const AnyMap& map);

}  // namespace octoreach
