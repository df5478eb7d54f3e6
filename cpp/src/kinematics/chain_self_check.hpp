#pragma once
// Internal: the self-collision check IK runs on the solutions of one chain at one reference posture.
// The checked pairs the chain moves are laid out flat, shape pair by shape pair, with the world box of
// every shape in one array: the links the chain never moves keep their boxes from the reference, the
// others are placed afresh per check, and a shape pair goes to the narrow phase only when its boxes
// overlap and its hinge certificate (hinge_pairs.hpp) does not already rule it out. The narrow phase
// runs in passes over those pairs, cheapest first: the mesh witnesses of every pair (one that confirms
// a contact ends the check), then GJK on the hulls of the pairs left open, then pair by pair the meshes'
// convex pieces and FCL (FCL alone on the pairs that are not two meshes), until one collides. The answer is the plain check's (first_colliding_pair over every
// pair): the boxes, the certificates, the passes, the order (the shape pair that collided last is
// tested first) and the witnesses only change its cost.
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <fcl/fcl.h>

#include "collision/mesh_pair_check.hpp"
#include "kinematics/hinge_pairs.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/types.hpp"

namespace octoreach::detail {

class ChainSelfCheck {
 public:
  ChainSelfCheck() = default;
  /// `pairs`: the checked pairs the chain moves (Chain::split_collision_pairs); `poses`: the link poses
  /// at the reference posture `reference` (a full robot configuration).
  ChainSelfCheck(const Chain& chain, const std::vector<std::pair<int, int>>& pairs, const std::vector<Pose>& poses,
                 const Eigen::VectorXd& reference);

  /// True when a pair collides at the link poses `poses` of the full configuration `full` (off-chain
  /// joints at the reference, so only the moved links' poses are read).
  bool collides(const Robot& robot, const std::vector<Pose>& poses, const Eigen::VectorXd& full);

 private:
  struct Box {
    double lo[3], hi[3];
  };
  struct ShapeRef {
    int link;
    const fcl::CollisionGeometryd* geometry;
    Pose origin;
    bool mesh;
  };
  struct Entry {
    int a, b;      // indices into shapes_
    int pair;      // index into the pairs (hinge certificates)
    int witness;   // index into witnesses_ (mesh pairs), or -1
  };
  static bool overlap(const Box& x, const Box& y) {
    // fcl::AABB::overlap: boxes that touch overlap
    return !(x.lo[0] > y.hi[0] || y.lo[0] > x.hi[0] || x.lo[1] > y.hi[1] || y.lo[1] > x.hi[1] ||
             x.lo[2] > y.hi[2] || y.lo[2] > x.hi[2]);
  }
  void place(int shape, const Pose& link_pose);

  std::vector<ShapeRef> shapes_;
  std::vector<Box> boxes_;          // per shape, world
  std::vector<Pose> world_;         // per shape, world pose
  std::vector<int> moved_;          // shapes on links the chain moves
  std::vector<Entry> entries_;      // walk order: the last hit first
  std::vector<char> hinge_;         // per pair: has a hinge certificate
  HingePairs hinges_;
  std::vector<MeshPairWitness> witnesses_;  // per mesh pair of shapes
  std::vector<std::size_t> open_;           // scratch: entries the witnesses left undecided
};

}  // namespace octoreach::detail
