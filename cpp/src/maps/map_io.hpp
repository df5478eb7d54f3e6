#pragma once
// Private: the octoreach map file container and bounds-checked byte streams.
//
// File layout (numbers in the machine's byte order: little endian on x86-64 and ARM64, where every
// map so far was written; a big-endian machine would read them as damaged, never silently):
//   "OCTOREACH-MAP\n"      14-byte magic
//   uint32 format version  (kFormatVersion)
//   uint32 kind length, kind text ("capability", "point", "surface")
//   uint32 header length, header text: "key=value\n" lines (build parameters, robot)
//   uint64 raw payload size, uint64 compressed size, uint32 CRC-32 of kind, header and compressed bytes
//   compressed payload (zlib)
// Format version 2 (surface maps, which record their room) adds named sections after the payload:
//   uint32 section count; per section: uint32 name length, name, uint64 raw size, uint64 compressed size,
//   uint32 CRC-32 of name and compressed bytes, compressed bytes (zlib)
// A version 1 file is a version 2 file without the section count: both are read.
// Format version 3 is version 2 for readers that know the capability map header's "poles" (a direction set that
// also holds straight up and down): only capability maps with poles are written in it, so that an older reader
// refuses them instead of rebuilding their direction set without the poles.
// Saves go through detail::write_file_atomically (temporary file, fsync, rename).
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "octoreach/map_provenance.hpp"
#include "octoreach/types.hpp"
#include "common/format.hpp"
#include "octoreach/voxel_octree.hpp"

namespace octoreach::detail {

/// The newest map file format version this library reads and writes (every older one is read too).
constexpr std::uint32_t kFormatVersion = 3;
/// The first format version (no sections).
constexpr std::uint32_t kFirstFormatVersion = 1;
/// Named sections of a version 2 map file.
using Sections = MapSections;

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void put_bytes(const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    bytes.insert(bytes.end(), p, p + n);
  }
  std::vector<char> bytes;
};

class ByteReader {
 public:
  ByteReader(const std::vector<char>& data, std::string what) : data_(data), what_(std::move(what)) {}
  template <class T>
  T get() {
    T v;
    need(sizeof(T));
    std::memcpy(&v, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  // n == 0 copies nothing: `out` may then be the null data() of an empty vector, which memcpy must never get.
  void get_bytes(void* out, std::size_t n) {
    need(n);
    if (n == 0) return;
    std::memcpy(out, data_.data() + pos_, n);
    pos_ += n;
  }
  bool done() const { return pos_ == data_.size(); }
  std::size_t remaining() const { return data_.size() - pos_; }
  [[noreturn]] void fail(const std::string& why) const { throw FileError(what_ + ": " + why); }

 private:
  void need(std::size_t n) {
    if (data_.size() - pos_ < n) fail("damaged map data (payload ends early)");
  }
  const std::vector<char>& data_;
  std::string what_;
  std::size_t pos_ = 0;
};

using Header = std::map<std::string, std::string>;

/// Writes kind + header + payload atomically to `path`, in format `version` (the kind's kFormatVersion);
/// `sections` need version 2 or later.
void write_map_file(const std::string& path, const std::string& kind, const Header& header,
                    const std::vector<char>& payload, std::uint32_t version = kFirstFormatVersion,
                    const Sections& sections = {});
/// Reads a map file of the expected kind; throws FileError naming the problem. `max_payload(header)`
/// says how many bytes the contents the header declares can take (payload_bound of its counts): a file
/// declaring more decompressed bytes (or more than limits::kMapPayloadBytes) is refused before
/// anything is allocated or inflated.
/// `sections` (when given) gets the file's sections (none in a version 1 file).
void read_map_file(const std::string& path, const std::string& kind, Header& header, std::vector<char>& payload,
                   const std::function<std::uint64_t(const Header&)>& max_payload, Sections* sections = nullptr);

/// The most bytes a payload of `voxels` records of `record_bytes` each can take: the voxel count, the
/// root flag, at most one child mask per tree level per voxel, the records (saturating at 2^64 - 1).
std::uint64_t payload_bound(std::uint64_t voxels, std::uint64_t record_bytes);
/// The header's voxel count, checked against limits::kMapVoxels.
std::uint64_t header_voxels(const Header& h, const std::string& path);
/// The kind a map file names (its magic, format version and kind field checked, the rest unread), with
/// any character but letters, digits, '_' and '-' shown as '?'; throws FileError naming the problem.
std::string read_map_kind(const std::string& path);

/// Header helpers: a missing or malformed key raises FileError naming it.
double header_double(const Header& h, const std::string& key, const std::string& path);
long long header_int(const Header& h, const std::string& key, const std::string& path);
std::string header_string(const Header& h, const std::string& key, const std::string& path);
std::uint64_t header_u64(const Header& h, const std::string& key, const std::string& path);
/// The robot model hash of a map header; 0 (unknown) in files written before maps recorded it.
std::uint64_t header_model_hash(const Header& h, const std::string& path);
/// The header entries of a provenance (robot, urdf_hash, model_hash), and the provenance a header records.
std::vector<std::pair<std::string, std::string>> provenance_entries(const MapProvenance& provenance);
MapProvenance header_provenance(const Header& h, const std::string& path);

/// Octree structure of a voxel tree: per inner node a child mask; at the finest depth `leaf(node)`
/// writes the voxel's record.
template <class LeafWriter>
void write_tree(const VoxelOcTree& tree, const VoxelNode* node, unsigned depth, ByteWriter& w, LeafWriter&& leaf) {
  if (depth == tree.getTreeDepth()) {
    leaf(*node);
    return;
  }
  std::uint8_t mask = 0;
  for (unsigned i = 0; i < 8; ++i)
    if (tree.nodeChildExists(node, i)) mask |= static_cast<std::uint8_t>(1u << i);
  w.put(mask);
  for (unsigned i = 0; i < 8; ++i)
    if (mask & (1u << i)) write_tree(tree, tree.getNodeChild(node, i), depth + 1, w, leaf);
}

/// Reads what write_tree wrote below `node`; an empty inner node is damage.
template <class LeafReader>
void read_tree(VoxelOcTree& tree, VoxelNode* node, unsigned depth, ByteReader& r, LeafReader&& leaf) {
  if (depth == tree.getTreeDepth()) {
    leaf(*node);
    return;
  }
  auto mask = r.get<std::uint8_t>();
  if (mask == 0) r.fail("damaged map data (empty inner node)");
  for (unsigned i = 0; i < 8; ++i)
    if (mask & (1u << i)) read_tree(tree, tree.createNodeChild(node, i), depth + 1, r, leaf);
}

/// Writes the leaves as an octomap ColorOcTree (.ot) coloured red (0) to blue (`top`), atomically.
void write_color_octree(const VoxelOcTree& tree, double top, const std::string& path);

}  // namespace octoreach::detail
