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


#include "map_io.hpp"
#include "octoreach/chain.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"

namespace octoreach {
namespace {


// Progress in stages: each stage owns a share of a fixed total of 1000 units.
struct StagedProgress {
  const ProgressCallback& cb;
  void report(double stage_start, double stage_share, double fraction) const {
    if (!cb) return;
    auto done = static_cast<std::size_t>(1000.0 * (stage_start + stage_share * std::min(1.0, fraction)));
    if (!cb(done, 1000)) throw Cancelled("capability map build cancelled");
  }
};

}  // namespace

void CapabilityMap::set_parameters_(const CapabilityMapOptions& o) {
  resolution_ = o.resolution;
  approach_axis_ = o.approach_axis.normalized();
  self_collision_ = o.self_collision;
  seed_ = o.seed;
  exhaustive_ = o.exhaustive;
  position_tolerance_ = o.position_tolerance;
  orientation_tolerance_ = o.orientation_tolerance;
}

CapabilityMap CapabilityMap::build(const Chain& chain, const CapabilityMapOptions& o, const ProgressCallback& progress) {
  if (!(o.resolution > 0) || !std::isfinite(o.resolution))
    throw std::invalid_argument("resolution must be a positive number of metres, got " + detail::format_double(o.resolution));
  if (o.resolution < 0.001) throw std::invalid_argument("resolution below 1 mm is not supported");
  if (!o.approach_axis.allFinite() || o.approach_axis.norm() < 1e-9)
    throw std::invalid_argument("approach_axis must be a non-zero vector");
  if (chain.dof() == 0) throw std::invalid_argument("the chain has no moving joints");
  if (!(o.position_tolerance > 0) || !(o.orientation_tolerance > 0))
    throw std::invalid_argument("IK tolerances must be positive");
  const auto t_start = std::chrono::steady_clock::now();
  const Robot& robot = chain.robot();
  StagedProgress stage{progress};

  CapabilityMap m;
  m.set_parameters_(o);
  m.orientations_ = OrientationSet::sphere(o.directions, o.rolls, o.symmetry);
  m.robot_name_ = robot.name();
  m.urdf_hash_ = robot.urdf_hash();
  m.base_link_ = chain.base_link();
  m.tip_link_ = chain.tip_link();
  m.dof_ = chain.dof();
  const OrientationSet& set = m.orientations_;
  const int O = set.size();
  m.words_ = (O + 63) / 64;
  m.tree_ = std::make_shared<VoxelOcTree>(o.resolution);
  VoxelOcTree& tree = *m.tree_;

  Eigen::VectorXd reference = o.reference.size() ? o.reference : robot.home();
  if (reference.size() != robot.dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(reference.size()) +
                                " entries, the robot has " + std::to_string(robot.dof()));
  if (o.self_collision) {
    std::vector<std::pair<int, int>> moving, fixed;
    chain.split_collision_pairs(moving, fixed);
    if (robot.in_self_collision_poses(robot.link_poses(reference), fixed))
      throw std::invalid_argument("the reference posture is in self-collision among links the chain does not move");
  }

  // Workspace bounds from forward kinematics.
  std::mt19937_64 rng(o.seed);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = Eigen::Vector3d::Constant(-1e9);
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3d p = chain.fk(chain.random_configuration(rng)).translation();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= 1.5 * o.resolution;
  hi.array() += 1.5 * o.resolution;
  octomap::OcTreeKey kmin, kmax;
  if (!tree.coordToKeyChecked(lo.x(), lo.y(), lo.z(), kmin) || !tree.coordToKeyChecked(hi.x(), hi.y(), hi.z(), kmax))
    throw std::invalid_argument("the arm's workspace does not fit an octree at this resolution");
  const int nx = kmax[0] - kmin[0] + 1, ny = kmax[1] - kmin[1] + 1, nz = kmax[2] - kmin[2] + 1;
  const std::size_t nvox = static_cast<std::size_t>(nx) * ny * nz;
  const std::size_t ncells = nvox * O;
  if (ncells > (1ull << 31))
    throw std::invalid_argument("resolution " + detail::format_double(o.resolution) + " with " + std::to_string(O) +
                                " orientations gives " + std::to_string(ncells) + " cells: too many");
  auto vox_index = [&](const Eigen::Vector3d& p, std::size_t& v) {
    octomap::OcTreeKey k;
    if (!tree.coordToKeyChecked(p.x(), p.y(), p.z(), k)) return false;
    int ix = k[0] - kmin[0], iy = k[1] - kmin[1], iz = k[2] - kmin[2];
    if (ix < 0 || iy < 0 || iz < 0 || ix >= nx || iy >= ny || iz >= nz) return false;
    v = (static_cast<std::size_t>(ix) * ny + iy) * nz + iz;
    return true;
  };
  auto vox_key = [&](std::size_t v) {
    int iz = v % nz, iy = (v / nz) % ny, ix = v / (static_cast<std::size_t>(ny) * nz);
    return octomap::OcTreeKey(kmin[0] + ix, kmin[1] + iy, kmin[2] + iz);
  };
  auto vox_centre = [&](std::size_t v) {
    octomap::point3d c = tree.keyToCoord(vox_key(v));
    return Eigen::Vector3d(c.x(), c.y(), c.z());
  };
  // Cached tool rotations per orientation.
  std::vector<Eigen::Matrix3d> rotations(O);
  for (int i = 0; i < O; ++i) rotations[i] = set.rotation(i, m.approach_axis_);

  // ---- Stage 1: forward-kinematics sampling (deterministic: fixed chunks, merged in order).
  const int dof = chain.dof();
  const std::size_t samples = o.fk_samples ? o.fk_samples : 40 * nvox;
  const std::size_t chunk = 8192, chunks_per_round = 16;
  const std::size_t nchunks = (samples + chunk - 1) / chunk;
  std::vector<std::int32_t> seed_row(ncells, -1);
  std::vector<float> seed_pool;
  for (std::size_t round = 0; round * chunks_per_round < nchunks; ++round) {
    std::size_t c0 = round * chunks_per_round, c1 = std::min(nchunks, c0 + chunks_per_round);
    std::vector<std::vector<std::pair<std::uint32_t, Eigen::VectorXf>>> found(c1 - c0);
    detail::parallel_for(c1 - c0, o.threads, [&](std::size_t ci, int) {
      std::mt19937_64 r(detail::mix64(o.seed, c0 + ci));
      std::size_t n = std::min(chunk, samples - (c0 + ci) * chunk);
      std::unordered_set<std::uint32_t> local;
      for (std::size_t s = 0; s < n; ++s) {
        Eigen::VectorXd q = chain.random_configuration(r);
        Pose T = chain.fk(q);
        std::size_t v;
        if (!vox_index(T.translation(), v)) continue;
        std::uint32_t cell = static_cast<std::uint32_t>(v * O + set.nearest(T.linear(), m.approach_axis_));
        if (seed_row[cell] >= 0 || !local.insert(cell).second) continue;
        found[ci].emplace_back(cell, q.cast<float>());
      }
    }, 1);
    for (auto& list : found)
      for (auto& [cell, q] : list)
        if (seed_row[cell] < 0) {
          seed_row[cell] = static_cast<std::int32_t>(seed_pool.size() / dof);
          seed_pool.insert(seed_pool.end(), q.data(), q.data() + dof);
        }
    stage.report(0.0, 0.15, double(c1) / nchunks);
  }

  // ---- Stage 2: IK at the voxel centres, seeded; then a flood fill over neighbouring cells.
  enum : std::uint8_t { kUntried = 0, kQueued = 1, kFailed = 2, kReachable = 3 };
  std::vector<std::uint8_t> status(ncells, kUntried);
  std::vector<std::int32_t> sol_row(ncells, -1);
  std::vector<float> sol_pool;
  std::size_t ik_calls = 0;

  IkOptions base_ik;
  base_ik.mode = set.rolls() > 1 ? IkMode::Full : IkMode::Approach;
  base_ik.position_tolerance = o.position_tolerance;
  base_ik.orientation_tolerance = o.orientation_tolerance;
  base_ik.approach_axis = m.approach_axis_;
  base_ik.check_self_collision = o.self_collision;
  base_ik.check_fixed_pairs = false;  // checked once above
  base_ik.reference = reference;
  base_ik.max_iterations = 25;  // seeds are near: a cell that needs more is almost always unreachable

  struct Item {
    std::uint32_t cell;
    std::int32_t seed;  // row in seed_pool (wave 0) or sol_pool (flood); -1 none
    std::array<std::int32_t, 3> more{{-1, -1, -1}};  // further seeds from sol_pool (retry pass)
  };
  auto neighbours = [&](std::uint32_t cell, std::vector<std::uint32_t>& out) {
    out.clear();
    std::size_t v = cell / O;
    int oi = cell % O;
    int di = oi / set.rolls(), ri = oi % set.rolls();
    int iz = v % nz, iy = (v / nz) % ny, ix = v / (static_cast<std::size_t>(ny) * nz);
    const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& s : d) {
      int jx = ix + s[0], jy = iy + s[1], jz = iz + s[2];
      if (jx < 0 || jy < 0 || jz < 0 || jx >= nx || jy >= ny || jz >= nz) continue;
      out.push_back(static_cast<std::uint32_t>(((static_cast<std::size_t>(jx) * ny + jy) * nz + jz) * O + oi));
    }
    for (int dn : set.neighbours(di)) out.push_back(static_cast<std::uint32_t>(v * O + dn * set.rolls() + ri));
    if (set.rolls() > 1) {
      out.push_back(static_cast<std::uint32_t>(v * O + di * set.rolls() + (ri + 1) % set.rolls()));
      out.push_back(static_cast<std::uint32_t>(v * O + di * set.rolls() + (ri + set.rolls() - 1) % set.rolls()));
    }
  };

  auto run_wave = [&](const std::vector<Item>& wave, const std::vector<float>& pool, int attempts,
                      std::vector<std::uint32_t>& newly) {
    std::vector<Eigen::VectorXf> results(wave.size());
    std::vector<char> ok(wave.size(), 0);
    detail::parallel_for(wave.size(), o.threads, [&](std::size_t i, int) {
      const Item& it = wave[i];
      IkOptions opt = base_ik;
      opt.attempts = attempts;
      opt.seed = detail::mix64(o.seed ^ 0xC0FFEEULL, it.cell);
      Pose target = Pose::Identity();
      target.linear() = rotations[it.cell % O];
      target.translation() = vox_centre(it.cell / O);
      Eigen::VectorXd s;
      if (it.seed >= 0)
        s = Eigen::Map<const Eigen::VectorXf>(pool.data() + static_cast<std::size_t>(it.seed) * dof, dof).cast<double>();
      auto q = chain.ik(target, opt, it.seed >= 0 ? &s : nullptr);
      for (std::int32_t extra : it.more) {
        if (q || extra < 0) break;
        s = Eigen::Map<const Eigen::VectorXf>(sol_pool.data() + static_cast<std::size_t>(extra) * dof, dof).cast<double>();
        opt.attempts = 1;
        q = chain.ik(target, opt, &s);
      }
      if (q) {
        results[i] = q->cast<float>();
        ok[i] = 1;
      }
    }, 8);
    ik_calls += wave.size();
    newly.clear();
    for (std::size_t i = 0; i < wave.size(); ++i) {
      std::uint32_t c = wave[i].cell;
      if (ok[i]) {
        status[c] = kReachable;
        sol_row[c] = static_cast<std::int32_t>(sol_pool.size() / dof);
        sol_pool.insert(sol_pool.end(), results[i].data(), results[i].data() + dof);
        newly.push_back(c);
      } else {
        status[c] = kFailed;
      }
    }
  };

  auto flood = [&](std::vector<std::uint32_t> frontier) {
    std::vector<std::uint32_t> nb;
    while (!frontier.empty()) {
      std::vector<Item> wave;
      for (std::uint32_t c : frontier) {
        neighbours(c, nb);
        for (std::uint32_t n : nb)
          if (status[n] == kUntried) {
            status[n] = kQueued;
            wave.push_back({n, sol_row[c]});
          }
      }
      // Cells sampled by FK but not tried yet keep their own seed in wave 0; here the neighbour's solution is used.
      run_wave(wave, sol_pool, 1, frontier);
      std::size_t reachable = std::count(status.begin(), status.end(), kReachable);
      stage.report(0.15, 0.8, std::min(1.0, double(reachable) / std::max<std::size_t>(1, seed_pool.size() / dof) * 0.9));
    }
  };

  std::vector<Item> wave0;
  for (std::uint32_t c = 0; c < ncells; ++c)
    if (seed_row[c] >= 0) {
      wave0.push_back({c, seed_row[c]});
      status[c] = kQueued;
    }
  std::vector<std::uint32_t> newly;
  run_wave(wave0, seed_pool, 1, newly);
  const char* debug = std::getenv("OCTOREACH_DEBUG");
  if (debug) std::fprintf(stderr, "capability map: wave0 %zu calls, %zu reachable\n", wave0.size(), newly.size());
  stage.report(0.15, 0.5, 1.0);
  flood(newly);
  if (debug) std::fprintf(stderr, "capability map: after flood %zu calls\n", ik_calls);
  // Retry pass: a failed cell next to several reachable ones gets their solutions as seeds
  // (a single neighbour's seed can sit on the wrong side of a joint limit or a collision).
  // One pass: a second recovered about 1% of what it tried on the PR2 arm.
  for (int pass = 0; pass < 1; ++pass) {
    std::vector<Item> retry;
    std::vector<std::uint32_t> nb;
    for (std::uint32_t c = 0; c < ncells; ++c) {
      if (status[c] != kFailed) continue;
      neighbours(c, nb);
      Item it{c, -1};
      int k = 0;
      for (std::uint32_t n : nb)
        if (status[n] == kReachable) {
          if (k == 0) it.seed = sol_row[n];
          else if (k <= 3) it.more[k - 1] = sol_row[n];
          ++k;
        }
      if (k >= 2) retry.push_back(it);
    }
    if (retry.empty()) break;
    run_wave(retry, sol_pool, 1, newly);
    if (debug) std::fprintf(stderr, "capability map: retry pass %d: %zu cells, %zu recovered\n", pass, retry.size(), newly.size());
    if (newly.empty()) break;
    flood(newly);
  }
  if (o.exhaustive) {
    std::vector<Item> rest;
    for (std::uint32_t c = 0; c < ncells; ++c)
      if (status[c] == kUntried) rest.push_back({c, -1});
    run_wave(rest, sol_pool, std::max(1, o.exhaustive_attempts), newly);
    flood(newly);
  }
  stage.report(0.95, 0.0, 1.0);

  // ---- Stage 3: the octree and the per-voxel records.
  std::size_t reachable_cells = 0;
  for (std::size_t v = 0; v < nvox; ++v) {
    int count = 0;
    for (int oi = 0; oi < O; ++oi) count += status[v * O + oi] == kReachable;
    if (!count) continue;
    VoxelNode* leaf = tree.touch(vox_key(v));
    std::uint32_t rec = static_cast<std::uint32_t>(m.sol_offset_.size());
    leaf->payload = rec;
    leaf->setValue(static_cast<float>(count) / O);
    m.bits_.resize(m.bits_.size() + m.words_, 0);
    m.sol_offset_.push_back(reachable_cells);
    for (int oi = 0; oi < O; ++oi)
      if (status[v * O + oi] == kReachable) {
        m.bits_[static_cast<std::size_t>(rec) * m.words_ + (oi >> 6)] |= 1ULL << (oi & 63);
        if (o.keep_solutions) {
          const float* q = sol_pool.data() + static_cast<std::size_t>(sol_row[v * O + oi]) * dof;
          m.solutions_.insert(m.solutions_.end(), q, q + dof);
        }
        ++reachable_cells;
      }
  }
  tree.update_inner_values();
  m.finish_();
  m.fk_samples_ = samples;
  m.stats_.fk_samples = samples;
  m.stats_.ik_calls = ik_calls;
  m.stats_.cells = ncells;
  m.stats_.reachable_cells = reachable_cells;
  m.stats_.voxels = m.sol_offset_.size();
  m.stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  stage.report(1.0, 0.0, 1.0);
  return m;
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

bool CapabilityMap::reachable(const Eigen::Vector3d& p, int orientation) const {
  if (orientation < 0 || orientation >= orientations_.size())
    throw std::invalid_argument("orientation index " + std::to_string(orientation) + " out of range [0, " +
                                std::to_string(orientations_.size()) + ")");
  std::uint32_t r = record(p);
  return r != DenseIndex::kNone && bit(r, orientation);
}

bool CapabilityMap::reachable(const Pose& T) const {
  std::uint32_t r = record(T.translation());
  return r != DenseIndex::kNone && bit(r, orientations_.nearest(T.linear(), approach_axis_));
}

std::optional<Eigen::VectorXd> CapabilityMap::solution(const Eigen::Vector3d& p, int orientation) const {
  if (!has_solutions() || !reachable(p, orientation)) return std::nullopt;
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
  using detail::format_double;
  return {{"robot", robot_name_},
          {"urdf_hash", std::to_string(urdf_hash_)},
          {"base_link", base_link_},
          {"tip_link", tip_link_},
          {"dof", std::to_string(dof_)},
          {"resolution", format_double(resolution_)},
          {"directions", std::to_string(orientations_.directions())},
          {"rolls", std::to_string(orientations_.rolls())},
          {"symmetry", std::to_string(orientations_.symmetry())},
          {"approach_axis", format_double(approach_axis_.x()) + " " + format_double(approach_axis_.y()) + " " +
                                format_double(approach_axis_.z())},
          {"self_collision", self_collision_ ? "1" : "0"},
          {"seed", std::to_string(seed_)},
          {"fk_samples", std::to_string(fk_samples_)},
          {"exhaustive", exhaustive_ ? "1" : "0"},
          {"position_tolerance", format_double(position_tolerance_)},
          {"orientation_tolerance", format_double(orientation_tolerance_)},
          {"voxels", std::to_string(voxel_count())},
          {"build_seconds", format_double(stats_.seconds)},
          {"octoreach_version", version()}};
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
  detail::write_map_file(path, "capability", h, w.bytes);
}

CapabilityMap CapabilityMap::load(const std::string& path) {
  detail::Header h;
  std::vector<char> payload;
  detail::read_map_file(path, "capability", h, payload);
  CapabilityMap m;
  using detail::header_double;
  using detail::header_int;
  using detail::header_string;
  m.robot_name_ = header_string(h, "robot", path);
  m.urdf_hash_ = detail::header_u64(h, "urdf_hash", path);
  m.base_link_ = header_string(h, "base_link", path);
  m.tip_link_ = header_string(h, "tip_link", path);
  m.dof_ = static_cast<int>(header_int(h, "dof", path));
  m.resolution_ = header_double(h, "resolution", path);
  int dirs = static_cast<int>(header_int(h, "directions", path));
  int rolls = static_cast<int>(header_int(h, "rolls", path));
  int sym = static_cast<int>(header_int(h, "symmetry", path));
  if (!(m.resolution_ >= 0.001) || dirs < 1 || dirs > 100000 || rolls < 1 || rolls > 360 || sym < 1 || sym > 64 ||
      m.dof_ < 1 || m.dof_ > 64)
    throw FileError("'" + path + "' has implausible map parameters");
  {
    std::istringstream axis(header_string(h, "approach_axis", path));
    if (!(axis >> m.approach_axis_.x() >> m.approach_axis_.y() >> m.approach_axis_.z()))
      throw FileError("'" + path + "' has a malformed approach_axis");
  }
  m.self_collision_ = header_int(h, "self_collision", path) != 0;
  m.seed_ = detail::header_u64(h, "seed", path);
  m.fk_samples_ = static_cast<std::size_t>(header_int(h, "fk_samples", path));
  m.exhaustive_ = header_int(h, "exhaustive", path) != 0;
  m.position_tolerance_ = header_double(h, "position_tolerance", path);
  m.orientation_tolerance_ = header_double(h, "orientation_tolerance", path);
  m.stats_.seconds = header_double(h, "build_seconds", path);
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
