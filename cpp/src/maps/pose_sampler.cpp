#include "octoreach/pose_sampler.hpp"

#include "common/cancel.hpp"

#include <cmath>

namespace octoreach {

bool CostMap::is_free(double x, double y) const {
  if (!(resolution > 0)) return false;
  double cx = (x - origin.x()) / resolution, cy = (y - origin.y()) / resolution;
  if (!(cx >= 0) || !(cy >= 0) || cx >= cost.cols() || cy >= cost.rows()) return false;
  return cost(static_cast<int>(cy), static_cast<int>(cx)) < threshold;
}

PoseSampler::PoseSampler(std::shared_ptr<const SurfaceMap> map, const PoseSamplerOptions& options)
    : map_(std::move(map)), options_(options), rng_(options.seed) {
  if (!map_) throw std::invalid_argument("PoseSampler needs a surface map");
  if (options_.candidates < 1 || std::uint64_t(options_.candidates) > limits::kSamplerCandidates)
    throw std::invalid_argument("candidates must be in [1, " + std::to_string(limits::kSamplerCandidates) + "], got " +
                                std::to_string(options_.candidates));
  if (!(options_.discount_sigma.array() > 0).all() || !options_.discount_sigma.allFinite())
    throw std::invalid_argument("discount_sigma entries must be positive and finite");
  if (map_->map().voxel_count() == 0)
    throw std::invalid_argument("the surface map is empty: " +
                                (map_->empty_reason().empty() ? std::string("no pose reaches the surface") : map_->empty_reason()));
  auto b = map_->map().bounds();
  lo_ = b.first;
  hi_ = b.second;
  if (options_.room_check && !map_->room().body().empty() && !map_->room().obstacles().empty()) {
    room_ = map_->shared_room();
    room_obstacles_ = std::shared_ptr<const Obstacles>(room_, &room_->obstacles());
  }
}

void PoseSampler::set_room(std::shared_ptr<const Obstacles> obstacles) {
  if (!obstacles) throw std::invalid_argument("set_room needs obstacles");
  if (map_->room().body().empty())
    throw std::invalid_argument("the surface map records no body to check against a room (a file written before maps "
                                "recorded their room, or built without the body check): give in_collision=(robot, "
                                "obstacles) instead");
  room_ = map_->shared_room();
  room_obstacles_ = std::move(obstacles);
}

void PoseSampler::set_collision(std::shared_ptr<const Robot> robot, std::shared_ptr<const Obstacles> obstacles,
                                const Eigen::VectorXd& reference) {
  if (!robot || !obstacles) throw std::invalid_argument("set_collision needs a robot and obstacles");
  if (!map_->provenance().matches(*robot))
    throw std::invalid_argument("the robot is not the one the surface map was built for");
  Eigen::VectorXd q = reference.size() ? reference : robot->home();
  robot_poses_ = robot->link_poses(q);
  root_in_reference_ = robot_poses_[robot->link_index(map_->reference_frame())].inverse();
  robot_ = std::move(robot);
  obstacles_ = std::move(obstacles);
  room_ = nullptr;
}

double PoseSampler::discount(const Eigen::Vector4d& c) const {
  double w = 1.0;
  for (const auto& p : history_) {
    Eigen::Vector4d d = c - p;
    d[3] = std::remainder(d[3], 2.0 * M_PI);
    double dist = d.cwiseQuotient(options_.discount_sigma).norm();
    w *= std::min(1.0, dist);
    if (w == 0) break;
  }
  return w;
}

void PoseSampler::reset() {
  history_.clear();
  rng_.seed(options_.seed);
}

std::optional<Eigen::Vector4d> PoseSampler::sample(double* score) {
  std::uniform_real_distribution<double> ux(lo_.x(), hi_.x()), uy(lo_.y(), hi_.y()), uz(lo_.z(), hi_.z()),
      ut(-M_PI, M_PI);
  const std::size_t max_draws = options_.max_draws ? options_.max_draws : std::size_t(2000) * options_.candidates;
  counts_ = {0, 0, 0, 0};
  double best = -1;
  Eigen::Vector4d best_pose;
  int found = 0;
  detail::CancellableScope cancellable;
  while (found < options_.candidates && counts_[0] < max_draws) {
    detail::poll_cancel("pose sampling cancelled");
    ++counts_[0];
    // Named draws: argument evaluation order is unspecified, and the stream must not depend on the compiler.
    const double x = ux(rng_), y = uy(rng_), z = uz(rng_), t = ut(rng_);
    Eigen::Vector4d c(x, y, z, t);
    // Heights outside the map's z range were never evaluated: clip into it, so a robot on the
    // floor (z range (0, 0)) gets z = 0 exactly.
    auto zr = map_->z_range();
    c[2] = std::min(std::max(c[2], zr.first), zr.second);
    double rs = map_->reachability(c[0], c[1], c[2], c[3]);
    if (rs <= 0) {
      ++counts_[1];
      continue;
    }
    if ((cost_map_ && !cost_map_->is_free(c[0], c[1])) || (is_free_ && !is_free_(c))) {
      ++counts_[2];
      continue;
    }
    bool collides = false;
    if (robot_) {
      Pose B = Pose::Identity();
      B.translation() = c.head<3>();
      B.linear() = Eigen::AngleAxisd(c[3], Eigen::Vector3d::UnitZ()).toRotationMatrix();
      collides = robot_->links_in_collision(robot_poses_, *obstacles_, B * root_in_reference_);
    }
    if (!collides && room_) collides = room_->body_collides(c, *room_obstacles_);
    if (!collides && in_collision_) collides = in_collision_(c);
    if (collides) {
      ++counts_[3];
      continue;
    }
    ++found;
    double s = rs * discount(c);
    if (s > best) {
      best = s;
      best_pose = c;
    }
  }
  if (found == 0) return std::nullopt;
  history_.push_back(best_pose);
  if (score) *score = best;
  return best_pose;
}

}  // namespace octoreach
