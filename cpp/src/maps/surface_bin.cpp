// One theta bin of a surface map build: the surface seen from the arm frame at the bin's yaw, the packed
// arm-check data of the bin, and the evaluation of every base position of the grid.
#include "maps/surface_bin.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "common/cancel.hpp"
#include "common/vector_clones.hpp"

namespace octoreach {
namespace {

using detail::BinCounts;
using detail::SurfaceBuild;
using detail::SurfaceGrid;

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
// What a valid grasp of capability cell (rec, orientation) counts in R_P: 1 (the paper's), or with quality_weight
// its cell's quality relative to the capability map's best cell.
inline float grasp_weight(const SurfaceBuild& b, std::uint32_t rec, int orientation) {
  return b.o.quality_weight ? static_cast<float>(b.cap.relative_quality(rec, orientation)) : 1.0f;
}

struct PackedBin {
  struct Entry {
    std::int32_t slot;  // CellSlots::kNone: no stored solution there
    std::uint32_t first, count;  // the low set's points in ArmClearance::shared_points()
    float weight;       // what a valid grasp counts (grasp_weight)
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
          entries[e] = {slot, 0, 0, 0.0f};
          continue;
        }
        entries[e] = {slot, b.clearance->shared_start(slot), b.clearance->shared_count(slot),
                      grasp_weight(b, records[l].rec, f.mapped[m])};
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

// The grasps of a theta bin that pass the arm checks at a candidate (base position, target): from the
// packed bin where the candidate's record is packed, else cell by cell. Each bin owns one: its cache of
// low sets (non-upright case) and its scratch, so no locking is needed and the result does not depend on
// the thread count.
class GraspCounter {
 public:
  GraspCounter(const SurfaceBuild& b, const BinFrame& f) : b_(b), f_(f), nh_(b.surface.halfplanes().size()) {
    if (b.o.check_arm && b.upright && f.fast) packed_.emplace(b, f);
    shared_points_ = packed_ ? b.clearance->shared_points() : nullptr;
    state_.resize(packed_ ? packed_->G : 0);
    // Fast path: d[j] = c_j - h_j . uv of each target, nh values per target.
    const auto& hp = b.surface.halfplanes();
    const std::size_t N = b.targets.size();
    dtab_.resize(f.fast ? N * nh_ : 0);
    if (f.fast)
      for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = 0; j < nh_; ++j)
          dtab_[i * nh_ + j] = static_cast<float>(hp[j].z() - hp[j].head<2>().dot(b.target_uv[i]));
  }

  bool packed() const { return packed_.has_value(); }
  // The record's index in the packed bin's CellSlots, or -1 when it is not packed.
  std::int32_t local(std::uint32_t rec) const { return packed_ ? b_.slots->local(rec) : -1; }
  // Grasps rejected for the arm so far.
  std::size_t arm_rejections() const { return arm_; }

  // Cell by cell: the grasps of the bin that the capability record `r` holds and that pass the arm
  // checks at target i (`centre`: the record's voxel centre, read in the non-upright case only).
  float plain_count(std::uint32_t r, std::size_t i, const Eigen::Vector3d& centre, const Pose& world_from_arm,
                    const detail::NearObstacles& near) {
    const float* d = f_.fast ? dtab_.data() + i * nh_ : nullptr;
    float count = 0;  // whole numbers without quality weights: exact in a float
    for (int mo : f_.mapped) {
      if (!b_.cap.record_has(r, mo)) continue;
      if (!b_.o.check_arm) {
        count += grasp_weight(b_, r, mo);
        continue;
      }
      const std::int32_t slot = b_.slots->slot(r, mo);
      if (slot < 0) throw std::logic_error("surface map: capability cell outside the precomputed layers");
      const bool ok = !f_.arm_under(b_, low_points(r, mo, slot, centre), b_.target_uv[i], d) &&
                      !b_.obstacles->collides(slot, near, world_from_arm, scratch_);
      if (!ok) ++arm_;
      if (ok) count += grasp_weight(b_, r, mo);
    }
    return count;
  }

  // The same from the packed bin (`local`: the record's index in the CellSlots).
  float packed_count(std::int32_t local, std::size_t i, const Pose& world_from_arm, const detail::NearObstacles& near) {
    const float* d = dtab_.data() + i * nh_;
    const bool rectangle = nh_ == 4;  // the loops unrolled
    if (rectangle) packed_->classify<4>(local, d, state_.data());
    else packed_->classify(local, d, state_.data());
    const PackedBin::Entry* E = packed_->entries.data() + static_cast<std::size_t>(local) * packed_->G;
    float count = 0;
    for (std::size_t m = 0; m < packed_->G; ++m) {
      if (E[m].slot < 0) continue;
      bool under = state_[m] == PackedBin::kUnder;
      if (state_[m] == PackedBin::kUndecided) {
        const std::uint32_t in_near = std::min(E[m].count, PackedBin::kNear), c = E[m].count - in_near;
        const Eigen::Vector3f* rest = shared_points_ + E[m].first + in_near;
        under = rectangle ? f_.any_inside<4>(rest, c, d) : f_.any_inside(rest, c, d);
      }
      const bool ok = !under && !b_.obstacles->collides(E[m].slot, near, world_from_arm, scratch_);
      if (!ok) ++arm_;
      if (ok) count += E[m].weight;
    }
    return count;
  }

 private:
  // The witness points of cell (rec, orient): shared in the upright case, else computed once per bin.
  detail::LowSetRef low_points(std::uint32_t rec, int orient, std::int32_t slot, const Eigen::Vector3d& centre) {
    if (b_.upright) return b_.clearance->shared(slot);
    auto it = own_low_.find(b_.clearance->key(rec, orient));
    if (it != own_low_.end()) return detail::LowSetRef::of(it->second);
    auto& out = own_low_[b_.clearance->key(rec, orient)];
    b_.clearance->compute(rec, orient, centre, f_.n_arm, poses_, out);
    return detail::LowSetRef::of(out);
  }

  const SurfaceBuild& b_;
  const BinFrame& f_;
  const std::size_t nh_;
  std::optional<PackedBin> packed_;
  const Eigen::Vector3f* shared_points_ = nullptr;
  std::vector<float> dtab_;
  std::vector<std::int32_t> state_;
  std::unordered_map<std::uint64_t, detail::LowSet> own_low_;
  std::vector<Pose> poses_;
  detail::ArmScratch scratch_;
  std::size_t arm_ = 0;
};

// A block of whole grid rows of a theta bin: its candidates and, per base position, the arm pose and the
// obstacles near the arm there.
//
// The candidates of a block are collected first, then evaluated record by record (the arm-check data of
// one capability voxel, its low sets and arm boxes, stays in cache over the few hundred targets that
// reach it; in grid order every candidate read another voxel's data), and last summed per base position
// in grid and target order, so the sums, and the bytes, are those of a position-by-position evaluation.
struct BinBlock {
  static constexpr std::size_t kCandidates = std::size_t(1) << 20;  // at most about this many per block
  std::size_t cell0 = 0;  // the block's first cell
  std::vector<Eigen::Vector3d> bases;
  std::vector<Pose, Eigen::aligned_allocator<Pose>> world_from_arm;
  std::vector<detail::NearObstacles> near;
  std::vector<Candidate> cands;
  std::vector<Eigen::Vector3d> centres;  // voxel centres of the candidates (not upright only)
  std::vector<std::uint32_t> keys, key_start;
  std::vector<std::pair<Candidate, std::uint32_t>> sorted;  // the candidates by key, with their index
  std::vector<float> counts;             // valid grasps of each candidate (their weights' sum)

  // Collects the rows ix0 .. ix1 - 1 (at least one, at most about kCandidates candidates); returns ix1.
  int collect(const SurfaceBuild& b, const BinFrame& f, const SurfaceGrid& g, int ix0) {
    const std::size_t row = static_cast<std::size_t>(g.ny) * g.nz, N = b.targets.size();
    cell0 = static_cast<std::size_t>(ix0) * row;
    cands.clear();
    centres.clear();
    bases.clear();
    world_from_arm.clear();
    near.clear();
    int ix1 = ix0;
    for (; ix1 < g.nx && (ix1 == ix0 || cands.size() < kCandidates); ++ix1)
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
    return ix1;
  }

  // Record by record (within a record in grid order: the answers do not depend on the order), by a
  // counting sort that moves the candidates themselves (reading them through a sorted index missed the
  // cache at every candidate).
  void sort_by_record(const SurfaceBuild& b, const GraspCounter& counter) {
    keys.resize(cands.size());
    std::uint32_t key_end = 0;
    for (std::size_t c = 0; c < cands.size(); ++c) {
      const std::int32_t local = counter.local(cands[c].rec);
      // Packed records first, by their index in the CellSlots; the others by record.
      keys[c] = local >= 0 ? static_cast<std::uint32_t>(local)
                           : static_cast<std::uint32_t>(counter.packed() ? b.slots->records().size() : 0) + cands[c].rec;
      key_end = std::max(key_end, keys[c] + 1);
    }
    key_start.assign(static_cast<std::size_t>(key_end) + 1, 0);
    for (std::uint32_t key : keys) ++key_start[key + 1];
    for (std::size_t key = 0; key < key_end; ++key) key_start[key + 1] += key_start[key];
    sorted.resize(cands.size());
    for (std::size_t c = 0; c < cands.size(); ++c) sorted[key_start[keys[c]]++] = {cands[c], static_cast<std::uint32_t>(c)};
  }

  // The valid grasps of every candidate, in sorted order.
  void count_grasps(const SurfaceBuild& b, GraspCounter& counter) {
    counts.assign(cands.size(), 0);
    std::size_t done = 0;
    for (const auto& [cd, c] : sorted) {
      if ((++done & 0xffff) == 0) detail::poll_cancel("surface map build cancelled");  // up to 2^20 per block
      const std::size_t at = cd.cell - cell0;
      const std::int32_t local = counter.local(cd.rec);
      counts[c] = local >= 0 ? counter.packed_count(local, cd.target, world_from_arm[at], near[at])
                             : counter.plain_count(cd.rec, cd.target, b.upright ? Eigen::Vector3d::Zero() : centres[c],
                                                   world_from_arm[at], near[at]);
    }
  }

  // Sums per base position, in target order, into theta bin k of the grid; a base position where the
  // body touches the surface or the room is rejected.
  void sum_into(const SurfaceBuild& b, const BinFrame& f, int k, SurfaceGrid& g, BinCounts& n) const {
    const double inv_g = 1.0 / b.place.grasps.orientations.size(), inv_n = 1.0 / b.targets.size();
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
  }
};

}  // namespace

namespace detail {

std::vector<int> bin_orientations(const SurfaceBuild& b, int k) { return BinFrame(b, k).mapped; }

BinCounts evaluate_bin(const SurfaceBuild& b, int k, SurfaceGrid& g) {
  const BinFrame f(b, k);
  GraspCounter counter(b, f);
  BinCounts n;
  BinBlock block;
  for (int ix0 = 0; ix0 < g.nx;) {
    const int ix1 = block.collect(b, f, g, ix0);
    n.candidates += block.cands.size();
    block.sort_by_record(b, counter);
    block.count_grasps(b, counter);
    block.sum_into(b, f, k, g, n);
    ix0 = ix1;
  }
  n.arm = counter.arm_rejections();
  return n;
}

}  // namespace detail
}  // namespace octoreach
