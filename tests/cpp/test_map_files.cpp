// The registry of map kinds: load_any returns each kind, map_kind reads the tag, a foreign file is a FileError.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "maps/map_io.hpp"
#include "octoreach/map_files.hpp"

using namespace octoreach;

namespace {
const std::string kArm = std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf";

std::string temp_path(const std::string& name) { return ::testing::TempDir() + "/octoreach_map_files_" + name; }

void write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// The FileError message of load(path), or "" when it loads or throws something else.
template <class Load>
std::string file_error(Load&& load) {
  try {
    load();
  } catch (const FileNotFound&) {
    return "";
  } catch (const FileError& e) {
    return e.what();
  } catch (...) {
  }
  return "";
}
}  // namespace

TEST(MapFiles, LoadAnyReturnsEachKind) {
  auto robot = Robot::from_urdf(kArm);
  CapabilityMapOptions co;
  co.resolution = 0.15;
  co.directions = 24;
  co.seed = 1;
  const CapabilityMap cap = CapabilityMap::build(robot->chain("base_link", "tool0"), co);
  PointMapOptions po;
  po.theta_bins = 4;
  const InversePointMap pm = InversePointMap::build(*robot, cap, po);
  SurfaceMapOptions so;
  so.theta_bins = 4;
  const SurfaceMap sm = SurfaceMap::build(*robot, cap, Surface::rectangle(0.6, 0.4, 0.4, 0.55), so);
  const std::string cpath = temp_path("a.orcm"), ppath = temp_path("a.orpm"), spath = temp_path("a.orsm");
  cap.save(cpath, true);
  pm.save(ppath);
  sm.save(spath);

  ASSERT_EQ(map_kinds().size(), std::variant_size_v<AnyMap>);
  EXPECT_EQ(map_kinds()[0].tag, "capability");
  EXPECT_EQ(map_kinds()[2].extension, ".orsm");
  EXPECT_EQ(map_kind(cpath), "capability");
  EXPECT_EQ(map_kind(ppath), "point");
  EXPECT_EQ(map_kind(spath), "surface");

  const AnyMap c = load_any(cpath), p = load_any(ppath), s = load_any(spath, "surface");
  ASSERT_TRUE(std::holds_alternative<CapabilityMap>(c));
  ASSERT_TRUE(std::holds_alternative<InversePointMap>(p));
  ASSERT_TRUE(std::holds_alternative<SurfaceMap>(s));
  EXPECT_EQ(std::string(kind_of(c)), "capability");
  EXPECT_EQ(std::string(kind_of(s)), "surface");
  EXPECT_EQ(std::get<CapabilityMap>(c).voxel_count(), cap.voxel_count());
  EXPECT_EQ(std::get<InversePointMap>(p).parameters(), pm.parameters());
  EXPECT_EQ(std::get<SurfaceMap>(s).parameters(), sm.parameters());
  for (const AnyMap* m : {&c, &p, &s}) {
    EXPECT_EQ(provenance_of(*m), MapProvenance::of(*robot));
    EXPECT_TRUE(provenance_of(*m).matches(*robot));
  }
  EXPECT_NE(file_error([&] { load_any(spath, "capability"); }).find("holds a surface map, expected a capability map"),
            std::string::npos);
  EXPECT_THROW(load_any(spath, "surfaces"), std::invalid_argument);
  for (const auto& path : {cpath, ppath, spath}) std::remove(path.c_str());
}

TEST(MapFiles, ForeignFilesAreFileErrorsNamingTheFile) {
  const std::string png = "\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {png, "not an octoreach map file"},
      {"", "not an octoreach map file"},
      {"robot: pr2\n", "not an octoreach map file"},
      {"OCTOREACH-MAP\n", "truncated"},
  };
  const std::string path = temp_path("foreign.orsm");
  for (const auto& [bytes, why] : cases) {
    write(path, bytes);
    for (const std::string& message : {file_error([&] { load_any(path); }), file_error([&] { map_kind(path); }),
                                       file_error([&] { load_any(path, "point"); })}) {
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(why), std::string::npos) << message;
    }
  }
  std::remove(path.c_str());
  EXPECT_THROW(load_any(temp_path("missing.orsm")), FileNotFound);
}

// A voxel record with no reachable cell reads an empty list of solutions: zero bytes into an empty vector,
// whose data() is null. The reader copies nothing then (a null memcpy is undefined behaviour, which the
// UndefinedBehaviorSanitizer build of `make test-sanitize` reports).
TEST(MapFiles, ZeroByteReadsCopyNothing) {
  const std::vector<char> data = {1, 2, 3, 4};
  detail::ByteReader r(data, "test bytes");
  std::vector<float> none;
  r.get_bytes(none.data(), 0);
  EXPECT_EQ(r.remaining(), 4u);
  EXPECT_EQ(r.get<std::uint32_t>(), 0x04030201u);
  r.get_bytes(nullptr, 0);  // at the end too
  EXPECT_TRUE(r.done());
  EXPECT_THROW(r.get_bytes(none.data(), 1), FileError);
}
