#pragma once
// Private: a MapRoom as the bytes of a map file's "room" section (map_io.hpp), and back.
//
// Layout (numbers as in the map file):
//   uint32 obstacle count, uint32 surface count (the first obstacles, the map's own surface);
//   per obstacle: string name, shape
//   uint32 body shape count; per body shape: string link, shape
//   string: uint32 length, bytes
//   shape: uint8 kind (Shape::Type), 12 doubles pose (rotation row by row, then translation), then per kind:
//     box: 3 doubles size; cylinder: radius, length; sphere: radius;
//     mesh: uint8 flag (1: a convex solid, FCL's Convex), its file name (string), 3 doubles scale, uint32 vertex
//       count, doubles x y z each, uint32 triangle count, int32 i j k each (the triangles as loaded: scaled);
//     octree: its OctoMap binary stream (uint64 length, bytes).
#include <memory>
#include <string>
#include <vector>

#include "octoreach/map_room.hpp"

namespace octoreach::detail {

/// \brief The name of the section that holds a surface map's room.
inline constexpr char kRoomSection[] = "room";

/// \brief The bytes of a room.
std::vector<char> room_bytes(const MapRoom& room);
/// \brief The room in `bytes` (a section of the map file `path`). \throws FileError naming the file and the
/// problem when the bytes are damaged (counts beyond the bytes, non-finite or invalid sizes, bad indices).
MapRoom room_from_bytes(const std::vector<char>& bytes, const std::string& path);
/// \brief The sections of a surface map file that record `room`.
MapSections room_sections(const MapRoom& room);
/// \brief The room the sections of map file `path` record; an empty room when they hold none (files written
/// before maps recorded their room). \throws FileError when the record is damaged
std::shared_ptr<const MapRoom> room_of_sections(const MapSections& sections, const std::string& path);

}  // namespace octoreach::detail
