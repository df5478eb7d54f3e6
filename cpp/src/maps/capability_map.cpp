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

  reference = reference_or_default(robot, chain, o.reference);
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

void CapabilityMap::add_voxel_(const octomap::OcTreeKey& key, const std::uint64_t* bits, const float* solutions) {
  std::size_t count = 0;
  for (int i = 0; i < words_; ++i) count += std::bitset<64>(bits[i]).count();
  VoxelNode* leaf = tree_->touch(key);
  leaf->payload = static_cast<std::uint32_t>(sol_offset_.size());
  leaf->setValue(static_cast<float>(count) / orientations_.size());
  bits_.insert(bits_.end(), bits, bits + words_);
  sol_offset_.push_back(stats_.reachable_cells);
  if (solutions) solutions_.insert(solutions_.end(), solutions, solutions + count * dof_);
  stats_.reachable_cells += count;
}

void CapabilityMap::finish_build_(std::size_t samples, std::size_t ik_calls, std::size_t cells, double seconds) {
  tree_->update_inner_values();
  finish_();
  fk_samples_ = samples;
  stats_.fk_samples = samples;
  stats_.ik_calls = ik_calls;
  stats_.cells = cells;
  stats_.voxels = sol_offset_.size();
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

  // The octree and the per-voxel records, in voxel order.
  std::vector<std::uint64_t> bits(m.words_);
  std::vector<float> sols;
  for (std::size_t v = 0; v < box.voxels; ++v) {
    std::fill(bits.begin(), bits.end(), 0);
    sols.clear();
    bool any = false;
    for (int oi = 0; oi < O; ++oi)
      if (builder.reachable(v * O + oi)) {
        any = true;
        bits[oi >> 6] |= 1ULL << (oi & 63);
        if (o.keep_solutions) sols.insert(sols.end(), builder.solution(v * O + oi), builder.solution(v * O + oi) + m.dof_);
      }
    if (any) m.add_voxel_(box.key(v), bits.data(), o.keep_solutions ? sols.data() : nullptr);
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
}

double CapabilityMap::reachability(const Eigen::Vector3d& p) const {
  std::uint32_t r = record(p);
  return r == DenseIndex::kNone ? 0.0 : d_[r];
}

bool CapabilityMap::vote_(const Eigen::Vector3d& p, int o) const {
  // Grid coordinates of p in units of voxels, measured from the centre of voxel key 0 (octomap's
  // voxel i spans [i, i + 1) * resolution; its centre is at (i + 0.5) * resolution).
  const double inv = 1.0 / resolution_;
  double base[3], frac[3];
  for (int a = 0; a < 3; ++a) {
    const double g = p[a] * inv - 0.5;
    base[a] = std::floor(g);
    frac[a] = g - base[a];
  }
  double yes = 0.0, left = 1.0;
  for (int k = 0; k < 8; ++k) {
    double w = 1.0;
    Eigen::Vector3d c;
    for (int a = 0; a < 3; ++a) {
      const bool up = (k >> a) & 1;
      w *= up ? frac[a] : 1.0 - frac[a];
      c[a] = (base[a] + (up ? 1.5 : 0.5)) * resolution_;  // the centre of the corner voxel
    }
    if (w <= 0.0) continue;
    const std::uint32_t r = record(c);
    if (r != DenseIndex::kNone && bit(r, o)) yes += w;
    left -= w;
    if (yes >= 0.5) return true;
    if (yes + left < 0.5 - 1e-12) return false;  // the rest cannot reach one half
  }
  return yes >= 0.5;
}

bool CapabilityMap::reachable(const Eigen::Vector3d& p, int orientation, CapabilityLookup lookup) const {
  if (orientation < 0 || orientation >= orientations_.size())
    throw std::invalid_argument("orientation index " + std::to_string(orientation) + " out of range [0, " +
                                std::to_string(orientations_.size()) + ")");
  if (lookup == CapabilityLookup::vote) return vote_(p, orientation);
  std::uint32_t r = record(p);
  return r != DenseIndex::kNone && bit(r, orientation);
}

bool CapabilityMap::reachable(const Pose& T, CapabilityLookup lookup) const {
  const int o = orientations_.nearest(T.linear(), approach_axis_);
  if (lookup == CapabilityLookup::vote) return vote_(T.translation(), o);
  std::uint32_t r = record(T.translation());
  return r != DenseIndex::kNone && bit(r, o);
}

void CapabilityMap::reachability(const double* points, std::size_t n, double* out) const {
  detail::batch_lookup_finite(points, n, 3, "point", " (NaN or inf)", [&](std::size_t i) {
    const double* p = points + 3 * i;
    out[i] = reachability(Eigen::Vector3d(p[0], p[1], p[2]));
  });
}

void CapabilityMap::reachable(const double* poses, std::size_t n, bool* out, CapabilityLookup lookup) const {
  detail::batch_lookup_finite(poses, n, 16, "pose", " (NaN or inf)", [&](std::size_t i) {
    Pose T;
    T.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses + 16 * i);
    out[i] = reachable(T, lookup);
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

const float* CapabilityMap::record_solution(std::uint32_t rec, int o) const {
  if (!has_solutions() || !bit(rec, o)) return nullptr;
  std::size_t rank = 0;
  const std::uint64_t* w = bits_.data() + static_cast<std::size_t>(rec) * words_;
  for (int i = 0; i < (o >> 6); ++i) rank += std::bitset<64>(w[i]).count();
  rank += std::bitset<64>(w[o >> 6] & ((1ULL << (o & 63)) - 1)).count();
  return solutions_.data() + (sol_offset_[rec] + rank) * dof_;
}

void CapabilityMap::voxels(std::vector<Eigen::Vector3d>& centres, std::vector<double>& values) const {
  centres.clear();
  values.clear();
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    centres.emplace_back(it.getX(), it.getY(), it.getZ());
    values.push_back(it->getValue());
  }
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> CapabilityMap::bounds() const {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  bool first = true;
  double h = resolution_ / 2;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
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
          {"octoreach_version", version()}});
  return p;
}


void CapabilityMap::save(const std::string& path, bool with_solutions) const {
  detail::Header h;
  for (auto& [k, v] : parameters()) h[k] = v;
  bool sols = with_solutions && has_solutions();
  h["solutions"] = sols ? "1" : "0";
  detail::ByteWriter w;
  w.put(static_cast<std::uint64_t>(voxel_count()));
  if (tree_->getRoot()) {
    w.put(std::uint8_t{1});
    write_tree(*tree_, tree_->getRoot(), 0, w, [&](const VoxelNode& n) {
      w.put_bytes(bits_.data() + static_cast<std::size_t>(n.payload) * words_, words_ * sizeof(std::uint64_t));
      if (sols) {
        std::size_t count = 0;
        for (int i = 0; i < words_; ++i) count += std::bitset<64>(bits_[static_cast<std::size_t>(n.payload) * words_ + i]).count();
        w.put_bytes(solutions_.data() + sol_offset_[n.payload] * dof_, count * dof_ * sizeof(float));
      }
    });
  } else {
    w.put(std::uint8_t{0});
  }
  detail::write_map_file(path, kKind, h, w.bytes, kFormatVersion);
}

CapabilityMap CapabilityMap::load(const std::string& path) {
  detail::Header h;
  std::vector<char> payload;
  // The contents the header declares: per voxel a bit per orientation, and (with solutions) a joint
  // vector per orientation; the counts are checked before they are multiplied.
  detail::read_map_file(path, kKind, h, payload, [&](const detail::Header& head) {
    const long long dirs = detail::header_int(head, "directions", path), rolls = detail::header_int(head, "rolls", path),
                    dof = detail::header_int(head, "dof", path);
    if (dirs < 1 || dirs > OrientationSet::kMaxDirections || rolls < 1 || rolls > OrientationSet::kMaxRolls ||
        dof < 1 || dof > 64)
      throw FileError("'" + path + "' has implausible map parameters");
    const std::uint64_t O = std::uint64_t(dirs) * std::uint64_t(rolls);
    std::uint64_t record = (O + 63) / 64 * sizeof(std::uint64_t);
    if (detail::header_int(head, "solutions", path) != 0) record += O * std::uint64_t(dof) * sizeof(float);
    return detail::payload_bound(detail::header_voxels(head, path), record);
  });
  CapabilityMap m;
  using detail::header_double;
  using detail::header_int;
  using detail::header_string;
  m.provenance_ = detail::header_provenance(h, path);
  m.base_link_ = header_string(h, "base_link", path);
  m.tip_link_ = header_string(h, "tip_link", path);
  m.resolution_ = header_double(h, "resolution", path);
  // counts checked at full width before they are narrowed
  const auto dof64 = header_int(h, "dof", path), dirs64 = header_int(h, "directions", path),
             rolls64 = header_int(h, "rolls", path), sym64 = header_int(h, "symmetry", path);
  if (!(m.resolution_ >= limits::kMinMapResolution && m.resolution_ <= limits::kMaxMapResolution) || dirs64 < 1 ||
      dirs64 > OrientationSet::kMaxDirections || rolls64 < 1 || rolls64 > OrientationSet::kMaxRolls || sym64 < 1 ||
      sym64 > 64 || dof64 < 1 || dof64 > 64)
    throw FileError("'" + path + "' has implausible map parameters");
  m.dof_ = static_cast<int>(dof64);
  const int dirs = static_cast<int>(dirs64), rolls = static_cast<int>(rolls64), sym = static_cast<int>(sym64);
  {
    std::istringstream axis(header_string(h, "approach_axis", path));
    if (!(axis >> m.approach_axis_.x() >> m.approach_axis_.y() >> m.approach_axis_.z()))
      throw FileError("'" + path + "' has a malformed approach_axis");
    if (!m.approach_axis_.allFinite() || std::abs(m.approach_axis_.norm() - 1.0) > 1e-6)
      throw FileError("'" + path + "' has an approach_axis that is not a unit vector");
  }
  m.self_collision_ = header_int(h, "self_collision", path) != 0;
  m.seed_ = detail::header_u64(h, "seed", path);
  m.fk_samples_ = static_cast<std::size_t>(header_int(h, "fk_samples", path));
  m.exhaustive_ = header_int(h, "exhaustive", path) != 0;
  m.position_tolerance_ = header_double(h, "position_tolerance", path);
  m.orientation_tolerance_ = header_double(h, "orientation_tolerance", path);
  // Files hold no timing (the same build gives the same bytes); files of older versions recorded one.
  m.stats_.seconds = h.count("build_seconds") ? header_double(h, "build_seconds", path) : 0.0;
  m.block_size_ = h.count("block_size") ? static_cast<int>(std::clamp<long long>(header_int(h, "block_size", path), 0, 1 << 20)) : 0;
  bool sols = header_int(h, "solutions", path) != 0;
  m.orientations_ = OrientationSet::sphere(dirs, rolls, sym);
  if (m.orientations_.directions() != dirs) throw FileError("'" + path + "' has an inconsistent direction count");
  const int O = m.orientations_.size();
  m.words_ = (O + 63) / 64;
  m.tree_ = std::make_shared<VoxelOcTree>(m.resolution_);
  detail::ByteReader r(payload, "'" + path + "'");
  auto count = r.get<std::uint64_t>();
  if (count > payload.size()) r.fail("damaged map data (voxel count)");
  std::size_t cells = 0;
  if (r.get<std::uint8_t>()) {
    VoxelOcTree& tree = *m.tree_;
    VoxelNode* new_root = tree.ensure_root();
    read_tree(tree, new_root, 0, r, [&](VoxelNode& n) {
      std::uint32_t rec = static_cast<std::uint32_t>(m.sol_offset_.size());
      if (rec >= count) r.fail("damaged map data (more voxels than recorded)");
      n.payload = rec;
      m.bits_.resize(m.bits_.size() + m.words_);
      r.get_bytes(m.bits_.data() + static_cast<std::size_t>(rec) * m.words_, m.words_ * sizeof(std::uint64_t));
      std::size_t c = 0;
      for (int i = 0; i < m.words_; ++i) c += std::bitset<64>(m.bits_[static_cast<std::size_t>(rec) * m.words_ + i]).count();
      if (c == 0 || c > static_cast<std::size_t>(O)) r.fail("damaged map data (voxel record)");
      m.sol_offset_.push_back(cells);
      if (sols) {
        std::size_t n_floats = c * m.dof_;
        if (r.remaining() < n_floats * sizeof(float)) r.fail("damaged map data (solutions end early)");
        std::size_t off = m.solutions_.size();
        m.solutions_.resize(off + n_floats);
        r.get_bytes(m.solutions_.data() + off, n_floats * sizeof(float));
      }
      cells += c;
      n.setValue(static_cast<float>(c) / O);
    });
    tree.update_inner_values();
  }
  if (!r.done()) r.fail("damaged map data (trailing bytes)");
  if (m.sol_offset_.size() != count) r.fail("damaged map data (voxel count mismatch)");
  m.stats_.voxels = count;
  m.stats_.reachable_cells = cells;
  m.finish_();
  return m;
}

void CapabilityMap::export_octovis(const std::string& path) const { detail::write_color_octree(*tree_, 1.0, path); }

}  // namespace octoreach
