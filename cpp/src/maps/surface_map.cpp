#include "octoreach/surface_map.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "common/cancel.hpp"
#include "common/checks.hpp"
#include "common/format.hpp"
#include "common/thread_pool.hpp"
#include "maps/batch.hpp"
#include "maps/map_io.hpp"
#include "maps/map_room_io.hpp"
#include "maps/reach_extent.hpp"
#include "maps/surface_bin.hpp"
#include "maps/surface_warning.hpp"

namespace octoreach {
namespace {

using detail::SurfaceBuild;
using detail::SurfaceGrid;

// The grid of base positions from which a target can be reached; "" or why there is none.
std::string make_grid(const SurfaceBuild& b, double res, SurfaceGrid& g) {
  std::vector<Eigen::Vector3d> cc;
  std::vector<double> cv;
  b.cap.voxels(cc, cv);
  if (cc.empty()) return "the capability map is empty";
  const double cres = b.cap.resolution();
  const detail::ReachExtent reach = detail::reach_extent(cc, b.place.reference_to_arm);
  const double rxy = reach.radius_xy + cres + res;
  Eigen::Vector3d tlo = b.targets[0], thi = b.targets[0];
  for (const auto& t : b.targets) {
    tlo = tlo.cwiseMin(t);
    thi = thi.cwiseMax(t);
  }
  double zlo = std::max(b.o.z_min, tlo.z() - reach.z_hi - cres), zhi = std::min(b.o.z_max, thi.z() - reach.z_lo + cres);
  if (zlo > zhi) return "no base height in the z range reaches the surface";
  octomap::OcTreeKey kmax;
  if (!b.tree.coordToKeyChecked(tlo.x() - rxy, tlo.y() - rxy, zlo, g.kmin) ||
      !b.tree.coordToKeyChecked(thi.x() + rxy, thi.y() + rxy, zhi, kmax))
    throw std::invalid_argument("the surface map does not fit an octree at this resolution");
  g.nx = kmax[0] - g.kmin[0] + 1;
  g.ny = kmax[1] - g.kmin[1] + 1;
  g.nz = kmax[2] - g.kmin[2] + 1;
  g.T = b.o.theta_bins;
  detail::check_grid_values(g.nx, g.ny, g.nz, g.T, "the surface map's");
  g.values.assign(g.cells() * g.T, 0.0f);
  return "";
}

// Arm-frame heights of the targets over every base height of the grid (upright case).
std::pair<double, double> target_heights_in_arm(const SurfaceBuild& b, const SurfaceGrid& g) {
  double za_lo = 1e9, za_hi = -1e9;
  for (int iz = 0; iz < g.nz; ++iz) {
    double bz = b.tree.keyToCoord(g.kmin[2] + iz);
    bz = std::min(std::max(bz, b.o.z_min), b.o.z_max);
    for (const auto& t : b.targets) {
      double za = t.z() - bz - b.place.reference_to_arm.translation().z();
      za_lo = std::min(za_lo, za);
      za_hi = std::max(za_hi, za);
    }
  }
  return {za_lo, za_hi};
}

void check_options(const CapabilityMap& cap, const SurfaceMapOptions& o) {
  if (cap.stats().voxels == 0)
    throw std::invalid_argument("the capability map of " + cap.base_link() + " -> " + cap.tip_link() +
                                " reaches no voxel (its warning says why): no surface map to build from it");
  if (o.check_arm && !cap.has_solutions())
    throw std::invalid_argument("the capability map holds no joint solutions, and the surface map checks the arm "
                                "against the surface with them: build it with keep_solutions=True and save it "
                                "with_solutions=True (command line: octoreach capability --with-solutions)");
  if (o.theta_bins < 1 || o.theta_bins > limits::kThetaBins)
    throw std::invalid_argument("theta_bins must be in [1, " + std::to_string(limits::kThetaBins) + "], got " +
                                std::to_string(o.theta_bins));
  const double res = o.resolution == 0 ? cap.resolution() : o.resolution;
  if (!(res > 0) || !std::isfinite(res))
    throw std::invalid_argument("resolution must be a number of metres above 0 (0 or None: the capability map's), got " +
                                detail::format_number(o.resolution));
  // Not strict, unlike the point map: poses are evaluated at heights clipped into the range, so
  // (0, 0) is one exact height (a robot on the floor).
  if (!std::isfinite(o.z_min) || !std::isfinite(o.z_max))
    throw std::invalid_argument("z_min and z_max (z_range) must be finite, got " + detail::format_number(o.z_min) +
                                ", " + detail::format_number(o.z_max));
  if (!(o.z_min <= o.z_max)) throw std::invalid_argument("z_min must not exceed z_max");
  if (o.quality_weight) cap.require_quality("quality_weight");
}

// Every obstacle but the slab meets the arm at its stored solutions (the slab has the finer "arm under
// the outline" test); the body meets them all. Adds the room to the body's `slab`; returns the arm's
// obstacles: the surface's boxes and the room.
std::shared_ptr<Obstacles> room_for_arm(const Surface& surface, const SurfaceMapOptions& o, Obstacles& slab) {
  auto others = std::make_shared<Obstacles>();
  for (const auto& [size, pose] : surface.boxes()) others->add_box(size, pose, "surface_box");
  if (o.obstacles) {
    others->add(*o.obstacles);
    slab.add(*o.obstacles);
  }
  return others;
}

// What the arm checks of a build read, owned for the build and wired into its SurfaceBuild: the arm's
// clearance over the surface, and with check_arm the cells a build can read and the obstacles near the
// arm at each of them.
class ArmChecks {
 public:
  ArmChecks(detail::SurfaceBuild& b, const detail::SurfaceGrid& g, std::shared_ptr<Obstacles> others)
      : clearance_(b.robot, b.cap, b.place, b.o.grasp_height) {
    b.clearance = &clearance_;
    if (!b.o.check_arm) return;
    // The cells a build can read: the orientations the grasps map to at some theta bin, and in the
    // upright case the records of the heights the targets have in the arm frame.
    std::vector<char> wanted(b.cap.orientations().size(), 0);
    for (int k = 0; k < b.o.theta_bins; ++k)
      for (int mo : detail::bin_orientations(b, k)) wanted[mo] = 1;
    if (b.upright) {
      auto [za_lo, za_hi] = target_heights_in_arm(b, g);
      slots_ = std::make_shared<const detail::CellSlots>(b.cap, wanted, za_lo, za_hi);
      clearance_.compute_shared(*slots_, b.o.threads);
    } else {
      slots_ = std::make_shared<const detail::CellSlots>(b.cap, wanted);
    }
    b.slots = slots_.get();
    obstacles_ = std::make_unique<const detail::ArmObstacles>(b.robot, b.cap, b.place, std::move(others), slots_,
                                                              b.o.threads);
    b.obstacles = obstacles_.get();
  }
  ArmChecks(const ArmChecks&) = delete;
  ArmChecks& operator=(const ArmChecks&) = delete;

 private:
  detail::ArmClearance clearance_;
  std::shared_ptr<const detail::CellSlots> slots_;
  std::unique_ptr<const detail::ArmObstacles> obstacles_;
};

// Every theta bin of the grid, one bin per task on the build's threads; the bins' counts added up.
detail::BinCounts evaluate_bins(const detail::SurfaceBuild& b, detail::SurfaceGrid& g, const ProgressCallback& progress) {
  const int T = b.o.theta_bins;
  std::atomic<std::size_t> bins_done{0}, candidates{0}, valid{0}, body_hits{0}, arm_hits{0};
  detail::parallel_for(T, b.o.threads, [&](std::size_t k, int tid) {
    detail::BinCounts n = detail::evaluate_bin(b, static_cast<int>(k), g);
    candidates += n.candidates;
    valid += n.valid;
    body_hits += n.body;
    arm_hits += n.arm;
    std::size_t finished = ++bins_done;
    if (progress && tid == 0 && !progress(finished, T)) throw Cancelled("surface map build cancelled");
  }, 1);
  return {candidates, valid, body_hits, arm_hits};
}

// The grid's base positions with a value above 0 at some theta bin become the map's voxels.
void store_grid(const detail::SurfaceGrid& g, PoseMap& map) {
  const int T = g.T;
  const std::size_t ncells = g.cells();
  for (std::size_t c = 0; c < ncells; ++c) {
    if ((c & 0xffff) == 0) detail::poll_cancel("surface map build cancelled");
    const float* v = g.values.data() + c * T;
    if (*std::max_element(v, v + T) <= 0) continue;
    int iz = c % g.nz, iy = (c / g.nz) % g.ny, ix = c / (static_cast<std::size_t>(g.ny) * g.nz);
    map.set_voxel(g.key(ix, iy, iz), v);
  }
  map.finalize();
}

}  // namespace

// A robot whose reference frame is not at its feet (Baxter's 'base' sits on top of its pedestal, a
// humanoid's root is its pelvis) stands sunk into the floor at the default height 0: every pose would
// be evaluated below the surface's real reach, and the map would look plausible and be wrong.
void check_standing(const Robot& robot, const ArmPlacement& place, const SurfaceMapOptions& o) {
  constexpr double kBelowFloor = 0.05;  // mesh tolerance of wheels and feet that touch the floor
  int link = -1;
  // The body only (links the arm does not move): an arm's home posture may dip below its own base.
  const double lowest = robot.lowest_point(place.link_poses, place.root_pose(0, 0, o.z_max, 0), &link, &place.roles.body);
  if (!(lowest < -kBelowFloor)) return;
  auto metres = [](double v) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << v;
    return s.str();
  };
  const std::string h = metres(o.z_max - lowest);
  throw std::invalid_argument(
      "robot '" + robot.name() + "' stands " + metres(-lowest) + " m deep in the floor: with its " +
      "reference frame '" + place.reference_frame + "' at z = " + metres(o.z_max) + " (the highest " +
      "base height asked for), its body link '" + robot.links()[link].name + "' reaches below z = 0. " +
      "The frame is not at the robot's feet: give its height above the floor, z_range=(" + h + ", " + h +
      ") in Python or --z " + h + " on the command line, or a reference_frame at the feet");
}

SurfaceMap SurfaceMap::build(const Robot& robot, const CapabilityMap& cap, const Surface& surface,
                             const SurfaceMapOptions& o, const ProgressCallback& progress) {
  detail::CancellableScope cancellable;
  const auto t0 = std::chrono::steady_clock::now();
  check_map_robot(robot, cap);
  check_options(cap, o);
  const ArmPlacement place = ArmPlacement::make(robot, cap, o.reference_frame, o.reference, o.grasps, o.grasp_subset);
  if (o.check_body) check_standing(robot, place, o);
  const double res = o.resolution == 0 ? cap.resolution() : o.resolution;
  SurfaceMap m;
  m.provenance_ = MapProvenance::of(robot);
  m.room_ = std::make_shared<const MapRoom>(MapRoom::of_build(robot, place, surface, o.obstacles.get(), o.check_body));
  m.reference_frame_ = place.reference_frame;
  m.arms_ = cap.base_link() + "->" + cap.tip_link();
  m.approach_axes_ = detail::format_vector(cap.approach_axis());
  m.polygon_ = surface.vertices();
  m.z_min_ = o.z_min;
  m.z_max_ = o.z_max;
  m.grasp_height_ = o.grasp_height;
  m.weight_ = o.quality_weight ? "quality" : "";
  m.checks_ = std::string(o.check_body ? "body" : "") + (o.check_body && o.check_arm ? "+" : "") + (o.check_arm ? "arm" : "");
  if (o.obstacles && !o.obstacles->empty()) m.checks_ += " (room: " + std::to_string(o.obstacles->size()) + " obstacles)";
  m.map_ = PoseMap(res, o.theta_bins);
  m.grasp_name_ = place.grasps.name;
  if (!(o.grasp_height >= 0) || !std::isfinite(o.grasp_height))
    throw std::invalid_argument("grasp_height must be zero or positive");

  detail::SurfaceBuild b{robot, cap, surface, o, place, m.map_.tree(), surface.sample_points(res), {},
                         place.reference_to_arm.inverse(), false, nullptr, surface.obstacles()};
  std::shared_ptr<Obstacles> others = room_for_arm(surface, o, *b.slab);
  for (auto& t : b.targets) t += o.grasp_height * surface.normal();
  m.stats_.surface_points = b.targets.size();
  detail::SurfaceGrid g;
  m.empty_reason_ = b.targets.empty()
                        ? "the surface holds no grid point at this resolution (polygon smaller than one cell)"
                        : make_grid(b, res, g);
  if (!m.empty_reason_.empty()) {
    m.map_.finalize();
    return m;
  }
  for (const auto& t : b.targets) b.target_uv.push_back(surface.project(t));
  b.upright = std::abs(place.reference_to_arm.linear()(2, 2) - 1.0) < 1e-9 && std::abs(surface.normal().z() - 1.0) < 1e-9;
  const ArmChecks arm_checks(b, g, std::move(others));

  const detail::BinCounts n = evaluate_bins(b, g, progress);
  store_grid(g, m.map_);
  m.stats_.base_poses = g.cells() * o.theta_bins;
  m.stats_.candidate_poses = n.candidates;
  m.stats_.valid_poses = n.valid;
  m.stats_.body_collisions = n.body;
  m.stats_.arm_rejections = n.arm;
  m.stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (m.map_.voxel_count() == 0) m.empty_reason_ = "no base pose reaches the surface (out of the arm's reach)";
  else m.warning_ = detail::surface_height_warning(b, m.map_.max_value());
  if (progress) progress(o.theta_bins, o.theta_bins);
  return m;
}

void SurfaceMap::reachability(const double* rows, std::size_t n, double* out) const {
  detail::batch_lookup_valid(rows, n, 4, "base pose", " (x, y, z, theta in m and rad)", [&](std::size_t i) {
    const double* r = rows + 4 * i;
    out[i] = reachability(r[0], r[1], r[2], r[3]);
  });
}

SurfaceMap SurfaceMap::combine(const std::vector<const SurfaceMap*>& maps, const std::string& mode) {
  if (maps.empty()) throw std::invalid_argument("combine needs at least one map");
  if (mode != "max" && mode != "min") throw std::invalid_argument("mode must be 'max' or 'min', got '" + mode + "'");
  const SurfaceMap& first = *maps[0];
  for (const SurfaceMap* m : maps) {
    if (m->provenance_ != first.provenance_)
      throw std::invalid_argument("cannot combine maps of different robots ('" + first.robot_name() + "' and '" +
                                  m->robot_name() + "')");
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
    if (m->weight_ != first.weight_)
      throw std::invalid_argument("cannot combine a quality-weighted map with one that is not (quality_weight differs)");
  }
  const int T = first.map_.theta_bins();
  SurfaceMap out;
  std::vector<const MapRoom*> rooms;
  for (const SurfaceMap* m : maps) rooms.push_back(m->room_.get());
  out.room_ = std::make_shared<const MapRoom>(MapRoom::combined(rooms));
  out.provenance_ = first.provenance_;
  out.reference_frame_ = first.reference_frame_;
  out.polygon_ = first.polygon_;
  out.z_min_ = first.z_min_;
  out.z_max_ = first.z_max_;
  out.grasp_height_ = first.grasp_height_;
  out.checks_ = first.checks_;
  out.weight_ = first.weight_;
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
  // The combination is suspicious when every part is (one arm at the edge of its reach, the other well in it, is not).
  if (std::all_of(maps.begin(), maps.end(), [](const SurfaceMap* m) { return !m->warning_.empty(); }))
    out.warning_ = first.warning_;
  out.map_ = PoseMap(first.map_.resolution(), T);
  for (std::size_t i = 0; i < maps.size(); ++i) {
    out.arms_ += (i ? " " + mode + " " : "") + maps[i]->arms_;
    out.approach_axes_ += (i ? " " + mode + " " : "") + maps[i]->approach_axes_;
  }
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
  Eigen::VectorXd flat(3 * polygon_.size());
  for (std::size_t i = 0; i < polygon_.size(); ++i) flat.segment<3>(3 * i) = polygon_[i];
  const auto provenance = detail::provenance_entries(provenance_);
  std::map<std::string, std::string> p(provenance.begin(), provenance.end());
  p.insert({{"reference_frame", reference_frame_},
          {"arms", arms_},
          {"approach_axes", approach_axes_},
          {"grasp_set", grasp_name_},
          {"polygon", detail::format_vector(flat)},
          {"surface_points", std::to_string(stats_.surface_points)},
          {"z_min", detail::format_number(z_min_)},
          {"grasp_height", detail::format_number(grasp_height_)},
          {"checks", checks_},
          {"body_collisions", std::to_string(stats_.body_collisions)},
          {"arm_rejections", std::to_string(stats_.arm_rejections)},
          {"z_max", detail::format_number(z_max_)},
          {"candidate_poses", std::to_string(stats_.candidate_poses)},
          {"valid_poses", std::to_string(stats_.valid_poses)}});  // no timing: the same build gives the same bytes
  if (!weight_.empty()) p.insert({"weight", weight_});  // absent for the paper's R_S: those files are unchanged
  return p;
}

void SurfaceMap::save(const std::string& path) const {
  map_.save(path, kKind, parameters(), kFormatVersion, detail::room_sections(*room_));
}

SurfaceMap SurfaceMap::load(const std::string& path) {
  std::map<std::string, std::string> h;
  SurfaceMap m;
  MapSections sections;
  m.map_ = PoseMap::load(path, kKind, h, &sections);
  m.room_ = detail::room_of_sections(sections, path);
  using detail::header_string;
  m.provenance_ = detail::header_provenance(h, path);
  m.stats_.surface_points = detail::header_u64(h, "surface_points", path);
  m.stats_.candidate_poses = detail::header_u64(h, "candidate_poses", path);
  m.stats_.valid_poses = detail::header_u64(h, "valid_poses", path);
  m.reference_frame_ = header_string(h, "reference_frame", path);
  m.arms_ = header_string(h, "arms", path);
  // Files written before the approach axis was recorded have no such line.
  if (auto it = h.find("approach_axes"); it != h.end()) m.approach_axes_ = it->second;
  m.grasp_name_ = header_string(h, "grasp_set", path);
  m.stats_.seconds = h.count("build_seconds") ? detail::header_double(h, "build_seconds", path) : 0.0;  // older files
  m.z_min_ = detail::header_double(h, "z_min", path);
  m.grasp_height_ = detail::header_double(h, "grasp_height", path);
  m.checks_ = header_string(h, "checks", path);
  if (auto it = h.find("weight"); it != h.end()) m.weight_ = it->second;
  m.stats_.body_collisions = detail::header_u64(h, "body_collisions", path);
  m.stats_.arm_rejections = detail::header_u64(h, "arm_rejections", path);
  m.z_max_ = detail::header_double(h, "z_max", path);
  std::istringstream poly(header_string(h, "polygon", path));
  double x, y, z;
  while (poly >> x >> y >> z) m.polygon_.emplace_back(x, y, z);
  bool finite = true;
  for (const auto& v : m.polygon_) finite = finite && v.allFinite();
  if (!(poly >> std::ws).eof() || m.polygon_.size() < 3 || !finite)
    throw FileError("'" + path + "' has a damaged polygon (at least 3 finite vertices expected)");
  if (!(m.z_min_ <= m.z_max_)) throw FileError("'" + path + "' has z_min > z_max (damaged header)");
  if (m.map_.voxel_count() == 0) m.empty_reason_ = "the map is empty";
  return m;
}

}  // namespace octoreach
