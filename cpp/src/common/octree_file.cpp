#include "common/octree_file.hpp"

#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <istream>
#include <streambuf>

#include <octomap/OcTree.h>

#include "common/file_read.hpp"
#include "common/format.hpp"
#include "octoreach/limits.hpp"
#include "octoreach/types.hpp"

namespace octoreach::detail {

namespace {

constexpr const char* kBinaryHeader = "# Octomap OcTree binary file";

// A read-only stream over a string's bytes (tellg and seekg work), so the file is held once, not copied into
// an istringstream for the header parse and again for octomap's reader.
class ByteStream : std::streambuf, public std::istream {
  using pos_type = std::streambuf::pos_type;
  using off_type = std::streambuf::off_type;

 public:
  explicit ByteStream(const std::string& bytes) : std::istream(static_cast<std::streambuf*>(this)) {
    char* b = const_cast<char*>(bytes.data());  // never written through: no put area
    setg(b, b, b + bytes.size());
  }

 private:
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    char* base = dir == std::ios_base::beg ? eback() : dir == std::ios_base::cur ? gptr() : egptr();
    const off_type at = (base - eback()) + off;
    if (at < 0 || at > egptr() - eback()) return pos_type(off_type(-1));
    setg(eback(), eback() + at, egptr());
    return pos_type(at);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }
};

// The header as octomap's AbstractOcTree::readHeader reads it (tokens until "data", comments skipped);
// returns the offset of the node data. octomap's own reader does the same parse, so the offsets agree.
struct BtHeader {
  std::string id;
  double res = 0;
  unsigned long long size = 0;
  std::size_t data_offset = 0;
};

BtHeader parse_header(const std::string& bytes, const std::string& path) {
  ByteStream s(bytes);
  std::string line;
  std::getline(s, line);
  if (line.compare(0, std::string(kBinaryHeader).size(), kBinaryHeader) != 0)
    throw FileError("'" + path + "' is not an OctoMap binary (.bt) file: its first line is not \"" + kBinaryHeader +
                    "\" (files of OctoMap before 1.4 are not read)");
  BtHeader h;
  auto skip_line = [&s] {
    char c;
    do c = char(s.get());
    while (s.good() && c != '\n');
  };
  std::string token;
  bool data = false;
  while (s.good() && !data) {
    s >> token;
    if (token == "data") {
      data = true;
      skip_line();
    } else if (token.compare(0, 1, "#") == 0) {
      skip_line();
    } else if (token == "id") {
      s >> h.id;
    } else if (token == "res") {
      s >> h.res;
    } else if (token == "size") {
      s >> h.size;
    } else {
      skip_line();
    }
  }
  if (!data || !s) throw FileError("'" + path + "' is not a readable OctoMap binary (.bt) file: no \"data\" line in its header");
  h.data_offset = std::size_t(s.tellg());
  return h;
}

// Walks the node data the way octomap's readBinaryNode does (two bytes per inner node, two bits per child,
// bit 2i+1 then bit 2i: 01 free leaf, 10 occupied leaf, 11 inner node, 00 unknown) without building anything: every inner node
// must be whole in the file, no node may lie below the finest level, and an inner node needs a child.
// Counts the nodes and the finest cells the leaves cover, so a file is rejected before octomap allocates.
struct NodeWalk {
  const std::string& bytes;
  const std::string& path;
  std::size_t pos;
  std::uint64_t nodes = 1;  // the root
  std::uint64_t cells = 0;

  [[noreturn]] void damaged(const std::string& why) const {
    throw FileError("'" + path + "' is damaged: " + why + " (node data byte " + std::to_string(pos) + ")");
  }

  void node(unsigned depth) {
    if (pos + 2 > bytes.size()) damaged("the node data ends inside a node");
    const unsigned bits = unsigned(std::uint8_t(bytes[pos])) | (unsigned(std::uint8_t(bytes[pos + 1])) << 8);
    pos += 2;
    if (bits == 0) damaged("an inner node without children");
    if (depth >= 16) damaged("a node below the finest resolution");
    unsigned inner = 0;
    for (unsigned i = 0; i < 8; ++i) {
      const unsigned code = (bits >> (2 * i)) & 3u;
      if (code == 0) continue;
      ++nodes;
      if (code == 3)
        inner |= 1u << i;
      else
        cells += std::uint64_t(1) << (3 * (15 - depth));  // a leaf at depth + 1 covers 8^(16 - depth - 1)
    }
    for (unsigned i = 0; i < 8; ++i)
      if (inner & (1u << i)) node(depth + 1);
  }
};

}  // namespace

void read_bt(octomap::OcTree& tree, const std::string& path, const std::string& what, std::uint64_t max_cells) {
  const std::string bytes = read_file_bounded(path, what, limits::kOctreeFileBytes);
  const BtHeader h = parse_header(bytes, path);
  if (!(h.res >= kMinOctreeResolution && h.res <= kMaxOctreeResolution))
    throw FileError("'" + path + "' states a resolution of " + format_number(h.res) + " m, outside [" +
                    format_number(kMinOctreeResolution) + ", " + format_number(kMaxOctreeResolution) + "] (damaged?)");
  if (h.size > 0) {
    NodeWalk walk{bytes, path, h.data_offset};
    walk.node(0);
    if (walk.nodes != h.size)
      throw FileError("'" + path + "' is damaged: its header states " + std::to_string(h.size) + " nodes, its data holds " +
                      std::to_string(walk.nodes));
    if (max_cells > 0 && walk.cells > max_cells)
      throw FileError("'" + path + "' covers more than " + std::to_string(max_cells) +
                      " cells at its finest resolution (the limit; damaged or too large a map)");
  }
  ByteStream s(bytes);
  if (!tree.readBinary(s)) throw FileError("'" + path + "' is not a readable OctoMap binary (.bt) file");
}

}  // namespace octoreach::detail
