#include "octoreach/surface_map.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include <fcl/fcl.h>

#include "map_io.hpp"
#include "octoreach/point_map.hpp"
#include "common/thread_pool.hpp"
#include "reach_extent.hpp"

namespace octoreach {
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
  }
  for (const auto& p : local) out.push_back(s.origin * p);
}

// The arm's witness points below the surface for one capability cell, nearest to the target first,
// with a summary for a quick "all outside one edge" test: for 32 horizontal directions phi_k the
// smallest projection of the points on (cos phi_k, sin phi_k), and the largest horizontal radius.
struct LowSet {
  static constexpr int kDirs = 32;
  std::vector<Eigen::Vector3f> points;
  std::array<float, kDirs> min_proj{};
  float r_max = 0;
  void summarise() {
    r_max = 0;
    for (const auto& w : points) r_max = std::max(r_max, w.head<2>().norm());
    for (int k = 0; k < kDirs; ++k) {
      float c = static_cast<float>(std::cos(2 * M_PI * k / kDirs)), s = static_cast<float>(std::sin(2 * M_PI * k / kDirs));
      float m = std::numeric_limits<float>::infinity();
      for (const auto& w : points) m = std::min(m, c * w.x() + s * w.y());
      min_proj[k] = m;
    }
  }
};

}  // namespace

SurfaceMap SurfaceMap::build(const Robot& robot, const CapabilityMap& cap, const Surface& surface,
                             const SurfaceMapOptions& o, const ProgressCallback& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (cap.robot_name() != robot.name() || cap.urdf_hash() != robot.urdf_hash())
    throw std::invalid_argument("the capability map was built for robot '" + cap.robot_name() +
                                "' (another URDF), not for '" + robot.name() + "'");
  if (o.check_arm && !cap.has_solutions())
    throw std::invalid_argument("the capability map holds no joint solutions (build it with keep_solutions=True "
                                "or save it with_solutions) : the surface map checks the arm against the surface");
  if (o.theta_bins < 1 || o.theta_bins > 360) throw std::invalid_argument("theta_bins must be in [1, 360]");
  const double res = o.resolution == 0 ? cap.resolution() : o.resolution;
  if (!(res > 0) || !std::isfinite(res)) throw std::invalid_argument("resolution must be positive");
  if (!(o.z_min <= o.z_max)) throw std::invalid_argument("z_min must not exceed z_max");

  SurfaceMap m;
  m.robot_name_ = robot.name();
  m.urdf_hash_ = robot.urdf_hash();
  m.reference_frame_ = o.reference_frame.empty() ? robot.links()[robot.root_link()].name : o.reference_frame;
  m.arms_ = cap.base_link() + "->" + cap.tip_link();
  m.polygon_ = surface.vertices();
  m.z_min_ = o.z_min;
  m.z_max_ = o.z_max;
  m.grasp_height_ = o.grasp_height;
  m.checks_ = std::string(o.check_body ? "body" : "") + (o.check_body && o.check_arm ? "+" : "") + (o.check_arm ? "arm" : "");
  m.map_ = PoseMap(res, o.theta_bins);
  const OrientationSet& set = cap.orientations();
  std::vector<int> dirs = o.grasps.empty() ? set.subset(o.grasp_subset) : o.grasps;
  m.grasp_name_ = o.grasps.empty() ? o.grasp_subset : "custom";
  if (dirs.empty()) throw std::invalid_argument("the grasp set is empty");
  const std::vector<int> grasps = grasp_orientations(set, dirs);

  if (!(o.grasp_height >= 0) || !std::isfinite(o.grasp_height))
    throw std::invalid_argument("grasp_height must be zero or positive");
  std::vector<Eigen::Vector3d> targets = surface.sample_points(res);
  for (auto& t : targets) t += o.grasp_height * surface.normal();
  m.stats_.surface_points = targets.size();
  if (targets.empty()) {
    m.empty_reason_ = "the surface holds no grid point at this resolution (polygon smaller than one cell)";
    m.map_.finalize();
    return m;
  }

  // Robot at the reference posture; the arm chain (its joints set per grasp from stored solutions).
  Eigen::VectorXd ref = o.reference.size() ? o.reference : robot.home();
  if (ref.size() != robot.dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(ref.size()) + " entries, the robot has " +
                                std::to_string(robot.dof()));
  const Chain arm = robot.chain(cap.base_link(), cap.tip_link());
  const std::vector<Pose> ref_poses = robot.link_poses(ref);
  const int ref_link = robot.link_index(m.reference_frame_);
  const Pose root_in_ref = ref_poses[ref_link].inverse();
  const Pose ref_to_arm = root_in_ref * ref_poses[robot.link_index(cap.base_link())];
  const std::uint64_t full = arm.dof() >= 64 ? ~0ULL : ((1ULL << arm.dof()) - 1);
  std::vector<int> body_links, arm_links;
  for (int li : robot.collision_links()) {
    std::uint64_t mask = arm.link_mask(li);
    if (mask == 0) body_links.push_back(li);
    else if (mask != full) arm_links.push_back(li);  // links rigid with the tip (the gripper) touch the object
  }
  std::vector<std::vector<Eigen::Vector3d>> link_witness(robot.links().size());
  for (int li : arm_links)
    for (const auto& s : robot.links()[li].shapes) witness_points(s, link_witness[li]);
  const Pose arm_base_in_root = ref_poses[robot.link_index(cap.base_link())];
  const Pose root_from_arm_base = arm_base_in_root.inverse();
  std::shared_ptr<Obstacles> slab = surface.obstacles();

  // Base-position grid: where a target can be reached from.
  std::vector<Eigen::Vector3d> cc;
  std::vector<double> cv;
  cap.voxels(cc, cv);
  if (cc.empty()) {
    m.empty_reason_ = "the capability map is empty";
    m.map_.finalize();
    return m;
  }
  const detail::ReachExtent reach = detail::reach_extent(cc, ref_to_arm);
  const double rxy = reach.radius_xy + cap.resolution() + res, wz_lo = reach.z_lo, wz_hi = reach.z_hi;
  Eigen::Vector3d tlo = targets[0], thi = targets[0];
  for (const auto& t : targets) {
    tlo = tlo.cwiseMin(t);
    thi = thi.cwiseMax(t);
  }
  double zlo = std::max(o.z_min, tlo.z() - wz_hi - cap.resolution()), zhi = std::min(o.z_max, thi.z() - wz_lo + cap.resolution());
  if (zlo > zhi) {
    m.empty_reason_ = "no base height in the z range reaches the surface";
    m.map_.finalize();
    return m;
  }
  const VoxelOcTree& tree = m.map_.tree();
  octomap::OcTreeKey kmin, kmax;
  if (!tree.coordToKeyChecked(tlo.x() - rxy, tlo.y() - rxy, zlo, kmin) ||
      !tree.coordToKeyChecked(thi.x() + rxy, thi.y() + rxy, zhi, kmax))
    throw std::invalid_argument("the surface map does not fit an octree at this resolution");
  const int nx = kmax[0] - kmin[0] + 1, ny = kmax[1] - kmin[1] + 1, nz = kmax[2] - kmin[2] + 1;
  const std::size_t ncells = static_cast<std::size_t>(nx) * ny * nz;
  const int T = o.theta_bins;
  std::vector<float> grid(ncells * T, 0.0f);
  const Surface* surf = &surface;
  std::vector<Eigen::Vector2d> target_uv;
  for (const auto& t : targets) target_uv.push_back(surf->project(t));
  const double inv_g = 1.0 / grasps.size(), inv_n = 1.0 / targets.size();
  const int O = set.size();

  // Witness points of the arm (relative to the reached voxel centre, arm frame) below the plane
  // through the target. For an upright arm frame and a horizontal surface the plane normal in the
  // arm frame is z whatever the yaw, so the points are computed once per capability cell, for the
  // voxel layers the targets can fall in; otherwise each yaw bin computes its own.
  const bool upright = std::abs(ref_to_arm.linear()(2, 2) - 1.0) < 1e-9 && std::abs(surface.normal().z() - 1.0) < 1e-9;
  std::unordered_map<std::uint64_t, LowSet> shared_low;
  std::vector<Pose> scratch;
  auto compute_low = [&](std::uint32_t rec, int orient, const Eigen::Vector3d& centre, const Eigen::Vector3d& n_arm,
                         std::vector<Pose>& poses, LowSet& low) {
    std::vector<Eigen::Vector3f>& out = low.points;
    const float* qf = cap.record_solution(rec, orient);
    Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXf>(qf, arm.dof()).cast<double>();
    robot.link_poses(arm.to_robot_configuration(q, ref), poses);
    for (int li : arm_links) {
      Pose in_arm = root_from_arm_base * poses[li];
      for (const auto& w : link_witness[li]) {
        Eigen::Vector3d rel = in_arm * w - centre;  // relative to the reached point
        // Below the surface top, which lies grasp_height under the reached point.
        if (n_arm.dot(rel) < -o.grasp_height - 1e-3) out.push_back(rel.cast<float>());
      }
    }
    // Nearest to the target first: those fall inside the outline soonest, ending the test early.
    std::sort(out.begin(), out.end(), [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
      return a.head<2>().squaredNorm() < b.head<2>().squaredNorm();
    });
    low.summarise();
  };
  if (upright && o.check_arm) {
    // Arm-frame heights of the targets over every base height in the grid.
    double za_lo = 1e9, za_hi = -1e9;
    for (int iz = 0; iz < nz; ++iz) {
      double bz = tree.keyToCoord(kmin[2] + iz);
      bz = std::min(std::max(bz, o.z_min), o.z_max);
      for (const auto& t : targets) {
        double za = t.z() - bz - ref_to_arm.translation().z();
        za_lo = std::min(za_lo, za);
        za_hi = std::max(za_hi, za);
      }
    }
    std::vector<std::pair<std::uint32_t, Eigen::Vector3d>> records;
    for (std::size_t i = 0; i < cc.size(); ++i)
      if (cc[i].z() >= za_lo - cap.resolution() && cc[i].z() <= za_hi + cap.resolution()) {
        Eigen::Vector3d centre;
        std::int64_t rec = cap.record_at(cc[i], &centre);
        if (rec >= 0) records.emplace_back(static_cast<std::uint32_t>(rec), centre);
      }
    std::vector<std::vector<std::pair<std::uint64_t, LowSet>>> parts(records.size());
    detail::parallel_for(records.size(), o.threads, [&](std::size_t i, int) {
      thread_local std::vector<Pose> poses;
      auto [rec, centre] = records[i];
      for (int orient = 0; orient < O; ++orient) {
        if (!cap.record_has(rec, orient)) continue;
        LowSet pts;
        compute_low(rec, orient, centre, Eigen::Vector3d::UnitZ(), poses, pts);
        parts[i].emplace_back(static_cast<std::uint64_t>(rec) * O + orient, std::move(pts));
      }
    }, 4);
    for (auto& part : parts)
      for (auto& [key, pts] : part) shared_low.emplace(key, std::move(pts));
  }

  std::atomic<std::size_t> bins_done{0}, candidates{0}, valid{0}, body_hits{0}, arm_hits{0};
  // One theta bin per task: each owns its cache of arm witness points, so no locking is needed
  // and the result does not depend on the thread count.
  detail::parallel_for(T, o.threads, [&](std::size_t k, int tid) {
    const double theta = 2.0 * M_PI * k / T;
    const Eigen::Matrix3d Rz = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Matrix3d M = Rz * ref_to_arm.linear();  // arm frame -> world rotation
    const Eigen::Vector3d n_arm = M.transpose() * surf->normal();
    Eigen::Matrix<double, 2, 3> A;
    A.row(0) = (M.transpose() * surf->u_axis()).transpose();
    A.row(1) = (M.transpose() * surf->v_axis()).transpose();
    std::vector<int> mapped;
    for (int g : grasps) {
      Eigen::Matrix3d Rw = set.rotation(g, cap.approach_axis());
      mapped.push_back(set.nearest(M.transpose() * Rw, cap.approach_axis()));
    }
    // Lazily filled: for cell (record, orientation), the uv offsets (relative to the target) of the
    // arm's witness points that lie below the surface plane.
    std::unordered_map<std::uint64_t, LowSet> own_low;
    std::vector<Pose> poses;
    auto low_points = [&](std::uint32_t rec, int orient, const Eigen::Vector3d& centre) -> const LowSet& {
      std::uint64_t key = static_cast<std::uint64_t>(rec) * O + orient;
      auto& cache = upright ? shared_low : own_low;
      auto it = cache.find(key);
      if (it != cache.end()) return it->second;
      if (upright) throw std::logic_error("surface map: capability cell outside the precomputed layers");
      auto& out = own_low[key];
      compute_low(rec, orient, centre, n_arm, poses, out);
      return out;
    };
    const Eigen::Matrix<float, 2, 3> Af = A.cast<float>();
    // Convex outline: its half-planes h . uv <= c become g . w <= c - h . uv_target in the arm frame,
    // with g = A^T h. In the upright case g is horizontal, so a cell's direction summary can show at
    // once that every witness point lies outside one edge.
    const auto& hp = surf->halfplanes();
    std::vector<Eigen::Vector3f> g(hp.size());
    std::vector<int> g_dir(hp.size());
    std::vector<float> g_norm(hp.size()), g_slack(hp.size());
    for (std::size_t j = 0; j < hp.size(); ++j) {
      g[j] = (A.transpose() * hp[j].head<2>()).cast<float>();
      double phi = std::atan2(g[j].y(), g[j].x());
      double step = 2 * M_PI / LowSet::kDirs;
      long kk = std::lround(phi / step);
      g_dir[j] = static_cast<int>(((kk % LowSet::kDirs) + LowSet::kDirs) % LowSet::kDirs);
      g_norm[j] = g[j].head<2>().norm();
      g_slack[j] = static_cast<float>(std::abs(phi - kk * step)) + 1e-6f;
    }
    const bool fast = upright && surf->convex();
    std::vector<float> d(hp.size());  // per target: c - h . uv_target
    std::size_t local_cand = 0, local_valid = 0, local_body = 0, local_arm = 0;
    for (int ix = 0; ix < nx; ++ix)
      for (int iy = 0; iy < ny; ++iy)
        for (int iz = 0; iz < nz; ++iz) {
          octomap::point3d bc = tree.keyToCoord(octomap::OcTreeKey(kmin[0] + ix, kmin[1] + iy, kmin[2] + iz));
          // Heights are evaluated inside the z range: a robot on the floor (z range (0, 0)) is
          // evaluated at z = 0 exactly and stored in the voxel holding 0.
          const Eigen::Vector3d base(bc.x(), bc.y(), std::min(std::max(double(bc.z()), o.z_min), o.z_max));
          double sum = 0;
          for (std::size_t i = 0; i < targets.size(); ++i) {
            // Target in the arm frame for a base at `base` with yaw theta.
            Eigen::Vector3d in_ref = Rz.transpose() * (targets[i] - base);
            // The fixed sub-resolution offset of the point map: targets on capability-voxel
            // boundaries (common when the grids line up) land in the same voxel on every machine.
            Eigen::Vector3d p = ref_to_arm.inverse() * in_ref + Eigen::Vector3d(1.3e-7, 0.7e-7, 0.3e-7);
            Eigen::Vector3d centre;
            std::int64_t rec = cap.record_at(p, &centre);
            if (rec < 0) continue;
            ++local_cand;
            int count = 0;
            if (fast)
              for (std::size_t j = 0; j < hp.size(); ++j)
                d[j] = static_cast<float>(hp[j].z() - hp[j].head<2>().dot(target_uv[i]));
            for (int mo : mapped) {
              if (!cap.record_has(static_cast<std::uint32_t>(rec), mo)) continue;
              bool ok = true;
              if (o.check_arm) {
                const LowSet& low = low_points(static_cast<std::uint32_t>(rec), mo, centre);
                if (fast) {
                  bool all_outside = low.points.empty();
                  for (std::size_t j = 0; j < hp.size() && !all_outside; ++j)
                    all_outside = g_norm[j] * (low.min_proj[g_dir[j]] - g_slack[j] * low.r_max) > d[j];
                  if (!all_outside)
                    for (const auto& w : low.points) {
                      bool inside = true;
                      for (std::size_t j = 0; j < hp.size() && inside; ++j) inside = g[j].dot(w) <= d[j];
                      if (inside) {
                        ok = false;
                        break;
                      }
                    }
                } else {
                  for (const auto& w : low.points)
                    if (surf->contains(target_uv[i] + (Af * w).cast<double>())) {
                      ok = false;
                      break;
                    }
                }
                if (!ok) ++local_arm;
              }
              count += ok;
            }
            if (count) {
              ++local_valid;
              sum += count * inv_g;
            }
          }
          if (sum <= 0) continue;
          if (o.check_body) {
            Pose B = Pose::Identity();
            B.translation() = base;
            B.linear() = Rz;
            if (robot.links_in_collision(ref_poses, *slab, B * root_in_ref, &body_links)) {
              ++local_body;
              continue;
            }
          }
          grid[((static_cast<std::size_t>(ix) * ny + iy) * nz + iz) * T + k] = static_cast<float>(sum * inv_n);
        }
    candidates += local_cand;
    valid += local_valid;
    body_hits += local_body;
    arm_hits += local_arm;
    std::size_t finished = ++bins_done;
    if (progress && tid == 0 && !progress(finished, T)) throw Cancelled("surface map build cancelled");
  }, 1);

  for (std::size_t c = 0; c < ncells; ++c) {
    const float* v = grid.data() + c * T;
    if (*std::max_element(v, v + T) <= 0) continue;
    int iz = c % nz, iy = (c / nz) % ny, ix = c / (static_cast<std::size_t>(ny) * nz);
    m.map_.set_voxel(octomap::OcTreeKey(kmin[0] + ix, kmin[1] + iy, kmin[2] + iz), v);
  }
  m.map_.finalize();
  m.stats_.base_poses = ncells * T;
  m.stats_.candidate_poses = candidates;
  m.stats_.valid_poses = valid;
  m.stats_.body_collisions = body_hits;
  m.stats_.arm_rejections = arm_hits;
  m.stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (m.map_.voxel_count() == 0) m.empty_reason_ = "no base pose reaches the surface (out of the arm's reach)";
  if (progress) progress(T, T);
  return m;
}

SurfaceMap SurfaceMap::combine(const std::vector<const SurfaceMap*>& maps, const std::string& mode) {
  if (maps.empty()) throw std::invalid_argument("combine needs at least one map");
  if (mode != "max" && mode != "min") throw std::invalid_argument("mode must be 'max' or 'min', got '" + mode + "'");
  const SurfaceMap& first = *maps[0];
  for (const SurfaceMap* m : maps) {
    if (m->robot_name_ != first.robot_name_ || m->urdf_hash_ != first.urdf_hash_)
      throw std::invalid_argument("cannot combine maps of different robots ('" + first.robot_name_ + "' and '" +
                                  m->robot_name_ + "')");
    if (m->reference_frame_ != first.reference_frame_)
      throw std::invalid_argument("cannot combine maps of different reference frames ('" + first.reference_frame_ +
                                  "' and '" + m->reference_frame_ + "')");
    if (std::abs(m->map_.resolution() - first.map_.resolution()) > 1e-12)
      throw std::invalid_argument("cannot combine maps of different resolutions");
    if (m->map_.theta_bins() != first.map_.theta_bins())
      throw std::invalid_argument("cannot combine maps of different theta bins");
    bool same_polygon = m->polygon_.size() == first.polygon_.size();
    for (std::size_t i = 0; same_polygon && i < m->polygon_.size(); ++i)
      same_polygon = (m->polygon_[i] - first.polygon_[i]).norm() < 1e-9;
    if (!same_polygon) throw std::invalid_argument("cannot combine maps of different surfaces (polygons differ)");
    if (m->z_min_ != first.z_min_ || m->z_max_ != first.z_max_)
      throw std::invalid_argument("cannot combine maps of different z ranges");
    if (m->grasp_name_ != first.grasp_name_ || m->grasp_height_ != first.grasp_height_ || m->checks_ != first.checks_)
      throw std::invalid_argument("cannot combine maps built with different grasp sets, grasp heights or checks");
  }
  const int T = first.map_.theta_bins();
  SurfaceMap out;
  out.robot_name_ = first.robot_name_;
  out.urdf_hash_ = first.urdf_hash_;
  out.reference_frame_ = first.reference_frame_;
  out.polygon_ = first.polygon_;
  out.z_min_ = first.z_min_;
  out.z_max_ = first.z_max_;
  out.grasp_height_ = first.grasp_height_;
  out.checks_ = first.checks_;
  out.stats_.surface_points = first.stats_.surface_points;
  for (const SurfaceMap* m : maps) {  // the combination's cost and scale are those of its parts
    out.stats_.seconds += m->stats_.seconds;
    out.stats_.base_poses += m->stats_.base_poses;
    out.stats_.candidate_poses += m->stats_.candidate_poses;
    out.stats_.valid_poses += m->stats_.valid_poses;
    out.stats_.body_collisions += m->stats_.body_collisions;
    out.stats_.arm_rejections += m->stats_.arm_rejections;
  }
  out.grasp_name_ = first.grasp_name_;
  out.map_ = PoseMap(first.map_.resolution(), T);
  for (std::size_t i = 0; i < maps.size(); ++i) out.arms_ += (i ? " " + mode + " " : "") + maps[i]->arms_;
  // Union of voxels; a voxel missing from a map counts as 0.
  std::map<std::tuple<int, int, int>, std::vector<float>> cells;
  for (std::size_t mi = 0; mi < maps.size(); ++mi) {
    const VoxelOcTree& tree = maps[mi]->map_.tree();
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
      auto key = it.getKey();
      auto& v = cells[{key[0], key[1], key[2]}];
      if (v.empty()) v.assign(T * maps.size(), 0.0f);
      const float* src = maps[mi]->map_.voxel_values(it.getX(), it.getY(), it.getZ());
      if (src) std::copy(src, src + T, v.begin() + mi * T);
    }
  }
  std::vector<float> vals(T);
  for (auto& [k, v] : cells) {
    for (int t = 0; t < T; ++t) {
      float r = v[t];
      for (std::size_t mi = 1; mi < maps.size(); ++mi) r = mode == "max" ? std::max(r, v[mi * T + t]) : std::min(r, v[mi * T + t]);
      vals[t] = r;
    }
    out.map_.set_voxel(octomap::OcTreeKey(std::get<0>(k), std::get<1>(k), std::get<2>(k)), vals.data());
  }
  out.map_.finalize();
  if (out.map_.voxel_count() == 0) out.empty_reason_ = "the combination is empty";
  return out;
}

std::map<std::string, std::string> SurfaceMap::parameters() const {
  std::ostringstream poly;
  poly.precision(17);
  for (std::size_t i = 0; i < polygon_.size(); ++i)
    poly << (i ? " " : "") << polygon_[i].x() << " " << polygon_[i].y() << " " << polygon_[i].z();
  return {{"robot", robot_name_},
          {"urdf_hash", std::to_string(urdf_hash_)},
          {"reference_frame", reference_frame_},
          {"arms", arms_},
          {"grasp_set", grasp_name_},
          {"polygon", poly.str()},
          {"surface_points", std::to_string(stats_.surface_points)},
          {"z_min", detail::format_double(z_min_)},
          {"grasp_height", detail::format_double(grasp_height_)},
          {"checks", checks_},
          {"body_collisions", std::to_string(stats_.body_collisions)},
          {"arm_rejections", std::to_string(stats_.arm_rejections)},
          {"z_max", detail::format_double(z_max_)},
          {"candidate_poses", std::to_string(stats_.candidate_poses)},
          {"valid_poses", std::to_string(stats_.valid_poses)},
          {"build_seconds", detail::format_double(stats_.seconds)}};
}

void SurfaceMap::save(const std::string& path) const { map_.save(path, "surface", parameters()); }

SurfaceMap SurfaceMap::load(const std::string& path) {
  std::map<std::string, std::string> h;
  SurfaceMap m;
  m.map_ = PoseMap::load(path, "surface", h);
  using detail::header_string;
  m.robot_name_ = header_string(h, "robot", path);
  m.urdf_hash_ = detail::header_u64(h, "urdf_hash", path);
  m.stats_.surface_points = detail::header_u64(h, "surface_points", path);
  m.stats_.candidate_poses = detail::header_u64(h, "candidate_poses", path);
  m.stats_.valid_poses = detail::header_u64(h, "valid_poses", path);
  m.reference_frame_ = header_string(h, "reference_frame", path);
  m.arms_ = header_string(h, "arms", path);
  m.grasp_name_ = header_string(h, "grasp_set", path);
  m.stats_.seconds = detail::header_double(h, "build_seconds", path);
  m.z_min_ = detail::header_double(h, "z_min", path);
  m.grasp_height_ = detail::header_double(h, "grasp_height", path);
  m.checks_ = header_string(h, "checks", path);
  m.stats_.body_collisions = detail::header_u64(h, "body_collisions", path);
  m.stats_.arm_rejections = detail::header_u64(h, "arm_rejections", path);
  m.z_max_ = detail::header_double(h, "z_max", path);
  std::istringstream poly(header_string(h, "polygon", path));
  double x, y, z;
  while (poly >> x >> y >> z) m.polygon_.emplace_back(x, y, z);
  if (m.map_.voxel_count() == 0) m.empty_reason_ = "the map is empty";
  return m;
}

}  // namespace octoreach
