// The threading contract (docs/architecture.md, "Threads and ownership"), hammered: every mutable object
// used from several threads at once. Run under ThreadSanitizer by `make test-sanitize` (OCTOREACH_SANITIZE=thread).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>
#include <vector>

#include "octoreach/exploration.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/orientation_set.hpp"
#include "octoreach/simulation.hpp"
#include "octoreach/types.hpp"

using namespace octoreach;

namespace {

std::vector<Eigen::Vector3d> cloud(int n, double shift, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(1.0, 2.0), y(-1.0, 1.0), z(0.0, 1.0);
  std::vector<Eigen::Vector3d> p(n);
  for (auto& q : p) q = {x(rng) + shift, y(rng), z(rng)};
  return p;
}

// A 5 cm map after one cloud, and a small camera: what the search-while-inserting tests start from.
ExplorationOptions coarse_map_options() {
  ExplorationOptions o;
  o.resolution = 0.05;
  return o;
}

CameraIntrinsics small_camera() {
  CameraIntrinsics cam;
  cam.width = 32;
  cam.height = 24;
  cam.max_range = 3.0;
  return cam;
}

}  // namespace

TEST(Threads, ExplorationMapInsertWhileReading) {
  ExplorationOptions o;
  o.resolution = 0.05;
  o.threads = 2;
  ExplorationMap m(o);
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int i = 0; i < 8; ++i) m.insert(cloud(3000, 0.01 * i, i), {0, 0, 0.5}, -1);
    done = true;
  });
  std::vector<std::thread> readers;
  std::atomic<long> reads{0};
  for (int r = 0; r < 3; ++r)
    readers.emplace_back([&, r] {
      while (!done) {
        switch (r) {
          case 0: {
            auto s = m.snapshot();
            (void)s;
            (void)m.frontier_voids();
            break;
          }
          case 1:
            (void)m.known_cells(CellState::Free);
            (void)m.changed_cells();
            (void)m.inside_hull({1.5, 0, 0.5});
            break;
          default:
            (void)m.void_clusters();
            (void)m.occupancy_digest();
            (void)m.state(Eigen::Vector3d(1.5, 0, 0.5));
        }
        ++reads;
      }
    });
  writer.join();
  for (auto& t : readers) t.join();
  EXPECT_GT(reads.load(), 0);
  auto a = m.snapshot(), b = m.recompute_from_scratch();
  EXPECT_EQ(a.frontier_cells, b.frontier_cells);
  EXPECT_EQ(a.void_cells, b.void_cells);
}

TEST(Threads, NextBestViewWhileInserting) {
  ExplorationMap m(coarse_map_options());
  m.insert(cloud(3000, 0, 1), {0, 0, 0.5}, -1);
  const CameraIntrinsics cam = small_camera();
  NbvOptions nbv;
  nbv.threads = 2;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int i = 1; i < 5; ++i) m.insert(cloud(3000, 0.01 * i, 10 + i), {0, 0, 0.5}, -1);
    done = true;
  });
  int runs = 0;
  while (!done || runs == 0) {
    (void)next_best_view(m, cam, nbv);
    ++runs;
  }
  writer.join();
  EXPECT_GT(runs, 0);
}

// The void enclosure is cached per map until the next insert: searches from several threads (with
// different ranges, so the cache is rebuilt under them) while another thread inserts.
TEST(Threads, EnclosureWeightedSearchesWhileInserting) {
  ExplorationMap m(coarse_map_options());
  m.insert(cloud(3000, 0, 1), {0, 0, 0.5}, -1);
  const CameraIntrinsics cam = small_camera();
  std::atomic<bool> done{false};
  std::atomic<int> runs{0};
  std::thread writer([&] {
    for (int i = 1; i < 5; ++i) m.insert(cloud(3000, 0.01 * i, 20 + i), {0, 0, 0.5}, -1);
    done = true;
  });
  std::vector<std::thread> readers;
  for (int t = 0; t < 2; ++t)
    readers.emplace_back([&, t] {
      NbvOptions nbv;
      nbv.threads = 1;
      nbv.enclosure_power = 2.0;
      nbv.enclosure_range = 0.3 + 0.1 * t;
      while (!done || runs.load() < 2) {
        (void)next_best_view(m, cam, nbv);
        (void)void_enclosure(m, nbv.enclosure_range);
        ++runs;
      }
    });
  writer.join();
  for (auto& t : readers) t.join();
  EXPECT_GE(runs.load(), 2);
  const auto e = void_enclosure(m, 0.5);
  EXPECT_EQ(e.size(), m.void_cell_count());
  for (const auto& [k, v] : e) EXPECT_TRUE(v >= 0.0 && v <= 1.0) << k;
}

TEST(Threads, SceneAddWhileCapturing) {
  Scene s;
  s.add_box({1, -1, 0}, {1.2, 1, 1});
  DepthCamera cam(48, 36, 1.0, 4.0, 0.001, 1);
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int i = 0; i < 200; ++i) {
      s.add_box({1.5 + 0.01 * i, -1, 0}, {1.6 + 0.01 * i, 1, 1});
      s.add_mesh({{2, 0, 0}, {2, 1, 0}, {2, 0, 1}}, {{0, 1, 2}});
    }
    done = true;
  });
  std::thread other([&] {
    while (!done) (void)cam.capture(s, look_at({0, 0, 0.5}, {1, 0, 0.5}), 1);
  });
  while (!done) (void)cam.capture(s, look_at({0, 0, 0.5}, {1, 0.2, 0.5}), 2);
  writer.join();
  other.join();
  SUCCEED();
}

TEST(Threads, ImmutableObjectsFromManyThreads) {
  const OrientationSet set = OrientationSet::sphere(500);
  std::vector<std::thread> ts;
  std::atomic<int> bad{0};
  for (int t = 0; t < 4; ++t)
    ts.emplace_back([&, t] {
      std::mt19937_64 rng(t);
      std::normal_distribution<double> g;
      for (int i = 0; i < 2000; ++i) {
        Eigen::Vector3d d(g(rng), g(rng), g(rng));
        int k = set.nearest_direction(d.normalized());
        if (k < 0 || k >= set.directions()) ++bad;
      }
    });
  for (auto& t : ts) t.join();
  EXPECT_EQ(bad.load(), 0);
}

// Cancellation: a check installed by the embedding program stops a long build, and only the build.
namespace {
std::atomic<int> g_checks{0};
bool cancel_always() {
  ++g_checks;
  return true;
}
}  // namespace

TEST(Cancellation, LongComputationStopsWithCancelled) {
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // past this thread's last poll
  g_checks = 0;
  set_cancel_check(&cancel_always);
  EXPECT_THROW((void)OrientationSet::sphere(100000), Cancelled);
  EXPECT_GE(g_checks.load(), 1);
  set_cancel_check(nullptr);
  EXPECT_EQ(OrientationSet::sphere(100).directions(), 100);
}
