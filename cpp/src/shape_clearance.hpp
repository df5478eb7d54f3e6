#pragma once
// Internal: a certificate that two collision shapes are apart, without FCL's narrow phase. Each shape
// gets a distance grid in its own frame, filled lazily (one FCL distance query from a grid node to the
// shape, the first time a node is read), and a cover of small spheres (cells of its local box that
// hold some of it: every cell for a primitive, the cells a triangle's box touches for a mesh). Shape A
// is apart from shape B when every sphere of A's cover is farther from B than its radius, by the lower
// bound distance(node) - |centre - node| (a distance is 1-Lipschitz) less a margin; first one sphere
// around the whole of A is tried. The certificate never says "apart" for shapes that touch, so a
// collision check that skips FCL where it holds gives the same answers; where it does not hold FCL
// decides. IK keeps one per thread and set-up (ik.cpp: CollisionSetup).
#include <cstdint>
#include <vector>

#include <fcl/fcl.h>

#include "octoreach/robot.hpp"
#include "octoreach/types.hpp"

namespace octoreach::detail {

class ShapeClearance {
 public:
  ShapeClearance() = default;
  explicit ShapeClearance(const Robot& robot);
  /// True when shape `sa` of link `a` at world pose `ta` certainly does not touch shape `sb` of link `b`
  /// at `tb`.
  bool apart(const Robot& robot, int a, std::size_t sa, const Pose& ta, int b, std::size_t sb, const Pose& tb);

 private:
  struct Field {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero();  // grid origin (shape frame): node (i, j, k) at lo + h (i, j, k)
    double h = 0;  // grid spacing (m)
    int n[3] = {0, 0, 0};
    Eigen::Vector3d box_lo = Eigen::Vector3d::Zero(), box_hi = Eigen::Vector3d::Zero();  // the local AABB
    std::vector<float> d;  // per node: distance to the shape (NaN: not measured yet)
    std::vector<Eigen::Vector3d> cover;  // sphere centres (shape frame), radius cover_radius, block by block
    double cover_radius = 0;
    struct Block {  // up to 3 x 3 x 3 cells of the cover: one sphere around them first
      Eigen::Vector3d centre;
      double radius;
      std::uint32_t begin, end;  // their entries in `cover`
    };
    std::vector<Block> blocks;
    double inv_h = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the sphere around the whole shape
    double radius = 0;
    const fcl::CollisionGeometryd* geometry = nullptr;
  };
  Field& field(const Robot& robot, int link, std::size_t shape);
  // A lower bound of the distance from point p (shape frame of f) to the shape.
  double lower_bound(Field& f, const Eigen::Vector3d& p);

  std::vector<std::vector<Field>> fields_;  // per link, per shape (built on first use)
  std::vector<std::vector<char>> ready_;
};

struct ShapeBoxes;

/// first_colliding_pair (collision_detail.hpp) with the shape pairs `clearance` certifies apart left to
/// it rather than to FCL: the same answer.
int first_colliding_pair(const Robot& robot, const ShapeBoxes& boxes, const std::vector<std::pair<int, int>>& pairs,
                         ShapeClearance& clearance);

}  // namespace octoreach::detail
