#pragma once
// A closed box with a 14 cm opening in its lid on a floor, and an exploration map of it (2.5 cm cells, the box's
// surroundings as the search space) after depth views from the given camera poses: void cells inside the box.
#include <memory>
#include <vector>

#include "octoreach/exploration.hpp"
#include "octoreach/simulation.hpp"

namespace octoreach::test_scenes {

inline std::unique_ptr<ExplorationMap> box_with_lid_opening(Scene& scene, const std::vector<Pose>& views) {
  scene.add_box({-1.5, -1.5, -0.05}, {1.5, 1.5, 0.0});
  scene.add_closed_box({0.6, -0.2, 0.0}, {1.0, 0.2, 0.4}, 0.02, "+z", 0.14, 0.14);
  ExplorationOptions o;
  o.resolution = 0.025;
  o.search_lo = {0.4, -0.4, 0.0};
  o.search_hi = {1.2, 0.4, 0.6};
  auto map = std::make_unique<ExplorationMap>(o);
  DepthCamera cam(48, 36, 1.0123, 4.0, 0.0, 0);
  for (const Pose& T : views) map->insert(cam.capture(scene, T), T.translation(), 4.0);
  return map;
}

}  // namespace octoreach::test_scenes
