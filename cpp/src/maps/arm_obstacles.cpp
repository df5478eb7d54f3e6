#include "arm_obstacles.hpp"

#include <algorithm>
#include <cmath>
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

namespace {

// Centimetre box rounded outwards; the arm frame spans far less than +-327 m.
void put_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::int16_t* out) {
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<std::int16_t>(std::max(-32000.0, std::floor(lo[k] * 100)));
    out[3 + k] = static_cast<std::int16_t>(std::min(32000.0, std::ceil(hi[k] * 100)));
  }
}

bool meets(const std::int16_t* box, const Eigen::Vector3d& lo_cm, const Eigen::Vector3d& hi_cm) {
  for (int k = 0; k < 3; ++k)
    if (box[k] > hi_cm[k] || box[3 + k] < lo_cm[k]) return false;
  return true;
}

}  // namespace

void ArmObstacles::compute(int threads, double za_lo, double za_hi) {
  if (empty()) return;
  for (int li : links_)
    if (!robot_.links()[li].shapes.empty()) shaped_.push_back(li);
  const std::size_t stride = 6 * (1 + shaped_.size());
  std::vector<Eigen::Vector3d> cc;
  std::vector<double> cv;
  cap_.voxels(cc, cv);
  std::vector<std::uint32_t> records;
  for (const auto& c : cc) {
    if (c.z() < za_lo - cap_.resolution() || c.z() > za_hi + cap_.resolution()) continue;
    std::int64_t rec = cap_.record_at(c);
    if (rec >= 0) records.push_back(static_cast<std::uint32_t>(rec));
  }
  std::vector<std::vector<std::uint64_t>> keys(records.size());
  std::vector<std::vector<std::int16_t>> parts(records.size());
  detail::parallel_for(records.size(), threads, [&](std::size_t i, int) {
    thread_local std::vector<Pose> poses;
    const std::uint32_t rec = records[i];
    for (int orient = 0; orient < orientations_; ++orient) {
      if (!cap_.record_has(rec, orient)) continue;
      const float* qf = cap_.record_solution(rec, orient);
      Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
      robot_.link_poses(arm_.to_robot_configuration(q, reference_), poses);
      const std::size_t at = parts[i].size();
      parts[i].resize(at + stride);
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (std::size_t j = 0; j < shaped_.size(); ++j) {
        const int li = shaped_[j];
        Eigen::Vector3d llo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), lhi = -llo;
        for (const auto& s : robot_.links()[li].shapes) {
          fcl::AABBd b = world_aabb(*s.geometry, arm_from_root_ * poses[li] * s.origin);
          llo = llo.cwiseMin(b.min_);
          lhi = lhi.cwiseMax(b.max_);
        }
        put_box(llo, lhi, parts[i].data() + at + 6 * (1 + j));
        lo = lo.cwiseMin(llo);
        hi = hi.cwiseMax(lhi);
      }
      put_box(lo, hi, parts[i].data() + at);
      keys[i].push_back(key(rec, orient));
    }
  }, 4);
  std::size_t total = 0;
  for (const auto& k : keys) total += k.size();
  boxes_cm_.reserve(total * stride);
  offset_.reserve(total);
  for (std::size_t i = 0; i < records.size(); ++i)
    for (std::size_t c = 0; c < keys[i].size(); ++c) {
      const std::int16_t* box = parts[i].data() + c * stride;
      for (int k = 0; k < 3; ++k) {
        reach_lo_[k] = std::min(reach_lo_[k], box[k] / 100.0);
        reach_hi_[k] = std::max(reach_hi_[k], box[3 + k] / 100.0);
      }
      offset_.emplace(keys[i][c], static_cast<std::uint32_t>(boxes_cm_.size()));
      boxes_cm_.insert(boxes_cm_.end(), box, box + stride);
    }
}

void ArmObstacles::near(const Pose& world_from_arm, NearObstacles& out) const {
  out.lo.clear();
  out.hi.clear();
  if (empty() || offset_.empty()) return;
  const Pose arm_from_world = world_from_arm.inverse();
  for (const auto& b : boxes_) {
    Eigen::Vector3d lo, hi;
    box_in_frame(arm_from_world, b.min_, b.max_, lo, hi);
    if ((lo.array() > reach_hi_.array()).any() || (hi.array() < reach_lo_.array()).any()) continue;
    out.lo.push_back(lo * 100);  // centimetres, as the arm boxes
    out.hi.push_back(hi * 100);
  }
}

// Link poses (arm frame) of the shaped links at the stored solution of a cell, from the scratch's
// cache, computed and cached on first use (the cache stops growing at 32 MB).
const float* ArmObstacles::link_poses(std::uint32_t rec, int orient, ArmScratch& s) const {
  const std::uint64_t k = key(rec, orient);
  auto it = s.at.find(k);
  if (it != s.at.end()) return s.pool.data() + it->second;
  const float* qf = cap_.record_solution(rec, orient);
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
  robot_.link_poses(arm_.to_robot_configuration(q, reference_), s.poses);
  const std::size_t n = 12 * shaped_.size();
  const bool keep = s.pool.size() + n <= (std::size_t(32) << 20) / sizeof(float);
  const std::size_t at = s.pool.size();
  thread_local std::vector<float> spare;  // a cell met once the cache is full
  float* out;
  if (keep) {
    s.pool.resize(at + n);
    out = s.pool.data() + at;
  } else {
    spare.resize(n);
    out = spare.data();
  }
  for (std::size_t j = 0; j < shaped_.size(); ++j) {
    Eigen::Matrix<float, 3, 4> m = (arm_from_root_ * s.poses[shaped_[j]]).matrix().topRows<3>().cast<float>();
    std::copy(m.data(), m.data() + 12, out + 12 * j);
  }
  if (keep) s.at.emplace(k, static_cast<std::uint32_t>(at));
  return out;
}

bool ArmObstacles::collides(std::uint32_t rec, int orient, const NearObstacles& near, const Pose& world_from_arm,
                            ArmScratch& scratch) const {
  if (near.empty()) return false;
  auto it = offset_.find(key(rec, orient));
  if (it == offset_.end()) return false;  // no stored solution: nothing to check
  const std::int16_t* box = boxes_cm_.data() + it->second;
  // The whole arm's box, then each link's box, against each near obstacle's box; FCL only for the
  // links whose box meets one.
  thread_local std::vector<int> hit;
  hit.clear();
  for (std::size_t j = 0; j < near.lo.size(); ++j) {
    if (!meets(box, near.lo[j], near.hi[j])) continue;
    for (std::size_t l = 0; l < shaped_.size(); ++l)
      if (meets(box + 6 * (1 + l), near.lo[j], near.hi[j]) && std::find(hit.begin(), hit.end(), int(l)) == hit.end())
        hit.push_back(static_cast<int>(l));
  }
  if (hit.empty()) return false;
  const float* P = link_poses(rec, orient, scratch);
  for (int l : hit) {
    Pose in_arm = Pose::Identity();
    in_arm.matrix().topRows<3>() = Eigen::Map<const Eigen::Matrix<float, 3, 4>>(P + 12 * l).cast<double>();
    const Pose world = world_from_arm * in_arm;
    for (const auto& s : robot_.links()[shaped_[l]].shapes)
      if (obstacles_->collides(*s.geometry, world * s.origin)) return true;
  }
  return false;
}

}  // namespace octoreach::detail
