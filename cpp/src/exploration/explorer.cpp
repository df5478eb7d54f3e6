// An exploration session in the user's own loop (explorer.hpp).
#include "octoreach/explorer.hpp"

#include <cmath>
#include <stdexcept>

#include "exploration/view_score.hpp"

namespace octoreach {

Explorer::Explorer(ExplorerSetup setup) : setup_(std::move(setup)) {
  setup_.camera.validate();
  setup_.options.validate();
  detail::validate_options(setup_.camera, setup_.options.search);  // (here, not at the first next_view)
  const Aabb& s = setup_.search_space;
  if (!s.lo.allFinite() || !s.hi.allFinite() || (s.hi.array() <= s.lo.array()).any())
    throw std::invalid_argument("search_space must be a finite box with lo < hi on every axis");
  if (setup_.bases.empty()) throw std::invalid_argument("bases must hold at least one base pose");
  for (std::size_t i = 0; i < setup_.bases.size(); ++i) check_rigid(setup_.bases[i], "base " + std::to_string(i));
  if (!(setup_.reach >= 0) || !std::isfinite(setup_.reach))
    throw std::invalid_argument("reach must be a finite number of metres >= 0, got " + std::to_string(setup_.reach));
  ExplorationOptions mo;
  mo.resolution = setup_.resolution;
  mo.void_fit_threshold = setup_.void_fit_threshold;
  mo.search_lo = s.lo;
  mo.search_hi = s.hi;
  mo.seed = setup_.options.search.seed;
  map_ = std::make_unique<ExplorationMap>(mo);
  seed_ = setup_.options.search.seed;
}

Explorer::~Explorer() = default;

InsertStats Explorer::integrate(const std::vector<Eigen::Vector3d>& points, const Pose& camera_pose) {
  check_rigid(camera_pose, "camera_pose");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw std::invalid_argument("points row " + std::to_string(i) +
                                  " is not finite (an organised cloud marks a pixel without return with NaN: drop "
                                  "those rows, or integrate the depth image)");
  if (setup_.options.learn_misses && map_->void_cell_count())
    expect_view(*map_, setup_.camera, camera_pose, setup_.options.search);
  ++views_;
  has_last_ = false;
  const InsertStats stats = map_->insert(points, camera_pose.translation(), setup_.camera.max_range);
  memory_.last_void_seen = memory_.last_void_seen.value_or(0) + stats.void_removed;  // a view may come in parts
  memory_.last_space_seen = memory_.last_space_seen.value_or(0) + stats.space_known;
  return stats;
}

InsertStats Explorer::integrate_depth(const std::vector<float>& depth, int width, int height, const Pose& camera_pose) {
  if (width != setup_.camera.width || height != setup_.camera.height ||
      depth.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument("depth image must be " + std::to_string(setup_.camera.height) + " x " +
                                std::to_string(setup_.camera.width) + " (the camera's), got " +
                                std::to_string(height) + " x " + std::to_string(width) + " with " +
                                std::to_string(depth.size()) + " values");
  check_rigid(camera_pose, "camera_pose");
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(depth.size());
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const float d = depth[std::size_t(v) * std::size_t(width) + std::size_t(u)];
      if (!std::isfinite(d) || d < 0)
        throw std::invalid_argument("depth image pixel (" + std::to_string(v) + ", " + std::to_string(u) +
                                    ") is " + std::to_string(d) + ": depths must be finite and >= 0 (0: no return)");
      if (d == 0) continue;
      const Eigen::Vector3d r = setup_.camera.ray(u + 0.5, v + 0.5);
      pts.push_back(camera_pose * (r * (double(d) / r.z())));
    }
  return integrate(pts, camera_pose);
}

void Explorer::view_failed() {
  if (!has_last_) throw std::logic_error("view_failed: no proposed view is pending");
  memory_.failed_views.push_back(last_camera_);
  ++views_;
  has_last_ = false;
}

NextView Explorer::next_view() {
  NextView out;
  ViewSites sites{setup_.bases, setup_.reach};
  ExploreOptions o = setup_.options;
  o.search.seed = seed_ + std::uint64_t(views_);
  o.search.ik.seed = o.search.seed;
  out.choice = choose_view(*map_, setup_.camera, sites, current_, o, memory_, setup_.strategy);
  out.stop = out.choice.stop;
  out.stop_reason = out.choice.stop_reason;
  if (!out.stop && views_ >= setup_.options.max_views) {  // the choice is reported, the budget ends the loop
    out.stop = true;
    out.stop_reason = "view budget";
  }
  if (out.choice.found) {
    out.camera_pose = out.choice.view.pose;
    out.q = out.choice.view.q;
    out.base = out.choice.base;
    out.base_pose = setup_.bases[std::size_t(out.base)];
    out.expected_gain = out.choice.utility;
  }
  if (!out.stop && out.choice.found) {
    current_ = out.base;
    last_camera_ = out.camera_pose.translation();
    has_last_ = true;
  }
  return out;
}

}  // namespace octoreach
