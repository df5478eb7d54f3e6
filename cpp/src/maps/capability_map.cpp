#include "octoreach/capability_map.hpp"

#include <algorithm>
#include <array>
#include <bitset>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <random>
#include <unordered_set>


#include "common/cancel.hpp"
#include "common/checks.hpp"
#include "maps/map_io.hpp"
#include "maps/batch.hpp"
#include "maps/capability_build.hpp"
#include "maps/capability_cells.hpp"
#include "octoreach/manipulability.hpp"
#include "octoreach/capability_blocks.hpp"
#include "octoreach/arm.hpp"
#include "octoreach/chain.hpp"

namespace octoreach {

void CapabilityMap::set_parameters_(const CapabilityMapOptions& o) {
  resolution_ = o.resolution;
  approach_axis_ = o.approach_axis.normalized();
  self_collision_ = o.self_collision;
  seed_ = o.seed;
  exhaustive_ = o.exhaustive;
  block_size_ = std::max(0, o.block_size);
  position_tolerance_ = o.position_tolerance;
  orientation_tolerance_ = o.orientation_tolerance;
}

namespace {

void check_options(const Chain& chain, const CapabilityMapOptions& o) {
  detail::check_map_resolution(o.resolution);  // the range load() accepts
  detail::check_finite(o.approach_axis, "approach_axis");
  if (o.approach_axis.norm() < 1e-9) throw std::invalid_argument("approach_axis must be a non-zero vector");
  if (chain.dof() == 0) throw std::invalid_argument("the chain has no moving joints");
  detail::check_positive(o.position_tolerance, "position_tolerance");
  detail::check_positive(o.orientation_tolerance, "orientation_tolerance");
  if (o.fk_samples > limits::kFkSamples)
    throw std::invalid_argument("fk_samples must be at most " + std::to_string(limits::kFkSamples) + ", got " +
                                std::to_string(o.fk_samples));
  if (o.block_size < 0 || o.block_size > 4096)
    throw std::invalid_argument("block_size must be 0 (one flood over the whole box) or voxels per block edge "
                                "(1 to 4096), got " + std::to_string(o.block_size));
}

}  // namespace

CapabilityMap CapabilityMap::shell_(const Chain& chain, const CapabilityMapOptions& o, Eigen::VectorXd& reference) {
  check_options(chain, o);
  const Robot& robot = chain.robot();
  CapabilityMap m;
  m.set_parameters_(o);
  m.orientations_ = OrientationSet::sphere(o.directions, o.rolls, o.symmetry);
  m.provenance_ = MapProvenance::of(robot);
  m.base_link_ = chain.base_link();
  m.tip_link_ = chain.tip_link();
  m.dof_ = chain.dof();
  m.words_ = (m.orientations_.size() + 63) / 64;
  m.tree_ = std::make_shared<VoxelOcTree>(o.resolution);
  m.cell_data_ = true;
  m.jacobian_rank_ = octoreach::jacobian_rank(chain);

  reference = reference_or_default(robot, chain, o.reference);
  m.reference_ = reference;
  if (o.self_collision) {
    std::vector<std::pair<int, int>> moving, fixed;
    chain.split_collision_pairs(moving, fixed);
    const std::vector<Pose> poses = robot.link_poses(reference);
    if (robot.in_self_collision_poses(poses, fixed)) {
      std::string names;
      for (auto [a, b] : robot.colliding_pairs(poses, fixed))
        names += (names.empty() ? "" : ", ") + robot.links()[a].name + "/" + robot.links()[b].name;
      throw std::invalid_argument(
          "the reference posture is in self-collision among links the chain does not move (" + names +
          "): allow these pairs (robot.with_sampled_collisions() samples the allowed-collision matrix as MoveIt's "
          "setup assistant does; robots.load() does it for robots without a complete SRDF; or "
          "robot.with_allowed_collisions([...]), or an SRDF with <disable_collisions>), or pass another reference "
          "posture (reference=...)");
    }
  }
  return m;
}

void CapabilityMap::add_voxel_(const octomap::OcTreeKey& key, const detail::VoxelCellData& cells) {
  append_record_(*tree_->touch(key), cells);
}

void CapabilityMap::append_record_(VoxelNode& leaf, const detail::VoxelCellData& cells) {
  const std::size_t count = cells.reachable_count();
  leaf.payload = static_cast<std::uint32_t>(sol_offset_.size());
  leaf.setValue(static_cast<float>(count) / orientations_.size());
  bits_.insert(bits_.end(), cells.bits.begin(), cells.bits.end());
  sol_offset_.push_back(stats_.reachable_cells);
  solutions_.insert(solutions_.end(), cells.solutions.begin(), cells.solutions.end());
  quality_.insert(quality_.end(), cells.quality.begin(), cells.quality.end());
  for (const CellQuality& q : cells.quality) max_quality_ = std::max(max_quality_, double(q.value()));
  if (cell_data_) {
    mixed_.insert(mixed_.end(), cells.mixed.begin(), cells.mixed.end());
    mixed_offset_.push_back(stats_.mixed_cells);
    mixed_solutions_.insert(mixed_solutions_.end(), cells.mixed_solutions.begin(), cells.mixed_solutions.end());
    stats_.mixed_cells += cells.mixed_count();
  }
  stats_.reachable_cells += count;
}

void CapabilityMap::finish_build_(std::size_t samples, std::size_t ik_calls, std::size_t cells, double seconds) {
  tree_->update_inner_values();
  finish_();
  fk_samples_ = samples;
  stats_.fk_samples = samples;
  stats_.ik_calls = ik_calls;
  stats_.cells = cells;
  stats_.seconds = seconds;
}

CapabilityMap CapabilityMap::build(const Chain& chain, const CapabilityMapOptions& o, const ProgressCallback& progress) {
  detail::CancellableScope cancellable;
  if (o.block_size > 0) return CapabilityBlocks(chain, o).build(progress);  // the block build (capability_blocks.hpp)
  const auto t_start = std::chrono::steady_clock::now();
  Eigen::VectorXd reference;
  CapabilityMap m = shell_(chain, o, reference);
  const int O = m.orientations_.size();
  const detail::CellBox box = detail::CellBox::around_workspace(chain, *m.tree_, O, o.seed);
  detail::CapabilityBuilder builder(chain, o, m.orientations_, m.approach_axis_, reference, box, progress);
  const std::size_t samples = builder.sample();
  builder.solve();

  builder.rate();
  // The octree and the per-voxel records, in voxel order.
  detail::VoxelCellData cells;
  for (std::size_t v = 0; v < box.voxels; ++v) {
    builder.collect(v, cells);
    if (!cells.empty()) m.add_voxel_(box.key(v), cells);
  }
  m.finish_build_(samples, builder.ik_calls(), box.cells,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count());
  builder.report(1.0, 0.0, 1.0);
  return m;
}

CapabilityMap CapabilityMap::build(const Robot& robot, const Arm& arm, const CapabilityMapOptions& options,
                                   const ProgressCallback& progress) {
  CapabilityMapOptions o = options;
  o.approach_axis = arm.approach_axis;
  return build(robot.chain(arm.base_link, arm.tip_link), o, progress);
}

void CapabilityMap::finish_() {
  d_.assign(sol_offset_.size(), 0.0f);
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it)
    if (it->payload != DenseIndex::kNone) d_[it->payload] = it->getValue();
  index_.build(*tree_);
  build_grid_();
  stats_.voxels = 0;
  for (float d : d_) stats_.voxels += d > 0;
}

namespace {
// Largest plain-lookup grid: 200 orientations over a box of 2.7 million voxels (a 2 m cube at 0.015 m); finer maps
// answer from their records.
constexpr std::size_t kGridBytes = std::size_t(64) << 20;
}  // namespace

void CapabilityMap::build_grid_() {
  grid_.clear();
  int lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};
  bool first = true;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (it->payload == DenseIndex::kNone) continue;
    for (int a = 0; a < 3; ++a) {
      const int k = it.getKey()[a];
      lo[a] = first ? k : std::min(lo[a], k);
      hi[a] = first ? k : std::max(hi[a], k);
    }
    first = false;
  }
  if (first) return;
  std::size_t bits = static_cast<std::size_t>(orientations_.size());
  for (int a = 0; a < 3; ++a) {
    grid_lo_[a] = lo[a] - 1;
    grid_dim_[a] = hi[a] - lo[a] + 3;
    bits *= static_cast<std::size_t>(grid_dim_[a]);
  }
  if (bits / 8 > kGridBytes) return;
  grid_.assign((bits + 63) / 64, 0);
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (it->payload == DenseIndex::kNone) continue;
    const std::uint64_t* w = bits_.data() + static_cast<std::size_t>(it->payload) * words_;
    for (int k = 0; k < words_; ++k)
      for (std::uint64_t b = w[k]; b; b &= b - 1) {
        const int o = 64 * k + __builtin_ctzll(b);
        const std::size_t i =
            ((static_cast<std::size_t>(o) * grid_dim_[0] + (it.getKey()[0] - grid_lo_[0])) * grid_dim_[1] +
             (it.getKey()[1] - grid_lo_[1])) * grid_dim_[2] + (it.getKey()[2] - grid_lo_[2]);
        grid_[i >> 6] |= 1ULL << (i & 63);
      }
  }
}

double CapabilityMap::reachability(const Eigen::Vector3d& p) const {
  std::uint32_t r = record(p);
  return r == DenseIndex::kNone ? 0.0 : d_[r];
}

namespace {

// Grid coordinates of p in voxels from the centre of voxel key 0 (octomap's voxel i spans [i, i + 1) * resolution,
// its centre is at (i + 0.5) * resolution): the lower corner's key and the fractions towards the upper ones.
// False when a corner falls outside the octree's keys.
bool corner_grid(const Eigen::Vector3d& p, double resolution, octomap::OcTreeKey& low, double frac[3]) {
  constexpr double kOffset = 32768.0;  // octomap's tree_max_val at depth 16: key = floor(x / res) + 32768
  const double inv = 1.0 / resolution;
  for (int a = 0; a < 3; ++a) {
    const double g = p[a] * inv - 0.5, base = std::floor(g);
    frac[a] = g - base;
    if (!(base + kOffset >= 0.0 && base + kOffset + 1.0 <= 65535.0)) return false;
    low[a] = static_cast<octomap::key_type>(base + kOffset);
  }
  return true;
}

// Corner k (bit a: one voxel up along axis a) of the 8 around a position: its key and trilinear weight.
inline double corner(const octomap::OcTreeKey& low, const double frac[3], int k, octomap::OcTreeKey& key) {
  double w = 1.0;
  key = low;
  for (int a = 0; a < 3; ++a) {
    const bool up = (k >> a) & 1;
    w *= up ? frac[a] : 1.0 - frac[a];
    key[a] = static_cast<octomap::key_type>(key[a] + up);
  }
  return w;
}

}  // namespace

void CapabilityMap::corners(const Eigen::Vector3d& p, std::uint32_t records[8], double weights[8]) const {
  octomap::OcTreeKey low;
  double frac[3];
  const bool inside = corner_grid(p, resolution_, low, frac);
  for (int k = 0; k < 8; ++k) {
    octomap::OcTreeKey key;
    weights[k] = corner(low, frac, k, key);
    records[k] = inside ? record_of_key(key) : DenseIndex::kNone;
  }
}

bool CapabilityMap::vote_(const Eigen::Vector3d& p, int o) const {
  octomap::OcTreeKey low;
  double frac[3];
  return corner_grid(p, resolution_, low, frac) && vote_corners_(low, frac, o);
}

bool CapabilityMap::vote_corners_(const octomap::OcTreeKey& low, const double frac[3], int o) const {
  int g[3];
  if (!grid_.empty())
    for (int a = 0; a < 3; ++a) {
      g[a] = low[a] - grid_lo_[a];
      // Both corners along an axis outside the grid's box (its rim is empty): no corner holds a record.
      if (g[a] < 0 || g[a] + 1 >= grid_dim_[a]) return false;
    }
  double yes = 0.0, left = 1.0;
  for (int k = 0; k < 8; ++k) {
    octomap::OcTreeKey key;
    const double w = corner(low, frac, k, key);
    if (w <= 0.0) continue;
    bool reach;
    if (!grid_.empty()) {
      reach = grid_bit_(o, g[0] + (k & 1), g[1] + ((k >> 1) & 1), g[2] + ((k >> 2) & 1));
    } else {
      const std::uint32_t r = record_of_key(key);
      reach = r != DenseIndex::kNone && bit(r, o);
    }
    if (reach) yes += w;
    left -= w;
    if (yes >= 0.5) return true;
    if (yes + left < 0.5 - 1e-12) return false;  // the rest cannot reach one half
  }
  return yes >= 0.5;
}

bool CapabilityMap::nearest_cell_(const Eigen::Vector3d& p, int o) const {
  if (grid_.empty()) {
    const std::uint32_t r = record(p);
    return r != DenseIndex::kNone && bit(r, o);
  }
  octomap::OcTreeKey key;
  if (!tree_->coordToKeyChecked(p.x(), p.y(), p.z(), key)) return false;
  int g[3];
  for (int a = 0; a < 3; ++a) {
    g[a] = key[a] - grid_lo_[a];
    if (g[a] < 0 || g[a] >= grid_dim_[a]) return false;
  }
  return grid_bit_(o, g[0], g[1], g[2]);
}

bool CapabilityMap::reachable(const Eigen::Vector3d& p, int orientation, CapabilityLookup lookup) const {
  if (orientation < 0 || orientation >= orientations_.size())
    throw std::invalid_argument("orientation index " + std::to_string(orientation) + " out of range [0, " +
                                std::to_string(orientations_.size()) + ")");
  if (lookup == CapabilityLookup::vote) return vote_(p, orientation);
  return nearest_cell_(p, orientation);
}

bool CapabilityMap::reachable(const Pose& T, CapabilityLookup lookup) const {
  const int o = orientations_.nearest(T.linear(), approach_axis_);
  if (lookup == CapabilityLookup::vote) return vote_(T.translation(), o);
  return nearest_cell_(T.translation(), o);
}

void CapabilityMap::reachability(const double* points, std::size_t n, double* out) const {
  detail::batch_lookup_finite(points, n, 3, "point", " (NaN or inf)", [&](std::size_t i) {
    const double* p = points + 3 * i;
    out[i] = reachability(Eigen::Vector3d(p[0], p[1], p[2]));
  });
}

void CapabilityMap::reachable(const double* poses, std::size_t n, bool* out, CapabilityLookup lookup) const {
  if (grid_.empty()) {
    detail::batch_lookup_finite(poses, n, 16, "pose", " (NaN or inf)", [&](std::size_t i) {
      Pose T;
      T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses + 16 * i);
      out[i] = reachable(T, lookup);
    });
    return;
  }
  // In groups: every pose's orientation and corners first, its grid words prefetched, then the lookups.
  constexpr std::size_t kGroup = 32;
  detail::batch_lookup_finite_groups(poses, n, 16, "pose", " (NaN or inf)", kGroup,
                                     [&](std::size_t i0, std::size_t i1, const bool* finite) {
    int o[kGroup];
    octomap::OcTreeKey low[kGroup];
    double frac[kGroup][3];
    bool keyed[kGroup];
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t k = i - i0;
      keyed[k] = false;
      if (!finite[k]) continue;
      const double* m = poses + 16 * i;
      Eigen::Matrix3d R;
      R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
      o[k] = orientations_.nearest(R, approach_axis_);
      // vote: the lower of the 8 corners (the grid words of its x and x + 1 planes); nearest cell: the voxel
      keyed[k] = lookup == CapabilityLookup::vote
                     ? corner_grid(Eigen::Vector3d(m[3], m[7], m[11]), resolution_, low[k], frac[k])
                     : tree_->coordToKeyChecked(m[3], m[7], m[11], low[k]);
      if (!keyed[k]) continue;
      int g[3];
      bool inside = true;
      for (int a = 0; a < 3; ++a) {
        g[a] = low[k][a] - grid_lo_[a];
        inside &= g[a] >= 0 && g[a] < grid_dim_[a];
      }
      if (!inside) {
        keyed[k] &= lookup == CapabilityLookup::vote;  // a nearest cell outside the grid is a no; a vote checks its corners
        continue;
      }
      const std::size_t b =
          ((static_cast<std::size_t>(o[k]) * grid_dim_[0] + g[0]) * grid_dim_[1] + g[1]) * grid_dim_[2] + g[2];
      __builtin_prefetch(grid_.data() + (b >> 6));
      if (lookup == CapabilityLookup::vote && g[0] + 1 < grid_dim_[0])
        __builtin_prefetch(grid_.data() + ((b + static_cast<std::size_t>(grid_dim_[1]) * grid_dim_[2]) >> 6));
    }
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t k = i - i0;
      if (!finite[k]) continue;
      if (lookup == CapabilityLookup::vote) {
        out[i] = keyed[k] && vote_corners_(low[k], frac[k], o[k]);
      } else {
        out[i] = keyed[k] && grid_bit_(o[k], low[k][0] - grid_lo_[0], low[k][1] - grid_lo_[1], low[k][2] - grid_lo_[2]);
      }
    }
  });
}

std::optional<Eigen::VectorXd> CapabilityMap::solution(const Eigen::Vector3d& p, int orientation) const {
  if (!has_solutions() || !reachable(p, orientation, CapabilityLookup::nearest_cell)) return std::nullopt;
  const float* q = record_solution(record(p), orientation);
  return Eigen::Map<const Eigen::VectorXf>(q, dof_).cast<double>();
}

std::int64_t CapabilityMap::record_at(const Eigen::Vector3d& p, Eigen::Vector3d* centre) const {
  std::uint32_t r = record(p);
  if (r == DenseIndex::kNone) return -1;
  if (centre) {
    octomap::OcTreeKey key = tree_->coordToKey(p.x(), p.y(), p.z());
    octomap::point3d c = tree_->keyToCoord(key);
    *centre = Eigen::Vector3d(c.x(), c.y(), c.z());
  }
  return r;
}

std::size_t CapabilityMap::rank_(const std::uint64_t* w, int o) const {
  std::size_t rank = 0;
  for (int i = 0; i < (o >> 6); ++i) rank += std::bitset<64>(w[i]).count();
  return rank + std::bitset<64>(w[o >> 6] & ((1ULL << (o & 63)) - 1)).count();
}

const float* CapabilityMap::record_solution(std::uint32_t rec, int o) const {
  if (!has_solutions() || !bit(rec, o)) return nullptr;
  return solutions_.data() + (sol_offset_[rec] + rank_(bits_.data() + std::size_t(rec) * words_, o)) * dof_;
}

const float* CapabilityMap::record_mixed_solution(std::uint32_t rec, int o) const {
  if (mixed_solutions_.empty() || !mixed_bit(rec, o)) return nullptr;
  return mixed_solutions_.data() + (mixed_offset_[rec] + rank_(mixed_.data() + std::size_t(rec) * words_, o)) * dof_;
}

const CellQuality* CapabilityMap::record_quality(std::uint32_t rec, int o) const {
  if (quality_.empty() || !bit(rec, o)) return nullptr;
  return quality_.data() + sol_offset_[rec] + rank_(bits_.data() + std::size_t(rec) * words_, o);
}

void CapabilityMap::require_quality(const std::string& what) const {
  if (!quality_.empty()) return;
  throw std::invalid_argument(
      what + " needs the quality of the map's cells, which this map does not hold (" +
      (has_solutions() ? "its file was written by an older octoreach" : "it was built or saved without joint solutions") +
      "): rebuild it with solutions, e.g. arms.capability_map(robot, arm, ...) (keep_solutions=True, the default) "
      "and save it with save(path, with_solutions=True)");
}

std::optional<CellQuality> CapabilityMap::quality(const Eigen::Vector3d& p, int orientation) const {
  require_quality("CapabilityMap.quality");
  if (orientation < 0 || orientation >= orientations_.size())
    throw std::invalid_argument("orientation index " + std::to_string(orientation) + " out of range [0, " +
                                std::to_string(orientations_.size()) + ")");
  const std::uint32_t r = record(p);
  if (r == DenseIndex::kNone || !bit(r, orientation)) return std::nullopt;
  return *record_quality(r, orientation);
}

std::vector<double> CapabilityMap::voxel_quality(bool max) const {
  require_quality("CapabilityMap.voxel_quality");
  std::vector<double> out;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (!(it->getValue() > 0)) continue;
    const std::uint32_t rec = it->payload;
    const std::size_t first = sol_offset_[rec];
    const std::size_t last = rec + 1 < sol_offset_.size() ? sol_offset_[rec + 1] : quality_.size();
    double sum = 0, best = 0;
    for (std::size_t k = first; k < last; ++k) {
      sum += quality_[k].value();
      best = std::max(best, double(quality_[k].value()));
    }
    out.push_back(max ? best : sum / double(last - first));
  }
  return out;
}

void CapabilityMap::voxels(std::vector<Eigen::Vector3d>& centres, std::vector<double>& values) const {
  centres.clear();
  values.clear();
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (!(it->getValue() > 0)) continue;  // a voxel of mixed cells only
    centres.emplace_back(it.getX(), it.getY(), it.getZ());
    values.push_back(it->getValue());
  }
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> CapabilityMap::bounds() const {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  bool first = true;
  double h = resolution_ / 2;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (!(it->getValue() > 0)) continue;
    Eigen::Vector3d c(it.getX(), it.getY(), it.getZ());
    if (first) {
      lo = c.array() - h;
      hi = c.array() + h;
      first = false;
    }
    lo = lo.cwiseMin((c.array() - h).matrix());
    hi = hi.cwiseMax((c.array() + h).matrix());
  }
  return {lo, hi};
}

std::vector<std::pair<std::string, std::string>> CapabilityMap::parameters() const {
  using detail::format_number;
  std::vector<std::pair<std::string, std::string>> p = detail::provenance_entries(provenance_);
  p.insert(p.end(), {
          {"base_link", base_link_},
          {"tip_link", tip_link_},
          {"dof", std::to_string(dof_)},
          {"resolution", format_number(resolution_)},
          {"directions", std::to_string(orientations_.directions())},
          {"rolls", std::to_string(orientations_.rolls())},
          {"symmetry", std::to_string(orientations_.symmetry())},
          {"approach_axis", detail::format_vector(approach_axis_)},
          {"self_collision", self_collision_ ? "1" : "0"},
          {"seed", std::to_string(seed_)},
          {"fk_samples", std::to_string(fk_samples_)},
          {"exhaustive", exhaustive_ ? "1" : "0"},
          {"position_tolerance", format_number(position_tolerance_)},
          {"orientation_tolerance", format_number(orientation_tolerance_)},
          {"block_size", std::to_string(block_size_)},
          {"voxels", std::to_string(voxel_count())},
          {"cell_data", cell_data_ ? "1" : "0"},
          {"jacobian_rank", std::to_string(jacobian_rank_)},
          {"reference", detail::format_vector(reference_)},
          {"octoreach_version", version()}});
  return p;
}


void CapabilityMap::export_octovis(const std::string& path) const {
  VoxelOcTree reachable(resolution_);  // the voxels with D > 0 (mixed-only voxels are not drawn)
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it)
    if (it->getValue() > 0) reachable.touch(it.getKey())->setValue(it->getValue());
  reachable.update_inner_values();
  detail::write_color_octree(reachable, 1.0, path);
}

}  // namespace octoreach
