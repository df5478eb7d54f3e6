#include "kinematics/chain_self_check.hpp"

#include <algorithm>

#include "collision/detail.hpp"
#include "octoreach/robot.hpp"

namespace octoreach::detail {

ChainSelfCheck::ChainSelfCheck(const Chain& chain, const std::vector<std::pair<int, int>>& pairs,
                               const std::vector<Pose>& poses, const Eigen::VectorXd& reference)
    : hinges_(chain, pairs, reference) {
  const Robot& robot = chain.robot();
  std::vector<int> first(robot.links().size(), -1);  // per link: its first shape in shapes_
  auto add_link = [&](int li) {
    if (first[li] >= 0) return;
    first[li] = static_cast<int>(shapes_.size());
    for (const Shape& s : robot.links()[li].shapes) {
      const int k = static_cast<int>(shapes_.size());
      shapes_.push_back({li, s.geometry.get(), s.origin, is_mesh(*s.geometry)});
      boxes_.emplace_back();
      world_.emplace_back();
      place(k, poses[li]);
      if (chain.link_mask(li) != 0) moved_.push_back(k);
    }
  };
  hinge_.assign(pairs.size(), 0);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [a, b] = pairs[p];
    add_link(a);
    add_link(b);
    hinge_[p] = hinges_.hinge_of(p) >= 0;
    const std::size_t na = robot.links()[a].shapes.size(), nb = robot.links()[b].shapes.size();
    for (std::size_t i = 0; i < na; ++i)
      for (std::size_t k = 0; k < nb; ++k)
      {
        const int sa = first[a] + static_cast<int>(i), sb = first[b] + static_cast<int>(k);
        int w = -1;
        if (shapes_[sa].mesh && shapes_[sb].mesh) {
          w = static_cast<int>(witnesses_.size());
          witnesses_.emplace_back();
        }
        entries_.push_back({sa, sb, static_cast<int>(p), w});
      }
  }
}

void ChainSelfCheck::place(int shape, const Pose& link_pose) {
  const ShapeRef& s = shapes_[shape];
  world_[shape] = link_pose * s.origin;
  const fcl::AABBd box = world_aabb(*s.geometry, world_[shape]);
  for (int d = 0; d < 3; ++d) {
    boxes_[shape].lo[d] = box.min_[d];
    boxes_[shape].hi[d] = box.max_[d];
  }
}

bool ChainSelfCheck::collides(const Robot& robot, const std::vector<Pose>& poses, const Eigen::VectorXd& full) {
  for (int k : moved_) place(k, poses[shapes_[k].link]);
  auto hit = [&](std::size_t e) {
    std::rotate(entries_.begin(), entries_.begin() + e, entries_.begin() + e + 1);
    return true;
  };
  open_.clear();
  for (std::size_t e = 0; e < entries_.size(); ++e) {  // boxes, certificates and witnesses
    const Entry& x = entries_[e];
    if (!overlap(boxes_[x.a], boxes_[x.b])) continue;
    if (hinge_[x.pair] && hinges_.certified_pair(robot, x.pair, full)) continue;
    if (x.witness >= 0) {
      const MeshVerdict v = mesh_witness_verdict(*shapes_[x.a].geometry, world_[x.a], *shapes_[x.b].geometry,
                                                 world_[x.b], witnesses_[x.witness]);
      if (v == MeshVerdict::touching) return hit(e);
      if (v == MeshVerdict::apart) continue;
    }
    open_.push_back(e);
  }
  // The pairs left open, each to the end before the next (GJK on the hulls, the meshes' convex pieces, then FCL):
  // a configuration in collision usually has many open pairs, and the first hit ends the check.
  for (std::size_t e : open_) {
    const Entry& x = entries_[e];
    const ShapeRef& sa = shapes_[x.a];
    const ShapeRef& sb = shapes_[x.b];
    const bool collides =
        x.witness >= 0
            ? !meshes_hulls_apart(*sa.geometry, world_[x.a], *sb.geometry, world_[x.b], witnesses_[x.witness]) &&
                  !meshes_pieces_apart(*sa.geometry, world_[x.a], *sb.geometry, world_[x.b], witnesses_[x.witness]) &&
                  meshes_fcl_collide(*sa.geometry, world_[x.a], *sb.geometry, world_[x.b], witnesses_[x.witness])
            : geometry_collide(sa.geometry, world_[x.a], sb.geometry, world_[x.b]);
    if (collides) return hit(e);
  }
  return false;
}

}  // namespace octoreach::detail
