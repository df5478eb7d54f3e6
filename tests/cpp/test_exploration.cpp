#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include <octomap/OcTree.h>

#include "octoreach/simulation.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/robot.hpp"
#include "stock_insert.hpp"

using namespace octoreach;

namespace {

// Camera pose (camera -> world) at `eye` looking at `target`, +z forward, image +y roughly down.

Scene cluttered_scene() {
  Scene s;
  s.add_box({-1.5, -1.5, -0.05}, {1.5, 1.5, 0.0});  // floor
  s.add_crate({0.3, -0.5, 0.0}, {0.7, -0.1, 0.3}, 0.02);
  s.add_closed_box({0.3, 0.2, 0.0}, {0.8, 0.6, 0.4}, 0.02, "-x", 0.12, 0.1);
  s.add_box({-0.2, 0.6, 0.0}, {0.6, 0.65, 0.2});  // a board
  return s;
}

// Every known cell of a tree at the finest resolution: key -> log-odds.
std::map<CellKey, float> leaf_cells(const octomap::OcTree& t) {
  std::map<CellKey, float> out;
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    octomap::OcTreeKey k = it.getKey();
    int size = 1 << (16 - it.getDepth());
    int mask = ~(size - 1);
    for (int z = 0; z < size; ++z)
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
          out[pack_key((k[0] & mask) + x, (k[1] & mask) + y, (k[2] & mask) + z)] = it->getLogOdds();
  }
  return out;
}

std::vector<Pose> survey_poses() {
  return {look_at({-0.6, 0.0, 0.9}, {0.5, 0.0, 0.1}), look_at({-0.3, -0.9, 0.8}, {0.5, 0.0, 0.1}),
          look_at({0.0, 0.9, 1.0}, {0.5, 0.1, 0.1}), look_at({1.4, 0.3, 0.9}, {0.5, 0.1, 0.1}),
          look_at({0.5, 0.0, 1.4}, {0.5, 0.0, 0.0})};
}

}  // namespace

TEST(DepthCamera, SeesTheFloorAtTheRightDepth) {
  Scene s;
  s.add_box({-2, -2, -0.1}, {2, 2, 0});
  DepthCamera cam(64, 48, 1.0, 4.0, 0.0, 0);
  auto pts = cam.capture(s, look_at({0, 0, 1.5}, {0, 0, 0}));
  ASSERT_EQ(pts.size(), 64u * 48u);
  for (const auto& p : pts) EXPECT_NEAR(p.z(), 0.0, 1e-9);
  // out of range: nothing
  DepthCamera near(64, 48, 1.0, 1.0, 0.0, 0);
  EXPECT_TRUE(near.capture(s, look_at({0, 0, 1.5}, {0, 0, 0})).empty());
  // noise is deterministic for a seed and changes depth
  DepthCamera n1(16, 12, 1.0, 4.0, 0.01, 7), n2(16, 12, 1.0, 4.0, 0.01, 7);
  auto a = n1.capture(s, look_at({0, 0, 1.5}, {0, 0, 0})), b = n2.capture(s, look_at({0, 0, 1.5}, {0, 0, 0}));
  ASSERT_EQ(a.size(), b.size());
  double dev = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i], b[i]);
    dev += std::abs(a[i].z());
  }
  EXPECT_GT(dev, 0.0);
}

TEST(DepthCamera, ClosedBoxOpeningLetsRaysIn) {
  Scene s;
  s.add_closed_box({0, 0, 0}, {0.5, 0.5, 0.5}, 0.02, "-x", 0.1, 0.1);
  double t;
  // through the hole to the far inner wall at x = 0.48
  EXPECT_TRUE(s.raycast({-1, 0.25, 0.25}, {1, 0, 0}, 4.0, t));
  EXPECT_NEAR(t, 1.48, 1e-9);
  // beside the hole: the outer wall at x = 0
  EXPECT_TRUE(s.raycast({-1, 0.1, 0.25}, {1, 0, 0}, 4.0, t));
  EXPECT_NEAR(t, 1.0, 1e-9);
  ASSERT_EQ(s.interiors().size(), 1u);
  EXPECT_THROW(s.add_closed_box({0, 0, 0}, {0.5, 0.5, 0.5}, 0.02, "up", 0.1, 0.1), std::invalid_argument);
  EXPECT_THROW(s.load_octomap("/nonexistent/world.bt"), FileError);
}

TEST(Scene, RaycastAndSolidRejectWhatIsNotARayOrAPoint) {
  Scene s;
  s.add_box({0, 0, 0}, {1, 1, 1});
  double t;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(s.raycast({0.5, 0.5, 3}, {0, 0, 0}, 4.0, t), std::invalid_argument);    // no direction
  EXPECT_THROW(s.raycast({0.5, 0.5, 3}, {0, 0, -2}, 4.0, t), std::invalid_argument);   // not unit: t would scale
  EXPECT_THROW(s.raycast({0.5, 0.5, 3}, {0, 0, -1}, inf, t), std::invalid_argument);   // endless ray
  EXPECT_THROW(s.raycast({nan, 0.5, 3}, {0, 0, -1}, 4.0, t), std::invalid_argument);
  ASSERT_TRUE(s.raycast({0.5, 0.5, 3}, {0, 0, -1}, 4.0, t));
  EXPECT_DOUBLE_EQ(t, 2.0);
  // the rays of a camera whose rotation passes as orthonormal (R^T R within 1e-6 of I) still pass as unit
  EXPECT_NO_THROW(s.raycast({0.5, 0.5, 3}, Eigen::Vector3d(0, 0, -1.000001), 4.0, t));
  DepthCamera cam(8, 6, 1.0, 4.0);
  Pose skewed = look_at({0.5, 0.5, 3}, {0.5, 0.5, 0});
  skewed.linear() *= 1.01;  // not a rotation
  EXPECT_THROW(cam.capture(s, skewed), std::invalid_argument);
  Pose mirrored = look_at({0.5, 0.5, 3}, {0.5, 0.5, 0});
  mirrored.linear().col(0) *= -1;  // orthonormal, but a reflection
  EXPECT_THROW(cam.capture(s, mirrored), std::invalid_argument);
  EXPECT_THROW(s.solid(Eigen::Vector3d(nan, 0, 0)), std::invalid_argument);
  try {
    s.solid(std::vector<Eigen::Vector3d>{{0.5, 0.5, 0.5}, {0, inf, 0}});
    FAIL() << "a point that is not finite was answered";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.solid(std::vector<Eigen::Vector3d>{{0.5, 0.5, 0.5}, {2, 2, 2}}), (std::vector<char>{1, 0}));
}

TEST(Pose, CheckRigidIsTheOneRule) {
  // every pose argument, Python's included (bindings' checked_pose), is checked by check_rigid
  Eigen::Matrix4d m = look_at({0.5, 0.5, 3}, {0.5, 0.5, 0}).matrix();
  EXPECT_NO_THROW(check_rigid(m, "pose"));
  Eigen::Matrix4d near = m;
  near.topLeftCorner<3, 3>() *= 1.0 + 2e-7;  // R^T R within 1e-6 of I: a rotation
  EXPECT_NO_THROW(check_rigid(near, "pose"));
  auto message = [](const Eigen::Matrix4d& x) {
    try {
      check_rigid(x, "camera_pose");
      EXPECT_TRUE(is_rigid(x));
    } catch (const std::invalid_argument& e) {
      EXPECT_FALSE(is_rigid(x));  // the batch lookups' test of a row is check_rigid's rule
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message(near), "accepted");
  Eigen::Matrix4d bad = m;
  bad(0, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(bad), "camera_pose is not finite (NaN or inf)");
  bad = m;
  bad.topLeftCorner<3, 3>() *= 1.01;  // scaled
  EXPECT_NE(message(bad).find("camera_pose is not a rigid transform"), std::string::npos) << message(bad);
  bad = m;
  bad.col(0) *= -1;  // a reflection
  EXPECT_NE(message(bad).find("not a rigid transform"), std::string::npos) << message(bad);
  bad = m;
  bad(3, 0) = 1e-3;  // last row
  EXPECT_NE(message(bad).find("not a rigid transform"), std::string::npos) << message(bad);
}

TEST(DepthCamera, MeshAndBoxAgree) {
  // a unit square at z = 0 as two triangles vs a thin box
  Scene mesh;
  mesh.add_mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  double t;
  ASSERT_TRUE(mesh.raycast({0.2, 0.3, 1}, Eigen::Vector3d(0, 0, -1), 4, t));
  EXPECT_NEAR(t, 1.0, 1e-12);
  EXPECT_FALSE(mesh.raycast({1.2, 0.3, 1}, Eigen::Vector3d(0, 0, -1), 4, t));
  EXPECT_THROW(mesh.add_mesh({{0, 0, 0}}, {{0, 1, 2}}), std::invalid_argument);
}

TEST(ExplorationMap, SameOccupancyAsStockInsertPointCloud) {
  Scene s = cluttered_scene();
  DepthCamera cam(160, 120, 1.0123, 2.0, 0.002, 3);
  ExplorationOptions o;
  o.resolution = 0.05;
  ExplorationMap fast(o);
  octomap::OcTree stock(o.resolution);
  for (const Pose& T : survey_poses()) {
    auto pts = cam.capture(s, T);
    pts.push_back(T.translation() + Eigen::Vector3d(0.1, 0.1, -3.5));  // beyond max range: a max-range ray
    fast.insert(pts, T.translation(), 2.0);
    bench::stock_insert(stock, pts, T.translation(), 2.0);
    auto a = leaf_cells(fast.octree()), b = leaf_cells(stock);
    ASSERT_EQ(a.size(), b.size());
    std::size_t occupied = 0;
    for (const auto& [k, v] : a) {
      auto it = b.find(k);
      ASSERT_NE(it, b.end());
      ASSERT_FLOAT_EQ(v, it->second);
      occupied += v > 0;
      // the cell cache agrees with the tree
      ASSERT_EQ(fast.state(k), v >= 0 ? CellState::Occupied : CellState::Free);
    }
    EXPECT_GT(occupied, 100u);
    EXPECT_EQ(fast.occupancy_digest(), occupancy_digest(stock));
  }
  EXPECT_EQ(fast.octree().size(), stock.size());
}

// The ray walk replicates computeRayKeys' arithmetic without its branches: check it on rays of
// every kind, including axis-aligned ones (zero direction components), end points on cell
// borders, rays beyond max_range and unlimited range.
TEST(ExplorationMap, RandomAndAxisAlignedRaysMatchStock) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1.5, 1.5);
  for (double res : {0.02, 0.05}) {
    for (double range : {1.2, -1.0}) {
      ExplorationOptions o;
      o.resolution = res;
      ExplorationMap fast(o);
      octomap::OcTree stock(res);
      const Eigen::Vector3d origin(0.013, -0.021, 0.4);
      std::vector<Eigen::Vector3d> pts;
      for (int i = 0; i < 4000; ++i) pts.emplace_back(origin + Eigen::Vector3d(U(rng), U(rng), U(rng)));
      for (int i = -20; i <= 20; ++i) {
        const double d = i * 0.07;
        pts.emplace_back(origin + Eigen::Vector3d(d, 0, 0));
        pts.emplace_back(origin + Eigen::Vector3d(0, d, 0));
        pts.emplace_back(origin + Eigen::Vector3d(0, 0, d));
        pts.emplace_back(origin + Eigen::Vector3d(d, d, 0));
        pts.emplace_back(origin + Eigen::Vector3d(d, -d, d));
        pts.emplace_back(Eigen::Vector3d(i * res, 0.5 * res, 1.0));  // on cell borders
      }
      fast.insert(pts, origin, range);
      bench::stock_insert(stock, pts, origin, range);
      auto a = leaf_cells(fast.octree()), b = leaf_cells(stock);
      ASSERT_EQ(a.size(), b.size()) << "res " << res << " range " << range;
      for (const auto& [k, v] : a) {
        auto it = b.find(k);
        ASSERT_NE(it, b.end());
        ASSERT_FLOAT_EQ(v, it->second);
      }
      EXPECT_EQ(fast.octree().size(), stock.size());
    }
  }
}

TEST(ExplorationMap, IncrementalEqualsFromScratchAfterEveryInsert) {
  Scene s = cluttered_scene();
  DepthCamera cam(120, 90, 1.0123, 2.5, 0.0, 0);
  ExplorationOptions o;
  o.resolution = 0.05;
  ExplorationMap m(o);
  std::size_t seen_voids = 0;
  for (const Pose& T : survey_poses()) {
    m.insert(cam.capture(s, T), T.translation(), 2.5);
    ExplorationSnapshot inc = m.snapshot(), ref = m.recompute_from_scratch();
    EXPECT_FALSE(inc.frontier_cells.empty());
    EXPECT_EQ(inc.frontier_cells, ref.frontier_cells);
    EXPECT_EQ(inc.frontier_clusters, ref.frontier_clusters);
    EXPECT_EQ(inc.void_cells, ref.void_cells);
    seen_voids = std::max(seen_voids, inc.void_cells.size());
    // every void cell is unknown and inside the hull; every frontier cell is free
    for (CellKey k : inc.void_cells) {
      ASSERT_EQ(m.state(k), CellState::Unknown);
      ASSERT_TRUE(m.inside_hull(m.center(k)));
    }
    for (CellKey k : inc.frontier_cells) ASSERT_EQ(m.state(k), CellState::Free);
    // void clusters partition the void cells
    std::size_t total = 0;
    for (const auto& v : m.void_clusters()) {
      total += v.cells.size();
      EXPECT_GE(v.eigenvalues[0], v.eigenvalues[1]);
      EXPECT_GE(v.eigenvalues[1], v.eigenvalues[2]);
      EXPECT_NEAR(v.axes.determinant(), 1.0, 1e-9);
    }
    EXPECT_EQ(total, inc.void_cells.size());
  }
  EXPECT_GT(seen_voids, 0u);
}

TEST(ExplorationMap, BadInputsRaiseOrDoNothing) {
  ExplorationMap m;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(m.insert({{1, 0, 0}}, {nan, 0, 0}, 4.0), std::invalid_argument);
  EXPECT_THROW(m.insert({{1, 0, 0}}, {1e4, 0, 0}, 4.0), std::invalid_argument);  // outside +-819 m
  EXPECT_THROW(m.insert({{1, 0, 0}}, {0, 0, 0}, nan), std::invalid_argument);
  InsertStats st = m.insert({}, {0, 0, 0}, 4.0);
  EXPECT_EQ(st.points, 0u);
  EXPECT_EQ(m.octree().size(), 0u);
  st = m.insert({{nan, 0, 0}, {1, 0, 0}}, {0, 0, 0}, 4.0);
  EXPECT_EQ(st.dropped, 1u);
  EXPECT_EQ(st.points, 1u);
  EXPECT_EQ(m.state(Eigen::Vector3d(1, 0, 0)), CellState::Occupied);
  EXPECT_EQ(m.state(Eigen::Vector3d(0.5, 0, 0)), CellState::Free);
  ExplorationOptions bad;
  bad.resolution = 0;
  EXPECT_THROW(ExplorationMap{bad}, std::invalid_argument);
}

TEST(DepthCamera, NormalsAndMissingReturnsAtGrazingAnglesAndBeyondRange) {
  Scene s;
  s.add_box({-5, -5, -0.1}, {5, 5, 0});  // floor
  s.add_box({1, -0.5, 0}, {1.2, 0.5, 1});  // a wall facing -x
  double t;
  Eigen::Vector3d n;
  ASSERT_TRUE(s.raycast({0, 0, 0.5}, {1, 0, 0}, 4.0, t, &n));
  EXPECT_NEAR(t, 1.0, 1e-12);
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d(-1, 0, 0)));
  ASSERT_TRUE(s.raycast({0, 0, 0.5}, Eigen::Vector3d(1, 0, -1).normalized(), 4.0, t, &n));
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d(0, 0, 1)));
  // looking along the floor: the floor's pixels far away meet it at grazing angles
  const Pose T = look_at({-2, 0, 0.3}, {0, 0, 0.1});
  DepthCamera all(64, 48, 1.0, 4.0, 0.0, 0), cut(64, 48, 1.0, 4.0, 0.0, 0, 75.0 * kPi / 180.0);
  auto a = all.capture(s, T), b = cut.capture(s, T);
  ASSERT_LT(b.size(), a.size());
  ASSERT_GT(b.size(), 0u);
  for (const auto& p : b) {  // every kept floor point is seen at <= 75 degrees from the floor's normal
    if (p.z() > 1e-6) continue;  // a wall point
    Eigen::Vector3d d = (p - T.translation()).normalized();
    EXPECT_GE(std::abs(d.z()), std::cos(75.0 * kPi / 180.0) - 1e-9);
  }
  std::size_t dropped = 0;
  for (const auto& p : a) {
    Eigen::Vector3d d = (p - T.translation()).normalized();
    if (p.z() <= 1e-6 && std::abs(d.z()) < std::cos(75.0 * kPi / 180.0) - 1e-6) ++dropped;
  }
  EXPECT_EQ(a.size() - b.size(), dropped);
  // noise never puts a point beyond the range
  DepthCamera noisy(64, 48, 1.0, 2.3, 0.2, 3);
  for (const auto& p : noisy.capture(s, T)) EXPECT_LE((p - T.translation()).norm(), 2.3 + 1e-9);
  EXPECT_THROW(DepthCamera(8, 8, 1.0, 4.0, 0.0, 0, 0.0), std::invalid_argument);
  EXPECT_THROW(DepthCamera(8, 8, 1.0, 4.0, 0.0, 0, 2.0), std::invalid_argument);
}
