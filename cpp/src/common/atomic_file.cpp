#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "octoreach/types.hpp"

namespace octoreach::detail {
namespace {

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// 16 random letters and digits: from getrandom, or (should it fail) from the clock, the pid and a counter;
// the name only has to be unguessable enough that creating it exclusively rarely collides.
std::string random_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  unsigned char raw[16];
  ssize_t got = ::getrandom(raw, sizeof raw, GRND_NONBLOCK);
  if (got != static_cast<ssize_t>(sizeof raw)) {
    std::uint64_t x = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                      (static_cast<std::uint64_t>(::getpid()) << 40) ^ (counter.fetch_add(1) * 0x9E3779B97F4A7C15ULL);
    for (auto& c : raw) {
      x ^= x >> 33;
      x *= 0xFF51AFD7ED558CCDULL;
      c = static_cast<unsigned char>(x >> 56);
    }
  }
  static const char kChars[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::string s;
  for (unsigned char c : raw) s += kChars[c % 36];
  return s;
}

// Refuses a target that is not a regular file: a device (as root, renaming over /dev/full would replace
// the device), a FIFO, a socket, a directory, or a symbolic link (a link may point anywhere: following
// it could write outside the folder the caller meant, replacing it would silently cut it).
void check_target(const std::string& path, const std::string& what) {
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) return;  // absent (or unreachable: the create below says why)
  const char* kind = S_ISREG(st.st_mode)    ? nullptr
                     : S_ISLNK(st.st_mode)  ? "a symbolic link (save to the file it points to, or remove it first)"
                     : S_ISDIR(st.st_mode)  ? "a directory"
                     : S_ISFIFO(st.st_mode) ? "a FIFO"
                     : S_ISCHR(st.st_mode)  ? "a character device"
                     : S_ISBLK(st.st_mode)  ? "a block device"
                                            : "not a regular file";
  if (kind) throw FileError("cannot write " + what + " '" + path + "': it is " + kind + "; refusing to replace it");
}

// Creates a new temporary file next to `path` exclusively (O_EXCL | O_NOFOLLOW: a file or link planted
// at the name makes the create fail instead of being followed) under an unpredictable name.
int create_temp(const std::string& path, const std::string& what, std::string& tmp) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    tmp = path + ".tmp." + random_suffix();
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) return fd;
    if (errno != EEXIST)
      throw FileError("cannot write " + what + " '" + path + "' (cannot create a temporary file in '" +
                      folder_of(path) + "': " + std::strerror(errno) + ")");
  }
  throw FileError("cannot write " + what + " '" + path + "' (no free temporary name in '" + folder_of(path) + "')");
}

// Makes the rename itself durable (best effort: some file systems refuse fsync on a folder).
void sync_folder(const std::string& path) {
  const int dir = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return;
  (void)::fsync(dir);
  ::close(dir);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           const std::string& what) {
  std::ostringstream buffer(std::ios::binary);
  write(buffer);
  if (!buffer) throw FileError("cannot write " + what + " '" + path + "' (serialising failed)");
  const std::string bytes = buffer.str();
  check_target(path, what);
  std::string tmp;
  int fd = create_temp(path, what, tmp);
  auto fail = [&](const std::string& why, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw FileError("cannot write " + what + " '" + path + "' (" + why + ": " + std::strerror(err) + ")");
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write failed", errno);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("fsync failed", errno);
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) fail("close failed", errno);
  // Checked again just before the rename: a link or device put there while the bytes were written is
  // refused too (rename replaces a link itself, never the file it points to).
  try {
    check_target(path, what);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("rename failed", errno);
  sync_folder(path);
}

}  // namespace octoreach::detail
