#include "maps/arm_obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fcl/fcl.h>

#include "collision/detail.hpp"
#include "common/thread_pool.hpp"
#include "common/vector_clones.hpp"

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
                           std::shared_ptr<const Obstacles> obstacles, std::shared_ptr<const CellSlots> slots,
                           int threads)
    : robot_(robot),
      cap_(cap),
      arm_(robot.chain(cap.base_link(), cap.tip_link())),
      reference_(place.reference),
      slots_(std::move(slots)),
      arm_from_root_(place.link_poses[robot.link_index(cap.base_link())].inverse()),
      obstacles_(std::move(obstacles)),
      reach_lo_(Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())),
      reach_hi_(-reach_lo_) {
  links_ = place.roles.arm;
  links_.insert(links_.end(), place.roles.tool.begin(), place.roles.tool.end());
  placing_ = robot.joints_placing(links_);
  if (!slots_) throw std::invalid_argument("ArmObstacles: no cells given");
  if (obstacles_)
    for (const auto& o : obstacles_->objects()) boxes_.push_back(o->getAABB());
  compute(threads);
}

namespace {

// Centimetre box rounded outwards; the arm frame spans far less than +-327 m.
void put_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::int16_t* out) {
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<std::int16_t>(std::max(-32000.0, std::floor(lo[k] * 100)));
    out[3 + k] = static_cast<std::int16_t>(std::min(32000.0, std::ceil(hi[k] * 100)));
  }
}

// An integer b exceeds h exactly when it exceeds floor(h), and falls short of h exactly when it falls
// short of ceil(h); the arm boxes are within +-32000 cm, so clamping far values changes no answer. A NaN
// bound widens the box (upper +1e9, lower -1e9): the obstacle then meets every link box and FCL decides.
std::int32_t cm_floor(double v) {
  return std::isnan(v) ? 1000000000 : static_cast<std::int32_t>(std::max(-1e9, std::min(1e9, std::floor(v))));
}
std::int32_t cm_ceil(double v) {
  return std::isnan(v) ? -1000000000 : static_cast<std::int32_t>(std::max(-1e9, std::min(1e9, std::ceil(v))));
}

// A link pose kept as float 3 x 4 (column-major), as a Pose.
Pose link_in_arm(const float* m) {
  Pose in_arm = Pose::Identity();
  in_arm.matrix().topRows<3>() = Eigen::Map<const Eigen::Matrix<float, 3, 4>>(m).cast<double>();
  return in_arm;
}

// cm_floor / cm_ceil clamped to the int16 range: the arm boxes lie within +-32000 cm, so an arm box
// meets the clamped box exactly when it meets the unclamped one.
std::int16_t cm16(std::int32_t v) { return static_cast<std::int16_t>(std::max(-32768, std::min(32767, v))); }

bool meets(const std::int16_t* box, const std::array<std::int16_t, 6>& near) {
  return !(box[0] > near[3] || box[3] < near[0] || box[1] > near[4] || box[4] < near[1] || box[2] > near[5] ||
           box[5] < near[2]);
}

// Link l's box (rows of `lanes` values from `rows`) meets `near`.
bool link_meets(const std::int16_t* rows, std::size_t lanes, std::size_t l, const std::array<std::int16_t, 6>& near) {
  return !(rows[l] > near[3] || rows[3 * lanes + l] < near[0] || rows[lanes + l] > near[4] ||
           rows[4 * lanes + l] < near[1] || rows[2 * lanes + l] > near[5] || rows[5 * lanes + l] < near[2]);
}

}  // namespace

void ArmObstacles::compute(int threads) {
  if (empty()) return;
  const CellSlots& slots = *slots_;
  for (int li : links_)
    if (!robot_.links()[li].shapes.empty()) {
      shaped_.push_back(li);
      shape_id_.push_back(shapes_);
      shapes_ += robot_.links()[li].shapes.size();
      for (const auto& sh : robot_.links()[li].shapes) {
        const fcl::AABBd& local = sh.geometry->aabb_local;
        shape_half_.push_back(0.5 * (local.max_ - local.min_));
      }
    }
  lanes_ = (shaped_.size() + 15) / 16 * 16;
  stride_ = 6 * (1 + lanes_);
  boxes_cm_.assign(slots.size() * stride_, 0);
  const auto& records = slots.records();
  detail::parallel_for(records.size(), threads, [&](std::size_t i, int) {
    thread_local std::vector<Pose> poses;
    for (std::uint32_t s = records[i].first; s < records[i].last; ++s) {
      const float* qf = cap_.record_solution(records[i].rec, slots.cell(s).orient);
      Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
      robot_.link_poses(arm_.to_robot_configuration(q, reference_), poses, placing_);
      std::int16_t* out = boxes_cm_.data() + s * stride_;
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (std::size_t j = 0; j < shaped_.size(); ++j) {
        const int li = shaped_[j];
        Eigen::Vector3d llo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), lhi = -llo;
        for (const auto& sh : robot_.links()[li].shapes) {
          fcl::AABBd b = world_aabb(*sh.geometry, arm_from_root_ * poses[li] * sh.origin);
          llo = llo.cwiseMin(b.min_);
          lhi = lhi.cwiseMax(b.max_);
        }
        std::int16_t link[6];
        put_box(llo, lhi, link);
        for (int r = 0; r < 6; ++r) out[6 + r * lanes_ + j] = link[r];
        lo = lo.cwiseMin(llo);
        hi = hi.cwiseMax(lhi);
      }
      put_box(lo, hi, out);
      for (std::size_t j = shaped_.size(); j < lanes_; ++j)  // spare lanes: an empty box, never read
        for (int r = 0; r < 6; ++r) out[6 + r * lanes_ + j] = r < 3 ? 32767 : -32768;
    }
  }, 4);
  for (std::size_t s = 0; s < slots.size(); ++s) {
    const std::int16_t* box = boxes_cm_.data() + s * stride_;
    for (int k = 0; k < 3; ++k) {
      reach_lo_[k] = std::min(reach_lo_[k], box[k] / 100.0);
      reach_hi_[k] = std::max(reach_hi_[k], box[3 + k] / 100.0);
    }
  }
}

void ArmObstacles::near(const Pose& world_from_arm, NearObstacles& out) const {
  out.cm.clear();
  out.obb.clear();
  out.index.clear();
  if (empty() || slots_->size() == 0) return;
  const Pose arm_from_world = world_from_arm.inverse();
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    const auto& b = boxes_[i];
    Eigen::Vector3d lo, hi;
    box_in_frame(arm_from_world, b.min_, b.max_, lo, hi);
    if ((lo.array() > reach_hi_.array()).any() || (hi.array() < reach_lo_.array()).any()) continue;
    const Eigen::Vector3d lo_cm = lo * 100, hi_cm = hi * 100;  // centimetres, as the arm boxes
    out.cm.push_back({cm16(cm_ceil(lo_cm[0])), cm16(cm_ceil(lo_cm[1])), cm16(cm_ceil(lo_cm[2])),
                      cm16(cm_floor(hi_cm[0])), cm16(cm_floor(hi_cm[1])), cm16(cm_floor(hi_cm[2]))});
    const Obb& world = obstacles_->oriented_box(i);
    out.obb.push_back({arm_from_world * world.centre, arm_from_world.linear() * world.axes, world.half});
    out.index.push_back(static_cast<std::uint32_t>(i));
  }
}

// Link poses (arm frame) of the shaped links at the stored solution of a cell, then the oriented boxes
// of their shapes (as Obb::of gives them for those poses: centre, axes), from the scratch's cache,
// computed and cached on first use (the cache stops growing at 64 MB).
const float* ArmObstacles::link_poses(std::int32_t slot, ArmScratch& s) const {
  if (s.at.empty()) s.at.assign(slots_->size(), ArmScratch::kNotYet);
  const std::uint32_t cached = s.at[static_cast<std::size_t>(slot)];
  if (cached != ArmScratch::kNotYet) return s.pool.data() + cached;
  const CellSlots::Cell& c = slots_->cell(static_cast<std::size_t>(slot));
  const float* qf = cap_.record_solution(c.rec, c.orient);
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm_.dof()).cast<double>();
  robot_.link_poses(arm_.to_robot_configuration(q, reference_), s.poses, placing_);
  const std::size_t n = 12 * (shaped_.size() + shapes_);
  const bool keep = s.pool.size() + n <= (std::size_t(64) << 20) / sizeof(float);
  const std::size_t at = s.pool.size();
  float* out;
  if (keep) {
    s.pool.resize(at + n);
    out = s.pool.data() + at;
  } else {
    s.spare.resize(n);
    out = s.spare.data();
  }
  float* boxes = out + 12 * shaped_.size();
  for (std::size_t j = 0; j < shaped_.size(); ++j) {
    Eigen::Matrix<float, 3, 4> m = (arm_from_root_ * s.poses[shaped_[j]]).matrix().topRows<3>().cast<float>();
    std::copy(m.data(), m.data() + 12, out + 12 * j);
    const Pose in_arm = link_in_arm(out + 12 * j);
    const auto& shapes = robot_.links()[shaped_[j]].shapes;
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      const Obb o = Obb::of(*shapes[k].geometry, in_arm * shapes[k].origin);
      float* b = boxes + 12 * (shape_id_[j] + k);
      Eigen::Map<Eigen::Vector3f> centre(b);
      Eigen::Map<Eigen::Matrix3f> axes(b + 3);
      centre = o.centre.cast<float>();
      axes = o.axes.cast<float>();
    }
  }
  if (keep) s.at[static_cast<std::size_t>(slot)] = static_cast<std::uint32_t>(at);
  return out;
}

OCTOREACH_VECTOR_CLONES bool ArmObstacles::collides(std::int32_t slot, const NearObstacles& near, const Pose& world_from_arm,
                            ArmScratch& scratch) const {
  if (near.empty()) return false;
  const std::int16_t* box = boxes_cm_.data() + static_cast<std::size_t>(slot) * stride_;
  // The whole arm's box, then each link's box, against each near obstacle's box; FCL only for the
  // links whose box meets one.
  // (One answer whatever the order the links are tried in: any link touching means a collision.)
  const std::int16_t* rows = box + 6;
  const std::size_t L = lanes_;
  if (scratch.hit.size() != L) scratch.hit.resize(L);
  std::int32_t* hit = scratch.hit.data();
  std::fill(hit, hit + L, 0);
  for (const auto& ob : near.cm) {
    if (!meets(box, ob)) continue;
    // link_meets for every lane, branch-free: all six differences >= 0 (no overflow in 32 bits).
    const std::int32_t lo0 = ob[0], lo1 = ob[1], lo2 = ob[2], hi0 = ob[3], hi1 = ob[4], hi2 = ob[5];
    for (std::size_t l = 0; l < L; ++l)
      hit[l] |= ~((hi0 - rows[l]) | (rows[3 * L + l] - lo0) | (hi1 - rows[L + l]) | (rows[4 * L + l] - lo1) |
                  (hi2 - rows[2 * L + l]) | (rows[5 * L + l] - lo2)) >> 31;
  }
  std::int32_t any = 0;
  for (std::size_t l = 0; l < shaped_.size(); ++l) any |= hit[l];  // (a spare lane may meet an unbounded box)
  if (!any) return false;
  const float* P = link_poses(slot, scratch);
  const float* boxes = P + 12 * shaped_.size();
  const auto& objects = obstacles_->objects();
  if (scratch.box_witness.empty()) scratch.box_witness.resize(shapes_ * objects.size());
  for (std::size_t l = 0; l < shaped_.size(); ++l) {
    if (!hit[l]) continue;
    const auto& shapes = robot_.links()[shaped_[l]].shapes;
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      const auto& s = shapes[k];
      // The exact pre-test of Obstacles::collides in the arm frame (the shape's oriented box, kept in
      // float: far below the test's 0.1 mm margin), against the near obstacles whose box meets the
      // link's (the others cannot reach it); then FCL's answer for the pair, through the mesh-box
      // check with this thread's witnesses where it applies.
      const std::size_t id = shape_id_[l] + k;
      const Obb shape{Eigen::Map<const Eigen::Vector3f>(boxes + 12 * id).cast<double>(),
                      Eigen::Map<const Eigen::Matrix3f>(boxes + 12 * id + 3).cast<double>(), shape_half_[id]};
      Pose world;  // the shape's world pose, as Obstacles::collides is given it (set on first use)
      bool placed = false;
      for (std::size_t j = 0; j < near.cm.size(); ++j) {
        if (!link_meets(rows, L, l, near.cm[j]) || shape.apart(near.obb[j])) continue;
        if (!placed) world = world_from_arm * link_in_arm(P + 12 * l) * s.origin;
        placed = true;
        const std::uint32_t i = near.index[j];
        const fcl::CollisionGeometryd& og = *objects[i]->collisionGeometry();
        const Pose at(objects[i]->getTransform().matrix());
        const bool touches =
            mesh_box_pair(*s.geometry, og)
                ? mesh_box_collide(*s.geometry, world, og, at, scratch.box_witness[id * objects.size() + i])
                : geometry_collide(s.geometry.get(), world, &og, at);
        if (touches) return true;
      }
    }
  }
  return false;
}

}  // namespace octoreach::detail
