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
#include "common/thread_pool.hpp"
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
  keeps_solutions_ = o.keep_solutions;
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
  m.orientations_ = OrientationSet::sphere(o.directions, o.rolls, o.symmetry, o.poles);
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
  builder.stage("sampled");
  builder.solve();
  builder.stage("solved");
  builder.rate();
  builder.stage("rated");
  // The octree and the per-voxel records, in voxel order: each slab of voxels collected on every core, then added.
  constexpr std::size_t kSlab = 4096;
  std::vector<detail::VoxelCellData> slab(kSlab);
  for (std::size_t v0 = 0; v0 < box.voxels; v0 += kSlab) {
    const std::size_t n = std::min(kSlab, box.voxels - v0);
    detail::parallel_for(n, o.threads, [&](std::size_t i, int) { builder.collect(v0 + i, slab[i]); }, 64);
    for (std::size_t i = 0; i < n; ++i)
      if (!slab[i].empty()) m.add_voxel_(box.key(v0 + i), slab[i]);
  }
  builder.stage("collected");
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

std::optional<Eigen::VectorXd> CapabilityMap::solution(const Eigen::Vector3d& p, int orientation) const {
  // No solutions is no answer, not "unreachable": said as quality() says it.
  if (!has_solutions())
    throw std::invalid_argument(
        "CapabilityMap.solution needs the joint solutions of the map's cells, which this map does not hold (it was "
        "built or saved without them): rebuild it with solutions, e.g. arms.capability_map(robot, arm, ...) "
        "(keep_solutions=True, the default) and save it with save(path, with_solutions=True)");
  if (!reachable(p, orientation, CapabilityLookup::nearest_cell)) return std::nullopt;
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
  if (has_quality()) return;  // (a map of mixed cells only holds no quality and answers none)
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
  if (orientations_.poles()) p.emplace_back("poles", "1");  // (absent: the files of maps without them unchanged)
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
