// Simulated depth camera (pinhole, ray cast into a Scene, optional depth noise) and camera poses.
#include "octoreach/simulation.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "common/cancel.hpp"
#include "common/format.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {

Eigen::Vector3d CameraIntrinsics::ray(double u, double v) const {
  double f = focal();
  return Eigen::Vector3d((u - 0.5 * width) / f, (v - 0.5 * height) / f, 1.0).normalized();
}
double CameraIntrinsics::focal() const { return 0.5 * width / std::tan(0.5 * fov); }
void CameraIntrinsics::validate() const {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("image size must be positive, got " + std::to_string(width) + " x " +
                                std::to_string(height));
  if (std::uint64_t(width) * std::uint64_t(height) > limits::kImagePixels)
    throw std::invalid_argument("image size " + std::to_string(width) + " x " + std::to_string(height) +
                                " is more than the limit of " + std::to_string(limits::kImagePixels) + " pixels");
  if (!(fov > 0 && fov < kPi)) throw std::invalid_argument("fov must be in (0, pi) radians, got " + std::to_string(fov));
  if (!(max_range > 0) || !(max_range <= limits::kCoordinate))
    throw std::invalid_argument("max_range must be a positive number of metres up to " +
                                std::to_string(int(limits::kCoordinate)) + ", got " + std::to_string(max_range));
}

DepthCamera::DepthCamera(int width, int height, double fov, double max_range, double noise, std::uint64_t seed,
                         double max_incidence)
    : noise_(noise), seed_(seed), max_incidence_(max_incidence) {
  intr_.width = width;
  intr_.height = height;
  intr_.fov = fov;
  intr_.max_range = max_range;
  intr_.validate();
  if (!(noise >= 0) || !std::isfinite(noise))
    throw std::invalid_argument("noise must be a non-negative standard deviation in metres, got " + std::to_string(noise));
  if (!(max_incidence > 0 && max_incidence <= kPi / 2))
    throw std::invalid_argument("max_incidence must be in (0, pi/2] radians, got " + std::to_string(max_incidence));
}

std::vector<Eigen::Vector3d> DepthCamera::capture(const Scene& scene, const Pose& pose, int threads) {
  detail::CancellableScope cancellable;  // rows are polled; the camera and the scene stay as they were
  check_rigid(pose, "capture: the camera pose");
  const int W = intr_.width, H = intr_.height;
  const std::uint64_t call = calls_++;
  struct SceneReadLock {  // the scene may not change during the capture
    const Scene& s;
    explicit SceneReadLock(const Scene& scene) : s(scene) { s.lock_shared_(); }
    ~SceneReadLock() { s.unlock_shared_(); }
  } lock(scene);
  std::vector<std::vector<Eigen::Vector3d>> rows(H);
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d o = pose.translation();
  const bool grazing = max_incidence_ < kPi / 2;
  const double min_cos = std::cos(max_incidence_);
  detail::parallel_for(std::size_t(H), threads, [&](std::size_t v, int) {
    std::mt19937_64 rng(seed_ * 0x9E3779B97F4A7C15ULL + call * 1000003ULL + v);
    std::normal_distribution<double> gauss(0.0, 1.0);
    auto& out = rows[v];
    for (int u = 0; u < W; ++u) {
      if ((u & 4095) == 4095) detail::poll_cancel("depth capture cancelled");  // rows of a wide image are long
      Eigen::Vector3d dc = intr_.ray(u + 0.5, v + 0.5);
      Eigen::Vector3d d = R * dc;
      double t;
      Eigen::Vector3d n;
      if (!scene.raycast(o, d, intr_.max_range, t, grazing ? &n : nullptr)) continue;
      if (grazing && std::abs(n.dot(d)) < min_cos) continue;  // grazing: no return
      double z = t * dc.z();
      if (noise_ > 0) z += noise_ * z * z * gauss(rng);
      if (z <= 0 || z / dc.z() > intr_.max_range) continue;  // beyond the range: no return
      out.push_back(o + d * (z / dc.z()));
    }
  }, 4);
  std::vector<Eigen::Vector3d> pts;
  for (auto& r : rows) pts.insert(pts.end(), r.begin(), r.end());
  return pts;
}

Pose camera_pose(const Eigen::Vector3d& position, const Eigen::Vector3d& forward, double roll) {
  if (!position.allFinite() || !forward.allFinite() || !std::isfinite(roll) || forward.norm() < 1e-12)
    throw std::invalid_argument("camera pose: need a finite position and roll and a non-zero finite direction");
  Eigen::Vector3d z = forward.normalized();
  Eigen::Vector3d up = std::abs(z.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d x = z.cross(up).normalized();
  Eigen::Vector3d y = z.cross(x);
  double c = std::cos(roll), s = std::sin(roll);
  Pose T = Pose::Identity();
  T.linear().col(0) = c * x + s * y;
  T.linear().col(1) = -s * x + c * y;
  T.linear().col(2) = z;
  T.translation() = position;
  return T;
}

Pose look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, double roll) {
  if (!eye.allFinite()) throw std::invalid_argument("look_at: eye must be finite, got " + detail::format_point(eye));
  if (!target.allFinite())
    throw std::invalid_argument("look_at: target must be finite, got " + detail::format_point(target));
  return camera_pose(eye, target - eye, roll);
}

}  // namespace octoreach
