#include "octoreach/point_map.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>

#include "maps/map_io.hpp"
#include "common/cancel.hpp"
#include "common/checks.hpp"
#include "common/thread_pool.hpp"
#include "maps/reach_extent.hpp"

namespace octoreach {

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
  // The fixed offset also makes derived theta bins equal direct ones.
  return reference_to_arm.inverse() * in_ref + target_offset();
}

}  // namespace

double InversePointMap::direct_reachability(const CapabilityMap& cap, const Pose& reference_to_arm,
                                            const std::vector<int>& orientations, double x, double y, double z,
                                            double theta) {
  if (orientations.empty()) throw std::invalid_argument("the grasp set is empty");
  check_rigid(reference_to_arm, "reference_to_arm");
  Eigen::Vector3d p = target_in_arm(reference_to_arm, x, y, z, theta);
  int count = 0;
  for (int g : orientations) count += cap.reachable(p, mapped_orientation(cap, reference_to_arm, g, theta));
  return static_cast<double>(count) / orientations.size();
}

namespace {

// Symmetry: the grasp set must map onto itself under the orientation set's z rotations, the theta
// bins must contain those rotations, and only 90 and 180 degree rotations map grid cells onto grid
// cells. With several rolls per direction a rotated roll need not be a roll of the set: no symmetry then.
bool grasps_symmetric(const OrientationSet& set, const std::vector<int>& grasps, const PointMapOptions& o) {
  const int sym = set.symmetry();
  bool symmetric = o.use_symmetry && (sym == 2 || sym == 4) && o.theta_bins % sym == 0 && set.rolls() == 1;
  if (!symmetric) return false;
  std::vector<char> in(set.size(), 0);
  for (int g : grasps) in[g] = 1;
  for (int g : grasps)
    for (int k = 1; k < sym; ++k)
      if (!in[set.rotated(g / set.rolls(), k) * set.rolls() + g % set.rolls()]) return false;
  return true;
}

// The point map's base-position grid: a square xy key range symmetric about the target (needed
// for exact 90 degree rotations of the grid) times the z layers; values [(ix * nxy + iy) * nz + iz] * T + k.
struct PointGrid {
  static constexpr int kC0 = 32768;  // key of the cell whose lower corner is 0
  int half = 0, nxy = 0, nz = 0, kz0 = 0, T = 0;
  std::vector<float> values;
  std::size_t columns() const { return static_cast<std::size_t>(nxy) * nxy; }
  octomap::OcTreeKey key(int ix, int iy, int iz) const { return octomap::OcTreeKey(kC0 - half + ix, kC0 - half + iy, kz0 + iz); }
  float& at(std::size_t col, int iz, int k) { return values[(col * nz + iz) * T + k]; }
};

// The grid around the target that covers every base position from which the arm reaches it;
// false when the z range leaves no layer.
bool make_grid(const CapabilityMap& cap, const Pose& reference_to_arm, const PointMapOptions& o, double res,
               const VoxelOcTree& tree, PointGrid& g) {
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> dvals;
  cap.voxels(centres, dvals);
  if (centres.empty()) return false;
  const detail::ReachExtent reach = detail::reach_extent(centres, reference_to_arm);
  const double rxy = reach.radius_xy + cap.resolution() + res;
  double z_lo = std::max(o.z_min, -reach.z_hi - cap.resolution() - res);
  double z_hi = std::min(o.z_max, -reach.z_lo + cap.resolution() + res);
  octomap::OcTreeKey kmin, kmax;
  if (!tree.coordToKeyChecked(-rxy, -rxy, z_lo, kmin) || !tree.coordToKeyChecked(rxy, rxy, z_hi, kmax))
    throw std::invalid_argument("the point map does not fit an octree at this resolution");
  const int c0 = PointGrid::kC0;
  g.half = std::max(c0 - kmin[0], kmax[0] - c0 + 1);
  g.half = std::max(g.half, std::max(c0 - kmin[1], kmax[1] - c0 + 1));
  g.nxy = 2 * g.half;
  g.nz = kmax[2] - kmin[2] + 1;
  g.kz0 = kmin[2];
  g.T = o.theta_bins;
  if (z_lo > z_hi) return false;
  detail::check_grid_values(g.nxy, g.nxy, g.nz, g.T, "the point map's");
  g.values.assign(g.columns() * g.nz * g.T, 0.0f);
  return true;
}

// What a grasp counts in R_P: 1 (the paper's), or its cell's quality relative to the map's best cell.
float grasp_weight(const CapabilityMap& cap, bool quality, const Eigen::Vector3d& p, int orientation) {
  if (!quality) return 1.0f;
  return static_cast<float>(cap.relative_quality(static_cast<std::uint32_t>(cap.record_at(p)), orientation));
}

// R_P of every grid pose of the first `direct_bins` theta bins, straight from the capability map.
void fill_direct_bins(const CapabilityMap& cap, const Pose& reference_to_arm, const std::vector<int>& grasps,
                      int direct_bins, bool quality, int threads, const VoxelOcTree& tree, PointGrid& g,
                      const ProgressCallback& progress) {
  const int T = g.T;
  // Per theta bin, the arm-frame orientation of each grasp (independent of position).
  std::vector<std::vector<int>> mapped(direct_bins);
  for (int k = 0; k < direct_bins; ++k)
    for (int o : grasps) mapped[k].push_back(mapped_orientation(cap, reference_to_arm, o, 2.0 * M_PI * k / T));
  const double inv = 1.0 / grasps.size();
  const std::size_t ncols = g.columns();
  std::atomic<std::size_t> done{0};
  detail::parallel_for(ncols, threads, [&](std::size_t col, int tid) {
    int ix = static_cast<int>(col / g.nxy), iy = static_cast<int>(col % g.nxy);
    for (int iz = 0; iz < g.nz; ++iz) {
      octomap::point3d c = tree.keyToCoord(g.key(ix, iy, iz));
      for (int k = 0; k < direct_bins; ++k) {
        Eigen::Vector3d p = target_in_arm(reference_to_arm, c.x(), c.y(), c.z(), 2.0 * M_PI * k / T);
        if (cap.reachability(p) <= 0) continue;
        float count = 0;  // whole numbers without quality weights: exact in a float
        for (int mo : mapped[k])
          if (cap.reachable(p, mo)) count += grasp_weight(cap, quality, p, mo);
        g.at(col, iz, k) = static_cast<float>(count * inv);
      }
    }
    std::size_t d = ++done;
    if (progress && tid == 0 && !progress(d, ncols)) throw Cancelled("point map build cancelled");
  }, 8);
}

// The other theta bins by rotating the grid: R_P(x, y, z, theta + 2 pi m / sym) =
// R_P(Rz(-2 pi m / sym) (x, y), z, theta).
void derive_rotated_bins(int sym, PointGrid& g) {
  const int T = g.T, step = T / sym, nxy = g.nxy, half = g.half;
  for (int ix = 0; ix < nxy; ++ix)
    for (int iy = 0; iy < nxy; ++iy, detail::poll_cancel("point map build cancelled"))
      for (int mrot = 1; mrot < sym; ++mrot) {
        double a = -2.0 * M_PI * mrot / sym;
        double cx = ix - half + 0.5, cy = iy - half + 0.5;
        double rx = std::cos(a) * cx - std::sin(a) * cy, ry = std::sin(a) * cx + std::cos(a) * cy;
        long jx = std::lround(rx - 0.5 + half), jy = std::lround(ry - 0.5 + half);
        bool inside = jx >= 0 && jy >= 0 && jx < nxy && jy < nxy && std::abs(rx - (jx - half + 0.5)) < 1e-6 &&
                      std::abs(ry - (jy - half + 0.5)) < 1e-6;
        const std::size_t col = static_cast<std::size_t>(ix) * nxy + iy;
        const std::size_t src = inside ? static_cast<std::size_t>(jx) * nxy + jy : 0;
        for (int iz = 0; iz < g.nz; ++iz)
          for (int k = 0; k < step; ++k) g.at(col, iz, mrot * step + k) = inside ? g.at(src, iz, k) : 0.0f;
      }
}

}  // namespace

InversePointMap InversePointMap::build(const Robot& robot, const CapabilityMap& cap, const PointMapOptions& o,
                                       const ProgressCallback& progress) {
  detail::CancellableScope cancellable;
  const auto t0 = std::chrono::steady_clock::now();
  check_map_robot(robot, cap);
  if (o.theta_bins < 1 || o.theta_bins > limits::kThetaBins)
    throw std::invalid_argument("theta_bins must be in [1, " + std::to_string(limits::kThetaBins) + "], got " +
                                std::to_string(o.theta_bins));
  double res = o.resolution == 0 ? cap.resolution() : o.resolution;
  if (!(res > 0) || !std::isfinite(res))
    throw std::invalid_argument("resolution must be positive, got " + detail::format_number(res));
  // Strict, unlike the surface map: heights here are a grid range relative to the target, not a
  // range poses are clipped into, so an empty range holds no pose.
  if (!std::isfinite(o.z_min) || !std::isfinite(o.z_max))
    throw std::invalid_argument("z_min and z_max (z_range) must be finite, got " + detail::format_number(o.z_min) +
                                ", " + detail::format_number(o.z_max));
  if (!(o.z_min < o.z_max)) throw std::invalid_argument("z_min must be below z_max");
  if (o.quality_weight) cap.require_quality("quality_weight");
  const ArmPlacement place = ArmPlacement::make(robot, cap, o.reference_frame, o.reference, o.grasps, o.grasp_subset);
  InversePointMap m;
  m.provenance_ = MapProvenance::of(robot);
  m.reference_frame_ = place.reference_frame;
  m.arm_base_ = cap.base_link();
  m.arm_tip_ = cap.tip_link();
  m.approach_axis_ = cap.approach_axis();
  m.grasp_name_ = place.grasps.name;
  m.grasp_orientations_ = place.grasps.orientations;
  m.weight_ = o.quality_weight ? "quality" : "";
  m.reference_to_arm_ = place.reference_to_arm;
  const OrientationSet& set = cap.orientations();
  const bool symmetric = grasps_symmetric(set, m.grasp_orientations_, o);
  m.used_symmetry_ = symmetric;

  m.map_ = PoseMap(res, o.theta_bins);
  const VoxelOcTree& tree = m.map_.tree();
  PointGrid g;
  if (!make_grid(cap, m.reference_to_arm_, o, res, tree, g)) {
    m.map_.finalize();
    return m;
  }
  const int sym = set.symmetry();
  fill_direct_bins(cap, m.reference_to_arm_, m.grasp_orientations_, symmetric ? g.T / sym : g.T, o.quality_weight,
                   o.threads, tree, g, progress);
  if (symmetric) derive_rotated_bins(sym, g);
  const std::size_t ncols = g.columns();
  for (std::size_t col = 0; col < ncols; ++col, detail::poll_cancel("point map build cancelled"))
    for (int iz = 0; iz < g.nz; ++iz) {
      const float* v = &g.at(col, iz, 0);
      if (*std::max_element(v, v + g.T) <= 0) continue;
      m.map_.set_voxel(g.key(static_cast<int>(col / g.nxy), static_cast<int>(col % g.nxy), iz), v);
    }
  m.map_.finalize();
  m.seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) progress(ncols, ncols);
  return m;
}

std::map<std::string, std::string> InversePointMap::parameters() const {
  using detail::format_number;
  const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> T = reference_to_arm_.matrix();  // row by row
  std::ostringstream g;
  for (std::size_t i = 0; i < grasp_orientations_.size(); ++i) g << (i ? " " : "") << grasp_orientations_[i];
  const auto provenance = detail::provenance_entries(provenance_);
  std::map<std::string, std::string> p(provenance.begin(), provenance.end());
  p.insert({{"reference_frame", reference_frame_},
          {"arm_base_link", arm_base_},
          {"arm_tip_link", arm_tip_},
          {"approach_axis", detail::format_vector(approach_axis_)},
          {"reference_to_arm", detail::format_vector(T.reshaped<Eigen::RowMajor>())},
          {"grasp_set", grasp_name_},
          {"grasp_orientations", g.str()},
          {"used_symmetry", used_symmetry_ ? "1" : "0"}});  // no timing: the same build gives the same bytes
  if (!weight_.empty()) p.insert({"weight", weight_});  // absent for the paper's R_P: those files are unchanged
  return p;
}

void InversePointMap::save(const std::string& path) const { map_.save(path, kKind, parameters(), kFormatVersion); }

InversePointMap InversePointMap::load(const std::string& path) {
  std::map<std::string, std::string> h;
  InversePointMap m;
  m.map_ = PoseMap::load(path, kKind, h);
  using detail::header_string;
  m.provenance_ = detail::header_provenance(h, path);
  m.reference_frame_ = header_string(h, "reference_frame", path);
  m.arm_base_ = header_string(h, "arm_base_link", path);
  m.arm_tip_ = header_string(h, "arm_tip_link", path);
  if (h.count("approach_axis")) {  // files written before point maps recorded it: +z
    std::istringstream axis(h.at("approach_axis"));
    if (!(axis >> m.approach_axis_.x() >> m.approach_axis_.y() >> m.approach_axis_.z()))
      throw FileError("'" + path + "' has a malformed approach_axis");
  }
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
  if (auto it = h.find("weight"); it != h.end()) m.weight_ = it->second;
  m.seconds_ = h.count("build_seconds") ? detail::header_double(h, "build_seconds", path) : 0.0;  // older files
  return m;
}

}  // namespace octoreach
