#pragma once
// Internal: a bounding volume hierarchy over a scene's triangles (world frame) for ray casting.
#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include <Eigen/Core>

#include "octoreach/simulation.hpp"
#include "simulation/ray_hits.hpp"

namespace octoreach {

struct Scene::Bvh {
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1, right = -1, first = 0, count = 0;
  };
  std::vector<Node> nodes;
  std::vector<Eigen::Vector3d> tris;  // reordered

  explicit Bvh(const std::vector<Eigen::Vector3d>& t) {
    std::size_t n = t.size() / 3;
    std::vector<int> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    std::vector<Eigen::Vector3d> cent(n);
    for (std::size_t i = 0; i < n; ++i) cent[i] = (t[3 * i] + t[3 * i + 1] + t[3 * i + 2]) / 3.0;
    build(t, idx, cent, 0, int(n));
    tris.reserve(t.size());
    for (int i : idx)
      for (int j = 0; j < 3; ++j) tris.push_back(t[3 * i + j]);
  }
  int build(const std::vector<Eigen::Vector3d>& t, std::vector<int>& idx, const std::vector<Eigen::Vector3d>& cent,
            int first, int count) {
    Node node;
    node.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    node.hi = -node.lo;
    for (int i = first; i < first + count; ++i)
      for (int j = 0; j < 3; ++j) {
        node.lo = node.lo.cwiseMin(t[3 * idx[i] + j]);
        node.hi = node.hi.cwiseMax(t[3 * idx[i] + j]);
      }
    int id = int(nodes.size());
    nodes.push_back(node);
    if (count <= 4) {
      nodes[id].first = first;
      nodes[id].count = count;
      return id;
    }
    int axis;
    (node.hi - node.lo).maxCoeff(&axis);
    int mid = first + count / 2;
    std::nth_element(idx.begin() + first, idx.begin() + mid, idx.begin() + first + count,
                     [&](int a, int b) { return cent[a][axis] < cent[b][axis]; });
    int l = build(t, idx, cent, first, mid - first);
    int r = build(t, idx, cent, mid, first + count - mid);
    nodes[id].left = l;
    nodes[id].right = r;
    return id;
  }
  bool raycast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& inv, double& best,
               int* best_tri = nullptr) const {
    bool hit = false;
    int stack[128];
    int sp = 0;
    stack[sp++] = 0;
    while (sp) {
      const Node& n = nodes[stack[--sp]];
      double tb;
      if (!detail::ray_box(o, inv, n.lo, n.hi, best, tb)) continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          double t;
          if (detail::ray_triangle(o, d, tris[3 * i], tris[3 * i + 1], tris[3 * i + 2], t) && t < best) {
            best = t;
            hit = true;
            if (best_tri) *best_tri = i;
          }
        }
      } else if (sp < 126) {
        stack[sp++] = n.left;
        stack[sp++] = n.right;
      }
    }
    return hit;
  }
};

}  // namespace octoreach
