#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "octoreach/capability_map.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/orientation_set.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {

const std::string kArm = std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf";

CapabilityMapOptions coarse_options() {
  CapabilityMapOptions o;
  o.resolution = 0.25;
  o.directions = 16;
  o.seed = 3;
  return o;
}

// One coarse map of the test arm, built once for the whole file.
const CapabilityMap& coarse_map() {
  static std::shared_ptr<Robot> robot = Robot::from_urdf(kArm);
  static const CapabilityMap map = CapabilityMap::build(robot->chain("base_link", "tool0"), coarse_options());
  return map;
}

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "octoreach_cm_" + name;
}

std::vector<char> read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(f), {});
}

void write_all(const std::string& path, const std::vector<char>& data) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(data.data(), static_cast<std::streamsize>(data.size()));
}

// Every voxel centre of the bounds (plus one voxel) times every orientation.
std::vector<std::pair<Eigen::Vector3d, int>> all_cells(const CapabilityMap& m) {
  auto [lo, hi] = m.bounds();
  const double r = m.resolution();
  std::vector<std::pair<Eigen::Vector3d, int>> out;
  for (double x = lo.x() - r / 2; x < hi.x() + r; x += r)
    for (double y = lo.y() - r / 2; y < hi.y() + r; y += r)
      for (double z = lo.z() - r / 2; z < hi.z() + r; z += r)
        for (int o = 0; o < m.orientations().size(); ++o) out.emplace_back(Eigen::Vector3d(x, y, z), o);
  return out;
}

}  // namespace

TEST(CapabilityMap, BuildsOnTestArm) {
  const CapabilityMap& m = coarse_map();
  EXPECT_EQ(m.base_link(), "base_link");
  EXPECT_EQ(m.tip_link(), "tool0");
  EXPECT_EQ(m.dof(), 6);
  EXPECT_EQ(m.orientations().directions(), 16);
  EXPECT_GT(m.voxel_count(), 20u);
  EXPECT_LE(m.stats().voxels, m.voxel_count());  // records also hold voxels with mixed cells only
  EXPECT_GT(m.stats().reachable_cells, m.stats().voxels);
  EXPECT_LT(m.stats().reachable_cells, m.stats().cells);
  EXPECT_TRUE(m.has_solutions());

  // D of every voxel is the share of its reachable orientations; stored solutions reach their cells.
  auto robot = Robot::from_urdf(kArm);
  Chain chain = robot->chain("base_link", "tool0");
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> values;
  m.voxels(centres, values);
  ASSERT_EQ(centres.size(), m.stats().voxels);  // the voxels with D > 0
  const int O = m.orientations().size();
  for (std::size_t i = 0; i < centres.size(); ++i) {
    int count = 0;
    for (int o = 0; o < O; ++o) {
      if (!m.reachable(centres[i], o)) {
        EXPECT_FALSE(m.solution(centres[i], o).has_value());
        continue;
      }
      ++count;
      auto q = m.solution(centres[i], o);
      ASSERT_TRUE(q.has_value());
      Pose T = chain.fk(*q);
      EXPECT_LE((T.translation() - centres[i]).norm(), 1e-3 + 1e-5);
      Eigen::Vector3d approach = T.linear() * m.approach_axis();
      EXPECT_LE(std::acos(std::min(1.0, approach.dot(m.orientations().direction(o)))), 1e-2 + 1e-4);
      EXPECT_TRUE(chain.within_limits(*q, 1e-6));
    }
    EXPECT_NEAR(values[i], double(count) / O, 1e-6);
    EXPECT_NEAR(m.reachability(centres[i]), values[i], 0.0);
  }
  EXPECT_EQ(m.reachability(Eigen::Vector3d(50, 0, 0)), 0.0);
}

TEST(CapabilityMap, RejectsBadOptions) {
  auto robot = Robot::from_urdf(kArm);
  Chain chain = robot->chain("base_link", "tool0");
  for (double r : {0.0, -0.1, std::nan("")}) {
    CapabilityMapOptions o = coarse_options();
    o.resolution = r;
    EXPECT_THROW(CapabilityMap::build(chain, o), std::invalid_argument) << r;
  }
  CapabilityMapOptions o = coarse_options();
  o.approach_axis.setZero();
  EXPECT_THROW(CapabilityMap::build(chain, o), std::invalid_argument);
}

TEST(CapabilityMap, SaveLoadRoundTrip) {
  const CapabilityMap& m = coarse_map();
  for (bool with_solutions : {false, true}) {
    const std::string path = temp_path(with_solutions ? "sol.map" : "plain.map");
    m.save(path, with_solutions);
    CapabilityMap l = CapabilityMap::load(path);
    EXPECT_EQ(l.has_solutions(), with_solutions);
    EXPECT_EQ(l.voxel_count(), m.voxel_count());
    EXPECT_EQ(l.resolution(), m.resolution());
    EXPECT_EQ(l.orientations().size(), m.orientations().size());
    EXPECT_EQ(l.parameters(), m.parameters());
    EXPECT_EQ(l.stats().reachable_cells, m.stats().reachable_cells);
    for (const auto& [p, o] : all_cells(m)) {
      ASSERT_EQ(l.reachable(p, o), m.reachable(p, o)) << p.transpose() << " " << o;
      if (with_solutions && m.reachable(p, o)) {
        auto a = m.solution(p, o), b = l.solution(p, o);
        ASSERT_TRUE(a && b);
        EXPECT_EQ(*a, *b);
      }
    }
    std::remove(path.c_str());
  }
}

TEST(CapabilityMap, DamagedFilesThrowFileError) {
  const std::string path = temp_path("damaged.map");
  coarse_map().save(path, true);
  const std::vector<char> bytes = read_all(path);
  ASSERT_GT(bytes.size(), 100u);
  for (std::size_t cut : {std::size_t{0}, std::size_t{10}, std::size_t{30}, bytes.size() / 2, bytes.size() - 1}) {
    write_all(path, std::vector<char>(bytes.begin(), bytes.begin() + cut));
    EXPECT_THROW(CapabilityMap::load(path), FileError) << "cut at " << cut;
  }
  std::mt19937 rng(1);
  std::vector<char> noise(2000);
  for (char& c : noise) c = static_cast<char>(rng());
  write_all(path, noise);
  EXPECT_THROW(CapabilityMap::load(path), FileError);
  std::vector<char> flipped = bytes;
  flipped[bytes.size() - 20] ^= 0x33;
  write_all(path, flipped);
  EXPECT_THROW(CapabilityMap::load(path), FileError);
  std::remove(path.c_str());
  EXPECT_THROW(CapabilityMap::load(path), FileError);
}

// The plain lookups answer from a grid of the reachable bits, or from the voxel records when the grid would be
// larger than its limit: dropping the grid of a small map runs that second path.
namespace octoreach {
struct CapabilityMapTestAccess {
  static bool has_grid(const CapabilityMap& m) { return !m.grid_.empty(); }
  static void drop_grid(CapabilityMap& m) { m.grid_.clear(); }
};
}  // namespace octoreach

// The plain lookups must say what the voxel records hold, pose by pose and in batches (which compute every
// orientation first), from the grid and from the records alike.
TEST(CapabilityMap, PlainLookupsReadTheRecords) {
  std::shared_ptr<Robot> robot = Robot::from_urdf(kArm);
  CapabilityMap m = CapabilityMap::build(robot->chain("base_link", "tool0"), coarse_options());
  auto [lo, hi] = m.bounds();
  const double r = m.resolution();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  const int n = 4000;
  std::vector<double> rows(16 * n);
  std::vector<Pose> poses(n);
  std::vector<int> dir(n);
  std::vector<char> stored(n), vote(n), tie(n), any(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) p[a] = lo[a] - 2 * r + u(rng) * (hi[a] - lo[a] + 4 * r);
    Pose& T = poses[i];
    T = Pose::Identity();
    T.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    T.translation() = p;
    const int o = dir[i] = m.orientations().nearest(T.linear(), m.approach_axis());
    // nearest cell: the record of the voxel holding p
    const std::uint32_t rec = m.record_of_key(m.tree().coordToKey(p.x(), p.y(), p.z()));
    stored[i] = rec != DenseIndex::kNone && m.record_has(rec, o);
    // vote: the 8 records around p weighted trilinearly
    std::uint32_t recs[8];
    double w[8], yes = 0;
    m.corners(p, recs, w);
    for (int k = 0; k < 8; ++k) {
      const bool has = recs[k] != DenseIndex::kNone && m.record_has(recs[k], o);
      yes += has ? w[k] : 0.0;
      any[i] |= has;  // any: one of the 8 records (with weight 0 too: a pose on a voxel face)
    }
    vote[i] = yes >= 0.5;
    tie[i] = std::abs(yes - 0.5) <= 1e-9;
    Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(rows.data() + 16 * i) = T.matrix();
  }
  EXPECT_GT(std::count(vote.begin(), vote.end(), 1), n / 50);  // the poses test both answers
  EXPECT_GT(std::count(vote.begin(), vote.end(), 0), n / 50);
  int any_not_vote = 0;  // any says yes wherever the vote does, and where some cell around disagrees with it
  for (int i = 0; i < n; ++i) {
    if (vote[i] && !tie[i]) EXPECT_TRUE(any[i]) << i;
    any_not_vote += any[i] && !vote[i];
  }
  EXPECT_GT(any_not_vote, n / 100);
  std::unique_ptr<bool[]> out(new bool[n]);
  ASSERT_TRUE(CapabilityMapTestAccess::has_grid(m));
  std::vector<char> grid_vote;  // the grid's votes, which the records' must equal, ties included
  for (const char* path : {"grid", "records"}) {
    SCOPED_TRACE(path);
    std::vector<char> by_pose_vote(n), by_pose_nearest(n), by_pose_any(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = poses[i].translation();
      EXPECT_EQ(m.reachable(p, dir[i], CapabilityLookup::nearest_cell), bool(stored[i])) << p.transpose();
      if (!tie[i]) EXPECT_EQ(m.reachable(p, dir[i], CapabilityLookup::vote), bool(vote[i])) << p.transpose();
      by_pose_vote[i] = m.reachable(poses[i], CapabilityLookup::vote);
      by_pose_nearest[i] = m.reachable(poses[i], CapabilityLookup::nearest_cell);
      by_pose_any[i] = m.reachable(poses[i], CapabilityLookup::any);
      EXPECT_EQ(m.reachable(p, dir[i], CapabilityLookup::any), bool(any[i])) << p.transpose();
      EXPECT_EQ(bool(by_pose_any[i]), bool(any[i])) << i;
      EXPECT_EQ(bool(by_pose_nearest[i]), bool(stored[i])) << i;
      if (!tie[i]) EXPECT_EQ(bool(by_pose_vote[i]), bool(vote[i])) << i;
    }
    for (auto [lookup, expected] : {std::make_pair(CapabilityLookup::vote, &by_pose_vote),
                                    std::make_pair(CapabilityLookup::nearest_cell, &by_pose_nearest),
                                    std::make_pair(CapabilityLookup::any, &by_pose_any)}) {
      m.reachable(rows.data(), n, out.get(), lookup);  // batched answers equal single ones
      for (int i = 0; i < n; ++i) EXPECT_EQ(out[i], bool((*expected)[i])) << i;
    }
    if (grid_vote.empty()) grid_vote = by_pose_vote;
    EXPECT_TRUE(grid_vote == by_pose_vote);
    // positions far outside the map, and outside the octree's keys: no from every lookup, one pose or a batch
    std::vector<double> far(rows.begin(), rows.begin() + 16 * 4);
    const double edge = 32768.0 * r;
    const double places[4][3] = {{1e6, 0, 0}, {edge, 0, 0}, {-edge - r, 0, 0}, {0, 0, edge - 0.5 * r}};
    for (int i = 0; i < 4; ++i)
      for (int a = 0; a < 3; ++a) far[16 * i + 4 * a + 3] = places[i][a];
    for (CapabilityLookup lookup : {CapabilityLookup::vote, CapabilityLookup::nearest_cell, CapabilityLookup::any}) {
      m.reachable(far.data(), 4, out.get(), lookup);
      for (int i = 0; i < 4; ++i) {
        EXPECT_FALSE(out[i]) << i;
        EXPECT_FALSE(m.reachable(Pose(Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(far.data() + 16 * i)
                                          .eval()), lookup)) << i;
      }
    }
    std::vector<double> bad = rows;
    bad[16 * 1234 + 5] = std::nan("");
    bad[16 * 3000 + 2] = std::nan("");  // a later group too: the first bad row is named
    try {
      m.reachable(bad.data(), n, out.get());
      ADD_FAILURE() << "a NaN pose was answered";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("pose 1234 is not finite"), std::string::npos) << e.what();
    }
    bad = rows;
    for (int k : {0, 4, 8}) bad[16 * 2000 + k] *= 1.5;  // a stretched rotation: both paths check every row
    try {
      m.reachable(bad.data(), n, out.get());
      ADD_FAILURE() << "a non-rigid pose was answered";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("pose 2000 is not a rigid transform"), std::string::npos) << e.what();
    }
    CapabilityMapTestAccess::drop_grid(m);
  }
}

TEST(OrientationSet, NearestDirectionIsExact) {
  for (int symmetry : {1, 4}) {
    OrientationSet s = OrientationSet::sphere(200, 1, symmetry);
    std::mt19937_64 rng(42);
    std::normal_distribution<double> g;
    for (int i = 0; i < 20000; ++i) {
      Eigen::Vector3d v(g(rng), g(rng), g(rng));
      v.normalize();
      int best = 0;
      for (int j = 1; j < s.directions(); ++j)
        if (s.direction(j).dot(v) > s.direction(best).dot(v)) best = j;
      int got = s.nearest_direction(v);
      // ties aside, the table lookup must find the brute-force nearest
      EXPECT_GE(s.direction(got).dot(v), s.direction(best).dot(v) - 1e-12) << v.transpose();
    }
  }
}

TEST(OrientationSet, RotatedAndNearestOrientation) {
  OrientationSet s = OrientationSet::sphere(64, 1, 4);
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int i = 0; i < s.directions(); ++i) {
    EXPECT_NEAR((Rz * s.direction(i) - s.direction(s.rotated(i, 1))).norm(), 0.0, 1e-9);
    EXPECT_EQ(s.rotated(s.rotated(i, 1), -1), i);
    const Eigen::Vector3d axis(1, 0, 0);
    EXPECT_EQ(s.nearest(s.rotation(i, axis), axis), i);
  }
  OrientationSet rolled = OrientationSet::sphere(32, 6, 4);
  for (int o = 0; o < rolled.size(); ++o) EXPECT_EQ(rolled.nearest(rolled.rotation(o, Eigen::Vector3d::UnitZ()), Eigen::Vector3d::UnitZ()), o);
  EXPECT_THROW(s.subset("nowhere"), std::invalid_argument);
}
