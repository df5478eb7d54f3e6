#include "arm_obstacles.hpp"

#include <algorithm>
#include <limits>

#include <fcl/fcl.h>

#include "../collision_detail.hpp"
#include "../common/thread_pool.hpp"

namespace octoreach::detail {
namespace {

// Box of a world-frame box (lo, hi) seen from a frame F (F_from_world): conservative.
void box_in_frame(const Pose& F_from_world, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Eigen::Vector3d& out_lo,
                  Eigen::Vector3d& out_hi) {
  Eigen::Vector3d c = F_from_world * (0.5 * (lo + hi));
  Eigen::Vector3d e = F_from_world.linear().cwiseAbs() * (0.5 * (hi - lo));
  out_lo = c - e;
  out_hi = c + e;
}

}  // namespace

ArmObstacles::ArmObstacles(const Robot& robot, const CapabilityMap& cap, const ArmPlacement& place,
                           std::shared_ptr<const Obstacles> obstacles)
    : robot_(robot),
      cap_(cap),
      arm_(robot.chain(cap.base_link(), cap.tip_link())),
      reference_(place.reference),
      arm_from_root_(place.link_poses[robot.link_index(cap.base_link())].inverse()),
      orientations_(cap.orientations().size()),
      obstacles_(std::move(obstacles)),
      reach_lo_(Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())),
      reach_hi_(-reach_lo_) {
  links_ = place.roles.arm;
  links_.insert(links_.end(), place.roles.tool.begin(), place.roles.tool.end());
  if (obstacles_)
    for (const auto& o : obstacles_->objects()) boxes_.push_back(o->getAABB());
}

void ArmObstacles::compute(int threads) {
  if (empty()) return;
  std::vector<Eigen::Vector3d> cc;
  std::vector<double> cv;
  cap_.voxels(cc, cv);
  std::vector<std::uint32_t> records;
  for (const auto& c : cc) {
    std::int64_t rec = cap_.record_at(c);
    if (rec >= 0) records.push_back(static_cast<std::uint32_t>(rec));
  }
  std::vector<std::vector<std::pair<std::uint64_t, ArmBox>>> parts(records.size());
  detail::parallel_for(records.size(), threads, [&](std::size_t i, int) {
    thread_local std::vector<Pose> poses;
    const std::uint32_t rec = records[i];
    for (int orient = 0; orient < orientations_; ++orient) {
      if (!cap_.record_has(rec, orient)) continue;
      const float* qf = cap_.record_solution(rec, orient);
      Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
      robot_.link_poses(arm_.to_robot_configuration(q, reference_), poses);
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (int li : links_)
        for (const auto& s : robot_.links()[li].shapes) {
          fcl::AABBd b = world_aabb(*s.geometry, arm_from_root_ * poses[li] * s.origin);
          lo = lo.cwiseMin(b.min_);
          hi = hi.cwiseMax(b.max_);
        }
      parts[i].emplace_back(key(rec, orient), ArmBox{lo.cast<float>(), hi.cast<float>()});
    }
  }, 4);
  for (auto& part : parts)
    for (auto& [k, box] : part) {
      reach_lo_ = reach_lo_.cwiseMin(box.lo.cast<double>());
      reach_hi_ = reach_hi_.cwiseMax(box.hi.cast<double>());
      arm_boxes_.emplace(k, box);
    }
}

void ArmObstacles::near(const Pose& world_from_arm, NearObstacles& out) const {
  out.lo.clear();
  out.hi.clear();
  if (empty() || arm_boxes_.empty()) return;
  const Pose arm_from_world = world_from_arm.inverse();
  for (const auto& b : boxes_) {
    Eigen::Vector3d lo, hi;
    box_in_frame(arm_from_world, b.min_, b.max_, lo, hi);
    if ((lo.array() > reach_hi_.array()).any() || (hi.array() < reach_lo_.array()).any()) continue;
    out.lo.push_back(lo);
    out.hi.push_back(hi);
  }
}

bool ArmObstacles::collides(std::uint32_t rec, int orient, const NearObstacles& near, const Pose& world_from_root,
                            std::vector<Pose>& poses) const {
  if (near.empty()) return false;
  auto it = arm_boxes_.find(key(rec, orient));
  if (it == arm_boxes_.end()) return false;  // no stored solution: nothing to check
  const Eigen::Vector3d lo = it->second.lo.cast<double>(), hi = it->second.hi.cast<double>();
  bool overlap = false;
  for (std::size_t j = 0; j < near.lo.size() && !overlap; ++j)
    overlap = (near.lo[j].array() <= hi.array()).all() && (near.hi[j].array() >= lo.array()).all();
  if (!overlap) return false;
  const float* qf = cap_.record_solution(rec, orient);
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
  robot_.link_poses(arm_.to_robot_configuration(q, reference_), poses);
  return robot_.links_in_collision(poses, *obstacles_, world_from_root, &links_);
}

}  // namespace octoreach::detail
