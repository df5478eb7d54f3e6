// The last chance's eyes (cpp/src/exploration/void_aims.hpp): rays out of void cells leave through observed-free
// space and may cross void cells past it (a box's inside seen in patches), never the surface in an occupied cell
// (surface_extents.hpp) or an unseen cell that is not a void; rays through the voids' gates find the eyes behind a
// small opening; and the optical axis turns, within a bound, to one the capability map reaches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "box_scene.hpp"
#include "exploration/exploration_state.hpp"
#include "exploration/view_score.hpp"
#include "exploration/void_aims.hpp"
#include "octoreach/capability_map.hpp"
#include "octoreach/exploration.hpp"
#include "octoreach/orientation_set.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/simulation.hpp"

using namespace octoreach;

namespace {

constexpr double kRes = 0.025;

// The box seen from above through the opening and from two sides at a low resolution: its inside is seen in
// patches (columns under the opening), the rest of it is void.
std::unique_ptr<ExplorationMap> box_seen_in_patches(Scene& scene) {
  return test_scenes::box_with_lid_opening(
      scene, {look_at({0.8, 0.0, 1.1}, {0.8, 0.0, 0.0}), look_at({0.7, 0.05, 1.0}, {0.9, -0.1, 0.0}),
              look_at({0.2, -0.6, 0.7}, {0.8, 0.0, 0.2}), look_at({0.2, 0.6, 0.7}, {0.8, 0.0, 0.2})});
}

// The rule of a ray out of void cell `c` towards `eye`: no surface of an occupied cell on the line, and past the
// first observed-free cell only free or void cells (unknown cells outside the search space count as free).
// `crossed` is set when a void cell lies past free space.
bool ray_rule_holds(const ExplorationMap& map, const Eigen::Vector3d& c, const Eigen::Vector3d& eye, bool& crossed) {
  const Eigen::Vector3d d = (eye - c).normalized();
  const double len = (eye - c).norm();
  const auto& o = map.options();
  const CellKey own = map.key_of(c);
  bool left = false;
  crossed = false;
  for (double s = 0; s <= len; s += kRes / 8) {
    const Eigen::Vector3d p = c + s * d;
    const CellKey k = map.key_of(p);
    if (k == own) continue;
    CellState st = map.state(k);
    const bool inside = (p.array() >= o.search_lo.array()).all() && (p.array() <= o.search_hi.array()).all();
    if (st == CellState::Unknown && !inside) st = CellState::Free;
    if (st == CellState::Occupied) {
      if (detail::surface_meets_line(detail::state(map), k, c, d)) return false;
      continue;  // past the part of the cell its surface fills
    }
    if (st == CellState::Free) left = true;
    if (st == CellState::Unknown && left) {
      if (!map.is_void(k)) return false;
      crossed = true;
    }
  }
  return true;
}

// A last chance's request: rays out of every void cell, `directions` per cell, eyes 0.15-1 m out.
detail::AimRequest rays_request(std::size_t poses, int directions, std::uint64_t seed) {
  detail::AimRequest req;
  req.poses = poses;
  req.every_cell = true;
  req.directions = directions;
  req.distance = {0.15, 1.0};
  req.seed = seed;
  return req;
}

// aim_at_voids on `map` under its read lock.
std::vector<Pose> aims_at_voids(const ExplorationMap& map, const NbvOptions& opt, const detail::AimRequest& req) {
  auto guard = detail::read_guard(map);
  const detail::ViewChecker checker(map, opt);
  return detail::aim_at_voids(map, checker, opt, req);
}

}  // namespace

TEST(VoidAims, RaysCrossVoidCellsPastFreeSpaceButNotWallsOrUnseenSpace) {
  Scene scene;
  auto map = box_seen_in_patches(scene);
  ASSERT_GT(map->void_cell_count(), 100u);
  NbvOptions opt;
  opt.min_distance = 0.05;
  const std::vector<Pose> poses = aims_at_voids(*map, opt, rays_request(100000, 64, 5));
  ASSERT_GT(poses.size(), 50u);
  // each pose looks at its void cell (max_turn 0): a void cell whose centre is on the optical axis, 0.15-1 m
  // out, from which the ray to the eye follows the rule
  std::size_t crossing = 0;
  for (const Pose& T : poses) {
    const Eigen::Vector3d eye = T.translation(), axis = T.linear().col(2);
    bool found = false, crossed_any = false;
    for (double s = 0.15 - kRes; s <= 1.0 + kRes && !found; s += kRes / 8) {
      const CellKey k = map->key_of(eye + s * axis);
      const Eigen::Vector3d c = map->center(k);
      const double off_axis = (c - eye - (c - eye).dot(axis) * axis).norm();
      bool crossed = false;
      if (map->is_void(k) && off_axis < 1e-6 && ray_rule_holds(*map, c, eye, crossed)) {
        found = true;
        crossed_any = crossed;
      }
    }
    EXPECT_TRUE(found) << "eye " << eye.transpose() << " axis " << axis.transpose();
    crossing += crossed_any ? 1 : 0;
  }
  // the patches matter: some eyes are only reached across void cells past free space
  EXPECT_GT(crossing, 0u);
}

TEST(VoidAims, RaysThroughTheGatesFindEyesOutsideASlotThatUniformRaysSeldomFind) {
  // a closed box with a 5 x 5 cm slot in its +x face, seen from every side but never through the slot: its
  // inside is void, and from most of its cells the slot spans under 1 % of the sphere
  Scene scene;
  scene.add_closed_box({0.6, -0.2, 0.2}, {1.0, 0.2, 0.6}, 0.02, "+x", 0.05, 0.05);
  ExplorationOptions o;
  o.resolution = kRes;
  o.search_lo = {0.4, -0.4, 0.0};
  o.search_hi = {1.4, 0.4, 0.8};
  ExplorationMap map(o);
  DepthCamera cam(48, 36, 1.0123, 4.0, 0.0, 0);
  for (const Pose& T : {look_at({1.6, 0.7, 0.9}, {0.8, 0.0, 0.4}), look_at({1.6, -0.7, 0.0}, {0.8, 0.0, 0.4}),
                        look_at({0.8, 0.0, 1.6}, {0.8, 0.0, 0.4}), look_at({0.0, 0.0, 0.4}, {0.8, 0.0, 0.4}),
                        look_at({0.8, -1.0, 0.4}, {0.8, 0.0, 0.4}), look_at({0.8, 1.0, 0.4}, {0.8, 0.0, 0.4}),
                        look_at({0.8, 0.0, -0.8}, {0.8, 0.0, 0.4})})
    map.insert(cam.capture(scene, T), T.translation(), 4.0);
  ASSERT_GT(map.void_cell_count(), 1000u);
  NbvOptions opt;
  opt.min_distance = 0.05;
  detail::AimRequest req = rays_request(1000000, 8, 3);
  const auto eyes = [&](bool gates) {
    req.through_gates = gates;
    return aims_at_voids(map, opt, req);
  };
  // the eyes that look into the box through the slot: outside it, their void cell inside it, the ray to it
  // following the rule
  const auto through_slot = [&](const std::vector<Pose>& poses) {
    std::size_t n = 0;
    for (const Pose& T : poses) {
      const Eigen::Vector3d eye = T.translation(), axis = T.linear().col(2);
      if (eye.x() < 1.0) continue;
      for (double s = 0.15 - kRes; s <= 1.0 + kRes; s += kRes / 8) {
        const CellKey k = map.key_of(eye + s * axis);
        const Eigen::Vector3d c = map.center(k);
        bool crossed = false;
        if (map.is_void(k) && (c - eye - (c - eye).dot(axis) * axis).norm() < 1e-6) {
          EXPECT_TRUE(ray_rule_holds(map, c, eye, crossed)) << "eye " << eye.transpose();
          n += (c.x() > 0.62 && c.x() < 0.98 && std::abs(c.y()) < 0.18 && c.z() > 0.22 && c.z() < 0.58) ? 1 : 0;
          break;
        }
      }
    }
    return n;
  };
  const std::size_t uniform = through_slot(eyes(false)), gated = through_slot(eyes(true));
  // as many rays either way (half of them through the gates): over twice as many eyes look in through the slot
  EXPECT_GT(gated, 2 * uniform + 20) << "uniform rays: " << uniform;
}

TEST(VoidAims, EyesAreARandomSampleOfTheRaysEyesTheSameForAnyThreadCount) {
  Scene scene;
  auto map = box_seen_in_patches(scene);
  NbvOptions opt;
  opt.min_distance = 0.05;
  const auto aims = [&](std::size_t poses, int threads) {
    opt.threads = threads;
    return aims_at_voids(*map, opt, rays_request(poses, 64, 9));
  };
  const std::vector<Pose> all = aims(1000000, 2);  // every ray's eye
  ASSERT_GT(all.size(), 200u);
  const std::vector<Pose> one = aims(100, 1), two = aims(100, 2);
  ASSERT_EQ(one.size(), 100u);
  ASSERT_EQ(two.size(), 100u);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_TRUE(one[i].isApprox(two[i], 0)) << i;
    // each is one of the rays' eyes
    EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const Pose& T) { return T.isApprox(one[i], 0); })) << i;
  }
}

TEST(VoidAims, AnAxisTurnsToTheNearestReachableDirectionWithinItsBound) {
  auto robot = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  CapabilityMapOptions co;
  co.resolution = 0.2;
  co.directions = 100;
  co.seed = 3;
  const CapabilityMap cap = CapabilityMap::build(robot->chain("base_link", "tool0"), co);
  ExplorationMap map;
  NbvOptions opt;
  opt.capability_map = &cap;
  opt.capability_orientations = true;
  // the arm stands turned and raised in the map: directions and positions go through its base frame
  opt.capability_base = Pose::Identity();
  opt.capability_base.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  opt.capability_base.translation() = Eigen::Vector3d(0.3, -0.2, 0.5);
  const detail::ViewChecker checker(map, opt);
  const OrientationSet& set = cap.orientations();
  const auto [lo, hi] = cap.bounds();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n;
  const double turn = 0.4;
  int kept = 0, turned = 0, refused = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d eye =
        opt.capability_base * (lo + (hi - lo).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng))));
    const Eigen::Vector3d axis = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
    const std::vector<Eigen::Vector3d> near = checker.turned_axes(axis, turn);
    for (std::size_t k = 0; k < near.size(); ++k) {  // within the bound, nearest first
      EXPECT_GE(near[k].dot(axis), std::cos(turn) - 1e-12);
      if (k) EXPECT_LE(near[k].dot(axis), near[k - 1].dot(axis) + 1e-12);
    }
    const std::optional<Eigen::Vector3d> got = checker.reachable_axis(eye, axis, near);
    if (checker.axis_reachable(camera_pose(eye, axis))) {  // a reachable axis is kept as it is
      ASSERT_TRUE(got);
      EXPECT_LT((*got - axis).norm(), 1e-12);
      ++kept;
      continue;
    }
    EXPECT_FALSE(checker.reachable_axis(eye, axis, checker.turned_axes(axis, 0.0)));  // no turn allowed: refused
    // the brute-force answer: the set's reachable direction (map frame) within `turn` nearest to the axis
    double best = std::cos(turn);
    int want = -1;
    for (int d = 0; d < set.directions(); ++d) {
      const Eigen::Vector3d w = opt.capability_base.linear() * set.direction(d);
      if (w.dot(axis) >= best && checker.axis_reachable(camera_pose(eye, w))) {
        best = w.dot(axis);
        want = d;
      }
    }
    if (want < 0) {
      EXPECT_FALSE(got);
      ++refused;
      continue;
    }
    ASSERT_TRUE(got);
    EXPECT_NEAR(got->dot(axis), best, 1e-12);
    EXPECT_TRUE(checker.axis_reachable(camera_pose(eye, *got)));
    ++turned;
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(turned, 0);
  EXPECT_GT(refused, 0);
}
