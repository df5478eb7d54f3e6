#include "octoreach/point_map.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>

#include "map_io.hpp"
#include "common/thread_pool.hpp"
#include "reach_extent.hpp"

namespace octoreach {

std::vector<int> grasp_orientations(const OrientationSet& set, const std::vector<int>& directions) {
  std::vector<int> out;
  for (int d : directions) {
    if (d < 0 || d >= set.directions())
      throw std::invalid_argument("grasp direction index " + std::to_string(d) + " out of range [0, " +
                                  std::to_string(set.directions()) + ")");
    for (int r = 0; r < set.rolls(); ++r) out.push_back(d * set.rolls() + r);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

// Orientation index, in the arm frame, of grasp orientation g for a base yawed by theta.
int mapped_orientation(const CapabilityMap& cap, const Pose& reference_to_arm, int g, double theta) {
  const OrientationSet& set = cap.orientations();
  Eigen::Matrix3d R_world = set.rotation(g, cap.approach_axis());
  Eigen::Matrix3d R_arm = reference_to_arm.linear().transpose() *
                          Eigen::AngleAxisd(-theta, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_world;
  return set.nearest(R_arm, cap.approach_axis());
}

// Target (origin) position in the arm frame for a base at (x, y, z, theta).
Eigen::Vector3d target_in_arm(const Pose& reference_to_arm, double x, double y, double z, double theta) {
  Eigen::Vector3d in_ref = Eigen::AngleAxisd(-theta, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(-x, -y, -z);
  // A target exactly on a capability-voxel boundary (common: rotated grid centres land on them)
  // would be assigned by rounding noise; a fixed offset far below the resolution makes the
  // assignment the same however the pose was computed, so derived theta bins equal direct ones.
  return reference_to_arm.inverse() * in_ref + Eigen::Vector3d(1.3e-7, 0.7e-7, 0.3e-7);
}

}  // namespace

double InversePointMap::direct_reachability(const CapabilityMap& cap, const Pose& reference_to_arm,
                                            const std::vector<int>& orientations, double x, double y, double z,
                                            double theta) {
  if (orientations.empty()) throw std::invalid_argument("the grasp set is empty");
  Eigen::Vector3d p = target_in_arm(reference_to_arm, x, y, z, theta);
  int count = 0;
  for (int g : orientations) count += cap.reachable(p, mapped_orientation(cap, reference_to_arm, g, theta));
  return static_cast<double>(count) / orientations.size();
}

InversePointMap InversePointMap::build(const Robot& robot, const CapabilityMap& cap, const PointMapOptions& o,
                                       const ProgressCallback& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (cap.robot_name() != robot.name() || cap.urdf_hash() != robot.urdf_hash())
    throw std::invalid_argument("the capability map was built for robot '" + cap.robot_name() +
                                "' (another URDF), not for '" + robot.name() + "'");
  if (o.theta_bins < 1 || o.theta_bins > 360)
    throw std::invalid_argument("theta_bins must be in [1, 360], got " + std::to_string(o.theta_bins));
  double res = o.resolution == 0 ? cap.resolution() : o.resolution;
  if (!(res > 0) || !std::isfinite(res))
    throw std::invalid_argument("resolution must be positive, got " + detail::format_double(res));
  if (!(o.z_min < o.z_max)) throw std::invalid_argument("z_min must be below z_max");
  InversePointMap m;
  m.robot_name_ = robot.name();
  m.urdf_hash_ = robot.urdf_hash();
  m.reference_frame_ = o.reference_frame.empty() ? robot.links()[robot.root_link()].name : o.reference_frame;
  m.arm_base_ = cap.base_link();
  m.arm_tip_ = cap.tip_link();
  const OrientationSet& set = cap.orientations();
  std::vector<int> dirs = o.grasps.empty() ? set.subset(o.grasp_subset) : o.grasps;
  m.grasp_name_ = o.grasps.empty() ? o.grasp_subset : "custom";
  if (dirs.empty()) throw std::invalid_argument("the grasp set is empty");
  m.grasp_orientations_ = octoreach::grasp_orientations(set, dirs);
  // Reference frame -> arm base link at the reference posture.
  Eigen::VectorXd q = o.reference.size() ? o.reference : robot.home();
  if (q.size() != robot.dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(q.size()) + " entries, the robot has " +
                                std::to_string(robot.dof()));
  std::vector<Pose> poses = robot.link_poses(q);
  m.reference_to_arm_ = poses[robot.link_index(m.reference_frame_)].inverse() * poses[robot.link_index(cap.base_link())];

  // Symmetry: the grasp set must map onto itself under the orientation set's z rotations,
  // the theta bins must contain those rotations, and the arm frame must not be tilted.
  const int sym = set.symmetry();
  // Only 90 and 180 degree rotations map grid cells onto grid cells.
  // With several rolls per direction a rotated roll need not be a roll of the set: no symmetry then.
  bool symmetric = o.use_symmetry && (sym == 2 || sym == 4) && o.theta_bins % sym == 0 && set.rolls() == 1;
  if (symmetric) {
    std::vector<char> in(set.size(), 0);
    for (int g : m.grasp_orientations_) in[g] = 1;
    for (int g : m.grasp_orientations_)
      for (int k = 1; k < sym && symmetric; ++k) {
        int rd = set.rotated(g / set.rolls(), k);
        if (!in[rd * set.rolls() + g % set.rolls()]) symmetric = false;
      }
  }
  m.used_symmetry_ = symmetric;

  // Grid: base positions whose target lies in the capability map.
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> dvals;
  cap.voxels(centres, dvals);
  m.map_ = PoseMap(res, o.theta_bins);
  if (centres.empty()) {
    m.map_.finalize();
    return m;
  }
  const detail::ReachExtent reach = detail::reach_extent(centres, m.reference_to_arm_);
  const double rxy = reach.radius_xy + cap.resolution() + res, wz_lo = reach.z_lo, wz_hi = reach.z_hi;
  double z_lo = std::max(o.z_min, -wz_hi - cap.resolution() - res), z_hi = std::min(o.z_max, -wz_lo + cap.resolution() + res);
  const VoxelOcTree& tree = m.map_.tree();
  octomap::OcTreeKey kmin, kmax;
  if (!tree.coordToKeyChecked(-rxy, -rxy, z_lo, kmin) || !tree.coordToKeyChecked(rxy, rxy, z_hi, kmax))
    throw std::invalid_argument("the point map does not fit an octree at this resolution");
  // Symmetric xy key range about the target (needed for exact 90 degree rotations of the grid).
  const int c0 = 32768;  // key of the cell whose lower corner is 0
  int half = std::max(c0 - kmin[0], kmax[0] - c0 + 1);
  half = std::max(half, std::max(c0 - kmin[1], kmax[1] - c0 + 1));
  const int nxy = 2 * half, nz = kmax[2] - kmin[2] + 1;
  if (z_lo > z_hi) {
    m.map_.finalize();
    return m;
  }
  const int T = o.theta_bins;
  const int direct_bins = symmetric ? T / sym : T;
  // Per theta bin, the arm-frame orientation of each grasp (independent of position).
  std::vector<std::vector<int>> mapped(direct_bins);
  for (int k = 0; k < direct_bins; ++k)
    for (int g : m.grasp_orientations_)
      mapped[k].push_back(mapped_orientation(cap, m.reference_to_arm_, g, 2.0 * M_PI * k / T));

  const std::size_t ncols = static_cast<std::size_t>(nxy) * nxy;
  std::vector<float> grid(ncols * nz * T, 0.0f);  // [(ix * nxy + iy) * nz + iz] * T + k
  auto centre_of = [&](int ix, int iy, int iz) {
    octomap::point3d c = tree.keyToCoord(octomap::OcTreeKey(c0 - half + ix, c0 - half + iy, kmin[2] + iz));
    return Eigen::Vector3d(c.x(), c.y(), c.z());
  };
  const double inv = 1.0 / m.grasp_orientations_.size();
  std::atomic<std::size_t> done{0};
  detail::parallel_for(ncols, o.threads, [&](std::size_t col, int tid) {
    int ix = static_cast<int>(col / nxy), iy = static_cast<int>(col % nxy);
    for (int iz = 0; iz < nz; ++iz) {
      Eigen::Vector3d c = centre_of(ix, iy, iz);
      for (int k = 0; k < direct_bins; ++k) {
        Eigen::Vector3d p = target_in_arm(m.reference_to_arm_, c.x(), c.y(), c.z(), 2.0 * M_PI * k / T);
        if (cap.reachability(p) <= 0) continue;
        int count = 0;
        for (int mo : mapped[k]) count += cap.reachable(p, mo);
        grid[(col * nz + iz) * T + k] = static_cast<float>(count * inv);
      }
    }
    std::size_t d = ++done;
    if (progress && tid == 0 && !progress(d, ncols)) throw Cancelled("point map build cancelled");
  }, 8);
  if (symmetric) {
    // R_P(x, y, z, theta + 2 pi m / sym) = R_P(Rz(-2 pi m / sym) (x, y), z, theta): a grid rotation.
    const int step = T / sym;
    for (int ix = 0; ix < nxy; ++ix)
      for (int iy = 0; iy < nxy; ++iy)
        for (int mrot = 1; mrot < sym; ++mrot) {
          // Rotate cell (ix, iy) by -mrot * 90 degrees about the target (sym == 4) or in general by angle.
          double a = -2.0 * M_PI * mrot / sym;
          double cx = ix - half + 0.5, cy = iy - half + 0.5;
          double rx = std::cos(a) * cx - std::sin(a) * cy, ry = std::sin(a) * cx + std::cos(a) * cy;
          long jx = std::lround(rx - 0.5 + half), jy = std::lround(ry - 0.5 + half);
          bool inside = jx >= 0 && jy >= 0 && jx < nxy && jy < nxy &&
                        std::abs(rx - (jx - half + 0.5)) < 1e-6 && std::abs(ry - (jy - half + 0.5)) < 1e-6;
          for (int iz = 0; iz < nz; ++iz)
            for (int k = 0; k < step; ++k) {
              float v = 0.0f;
              if (inside) v = grid[((static_cast<std::size_t>(jx) * nxy + jy) * nz + iz) * T + k];
              grid[((static_cast<std::size_t>(ix) * nxy + iy) * nz + iz) * T + mrot * step + k] = v;
            }
        }
  }
  for (std::size_t col = 0; col < ncols; ++col)
    for (int iz = 0; iz < nz; ++iz) {
      const float* v = grid.data() + (col * nz + iz) * T;
      if (*std::max_element(v, v + T) <= 0) continue;
      int ix = static_cast<int>(col / nxy), iy = static_cast<int>(col % nxy);
      m.map_.set_voxel(octomap::OcTreeKey(c0 - half + ix, c0 - half + iy, kmin[2] + iz), v);
    }
  m.map_.finalize();
  m.seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) progress(ncols, ncols);
  return m;
}

std::map<std::string, std::string> InversePointMap::parameters() const {
  using detail::format_double;
  std::ostringstream T, g;
  T.precision(17);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) T << reference_to_arm_.matrix()(i, j) << (i == 3 && j == 3 ? "" : " ");
  for (std::size_t i = 0; i < grasp_orientations_.size(); ++i) g << (i ? " " : "") << grasp_orientations_[i];
  return {{"robot", robot_name_},
          {"urdf_hash", std::to_string(urdf_hash_)},
          {"reference_frame", reference_frame_},
          {"arm_base_link", arm_base_},
          {"arm_tip_link", arm_tip_},
          {"reference_to_arm", T.str()},
          {"grasp_set", grasp_name_},
          {"grasp_orientations", g.str()},
          {"used_symmetry", used_symmetry_ ? "1" : "0"},
          {"build_seconds", format_double(seconds_)}};
}

void InversePointMap::save(const std::string& path) const { map_.save(path, "point", parameters()); }

InversePointMap InversePointMap::load(const std::string& path) {
  std::map<std::string, std::string> h;
  InversePointMap m;
  m.map_ = PoseMap::load(path, "point", h);
  using detail::header_string;
  m.robot_name_ = header_string(h, "robot", path);
  m.urdf_hash_ = detail::header_u64(h, "urdf_hash", path);
  m.reference_frame_ = header_string(h, "reference_frame", path);
  m.arm_base_ = header_string(h, "arm_base_link", path);
  m.arm_tip_ = header_string(h, "arm_tip_link", path);
  m.grasp_name_ = header_string(h, "grasp_set", path);
  {
    std::istringstream s(header_string(h, "reference_to_arm", path));
    Eigen::Matrix4d M;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (!(s >> M(i, j))) throw FileError("'" + path + "' has a malformed reference_to_arm");
    m.reference_to_arm_.matrix() = M;
  }
  {
    std::istringstream s(header_string(h, "grasp_orientations", path));
    int g;
    while (s >> g) m.grasp_orientations_.push_back(g);
  }
  m.used_symmetry_ = detail::header_int(h, "used_symmetry", path) != 0;
  m.seconds_ = detail::header_double(h, "build_seconds", path);
  return m;
}

}  // namespace octoreach
