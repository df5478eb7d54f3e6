// A MapRoom as the bytes of a map file's "room" section, and back (the layout is in map_room_io.hpp).
#include "maps/map_room_io.hpp"

#include <sstream>
#include <stdexcept>

#include <fcl/fcl.h>
#include <octomap/OcTree.h>

#include "maps/map_io.hpp"

namespace octoreach::detail {
namespace {

constexpr std::uint32_t kMaxText = 4096;  // a name or a mesh file name

void put_text(ByteWriter& w, const std::string& text) {
  w.put(static_cast<std::uint32_t>(text.size()));
  w.put_bytes(text.data(), text.size());
}

std::string get_text(ByteReader& r) {
  const auto n = r.get<std::uint32_t>();
  if (n > kMaxText || n > r.remaining()) r.fail("damaged room record (text length)");
  std::string text(n, '\0');
  r.get_bytes(text.data(), n);
  return text;
}

std::string octree_bytes(const Shape& s) {
  const std::shared_ptr<const octomap::OcTree>& tree = s.octree;
  if (!tree) throw std::invalid_argument("an OctoMap obstacle given as an FCL geometry (without its map) cannot be recorded "
                                         "in a map file: add it as an OctoMap (Obstacles.add_octree)");
  std::ostringstream out;
  if (!tree->writeBinaryConst(out)) throw FileError("cannot record an OctoMap obstacle");
  return out.str();
}

void put_shape(ByteWriter& w, const Shape& s) {
  w.put(static_cast<std::uint8_t>(s.type));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.put(s.origin.linear()(i, j));
  for (int i = 0; i < 3; ++i) w.put(s.origin.translation()[i]);
  switch (s.type) {
    case Shape::Type::Box:
      for (int i = 0; i < 3; ++i) w.put(s.size[i]);
      break;
    case Shape::Type::Cylinder:
      w.put(s.radius);
      w.put(s.length);
      break;
    case Shape::Type::Sphere: w.put(s.radius); break;
    case Shape::Type::Mesh: {
      const bool convex = s.geometry && s.geometry->getNodeType() == fcl::GEOM_CONVEX;
      w.put(static_cast<std::uint8_t>(convex));  // a convex solid (a slab's prism) stays one: FCL fills it
      put_text(w, s.mesh_path);
      for (int i = 0; i < 3; ++i) w.put(s.scale[i]);
      std::vector<Eigen::Vector3d> v;
      std::vector<Eigen::Vector3i> t;
      s.mesh_triangles(v, t);
      w.put(static_cast<std::uint32_t>(v.size()));
      for (const auto& p : v) w.put_bytes(p.data(), 3 * sizeof(double));
      w.put(static_cast<std::uint32_t>(t.size()));
      for (const auto& f : t) w.put_bytes(f.data(), 3 * sizeof(int));
      break;
    }
    case Shape::Type::Octree: {
      const std::string bytes = octree_bytes(s);
      w.put(static_cast<std::uint64_t>(bytes.size()));
      w.put_bytes(bytes.data(), bytes.size());
      break;
    }
  }
}

Pose get_pose(ByteReader& r) {
  Pose T = Pose::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T.linear()(i, j) = r.get<double>();
  for (int i = 0; i < 3; ++i) T.translation()[i] = r.get<double>();
  const Eigen::Matrix3d R = T.linear();
  if (!T.matrix().allFinite() || !((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6))
    r.fail("damaged room record (a pose that is not a rigid transform)");
  return T;
}

// A convex mesh as FCL's convex solid (its faces the triangles).
Shape convex_mesh(const MeshVertices& v, const MeshTriangles& t, const Pose& T) {
  auto points = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (Eigen::Index i = 0; i < v.rows(); ++i) points->push_back(v.row(i).transpose());
  auto faces = std::make_shared<std::vector<int>>();
  for (Eigen::Index i = 0; i < t.rows(); ++i) faces->insert(faces->end(), {3, t(i, 0), t(i, 1), t(i, 2)});
  return Shape::of(std::make_shared<fcl::Convexd>(points, int(t.rows()), faces), T);
}

Shape get_mesh(ByteReader& r, const Pose& T) {
  const auto convex = r.get<std::uint8_t>();
  if (convex > 1) r.fail("damaged room record (mesh flag)");
  std::string path = get_text(r);
  Eigen::Vector3d scale;
  for (int i = 0; i < 3; ++i) scale[i] = r.get<double>();
  const auto nv = r.get<std::uint32_t>();
  if (nv > r.remaining() / (3 * sizeof(double))) r.fail("damaged room record (mesh vertex count)");
  MeshVertices v(nv, 3);
  for (std::uint32_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k) v(i, k) = r.get<double>();
  const auto nt = r.get<std::uint32_t>();
  if (nt > r.remaining() / (3 * sizeof(int))) r.fail("damaged room record (mesh triangle count)");
  MeshTriangles t(nt, 3);
  for (std::uint32_t i = 0; i < nt; ++i)
    for (int k = 0; k < 3; ++k) {
      t(i, k) = r.get<int>();
      if (t(i, k) < 0 || std::uint32_t(t(i, k)) >= nv) r.fail("damaged room record (mesh vertex index)");
    }
  if (!v.allFinite() || !scale.allFinite()) r.fail("damaged room record (non-finite mesh)");
  if (nt == 0) r.fail("damaged room record (a mesh without triangles)");
  Shape s = convex ? convex_mesh(v, t, T) : Shape::triangle_mesh(v, t, T);
  s.mesh_path = std::move(path);  // where it came from (the triangles are already scaled)
  s.scale = scale;
  return s;
}

Shape get_octree(ByteReader& r, const Pose& T) {
  const auto n = r.get<std::uint64_t>();
  if (n > r.remaining()) r.fail("damaged room record (OctoMap length)");
  std::string bytes(n, '\0');
  r.get_bytes(bytes.data(), n);
  std::istringstream in(bytes);
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  if (!tree->readBinary(in)) r.fail("damaged room record (OctoMap)");
  const double res = tree->getResolution();
  if (!(res >= limits::kMinOctreeResolution) || !(res <= limits::kMaxOctreeResolution))
    r.fail("damaged room record (OctoMap resolution)");
  return Shape::from_octree(std::move(tree), T);
}

Shape get_shape(ByteReader& r) {
  const auto kind = r.get<std::uint8_t>();
  if (kind > static_cast<std::uint8_t>(Shape::Type::Octree)) r.fail("damaged room record (shape kind)");
  const Pose T = get_pose(r);
  try {
    switch (static_cast<Shape::Type>(kind)) {
      case Shape::Type::Box: {
        Eigen::Vector3d size;
        for (int i = 0; i < 3; ++i) size[i] = r.get<double>();
        return Shape::box(size, T);
      }
      case Shape::Type::Cylinder: {
        const double radius = r.get<double>(), length = r.get<double>();
        return Shape::cylinder(radius, length, T);
      }
      case Shape::Type::Sphere: return Shape::sphere(r.get<double>(), T);
      case Shape::Type::Mesh: return get_mesh(r, T);
      case Shape::Type::Octree: return get_octree(r, T);
    }
  } catch (const std::invalid_argument& e) {  // sizes out of range: the file is damaged
    r.fail(std::string("damaged room record (") + e.what() + ")");
  }
  r.fail("damaged room record (shape kind)");
}

// A count of records that take at least `least` bytes each.
std::uint32_t get_count(ByteReader& r, std::size_t least) {
  const auto n = r.get<std::uint32_t>();
  if (n > r.remaining() / least) r.fail("damaged room record (count)");
  return n;
}

}  // namespace

std::vector<char> room_bytes(const MapRoom& room) {
  ByteWriter w;
  const Obstacles& obstacles = room.obstacles();
  w.put(static_cast<std::uint32_t>(obstacles.size()));
  w.put(static_cast<std::uint32_t>(room.surface_count()));
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    put_text(w, obstacles.names()[i]);
    put_shape(w, obstacles.shapes()[i]);
  }
  w.put(static_cast<std::uint32_t>(room.body().size()));
  for (std::size_t i = 0; i < room.body().size(); ++i) {
    put_text(w, room.body_links()[i]);
    put_shape(w, room.body()[i]);
  }
  return std::move(w.bytes);
}

MapRoom room_from_bytes(const std::vector<char>& bytes, const std::string& path) {
  ByteReader r(bytes, "'" + path + "'");
  constexpr std::size_t kLeast = 4 + 1 + 12 * sizeof(double) + sizeof(double);  // a name, a kind, a pose, a size
  Obstacles obstacles;
  const std::uint32_t count = get_count(r, kLeast), surface_count = r.get<std::uint32_t>();
  if (surface_count > count) r.fail("damaged room record (surface count)");
  for (std::uint32_t i = 0; i < count; ++i) {
    std::string name = get_text(r);
    obstacles.add(get_shape(r), name);
  }
  std::vector<Shape> body;
  std::vector<std::string> links;
  for (std::uint32_t i = 0, n = get_count(r, kLeast); i < n; ++i) {
    links.push_back(get_text(r));
    body.push_back(get_shape(r));
  }
  if (!r.done()) r.fail("damaged room record (trailing bytes)");
  return MapRoom(std::move(obstacles), surface_count, std::move(body), std::move(links));
}

MapSections room_sections(const MapRoom& room) { return {{kRoomSection, room_bytes(room)}}; }

std::shared_ptr<const MapRoom> room_of_sections(const MapSections& sections, const std::string& path) {
  const auto it = sections.find(kRoomSection);
  if (it == sections.end()) return std::make_shared<const MapRoom>();
  return std::make_shared<const MapRoom>(room_from_bytes(it->second, path));
}

}  // namespace octoreach::detail
