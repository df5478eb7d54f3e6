#pragma once
// Internal: the one way octoreach writes a file. The bytes go to a temporary file next to the
// target, created exclusively under an unpredictable name (`<path>.tmp.<16 random characters>`,
// O_EXCL | O_NOFOLLOW: nothing planted in a shared folder is followed or overwritten); every write
// is checked, the file is fsync'ed, then renamed over the target: a failed or interrupted write
// leaves the old file untouched and no temporary file behind. A target that exists and is not a
// regular file (a symbolic link, device, FIFO, socket or directory) is refused, never replaced.
#include <functional>
#include <ostream>
#include <string>

namespace octoreach::detail {

/// \brief Writes what `write` puts into the stream to `path` atomically.
/// \throws FileError naming the path (and `what`, e.g. "map file") when any step fails or the target
/// is not a regular file.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           const std::string& what = "file");

}  // namespace octoreach::detail
