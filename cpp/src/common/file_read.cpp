#include "common/file_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "octoreach/types.hpp"

namespace octoreach::detail {
namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Closes the descriptor on every way out.
struct Fd {
  int fd;
  explicit Fd(int f) : fd(f) {}
  Fd(Fd&& o) noexcept : fd(o.fd) { o.fd = -1; }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// Opens `path` without blocking (a FIFO with no writer would block a plain open) and checks what it is.
Fd open_checked(const std::string& path, const std::string& what, std::uint64_t max_bytes, struct stat& st,
                const char* verb) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY)};
  if (f.fd < 0) {
    const int err = errno;
    if (err == ENOENT) throw FileNotFound(std::string("cannot ") + verb + " " + what + " '" + path + "' (no such file)");
    throw FileError(std::string("cannot ") + verb + " " + what + " '" + path + "' (" + std::strerror(err) + ")");
  }
  if (::fstat(f.fd, &st) != 0)
    throw FileError("cannot read " + what + " '" + path + "' (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode))
    throw FileError("cannot read " + what + " '" + path + "': it is " + kind_of(st.st_mode) + ", not a regular file");
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes)
    throw FileError("cannot read " + what + " '" + path + "': it holds " + std::to_string(st.st_size) +
                    " bytes, more than the limit of " + std::to_string(max_bytes) + " bytes for a " + what);
  return f;
}

}  // namespace

std::string read_file_bounded(const std::string& path, const std::string& what, std::uint64_t max_bytes) {
  struct stat st;
  Fd f = open_checked(path, what, max_bytes, st, "read");
  // Read to the end, in case the file grew since fstat, but never past the limit.
  std::string bytes(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t done = 0;
  for (;;) {
    if (done > max_bytes)
      throw FileError("cannot read " + what + " '" + path + "': it grew beyond the limit of " +
                      std::to_string(max_bytes) + " bytes while being read");
    if (done == bytes.size()) bytes.resize(bytes.size() + 4096);
    const ssize_t n = ::read(f.fd, &bytes[done], bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileError("cannot read " + what + " '" + path + "' (" + std::strerror(errno) + ")");
    }
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  return bytes;
}

void check_file_bounded(const std::string& path, const std::string& what, std::uint64_t max_bytes) {
  struct stat st;
  open_checked(path, what, max_bytes, st, "open");
}

}  // namespace octoreach::detail
