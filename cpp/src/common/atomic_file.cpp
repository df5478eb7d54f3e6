#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "octoreach/types.hpp"

namespace octoreach::detail {
namespace {

std::string temp_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           const std::string& what) {
  std::ostringstream buffer(std::ios::binary);
  write(buffer);
  if (!buffer) throw FileError("cannot write " + what + " '" + path + "' (serialising failed)");
  const std::string bytes = buffer.str();
  const std::string tmp = temp_name(path);
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    throw FileError("cannot write " + what + " '" + path + "' (cannot create '" + tmp + "': " + std::strerror(errno) + ")");
  auto fail = [&](const std::string& why) {
    int err = errno;
    ::close(fd);
    std::remove(tmp.c_str());
    throw FileError("cannot write " + what + " '" + path + "' (" + why + ": " + std::strerror(err) + ")");
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write failed");
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("fsync failed");
  if (::close(fd) != 0) {
    std::remove(tmp.c_str());
    throw FileError("cannot write " + what + " '" + path + "' (close failed: " + std::strerror(errno) + ")");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    int err = errno;
    std::remove(tmp.c_str());
    throw FileError("cannot write " + what + " '" + path + "' (rename failed: " + std::strerror(err) + ")");
  }
}

}  // namespace octoreach::detail
