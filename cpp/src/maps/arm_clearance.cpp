#include "maps/arm_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include "common/thread_pool.hpp"

namespace octoreach::detail {
namespace {

// Points on a shape's surface (link frame) that stand for the shape when testing whether an arm
// passes under a surface: box faces on a 3 x 3 grid, cylinder rims, sphere extremes, mesh vertices.
void witness_points(const Shape& s, std::vector<Eigen::Vector3d>& out) {
  std::vector<Eigen::Vector3d> local;
  switch (s.type) {
    case Shape::Type::Box: {
      Eigen::Vector3d h = s.size / 2;
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b)
          for (int c = -1; c <= 1; ++c)
            if (a || b || c) local.emplace_back(a * h.x(), b * h.y(), c * h.z());
      break;
    }
    case Shape::Type::Cylinder:
      for (int k = 0; k < 12; ++k) {
        double t = 2 * M_PI * k / 12;
        for (double z : {-s.length / 2, 0.0, s.length / 2})
          local.emplace_back(s.radius * std::cos(t), s.radius * std::sin(t), z);
      }
      break;
    case Shape::Type::Sphere:
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b)
          for (int c = -1; c <= 1; ++c)
            if (a || b || c) local.push_back(Eigen::Vector3d(a, b, c).normalized() * s.radius);
      break;
    case Shape::Type::Mesh: {
      auto* bvh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(s.geometry.get());
      if (!bvh || bvh->num_vertices == 0) break;
      int stride = std::max(1, bvh->num_vertices / 48);
      for (int i = 0; i < bvh->num_vertices; i += stride) local.push_back(bvh->vertices[i]);
      break;
    }
    case Shape::Type::Octree: break;  // a robot's links have none
  }
  for (const auto& p : local) out.push_back(s.origin * p);
}

}  // namespace

void LowSet::summarise() {
  // The kDirs directions (cos, sin), computed once.
  static const std::array<std::array<float, 2>, kDirs> dirs = [] {
    std::array<std::array<float, 2>, kDirs> d{};
    for (int k = 0; k < kDirs; ++k)
      d[k] = {static_cast<float>(std::cos(2 * M_PI * k / kDirs)), static_cast<float>(std::sin(2 * M_PI * k / kDirs))};
    return d;
  }();
  r_max = 0;
  for (const auto& w : points) r_max = std::max(r_max, w.head<2>().norm());
  // Point by point, every direction at once (lanes): per direction the same products and minimum
  // (std::min(m, v) is v < m ? v : m) in the same order as one direction at a time.
  min_proj.fill(std::numeric_limits<float>::infinity());
  for (const auto& w : points) {
    const float x = w.x(), y = w.y();
    for (int k = 0; k < kDirs; ++k) {
      const float v = dirs[k][0] * x + dirs[k][1] * y;
      min_proj[k] = v < min_proj[k] ? v : min_proj[k];
    }
  }
}

ArmClearance::ArmClearance(const Robot& robot, const CapabilityMap& cap, const ArmPlacement& place, double grasp_height)
    : robot_(robot),
      cap_(cap),
      arm_(robot.chain(cap.base_link(), cap.tip_link())),
      reference_(place.reference),
      arm_links_(place.roles.arm),  // links rigid with the tip (the gripper) touch the object
      link_witness_(robot.links().size()),
      root_from_arm_base_(place.link_poses[robot.link_index(cap.base_link())].inverse()),
      grasp_height_(grasp_height),
      orientations_(cap.orientations().size()) {
  for (int li : arm_links_)
    for (const auto& s : robot.links()[li].shapes) witness_points(s, link_witness_[li]);
  placing_ = robot.joints_placing(arm_links_);
}

void ArmClearance::compute(std::uint32_t rec, int orient, const Eigen::Vector3d& centre, const Eigen::Vector3d& n_arm,
                           std::vector<Pose>& poses, LowSet& low) const {
  std::vector<Eigen::Vector3f>& out = low.points;
  const float* qf = cap_.record_solution(rec, orient);
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
  robot_.link_poses(arm_.to_robot_configuration(q, reference_), poses, placing_);
  for (int li : arm_links_) {
    Pose in_arm = root_from_arm_base_ * poses[li];
    for (const auto& w : link_witness_[li]) {
      Eigen::Vector3d rel = in_arm * w - centre;  // relative to the reached point
      // Below the surface top, which lies grasp_height under the reached point.
      if (n_arm.dot(rel) < -grasp_height_ - 1e-3) out.push_back(rel.cast<float>());
    }
  }
  // Nearest to the target first: those fall inside the outline soonest, ending the test early (the
  // order changes no answer, only how soon a test ends). Sorted by key, the keys computed once.
  thread_local std::vector<std::pair<float, std::uint32_t>> order;
  thread_local std::vector<Eigen::Vector3f> sorted;
  order.resize(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) order[i] = {out[i].head<2>().squaredNorm(), static_cast<std::uint32_t>(i)};
  std::sort(order.begin(), order.end());
  sorted.resize(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) sorted[i] = out[order[i].second];
  out.swap(sorted);
  low.summarise();
}

void ArmClearance::compute_shared(const CellSlots& slots, int threads) {
  std::vector<LowSet> low(slots.size());
  const auto& records = slots.records();
  detail::parallel_for(records.size(), threads, [&](std::size_t i, int) {
    thread_local std::vector<Pose> poses;
    const auto& R = records[i];
    for (std::uint32_t s = R.first; s < R.last; ++s)
      compute(R.rec, slots.cell(s).orient, R.centre, Eigen::Vector3d::UnitZ(), poses, low[s]);
  }, 4);
  std::size_t total = 0;
  for (const auto& l : low) total += l.points.size();
  if (total > 0xffffffffu) throw std::length_error("surface map: too many arm witness points below the surface");
  points_.clear();
  points_.reserve(total);
  start_.assign(1, 0);
  summary_.assign(low.size() * kSummary, 0.0f);
  for (std::size_t s = 0; s < low.size(); ++s) {
    points_.insert(points_.end(), low[s].points.begin(), low[s].points.end());
    start_.push_back(static_cast<std::uint32_t>(points_.size()));
    std::copy(low[s].min_proj.begin(), low[s].min_proj.end(), summary_.begin() + s * kSummary);
    summary_[s * kSummary + LowSet::kDirs] = low[s].r_max;
    std::vector<Eigen::Vector3f>().swap(low[s].points);
  }
}

}  // namespace octoreach::detail
