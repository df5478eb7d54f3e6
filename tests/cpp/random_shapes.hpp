// Random test shapes and poses shared by the C++ collision tests (mesh-pair and mesh-box checks).
#pragma once

#include <memory>
#include <random>

#include <Eigen/Geometry>

#include "collision/detail.hpp"
#include "octoreach/types.hpp"

namespace octoreach::test {

// A triangle soup (FCL tests triangles, so it need not be closed): n random triangles of edge ~0.1 m
// around centres within a box of half-size (2.5 h, h, h): stretched along x, so that its hull holds much
// empty room and hull and mesh differ.
inline std::shared_ptr<fcl::CollisionGeometryd> soup(std::mt19937_64& rng, int n, double h) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> v(3 * n, 3);
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> t(n, 3);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d c(2.5 * h * u(rng), h * u(rng), h * u(rng));
    for (int k = 0; k < 3; ++k) {
      v.row(3 * i + k) = (c + 0.05 * Eigen::Vector3d(u(rng), u(rng), u(rng))).transpose();
      t(i, k) = 3 * i + k;
    }
  }
  return make_mesh(v, t);
}

// A uniformly random rotation and a translation within a cube of half-size `spread`.
inline Pose random_pose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Pose T = Pose::Identity();
  T.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  T.translation() = spread * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return T;
}

}  // namespace octoreach::test
