#pragma once
// Internal: the one way octoreach writes a file. The bytes go to a temporary file next to the
// target, every write is checked, the file is flushed and fsync'ed, then renamed over the target:
// a failed or interrupted write leaves the old file untouched.
#include <functional>
#include <ostream>
#include <string>

namespace octoreach::detail {

/// \brief Writes what `write` puts into the stream to `path` atomically.
/// \throws FileError naming the path (and `what`, e.g. "map file") when any step fails.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           const std::string& what = "file");

}  // namespace octoreach::detail
