#include "kinematics/hinge_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fcl/fcl.h>

#include "collision/detail.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::detail {
namespace {

// Added to what half a bucket can close: FCL's distance and its collision test need not agree to the
// last bit, so a certified pair is kept at least this far apart.
constexpr double kMargin = 1e-4;

}  // namespace

double HingePairs::bucket_width(double radius) { return std::min(0.05, 3e-3 / std::max(radius, 1e-6)); }

HingePairs::HingePairs(const Chain& chain, const std::vector<std::pair<int, int>>& pairs,
                       const Eigen::VectorXd& reference)
    : pairs_(pairs), hinge_of_(pairs.size(), -1) {
  const Robot& robot = chain.robot();
  // A joint that mimics a chain joint moves links the chain's masks do not see: no certificates then.
  for (const Joint& j : robot.joints())
    if (j.mimic >= 0)
      for (const auto& s : chain.segments())
        if (s.robot_joint == j.mimic) return;
  base_ = chain.to_robot_configuration(
      chain.lower().cwiseMax(Eigen::VectorXd::Zero(chain.dof())).cwiseMin(chain.upper()), reference);
  robot.link_poses(base_, poses_);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [a, b] = pairs[p];
    const std::uint64_t ma = chain.link_mask(a), mb = chain.link_mask(b), x = ma ^ mb;
    if (x == 0 || (x & (x - 1)) != 0) continue;  // not exactly one joint between them
    int i = 0;
    while (!((x >> i) & 1ULL)) ++i;
    const int turned = (ma & x) ? a : b;
    const Joint& j = robot.joints()[chain.segments()[i].robot_joint];
    Hinge h;
    h.pair = static_cast<int>(p);
    h.config_index = j.index;
    if (j.type == JointType::Prismatic) {
      h.radius = 1.0;  // a translation by t moves every point by |t|
    } else {
      const Pose frame = poses_[j.parent_link] * j.origin;
      const Eigen::Vector3d axis = (frame.linear() * j.axis).normalized(), o = frame.translation();
      for (const Shape& s : robot.links()[turned].shapes) {
        const fcl::AABBd box = world_aabb(*s.geometry, poses_[turned] * s.origin);
        for (int c = 0; c < 8; ++c) {
          Eigen::Vector3d corner((c & 1) ? box.max_.x() : box.min_.x(), (c & 2) ? box.max_.y() : box.min_.y(),
                                 (c & 4) ? box.max_.z() : box.min_.z());
          h.radius = std::max(h.radius, (corner - o).cross(axis).norm());
        }
      }
    }
    const bool continuous = j.type == JointType::Continuous;
    h.lo = continuous ? -kPi : j.lower;
    h.hi = continuous ? kPi : j.upper;
    if (!(h.hi > h.lo) || !std::isfinite(h.lo) || !std::isfinite(h.hi) || !(h.radius > 0)) continue;
    h.width = bucket_width(h.radius);
    h.bucket.assign(static_cast<std::size_t>(std::ceil((h.hi - h.lo) / h.width)), -1);
    hinge_of_[p] = static_cast<int>(hinges_.size());
    hinges_.push_back(std::move(h));
  }
}

double HingePairs::distance(const Robot& robot, const Hinge& h, double v) {
  Eigen::VectorXd cfg = base_;
  cfg[h.config_index] = v;
  robot.link_poses(cfg, poses_);
  const auto [a, b] = pairs_[h.pair];
  double d = std::numeric_limits<double>::infinity();
  for (const Shape& sa : robot.links()[a].shapes)
    for (const Shape& sb : robot.links()[b].shapes) {
      fcl::DistanceRequestd request;
      fcl::DistanceResultd result;
      const Pose ta = poses_[a] * sa.origin, tb = poses_[b] * sb.origin;
      fcl::distance(sa.geometry.get(), fcl::Transform3d(ta.matrix()), sb.geometry.get(), fcl::Transform3d(tb.matrix()),
                    request, result);
      d = std::min(d, result.min_distance);
      if (!(d > 0)) return 0.0;
    }
  return d;
}

bool HingePairs::certified(const Robot& robot, std::size_t hi, double v) {
  Hinge& h = hinges_[hi];
  if (!(v >= h.lo && v <= h.hi)) return false;
  const std::size_t n = h.bucket.size();
  const std::size_t k = std::min(n - 1, static_cast<std::size_t>((v - h.lo) / h.width));
  if (h.bucket[k] < 0) {
    const double c = h.lo + (k + 0.5) * h.width;
    // Every bucket wholly within `reach` of the centre is free: turning by less than reach moves no
    // point of the turned link by more than the distance (less the margin).
    const double reach = (distance(robot, h, c) - kMargin) / h.radius;
    h.bucket[k] = reach > 0.5 * h.width ? 1 : 0;
    for (std::size_t j = k + 1; j < n && h.lo + (j + 1) * h.width - c < reach; ++j) h.bucket[j] = 1;
    for (std::size_t j = k; j-- > 0 && c - (h.lo + j * h.width) < reach;) h.bucket[j] = 1;
  }
  return h.bucket[k] == 1;
}

}  // namespace octoreach::detail
