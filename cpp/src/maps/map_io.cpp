#include "maps/map_io.hpp"

#include "common/atomic_file.hpp"
#include "common/file_read.hpp"
#include "octoreach/limits.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <cmath>

#include <octomap/ColorOcTree.h>
#include <zlib.h>

namespace octoreach {
int map_format_version() { return static_cast<int>(detail::kFormatVersion); }
}  // namespace octoreach

namespace octoreach::detail {
namespace {
const char kMagic[] = "OCTOREACH-MAP\n";
constexpr std::size_t kMagicLen = sizeof(kMagic) - 1;

template <class T>
void put(std::ostream& s, const T& v) {
  s.write(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T>
bool get(std::istream& s, T& v) {
  return static_cast<bool>(s.read(reinterpret_cast<char*>(&v), sizeof(T)));
}
}  // namespace

void write_map_file(const std::string& path, const std::string& kind, const Header& header,
                    const std::vector<char>& payload) {
  std::string text;
  for (const auto& [k, v] : header) {
    if (k.find_first_of("=\n") != std::string::npos || v.find('\n') != std::string::npos)
      throw std::invalid_argument("map header entry '" + k + "' holds '=' or a newline");
    text += k + "=" + v + "\n";
  }
  uLongf bound = compressBound(payload.size());
  std::vector<Bytef> compressed(bound);
  if (compress2(compressed.data(), &bound, reinterpret_cast<const Bytef*>(payload.data()), payload.size(), 6) != Z_OK)
    throw FileError("cannot compress map data for '" + path + "'");
  compressed.resize(bound);
  // The checksum covers the kind, the header (build parameters) and the payload.
  std::uint32_t crc = crc32(0L, reinterpret_cast<const Bytef*>(kind.data()), kind.size());
  crc = crc32(crc, reinterpret_cast<const Bytef*>(text.data()), text.size());
  crc = crc32(crc, compressed.data(), compressed.size());

  write_file_atomically(path, [&](std::ostream& f) {
    f.write(kMagic, kMagicLen);
    put(f, kFormatVersion);
    put(f, static_cast<std::uint32_t>(kind.size()));
    f.write(kind.data(), kind.size());
    put(f, static_cast<std::uint32_t>(text.size()));
    f.write(text.data(), text.size());
    put(f, static_cast<std::uint64_t>(payload.size()));
    put(f, static_cast<std::uint64_t>(compressed.size()));
    put(f, crc);
    f.write(reinterpret_cast<const char*>(compressed.data()), compressed.size());
  }, "map file");
}

namespace {
std::ifstream open_map_file(const std::string& path) {
  check_file_bounded(path, "map file", limits::kMapFileBytes);  // a FIFO would block the open
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    if (errno == ENOENT) throw FileNotFound("cannot open map file '" + path + "' (no such file)");
    throw FileError("cannot open map file '" + path + "'");
  }
  return f;
}

// Reads the magic, the format version and the kind field; returns the kind as written.
std::string read_kind_field(std::istream& f, const std::string& path) {
  char magic[kMagicLen];
  if (!f.read(magic, kMagicLen) || std::memcmp(magic, kMagic, kMagicLen) != 0)
    throw FileError("'" + path + "' is not an octoreach map file (bad magic)");
  std::uint32_t version = 0, klen = 0;
  if (!get(f, version)) throw FileError("'" + path + "' is truncated (no format version)");
  if (version < kOldestFormatVersion || version > kFormatVersion)
    throw FileError("'" + path + "' has map format version " + std::to_string(version) + ", this octoreach reads " +
                    std::to_string(kOldestFormatVersion) + " to " + std::to_string(kFormatVersion));
  if (!get(f, klen) || klen > 64) throw FileError("'" + path + "' is damaged (bad kind field)");
  std::string file_kind(klen, '\0');
  if (!f.read(file_kind.data(), klen)) throw FileError("'" + path + "' is truncated (kind)");
  return file_kind;
}

std::string printable(std::string kind) {
  for (char& c : kind)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '?';  // damaged: keep it printable
  return kind;
}
}  // namespace

std::string read_map_kind(const std::string& path) {
  std::ifstream f = open_map_file(path);
  return printable(read_kind_field(f, path));
}

void read_map_file(const std::string& path, const std::string& kind, Header& header, std::vector<char>& payload,
                   const std::function<std::uint64_t(const Header&)>& max_payload) {
  std::ifstream f = open_map_file(path);
  f.seekg(0, std::ios::end);
  const std::uint64_t file_size = std::uint64_t(std::max<std::streamoff>(0, f.tellg()));
  f.seekg(0, std::ios::beg);
  const std::string file_kind = read_kind_field(f, path);
  if (file_kind != kind) throw FileError("'" + path + "' holds a " + printable(file_kind) + " map, expected a " + kind + " map");
  std::uint32_t hlen = 0;
  if (!get(f, hlen) || hlen > (1u << 24)) throw FileError("'" + path + "' is damaged (bad header length)");
  std::string text(hlen, '\0');
  if (!f.read(text.data(), hlen)) throw FileError("'" + path + "' is truncated (header)");
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    auto eq = line.find('=');
    if (eq == std::string::npos) throw FileError("'" + path + "' is damaged (header line without '=')");
    header[line.substr(0, eq)] = line.substr(eq + 1);
  }
  std::uint64_t raw = 0, size = 0;
  std::uint32_t crc = 0;
  if (!get(f, raw) || !get(f, size) || !get(f, crc)) throw FileError("'" + path + "' is truncated (payload sizes)");
  // zlib expands at most about 1032 times: a larger raw size is damage, and must not drive an allocation.
  if (size > (1ull << 34) || raw > 1032 * size + 1024) throw FileError("'" + path + "' is damaged (implausible sizes)");
  if (size > file_size) throw FileError("'" + path + "' is truncated (payload has fewer bytes than its header says)");
  // The decompressed size is bounded by what the header declares, before anything is allocated.
  if (raw > limits::kMapPayloadBytes)
    throw FileError("'" + path + "' declares " + std::to_string(raw) + " bytes of map data, more than the limit of " +
                    std::to_string(limits::kMapPayloadBytes) + " (damaged?)");
  const std::uint64_t declared = max_payload(header);
  if (raw > declared)
    throw FileError("'" + path + "' is damaged: its payload declares " + std::to_string(raw) +
                    " bytes, more than the " + std::to_string(declared) + " its header's counts can take");
  std::vector<Bytef> compressed(size);
  if (!f.read(reinterpret_cast<char*>(compressed.data()), size))
    throw FileError("'" + path + "' is truncated (payload has fewer bytes than its header says)");
  std::uint32_t actual = crc32(0L, reinterpret_cast<const Bytef*>(file_kind.data()), file_kind.size());
  actual = crc32(actual, reinterpret_cast<const Bytef*>(text.data()), text.size());
  actual = crc32(actual, compressed.data(), compressed.size());
  if (actual != crc)
    throw FileError("'" + path + "' is damaged (checksum mismatch)");
  payload.resize(raw);
  uLongf out = raw;
  if (uncompress(reinterpret_cast<Bytef*>(payload.data()), &out, compressed.data(), size) != Z_OK || out != raw)
    throw FileError("'" + path + "' is damaged (payload does not decompress)");
}

std::uint64_t payload_bound(std::uint64_t voxels, std::uint64_t record_bytes) {
  constexpr std::uint64_t kMasksPerVoxel = 16;  // the octree's depth: one child mask per level on a voxel's path
  std::uint64_t per_voxel = 0, records = 0, total = 0;
  if (__builtin_add_overflow(record_bytes, kMasksPerVoxel, &per_voxel) ||
      __builtin_mul_overflow(voxels, per_voxel, &records) || __builtin_add_overflow(records, 9u, &total))
    return ~std::uint64_t(0);
  return total;
}

std::uint64_t header_voxels(const Header& h, const std::string& path) {
  const std::uint64_t v = header_u64(h, "voxels", path);
  if (v > limits::kMapVoxels)
    throw FileError("'" + path + "' declares " + std::to_string(v) + " voxels, more than the limit of " +
                    std::to_string(limits::kMapVoxels) + " (damaged?)");
  return v;
}

double header_double(const Header& h, const std::string& key, const std::string& path) {
  auto it = h.find(key);
  if (it == h.end()) throw FileError("'" + path + "' lacks header entry '" + key + "'");
  try {
    std::size_t pos = 0;
    double v = std::stod(it->second, &pos);
    if (pos != it->second.size() || std::isnan(v)) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw FileError("'" + path + "' has a malformed header entry '" + key + "'");
  }
}

long long header_int(const Header& h, const std::string& key, const std::string& path) {
  auto it = h.find(key);
  if (it == h.end()) throw FileError("'" + path + "' lacks header entry '" + key + "'");
  try {
    std::size_t pos = 0;
    long long v = std::stoll(it->second, &pos);
    if (pos != it->second.size()) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw FileError("'" + path + "' has a malformed header entry '" + key + "'");
  }
}

std::uint64_t header_u64(const Header& h, const std::string& key, const std::string& path) {
  auto it = h.find(key);
  if (it == h.end()) throw FileError("'" + path + "' lacks header entry '" + key + "'");
  try {
    std::size_t pos = 0;
    if (it->second.empty() || it->second[0] == '-') throw std::invalid_argument("");
    unsigned long long v = std::stoull(it->second, &pos);
    if (pos != it->second.size()) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw FileError("'" + path + "' has a malformed header entry '" + key + "'");
  }
}

std::uint64_t header_model_hash(const Header& h, const std::string& path) {
  return h.count("model_hash") ? header_u64(h, "model_hash", path) : 0;
}

std::string header_string(const Header& h, const std::string& key, const std::string& path) {
  auto it = h.find(key);
  if (it == h.end()) throw FileError("'" + path + "' lacks header entry '" + key + "'");
  return it->second;
}

void write_color_octree(const VoxelOcTree& tree, double top, const std::string& path) {
  octomap::ColorOcTree color(tree.getResolution());
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    double v = std::min(1.0, std::max(0.0, it->getValue() / top));
    octomap::ColorOcTreeNode* n = color.updateNode(it.getKey(), true);
    // red (low) -> blue (high), as in the paper's figures
    n->setColor(static_cast<std::uint8_t>(255 * (1 - v)), static_cast<std::uint8_t>(80 * std::sin(M_PI * v)),
                static_cast<std::uint8_t>(255 * v));
  }
  color.updateInnerOccupancy();
  write_file_atomically(path, [&](std::ostream& f) {
    if (!color.write(f)) f.setstate(std::ios::failbit);
  }, "octovis file");
}

}  // namespace octoreach::detail
