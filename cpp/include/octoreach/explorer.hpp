#pragma once
/// \file explorer.hpp
/// \brief An exploration session in the user's own loop: it owns the map and the loop's memory, takes the
/// robot's clouds (or depth images) with the camera pose they were taken from, and answers the next view
/// (camera pose, joints, base) or why to stop, with the strategy the benchmarks use (choose_view).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/exploration.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/view_choice.hpp"

namespace octoreach {

/// \brief What an Explorer is built from. The camera is carried by options.search.chain (tip = camera frame,
/// +z its optical axis; nullptr: a free camera inside options.search's workspace), whose base may stand at
/// any of `bases` (chain base -> map; the robot starts at bases[0]).
struct ExplorerSetup {
  CameraIntrinsics camera;
  Aabb search_space;                    ///< the region to explore (map frame); must be finite and non-empty
  std::vector<Pose> bases{Pose::Identity()};
  double reach = 0.0;                   ///< m around each base the camera stays within (0: no bound)
  double resolution = ExplorationOptions().resolution;                  ///< map cell edge, m
  double void_fit_threshold = ExplorationOptions().void_fit_threshold;  ///< the map's void clustering
  ExploreOptions options;               ///< the loop's settings (search, stop rule, looks); its seed is the run's
  ViewStrategy strategy = ViewStrategy::FrontierVoid;
};

/// \brief The next view an Explorer proposes, or why it stops.
struct NextView {
  bool stop = false;
  std::string stop_reason;  ///< choose_view's reasons, or "view budget"
  Pose camera_pose = Pose::Identity();  ///< camera -> map
  Eigen::VectorXd q;                    ///< chain joints (empty without a chain)
  int base = 0;                         ///< index into ExplorerSetup::bases
  Pose base_pose = Pose::Identity();    ///< that base (chain base -> map)
  double expected_gain = 0.0;           ///< the utility the stop rule looks at (expected void cells for ours)
  ViewChoice choice;                    ///< choose_view's whole answer (gains, counts, the search)
};

/// \brief One exploration session (see the file comment). Not thread-safe: one loop drives it.
class Explorer {
 public:
  /// \throws std::invalid_argument naming a bad setup value (camera, search space, bases, reach, options).
  explicit Explorer(ExplorerSetup setup);
  ~Explorer();

  /// \brief Integrates a cloud (map frame, N points) taken from `camera_pose` (camera -> map). The view is
  /// announced first (options.learn_misses: expect_view), as the loop does, and the void cells the insert took
  /// off the void set are added to memory().last_void_seen (the stop rule's evidence, read by the next
  /// next_view), the search space's cells it made known to memory().last_space_seen (beyond_voids' evidence). \throws std::invalid_argument for a non-finite point or a pose that is not a rigid transform;
  /// the explorer is then unchanged.
  InsertStats integrate(const std::vector<Eigen::Vector3d>& points, const Pose& camera_pose);
  /// \brief Integrates a depth image (row-major, height x width metres along the optical axis; 0 = no
  /// return) of the setup's camera taken from `camera_pose`. \throws std::invalid_argument for a wrong size,
  /// a negative, NaN or infinite depth, or a non-rigid pose; the explorer is then unchanged.
  InsertStats integrate_depth(const std::vector<float>& depth, int width, int height, const Pose& camera_pose);
  /// \brief The last proposed view was not taken (the motion failed): no view near its camera is proposed
  /// again; it counts as a view of the budget.
  void view_failed();
  /// \brief The next view from the current map, or the stop decision (choose_view's; "view budget" once
  /// options.max_views views are taken, with the choice still reported). The robot is assumed to drive to
  /// the proposed base.
  NextView next_view();

  const ExplorationMap& map() const { return *map_; }
  const ChoiceMemory& memory() const { return memory_; }
  const ExplorerSetup& setup() const { return setup_; }
  int views() const { return views_; }          ///< views integrated or failed
  int current_base() const { return current_; }

 private:
  ExplorerSetup setup_;
  std::unique_ptr<ExplorationMap> map_;
  ChoiceMemory memory_;
  int views_ = 0, current_ = 0;
  std::uint64_t seed_ = 0;
  bool has_last_ = false;
  Eigen::Vector3d last_camera_ = Eigen::Vector3d::Zero();
};

}  // namespace octoreach
