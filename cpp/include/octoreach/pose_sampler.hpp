#pragma once
/// \file pose_sampler.hpp
/// \brief Sampling good, well spread base poses from a surface map (the grounding attachment).

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "octoreach/robot.hpp"
#include "octoreach/surface_map.hpp"

namespace octoreach {

/// \brief A 2D navigation cost map: cell (row, col) covers x in [ox + col r, ox + (col+1) r),
/// y in [oy + row r, ...). A pose is free when its cell's cost is below `threshold`; outside the grid
/// it is not free.
struct CostMap {
  Eigen::MatrixXf cost;  ///< rows = y cells, cols = x cells
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double resolution = 0.05;
  double threshold = 0.5;
  bool is_free(double x, double y) const;
};

/// \brief Options of the sampler (the paper's defaults).
struct PoseSamplerOptions {
  int candidates = 40;  ///< valid candidates drawn per sample; the best R_S x w wins
  Eigen::Vector4d discount_sigma = Eigen::Vector4d(0.5, 0.5, 0.5, kPi / 4);  ///< S of eq. (3)
  std::uint64_t seed = 0;
  std::size_t max_draws = 0;  ///< give up after this many draws per sample (0: 2000 x candidates)
  /// Check the body against the room the map was built with (SurfaceMap::room), unless a collision test
  /// replaces it (set_room, set_collision, set_in_collision).
  bool room_check = true;
};

/// \brief Draws continuous base poses (x, y, z, theta) inside a surface map's bounds and keeps valid
/// ones, cheapest test first: R_S > 0, free in the cost map / callback, no collision of the robot
/// (at its reference posture) with the environment. Returns the valid candidate with the highest
/// R_S x w, w = prod over earlier samples of min(1, ||(c - p) / sigma||) (eq. 3, angles wrapped).
class PoseSampler {
 public:
  using PoseTest = std::function<bool(const Eigen::Vector4d&)>;
  PoseSampler(std::shared_ptr<const SurfaceMap> map, const PoseSamplerOptions& options = {});

  void set_cost_map(const CostMap& map) { cost_map_ = map; }
  void set_is_free(PoseTest test) { is_free_ = std::move(test); }
  /// \brief Full-robot collision test: the robot at `reference` (empty: home) with its map reference
  /// frame at the candidate pose, against `obstacles` (world frame).
  void set_collision(std::shared_ptr<const Robot> robot, std::shared_ptr<const Obstacles> obstacles,
                     const Eigen::VectorXd& reference = Eigen::VectorXd());
  void set_in_collision(PoseTest test) {
    in_collision_ = std::move(test);
    room_ = nullptr;
  }
  /// \brief The body the map records (SurfaceMap::room) checked against `obstacles` (world frame) instead of the
  /// room it records. \throws std::invalid_argument when the map records no body (a file written before maps
  /// recorded their room, or a build without the body check): use set_collision then.
  void set_room(std::shared_ptr<const Obstacles> obstacles);
  /// \brief True when the sampler checks the map's body against a room (its own or set_room's).
  bool checks_room() const { return room_ != nullptr; }

  /// \brief One pose, or nothing when no valid candidate was found within max_draws draws.
  std::optional<Eigen::Vector4d> sample(double* score = nullptr);
  /// \brief Forgets the history (and restarts the random stream).
  void reset();
  const std::vector<Eigen::Vector4d>& history() const { return history_; }
  /// \brief The discount w of eq. (3) of a candidate against the history.
  double discount(const Eigen::Vector4d& candidate) const;
  /// \brief Draw counts of the last sample: total, rejected by R_S, by the cost map, by collision.
  const std::array<std::size_t, 4>& last_counts() const { return counts_; }

 private:
  std::shared_ptr<const SurfaceMap> map_;
  PoseSamplerOptions options_;
  std::mt19937_64 rng_;
  Eigen::Vector3d lo_, hi_;
  std::optional<CostMap> cost_map_;
  PoseTest is_free_, in_collision_;
  std::shared_ptr<const Robot> robot_;
  std::shared_ptr<const Obstacles> obstacles_;
  std::vector<Pose> robot_poses_;
  std::shared_ptr<const MapRoom> room_;            // the body checked against room_obstacles_
  std::shared_ptr<const Obstacles> room_obstacles_;
  Pose root_in_reference_ = Pose::Identity();
  std::vector<Eigen::Vector4d> history_;
  std::array<std::size_t, 4> counts_{{0, 0, 0, 0}};
};

}  // namespace octoreach
