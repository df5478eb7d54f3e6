#include "octoreach/surface_map.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <fcl/fcl.h>

#include "common/cancel.hpp"
#include "common/format.hpp"
#include "common/thread_pool.hpp"
#include "maps/map_io.hpp"
#include "common/vector_clones.hpp"
#include "maps/arm_clearance.hpp"
#include "maps/arm_obstacles.hpp"
#include "maps/batch.hpp"
#include "maps/cell_slots.hpp"
#include "maps/reach_extent.hpp"

namespace octoreach {
namespace {

// Base-position grid of a surface map: the octree keys kmin + (ix, iy, iz), T theta bins per cell,
// values [((ix * ny + iy) * nz + iz) * T + k].
struct SurfaceGrid {
  octomap::OcTreeKey kmin;
  int nx = 0, ny = 0, nz = 0, T = 0;
  std::vector<float> values;
  std::size_t cells() const { return static_cast<std::size_t>(nx) * ny * nz; }
  octomap::OcTreeKey key(int ix, int iy, int iz) const { return octomap::OcTreeKey(kmin[0] + ix, kmin[1] + iy, kmin[2] + iz); }
};

// What every theta bin of a build reads.
struct SurfaceBuild {
  const Robot& robot;
  const CapabilityMap& cap;
  const Surface& surface;
  const SurfaceMapOptions& o;
  const ArmPlacement& place;
  const VoxelOcTree& tree;          // of the map being built: key <-> coordinate
  std::vector<Eigen::Vector3d> targets;  // grasp points, grasp_height above the surface
  std::vector<Eigen::Vector2d> target_uv;
  Pose arm_from_reference;
  bool upright = false;             // arm frame upright and surface horizontal
  detail::ArmClearance* clearance = nullptr;
  std::shared_ptr<Obstacles> slab;        // the surface, its boxes and the rest of the room: the body check
  const detail::ArmObstacles* obstacles = nullptr;  // its boxes and the rest of the room: the arm check
  const detail::CellSlots* slots = nullptr;  // the cells the arm checks read (check_arm only)
};

struct BinCounts {
  std::size_t candidates = 0, valid = 0, body = 0, arm = 0;
};

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

// The surface seen from the arm frame at one yaw: grasp orientations, plane axes, and for a convex
// outline its half-planes h . uv <= c as g . w <= c - h . uv_target (g = A^T h). In the upright case
// g is horizontal, so a low set's direction summary can show at once that every witness point lies
// outside one edge.
struct BinFrame {
  double theta;
  Eigen::Matrix3d Rz;
  Eigen::Vector3d n_arm;
  Eigen::Matrix<float, 2, 3> Af;
  std::vector<int> mapped;
  std::vector<Eigen::Vector3f> g;
  std::vector<int> g_dir;
  std::vector<float> g_norm, g_slack;
  bool fast = false;

  BinFrame(const SurfaceBuild& b, int k) {
    const Surface& surf = b.surface;
    const OrientationSet& set = b.cap.orientations();
    theta = 2.0 * M_PI * k / b.o.theta_bins;
    Rz = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Matrix3d M = Rz * b.place.reference_to_arm.linear();  // arm frame -> world rotation
    n_arm = M.transpose() * surf.normal();
    Eigen::Matrix<double, 2, 3> A;
    A.row(0) = (M.transpose() * surf.u_axis()).transpose();
    A.row(1) = (M.transpose() * surf.v_axis()).transpose();
    Af = A.cast<float>();
    for (int o : b.place.grasps.orientations) {
      Eigen::Matrix3d Rw = set.rotation(o, b.cap.approach_axis());
      mapped.push_back(set.nearest(M.transpose() * Rw, b.cap.approach_axis()));
    }
    const auto& hp = surf.halfplanes();
    g.resize(hp.size());
    g_dir.resize(hp.size());
    g_norm.resize(hp.size());
    g_slack.resize(hp.size());
    for (std::size_t j = 0; j < hp.size(); ++j) {
      g[j] = (A.transpose() * hp[j].head<2>()).cast<float>();
      double phi = std::atan2(g[j].y(), g[j].x());
      double step = 2 * M_PI / detail::LowSet::kDirs;
      long kk = std::lround(phi / step);
      g_dir[j] = static_cast<int>(((kk % detail::LowSet::kDirs) + detail::LowSet::kDirs) % detail::LowSet::kDirs);
      g_norm[j] = g[j].head<2>().norm();
      g_slack[j] = static_cast<float>(std::abs(phi - kk * step)) + 1e-6f;
    }
    fast = b.upright && surf.convex();
  }

  // Fast path: a bound of the low set along half-plane j's direction; every witness point lies outside
  // that edge when it exceeds d[j].
  float bound(const detail::LowSetRef& low, std::size_t j) const {
    return g_norm[j] * (low.min_proj[g_dir[j]] - g_slack[j] * low.r_max);
  }

  // Fast path: true when one of the points lies inside every half-plane. Blocks of eight points are
  // tested against every half-plane at once (the compiler vectorises it); the products and sums are
  // Eigen's dot product's, x + (y + z), so the answers are the same. NH: the number of half-planes
  // when known at compile time (the loops unrolled), 0 for any.
  template <std::size_t NH = 0>
  OCTOREACH_VECTOR_CLONES bool any_inside(const Eigen::Vector3f* points, std::uint32_t count, const float* d) const {
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points are read as a flat float array");
    constexpr std::uint32_t kBlock = 8;
    const std::size_t nh = NH ? NH : g.size();
    std::uint32_t p = 0;
    for (; p + kBlock <= count; p += kBlock) {
      const float* w = points[p].data();
      float x[kBlock], y[kBlock], z[kBlock];  // the block's coordinates side by side (vector lanes)
      std::int32_t in[kBlock];
      for (std::uint32_t i = 0; i < kBlock; ++i) {
        x[i] = w[3 * i];
        y[i] = w[3 * i + 1];
        z[i] = w[3 * i + 2];
        in[i] = -1;
      }
      for (std::size_t j = 0; j < nh; ++j) {
        const float gx = g[j].x(), gy = g[j].y(), gz = g[j].z(), dj = d[j];
        for (std::uint32_t i = 0; i < kBlock; ++i) in[i] &= -static_cast<std::int32_t>(gx * x[i] + (gy * y[i] + gz * z[i]) <= dj);
      }
      std::int32_t any = 0;
      for (std::uint32_t i = 0; i < kBlock; ++i) any |= in[i];
      if (any) return true;
    }
    for (; p < count; ++p) {
      bool inside = true;
      for (std::size_t j = 0; j < nh && inside; ++j) inside = g[j].dot(points[p]) <= d[j];
      if (inside) return true;
    }
    return false;
  }

  // True when a witness point of `low` lies under the surface outline. d[j] = c_j - h_j . uv_target (fast path).
  bool arm_under(const SurfaceBuild& b, const detail::LowSetRef& low, const Eigen::Vector2d& target_uv,
                 const float* d) const {
    if (!fast) {
      for (std::uint32_t p = 0; p < low.count; ++p)
        if (b.surface.contains(target_uv + (Af * low.points[p]).cast<double>())) return true;
      return false;
    }
    bool all_outside = low.count == 0;
    for (std::size_t j = 0; j < g.size() && !all_outside; ++j) all_outside = bound(low, j) > d[j];
    if (all_outside) return false;
    return any_inside(low.points, low.count, d);
  }
};

// The arm-check cells of one theta bin (upright arm, convex outline), packed record by record: for
// each record of the CellSlots and each grasp of the bin, the slot, where its low set lies and the
// low set's bounds along the half-planes. A candidate then reads one short run of memory instead of a
// scattered low set per grasp (the build was bound by those memory reads), and tests the bounds of
// all grasps of its record in one pass (grasps side by side: the compiler vectorises it). The bounds
// are the ones arm_under computes, so the answers are the same.
struct PackedBin {
  struct Entry {
    std::int32_t slot;  // CellSlots::kNone: no stored solution there
    std::uint32_t first, count;  // the low set's points in ArmClearance::shared_points()
  };
  // The first kNear points of each low set (the nearest to the target, which end most tests) are
  // kept beside the bounds as their products with the half-planes, g_j . w (the values any_inside
  // compares), so a test of them is nh comparisons per point. A missing point or bound is +inf (a
  // missing point is never inside; no low set means every point outside).
  static constexpr std::uint32_t kNear = 2;
  enum State : std::int32_t { kOutside = 0, kUnder = 1, kUndecided = 2 };
  std::size_t G = 0, nh = 0;
  std::vector<Entry> entries;  // [local record * G + grasp]
  std::vector<float> bounds;   // [(local record * nh + half-plane) * G + grasp]
  std::vector<float> near;     // [((local record * kNear + point) * nh + half-plane) * G + grasp]

  // Per grasp of record `local` at a target (d): kOutside when a bound puts every witness point
  // outside an edge, else kUnder when one of the first kNear points lies inside every half-plane,
  // else kUndecided (the remaining points decide). NH as in BinFrame::any_inside.
  template <std::size_t NH = 0>
  OCTOREACH_VECTOR_CLONES void classify(std::size_t local, const float* d, std::int32_t* state) const {
    const std::size_t n = NH ? NH : nh;
    const float* B = bounds.data() + local * n * G;
    const float* P = near.data() + local * kNear * n * G;
    for (std::size_t m = 0; m < G; ++m) {  // branch-free masks (-1: true), vectorised over the grasps
      std::int32_t outside = 0, under = 0;
      for (std::size_t j = 0; j < n; ++j) outside |= -static_cast<std::int32_t>(B[j * G + m] > d[j]);
      for (std::uint32_t p = 0; p < kNear; ++p) {
        std::int32_t inside = -1;
        for (std::size_t j = 0; j < n; ++j) inside &= -static_cast<std::int32_t>(P[(p * n + j) * G + m] <= d[j]);
        under |= inside;
      }
      state[m] = ~outside & (kUndecided + under);  // kOutside, else kUnder (under = -1) or kUndecided
    }
  }

  PackedBin(const SurfaceBuild& b, const BinFrame& f) : G(f.mapped.size()), nh(f.g.size()) {
    const auto& records = b.slots->records();
    constexpr float kInf = std::numeric_limits<float>::infinity();
    entries.resize(records.size() * G);
    bounds.assign(entries.size() * nh, kInf);
    near.assign(entries.size() * kNear * nh, kInf);
    for (std::size_t l = 0; l < records.size(); ++l)
      for (std::size_t m = 0; m < G; ++m) {
        const std::size_t e = l * G + m;
        const std::int32_t slot = b.slots->slot(records[l].rec, f.mapped[m]);
        if (slot < 0) {
          if (b.cap.record_has(records[l].rec, f.mapped[m]))
            throw std::logic_error("surface map: capability cell outside the precomputed layers");
          entries[e] = {slot, 0, 0};
          continue;
        }
        entries[e] = {slot, b.clearance->shared_start(slot), b.clearance->shared_count(slot)};
        const detail::LowSetRef low = b.clearance->shared(slot);
        for (std::size_t j = 0; j < nh && low.count > 0; ++j) bounds[(l * nh + j) * G + m] = f.bound(low, j);
        for (std::uint32_t p = 0; p < std::min(low.count, kNear); ++p)
          for (std::size_t j = 0; j < nh; ++j) near[((l * kNear + p) * nh + j) * G + m] = f.g[j].dot(low.points[p]);
      }
  }
};

// A (base position, target) pair of a theta bin whose target falls in a capability voxel.
struct Candidate {
  std::uint32_t cell;  // index into the grid's cells
  std::uint32_t target;
  std::uint32_t rec;   // the capability record
};

// R_S of every base position of the grid at theta bin k, into g.values. Each bin owns its cache of
// low sets (non-upright case), so no locking is needed and the result does not depend on the thread count.
//
// The candidates of a block of grid rows are collected first, then evaluated record by record (the
// arm-check data of one capability voxel, its low sets and arm boxes, stays in cache over the few
// hundred targets that reach it; in grid order every candidate read another voxel's data), and last
// summed per base position in grid and target order, so the sums, and the bytes, are those of a
// position-by-position evaluation.
BinCounts evaluate_bin(const SurfaceBuild& b, int k, SurfaceGrid& g) {
  const BinFrame f(b, k);
  const auto& hp = b.surface.halfplanes();
  const std::size_t nh = hp.size(), N = b.targets.size();
  std::unordered_map<std::uint64_t, detail::LowSet> own_low;
  std::vector<Pose> poses;
  detail::ArmScratch arm_scratch;
  auto low_points = [&](std::uint32_t rec, int orient, std::int32_t slot, const Eigen::Vector3d& centre) -> detail::LowSetRef {
    if (b.upright) return b.clearance->shared(slot);
    auto it = own_low.find(b.clearance->key(rec, orient));
    if (it != own_low.end()) return detail::LowSetRef::of(it->second);
    auto& out = own_low[b.clearance->key(rec, orient)];
    b.clearance->compute(rec, orient, centre, f.n_arm, poses, out);
    return detail::LowSetRef::of(out);
  };
  std::optional<PackedBin> packed;
  if (b.o.check_arm && b.upright && f.fast) packed.emplace(b, f);
  const Eigen::Vector3f* shared_points = packed ? b.clearance->shared_points() : nullptr;
  // Fast path: d[j] = c_j - h_j . uv of each target, nh values per target.
  std::vector<float> dtab(f.fast ? N * nh : 0);
  if (f.fast)
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < nh; ++j)
        dtab[i * nh + j] = static_cast<float>(hp[j].z() - hp[j].head<2>().dot(b.target_uv[i]));
  BinCounts n;
  // Grasps of the bin that pass the arm checks at a candidate (the cell's record `r`, target i).
  auto plain_count = [&](std::uint32_t r, std::size_t i, const Eigen::Vector3d& centre, const Pose& world_from_arm,
                         const detail::NearObstacles& near) {
    const float* d = f.fast ? dtab.data() + i * nh : nullptr;
    int count = 0;
    for (int mo : f.mapped) {
      if (!b.cap.record_has(r, mo)) continue;
      if (!b.o.check_arm) {
        ++count;
        continue;
      }
      const std::int32_t slot = b.slots->slot(r, mo);
      if (slot < 0) throw std::logic_error("surface map: capability cell outside the precomputed layers");
      const bool ok = !f.arm_under(b, low_points(r, mo, slot, centre), b.target_uv[i], d) &&
                      !b.obstacles->collides(slot, near, world_from_arm, arm_scratch);
      if (!ok) ++n.arm;
      count += ok;
    }
    return count;
  };
  // The same from the packed bin (`local`: the record's index in the CellSlots).
  std::vector<std::int32_t> state(packed ? packed->G : 0);
  auto packed_count = [&](std::int32_t local, std::size_t i, const Pose& world_from_arm, const detail::NearObstacles& near) {
    const float* d = dtab.data() + i * nh;
    const bool rectangle = nh == 4;  // the loops unrolled
    if (rectangle) packed->classify<4>(local, d, state.data());
    else packed->classify(local, d, state.data());
    const PackedBin::Entry* E = packed->entries.data() + static_cast<std::size_t>(local) * packed->G;
    int count = 0;
    for (std::size_t m = 0; m < packed->G; ++m) {
      if (E[m].slot < 0) continue;
      bool under = state[m] == PackedBin::kUnder;
      if (state[m] == PackedBin::kUndecided) {
        const std::uint32_t in_near = std::min(E[m].count, PackedBin::kNear), c = E[m].count - in_near;
        const Eigen::Vector3f* rest = shared_points + E[m].first + in_near;
        under = rectangle ? f.any_inside<4>(rest, c, d) : f.any_inside(rest, c, d);
      }
      const bool ok = !under && !b.obstacles->collides(E[m].slot, near, world_from_arm, arm_scratch);
      if (!ok) ++n.arm;
      count += ok;
    }
    return count;
  };
  const double inv_g = 1.0 / b.place.grasps.orientations.size(), inv_n = 1.0 / b.targets.size();
  // Per base position of the block: its arm pose and the obstacles near the arm there.
  const std::size_t row = static_cast<std::size_t>(g.ny) * g.nz;
  std::vector<Eigen::Vector3d> bases;
  std::vector<Pose, Eigen::aligned_allocator<Pose>> world_from_arm;
  std::vector<detail::NearObstacles> near;
  std::vector<Candidate> cands;
  std::vector<Eigen::Vector3d> centres;  // voxel centres of the candidates (not upright only)
  std::vector<std::uint32_t> keys, key_start;
  std::vector<std::pair<Candidate, std::uint32_t>> sorted;  // the candidates by key, with their index
  std::vector<std::uint32_t> counts;     // valid grasps of each candidate
  constexpr std::size_t kBlockCandidates = std::size_t(1) << 20;
  for (int ix0 = 0; ix0 < g.nx;) {
    // A block of whole grid rows ix0 .. ix1 - 1 with at most about kBlockCandidates candidates.
    const std::size_t cell0 = static_cast<std::size_t>(ix0) * row;
    cands.clear();
    centres.clear();
    bases.clear();
    world_from_arm.clear();
    near.clear();
    int ix1 = ix0;
    for (; ix1 < g.nx && (ix1 == ix0 || cands.size() < kBlockCandidates); ++ix1)
      for (int iy = 0; iy < g.ny; ++iy, detail::poll_cancel("surface map build cancelled"))
        for (int iz = 0; iz < g.nz; ++iz) {
          const auto cell = static_cast<std::uint32_t>((static_cast<std::size_t>(ix1) * g.ny + iy) * g.nz + iz);
          octomap::point3d bc = b.tree.keyToCoord(g.key(ix1, iy, iz));
          // Heights are evaluated inside the z range: a robot on the floor (z range (0, 0)) is
          // evaluated at z = 0 exactly and stored in the voxel holding 0.
          const Eigen::Vector3d bs(bc.x(), bc.y(), std::min(std::max(double(bc.z()), b.o.z_min), b.o.z_max));
          bases.push_back(bs);
          world_from_arm.push_back(base_pose(bs.x(), bs.y(), bs.z(), f.theta) * b.place.reference_to_arm);
          near.emplace_back();
          if (b.o.check_arm) b.obstacles->near(world_from_arm.back(), near.back());
          for (std::size_t i = 0; i < N; ++i) {
            Eigen::Vector3d in_ref = f.Rz.transpose() * (b.targets[i] - bs);
            Eigen::Vector3d p = b.arm_from_reference * in_ref + target_offset();
            Eigen::Vector3d centre;
            // The voxel centre serves the low sets computed per bin (not upright) only.
            std::int64_t rec = b.cap.record_at(p, b.upright ? nullptr : &centre);
            if (rec < 0) continue;
            cands.push_back({cell, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(rec)});
            if (!b.upright) centres.push_back(centre);
          }
        }
    n.candidates += cands.size();
    // Record by record (within a record in grid order: the answers do not depend on the order), by a
    // counting sort that moves the candidates themselves (reading them through a sorted index missed
    // the cache at every candidate).
    keys.resize(cands.size());
    std::uint32_t key_end = 0;
    for (std::size_t c = 0; c < cands.size(); ++c) {
      const std::int32_t local = packed ? b.slots->local(cands[c].rec) : -1;
      // Packed records first, by their index in the CellSlots; the others by record.
      keys[c] = local >= 0 ? static_cast<std::uint32_t>(local)
                           : static_cast<std::uint32_t>(packed ? b.slots->records().size() : 0) + cands[c].rec;
      key_end = std::max(key_end, keys[c] + 1);
    }
    key_start.assign(static_cast<std::size_t>(key_end) + 1, 0);
    for (std::uint32_t key : keys) ++key_start[key + 1];
    for (std::size_t key = 0; key < key_end; ++key) key_start[key + 1] += key_start[key];
    sorted.resize(cands.size());
    for (std::size_t c = 0; c < cands.size(); ++c) sorted[key_start[keys[c]]++] = {cands[c], static_cast<std::uint32_t>(c)};
    counts.assign(cands.size(), 0);
    std::size_t done = 0;
    for (const auto& [cd, c] : sorted) {
      if ((++done & 0xffff) == 0) detail::poll_cancel("surface map build cancelled");  // up to 2^20 per block
      const std::size_t at = cd.cell - cell0;
      const std::int32_t local = packed ? b.slots->local(cd.rec) : -1;
      const int count = local >= 0 ? packed_count(local, cd.target, world_from_arm[at], near[at])
                                   : plain_count(cd.rec, cd.target, b.upright ? Eigen::Vector3d::Zero() : centres[c],
                                                 world_from_arm[at], near[at]);
      counts[c] = static_cast<std::uint32_t>(count);
    }
    // Sums per base position, in target order.
    std::size_t c = 0;
    for (std::size_t at = 0; at < world_from_arm.size(); ++at) {
      const std::size_t cell = cell0 + at;
      double sum = 0;
      for (; c < cands.size() && cands[c].cell == cell; ++c)
        if (counts[c]) {
          ++n.valid;
          sum += counts[c] * inv_g;
        }
      if (sum <= 0) continue;
      const Eigen::Vector3d& bs = bases[at];
      if (b.o.check_body &&
          b.robot.links_in_collision(b.place.link_poses, *b.slab, b.place.root_pose(bs.x(), bs.y(), bs.z(), f.theta),
                                     &b.place.roles.body)) {
        ++n.body;
        continue;
      }
      g.values[cell * g.T + k] = static_cast<float>(sum * inv_n);
    }
    ix0 = ix1;
  }
  return n;
}

void check_options(const CapabilityMap& cap, const SurfaceMapOptions& o) {
  if (o.check_arm && !cap.has_solutions())
    throw std::invalid_argument("the capability map holds no joint solutions (build it with keep_solutions=True "
                                "or save it with_solutions) : the surface map checks the arm against the surface");
  if (o.theta_bins < 1 || o.theta_bins > 360) throw std::invalid_argument("theta_bins must be in [1, 360]");
  const double res = o.resolution == 0 ? cap.resolution() : o.resolution;
  if (!(res > 0) || !std::isfinite(res)) throw std::invalid_argument("resolution must be positive");
  // Not strict, unlike the point map: poses are evaluated at heights clipped into the range, so
  // (0, 0) is one exact height (a robot on the floor).
  if (!(o.z_min <= o.z_max)) throw std::invalid_argument("z_min must not exceed z_max");
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
  m.robot_name_ = robot.name();
  m.urdf_hash_ = robot.urdf_hash();
  m.model_hash_ = robot.model_hash();
  m.reference_frame_ = place.reference_frame;
  m.arms_ = cap.base_link() + "->" + cap.tip_link();
  m.approach_axes_ = detail::format_vector(cap.approach_axis());
  m.polygon_ = surface.vertices();
  m.z_min_ = o.z_min;
  m.z_max_ = o.z_max;
  m.grasp_height_ = o.grasp_height;
  m.checks_ = std::string(o.check_body ? "body" : "") + (o.check_body && o.check_arm ? "+" : "") + (o.check_arm ? "arm" : "");
  if (o.obstacles && !o.obstacles->empty()) m.checks_ += " (room: " + std::to_string(o.obstacles->size()) + " obstacles)";
  m.map_ = PoseMap(res, o.theta_bins);
  m.grasp_name_ = place.grasps.name;
  if (!(o.grasp_height >= 0) || !std::isfinite(o.grasp_height))
    throw std::invalid_argument("grasp_height must be zero or positive");

  SurfaceBuild b{robot, cap, surface, o, place, m.map_.tree(), surface.sample_points(res), {},
                 place.reference_to_arm.inverse(), false, nullptr, surface.obstacles()};
  // Every obstacle but the slab meets the arm at its stored solutions (the slab has the finer
  // "arm under the outline" test); the body meets them all.
  auto others = std::make_shared<Obstacles>();
  for (const auto& [size, pose] : surface.boxes()) others->add_box(size, pose, "surface_box");
  if (o.obstacles) {
    others->add(*o.obstacles);
    b.slab->add(*o.obstacles);
  }
  for (auto& t : b.targets) t += o.grasp_height * surface.normal();
  m.stats_.surface_points = b.targets.size();
  SurfaceGrid g;
  m.empty_reason_ = b.targets.empty()
                        ? "the surface holds no grid point at this resolution (polygon smaller than one cell)"
                        : make_grid(b, res, g);
  if (!m.empty_reason_.empty()) {
    m.map_.finalize();
    return m;
  }
  for (const auto& t : b.targets) b.target_uv.push_back(surface.project(t));
  b.upright = std::abs(place.reference_to_arm.linear()(2, 2) - 1.0) < 1e-9 && std::abs(surface.normal().z() - 1.0) < 1e-9;
  detail::ArmClearance clearance(robot, cap, place, o.grasp_height);
  b.clearance = &clearance;
  std::shared_ptr<const detail::CellSlots> slots;
  std::unique_ptr<const detail::ArmObstacles> arm_obstacles;
  if (o.check_arm) {
    // The cells a build can read: the orientations the grasps map to at some theta bin, and in the
    // upright case the records of the heights the targets have in the arm frame.
    std::vector<char> wanted(cap.orientations().size(), 0);
    for (int k = 0; k < o.theta_bins; ++k)
      for (int mo : BinFrame(b, k).mapped) wanted[mo] = 1;
    if (b.upright) {
      auto [za_lo, za_hi] = target_heights_in_arm(b, g);
      slots = std::make_shared<const detail::CellSlots>(cap, wanted, za_lo, za_hi);
      clearance.compute_shared(*slots, o.threads);
    } else {
      slots = std::make_shared<const detail::CellSlots>(cap, wanted);
    }
    b.slots = slots.get();
    arm_obstacles = std::make_unique<const detail::ArmObstacles>(robot, cap, place, others, slots, o.threads);
    b.obstacles = arm_obstacles.get();
  }

  const int T = o.theta_bins;
  std::atomic<std::size_t> bins_done{0}, candidates{0}, valid{0}, body_hits{0}, arm_hits{0};
  detail::parallel_for(T, o.threads, [&](std::size_t k, int tid) {
    BinCounts n = evaluate_bin(b, static_cast<int>(k), g);
    candidates += n.candidates;
    valid += n.valid;
    body_hits += n.body;
    arm_hits += n.arm;
    std::size_t finished = ++bins_done;
    if (progress && tid == 0 && !progress(finished, T)) throw Cancelled("surface map build cancelled");
  }, 1);

  const std::size_t ncells = g.cells();
  for (std::size_t c = 0; c < ncells; ++c) {
    if ((c & 0xffff) == 0) detail::poll_cancel("surface map build cancelled");
    const float* v = g.values.data() + c * T;
    if (*std::max_element(v, v + T) <= 0) continue;
    int iz = c % g.nz, iy = (c / g.nz) % g.ny, ix = c / (static_cast<std::size_t>(g.ny) * g.nz);
    m.map_.set_voxel(g.key(ix, iy, iz), v);
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

void SurfaceMap::reachability(const double* rows, std::size_t n, double* out) const {
  detail::batch_lookup_finite(rows, n, 4, "base pose", " (x, y, z, theta in m and rad)", [&](std::size_t i) {
    const double* r = rows + 4 * i;
    out[i] = reachability(r[0], r[1], r[2], r[3]);
  });
}

SurfaceMap SurfaceMap::combine(const std::vector<const SurfaceMap*>& maps, const std::string& mode) {
  if (maps.empty()) throw std::invalid_argument("combine needs at least one map");
  if (mode != "max" && mode != "min") throw std::invalid_argument("mode must be 'max' or 'min', got '" + mode + "'");
  const SurfaceMap& first = *maps[0];
  for (const SurfaceMap* m : maps) {
    if (m->robot_name_ != first.robot_name_ || m->urdf_hash_ != first.urdf_hash_ || m->model_hash_ != first.model_hash_)
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
  out.model_hash_ = first.model_hash_;
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
  return {{"robot", robot_name_},
          {"urdf_hash", std::to_string(urdf_hash_)},
          {"model_hash", std::to_string(model_hash_)},
          {"reference_frame", reference_frame_},
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
          {"valid_poses", std::to_string(stats_.valid_poses)}};  // no timing: the same build gives the same bytes
}

void SurfaceMap::save(const std::string& path) const { map_.save(path, "surface", parameters()); }

SurfaceMap SurfaceMap::load(const std::string& path) {
  std::map<std::string, std::string> h;
  SurfaceMap m;
  m.map_ = PoseMap::load(path, "surface", h);
  using detail::header_string;
  m.robot_name_ = header_string(h, "robot", path);
  m.urdf_hash_ = detail::header_u64(h, "urdf_hash", path);
  m.model_hash_ = detail::header_model_hash(h, path);
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
