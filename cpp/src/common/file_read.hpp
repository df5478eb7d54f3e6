#pragma once
// Internal: the one way octoreach opens a file it reads. The path must name a regular file (a FIFO
// would block the open or the read forever, a device such as /dev/zero never ends) of at most a stated
// number of bytes (octoreach/limits.hpp), checked on the open file before anything is read.
#include <cstdint>
#include <string>

namespace octoreach::detail {

/// \brief The whole content of `path`.
/// \throws FileNotFound when it does not exist; FileError naming the path (and `what`, e.g. "URDF file")
/// when it is not a regular file, holds more than max_bytes bytes or cannot be read.
std::string read_file_bounded(const std::string& path, const std::string& what, std::uint64_t max_bytes);

/// \brief For files a library opens itself (assimp meshes): the checks of read_file_bounded, without
/// reading.
void check_file_bounded(const std::string& path, const std::string& what, std::uint64_t max_bytes);

}  // namespace octoreach::detail
